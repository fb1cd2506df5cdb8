//! Safety before speed: the time-step bound checked at load, and blow-up detection during the run (reference §3.6,
//! §10.4). Every error carries the time (the run's report says it, so the message does not repeat it) and names the
//! bodies involved and a time step to try.

use crate::bodies::{Bodies, BodyId, BodyKind};
use crate::integrator::max_stable_time_step_elongated;
use crate::interactions::{ContactModel, InteractionTable};
use crate::shape::{ShapeKind, flat_contact_ratio};
use gc2d_contact::{AreaFormulation, PairProperties};
use gc2d_geometry::{Aabb, DVec2, area_contact};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Limits of the run-time blow-up checks.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SafetyLimits {
    /// Largest overlap allowed: for the overlap-area law the overlap area as a fraction of the smaller particle's
    /// area, for penetration laws the depth as a fraction of the smaller particle's diameter. Settled piles at the
    /// thesis's parameters stay below 1e-3; an overlap of 5 % means a particle has tunnelled into another.
    pub max_overlap_fraction: f64,
    /// Largest unexplained energy gain allowed, as a fraction of the energy scale of the run (see
    /// [`crate::ledger::EnergyLedger::energy_scale`]). The ledger books damping at the end-of-step force, so its error
    /// is first order in Δt and can reach a quarter of the energy in play during the very first contact steps of a
    /// sound damped run; a blow-up creates energy many times the energy in play. The default, 1.0, stops a run only
    /// when it has gained more energy than everything the run has moved around.
    pub max_energy_gain_fraction: f64,
    /// Largest distance any point of a particle may travel in one step, as a fraction of the particle's inscribed
    /// radius. A particle can pass through a thin wall or another particle without a single step seeing them overlap
    /// only if it moves further than its own width, at least twice its inscribed radius, in one step; the overlap
    /// check cannot see that, this one does. The default, 1.0, is far above sound runs: at the §3.6 bound a particle
    /// travels its inscribed radius per step only at about 80 m/s (ρ = 5000 kg/m², E = 1e7 N/m).
    pub max_travel_fraction: f64,
    /// Largest overlap allowed between bodies at the start, as a fraction of the smaller particle's area. The default,
    /// [`INITIAL_OVERLAP_TOLERANCE`], refuses anything beyond round-off: a start-time overlap is treated as a brand-new
    /// contact, so its damping kicks the bodies apart and its elastic energy is missing from the ledger's start. Raise
    /// it only for deliberately pre-loaded contacts (an undamped oscillator, say), and judge energy with that in mind.
    pub max_initial_overlap_fraction: f64,
    /// Run with a Δt above the stable bound anyway (for experiments on instability).
    pub allow_unsafe_time_step: bool,
    /// The highest normal impact speed the scene expects, m/s: a Hertz contact stiffens with depth, so its stable
    /// time step depends on how hard bodies can hit (a mill: about twice the rotor's tip speed).
    pub max_impact_speed: f64,
}

impl Default for SafetyLimits {
    fn default() -> Self {
        Self {
            max_overlap_fraction: 0.05,
            max_energy_gain_fraction: 1.0,
            max_travel_fraction: 1.0,
            max_initial_overlap_fraction: INITIAL_OVERLAP_TOLERANCE,
            allow_unsafe_time_step: false,
            max_impact_speed: DEFAULT_MAX_IMPACT_SPEED,
        }
    }
}

/// The impact speed a scene is assumed to stay below unless it says otherwise, m/s: well above the speeds of piles,
/// silos and drums, which fall a few centimetres.
pub const DEFAULT_MAX_IMPACT_SPEED: f64 = 10.0;

/// A run that cannot start or cannot go on.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SafetyError {
    /// Δt above the bound of the stiffest contact model a particle meets: (π/10)·sqrt(m/E) of eq. (2.9) for the
    /// overlap-area law, the bound of [`gc2d_contact::PenetrationLaw::max_time_step`] for penetration laws.
    #[error(
        "time step {dt:.3e} s is above the stable bound {safe_dt:.3e} s of particle {particle} (inscribed radius \
         {inscribed_radius:.3e} m) against the stiffest contact model its material meets; use a time step of at most \
         {safe_dt:.3e} s, or allow unsafe time steps explicitly"
    )]
    UnsafeTimeStep {
        /// The requested Δt, s.
        dt: f64,
        /// The bound, s.
        safe_dt: f64,
        /// The particle that sets the bound.
        particle: u32,
        /// Its inscribed radius, m.
        inscribed_radius: f64,
    },
    /// A position, velocity or kinetic energy became NaN or infinite.
    #[error(
        "the simulation blew up: particle {body} has a position, velocity or kinetic energy \
         that is not a finite number; reduce the time step (try {suggested_dt:.3e} s)"
    )]
    NotFinite {
        /// Simulated time, s.
        time: f64,
        /// Step number.
        step: u64,
        /// The first offending body.
        body: u32,
        /// A time step to try, s.
        suggested_dt: f64,
    },
    /// Two bodies overlap far more than elastic contacts ever do: one has tunnelled into the other (the time step is
    /// too large), or an impact pressed them together deeper than their contact allows (it is too soft).
    #[error(
        "the simulation blew up: bodies {a} and {b} overlap by {percent:.1} % of the \
         smaller particle's {measure} (limit {limit_percent:.1} %); {}",
        overlap_advice(*.approach_per_step, *.approach_speed_m_s, *.suggested_dt)
    )]
    ExcessiveOverlap {
        /// Simulated time, s.
        time: f64,
        /// Step number.
        step: u64,
        /// First body.
        a: u32,
        /// Second body.
        b: u32,
        /// Overlap in percent of the smaller particle's `measure`.
        percent: f64,
        /// What the overlap is measured against: `area` (the overlap area, for the overlap-area law) or `diameter (the
        /// depth)` (the penetration depth, for penetration laws such as Hertz), as `run.max_overlap_fraction` is.
        measure: &'static str,
        /// The limit in percent.
        limit_percent: f64,
        /// How fast the bodies move relative to each other along the contact normal (closing, or thrown apart by
        /// the overlap's force within the step), m/s.
        approach_speed_m_s: f64,
        /// How far they move in one step at that speed, as a fraction of the overlap's depth: near 1 or above when
        /// one step made the overlap (the time step is the cause), small when it grew over many steps (the contact
        /// is too soft for the impact).
        approach_per_step: f64,
        /// A time step to try, s.
        suggested_dt: f64,
    },
    /// A particle moved so far in one step that it could have passed through a thin wall or another particle
    /// unseen (no step ever sees an overlap when it jumps right across).
    #[error(
        "the simulation blew up: particle {body} moved {travel:.3e} m in one step, \
         more than {limit_percent:.0} % of its inscribed radius {inscribed_radius:.3e} m, so it could pass through a \
         thin wall or another particle without ever overlapping it; reduce the time step (try {suggested_dt:.3e} s)"
    )]
    ExcessiveTravel {
        /// Simulated time, s.
        time: f64,
        /// Step number.
        step: u64,
        /// The first offending particle.
        body: u32,
        /// Largest distance a point of the particle moved in the step, (|v| + |ω|·R)·Δt with R its farthest vertex
        /// from the centroid, m.
        travel: f64,
        /// Its inscribed radius, m.
        inscribed_radius: f64,
        /// The limit in percent of the inscribed radius.
        limit_percent: f64,
        /// A time step to try, s.
        suggested_dt: f64,
    },
    /// Two bodies already overlap when the run starts. Their elastic energy is not in the energy ledger, and the
    /// first step sees the whole overlap as new, so the normal damping kicks them apart as if they had collided at
    /// overlap-depth/Δt: the energy check would stop the run with a misleading "reduce the time step".
    #[error(
        "bodies {a} and {b} overlap by {percent:.3} % of the smaller particle's area at the start (t = 0 s, before \
         step 1); particles must start apart — place them further apart (for a generated block, a grid spacing of \
         at least the particle size); a smaller time step does not help"
    )]
    InitialOverlap {
        /// First body.
        a: u32,
        /// Second body.
        b: u32,
        /// Overlap in percent of the smaller particle's area (of the wall's partner for a wall).
        percent: f64,
    },
    /// The total energy rose by more than the work put in can explain.
    #[error(
        "the simulation blew up: the energy rose by {gain:.3e} {energy_unit} more than the work done on the system \
         explains ({percent:.0} % of the run's energy scale){}; reduce the time step (try {suggested_dt:.3e} s)",
        most_energetic_in_words(*.most_energetic, energy_unit)
    )]
    EnergyJump {
        /// Simulated time, s.
        time: f64,
        /// Step number.
        step: u64,
        /// Unexplained gain, in `energy_unit`.
        gain: f64,
        /// The unit of the energies: `J/m` per unit thickness, `J` for sphere-equivalent masses.
        energy_unit: &'static str,
        /// The living particle with the most kinetic energy at the stop and that energy, in `energy_unit`: where a
        /// blow-up is, as a rule (the ledger does not say which bodies gained the energy). `None` without particles.
        most_energetic: Option<(u32, f64)>,
        /// The gain in percent of the energy scale.
        percent: f64,
        /// A time step to try, s.
        suggested_dt: f64,
    },
}

/// The part of an [`SafetyError::EnergyJump`] that names the particle with the most kinetic energy, if any.
fn most_energetic_in_words(most_energetic: Option<(u32, f64)>, energy_unit: &str) -> String {
    most_energetic.map_or(String::new(), |(body, kinetic)| {
        format!(
            "; the energy balance does not say which bodies gained it, but the particle with the most kinetic energy \
             at the stop is body {body} ({kinetic:.3e} {energy_unit})"
        )
    })
}

/// An overlap that one step's approach makes less than this fraction of is blamed on the contact's softness, not on
/// the time step: it grew over at least this many steps, which a smaller step would only resolve more finely.
pub const SOFT_CONTACT_APPROACH_FRACTION: f64 = 0.25;

/// The advice of an [`SafetyError::ExcessiveOverlap`]: a smaller Δt when one step's approach made a good part of the
/// overlap, a stiffer contact (or a larger overlap limit) when the overlap grew over many steps of an impact.
fn overlap_advice(approach_per_step: f64, approach_speed: f64, suggested_dt: f64) -> String {
    if approach_per_step < SOFT_CONTACT_APPROACH_FRACTION {
        format!(
            "the bodies move at {approach_speed:.3} m/s relative to each other along the contact normal, {:.1} % of \
             the overlap's depth per step, so the overlap \
             grew over many steps and a smaller time step would not prevent it: the contact is too soft for this \
             impact — stiffen it (a larger Young's modulus of the two materials, or of their interaction) or allow \
             more overlap (`run.max_overlap_fraction`)",
            100.0 * approach_per_step
        )
    } else {
        format!(
            "the bodies move at {approach_speed:.3} m/s relative to each other along the contact normal, {:.0} % of \
             the overlap's depth in one step: a particle \
             moved too far in one step — reduce the time step (try {suggested_dt:.3e} s)",
            100.0 * approach_per_step
        )
    }
}

impl SafetyError {
    /// The bodies the error names, by id (for a front end that knows the scene's names for them).
    pub fn bodies(&self) -> Vec<u32> {
        match *self {
            SafetyError::UnsafeTimeStep { particle, .. } => vec![particle],
            SafetyError::NotFinite { body, .. } | SafetyError::ExcessiveTravel { body, .. } => vec![body],
            SafetyError::ExcessiveOverlap { a, b, .. } | SafetyError::InitialOverlap { a, b, .. } => vec![a, b],
            SafetyError::EnergyJump { most_energetic, .. } => {
                most_energetic.map(|(body, _)| body).into_iter().collect()
            }
        }
    }
}

/// The particle whose time-step bound is the lowest, and that bound.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeStepBound {
    /// The largest stable Δt, s: the one to offer ([`ParticleTimeStep::stable`]).
    pub dt: f64,
    /// The particle that sets it.
    pub particle: BodyId,
    /// The Δt above which a run is refused, s: the smallest [`ParticleTimeStep::reference`] (for the overlap-area
    /// law the §3.6 bound, where the integrator itself fails; between `dt` and it a run goes on, and flat contacts
    /// may chatter or change their energy by percents).
    pub refusal: f64,
}

/// What the time-step bound of one particle depends on, at its current size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParticleInertia {
    /// Radius of the largest circle about the centroid inside the particle, m.
    pub inscribed_radius: f64,
    /// Mass per area of its outline, kg/m² (the overlap-area law's bound uses the inscribed circle's mass).
    pub area_density: f64,
    /// Mass, kg.
    pub mass: f64,
    /// Moment of inertia, kg·m².
    pub inertia: f64,
    /// The radius penetration laws give it (a disk's radius, a polygon's equal-area radius), m.
    pub contact_radius: f64,
    /// Distance of its farthest point from the centroid, m (bounds the contact chords it can have).
    pub reach: f64,
    /// κ, the c/l of two copies meeting face on ([`crate::shape::flat_contact_ratio`]); 0 for disks.
    pub flat_contact_ratio: f64,
}

/// The time-step bounds of one particle against the contact models it meets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParticleTimeStep {
    /// The largest stable Δt, s: what a scene may use at most ([`particle_time_step`]).
    pub stable: f64,
    /// The Δt the automatic choice is a fraction of, s: for the overlap-area law the §3.6 bound (π/10)·sqrt(m/E)
    /// before the flat-contact and damping limits (so that scenes those limits do not bind keep their Δt), for a
    /// penetration law its stable bound.
    pub reference: f64,
}

impl ParticleTimeStep {
    /// The automatic Δt: `fraction` of the reference, never above the stable bound, s.
    pub fn automatic(&self, fraction: f64) -> f64 {
        (fraction * self.reference).min(self.stable)
    }
}

/// ω·Δt allowed for the stiffest flat contact of the overlap-area law, ω = sqrt(k/m⊥): two equal squares meeting
/// face on (γ = 0) change their energy by up to ±1.1 % at 0.2 (the force jumps in at the first step of a flat
/// contact, an error ∝ ω·Δt), ±2.3 % at 0.3 and up to +34 % at the §3.6 bound, where ω·Δt = 0.79 (docs/model.md,
/// "Automatic Δt").
pub const FLAT_CONTACT_OMEGA_DT: f64 = 0.2;

/// C·Δt/m⊥ allowed for the normal damping C = γ·sqrt(E·m⊥)·c/l of the overlap-area law: a body resting on a flat
/// face chatters at the Nyquist frequency from about 0.26 on (docs/validation.md, "Damping limit of flat
/// contacts"); at 0.2 a face-on collision at γ = 0.5 still rings for its few steps (force alternating by about 15 %
/// of its peak), at 0.1 it barely does. 0.2 keeps the automatic Δt of the bundled scenes (their smallest random
/// shapes sit at 0.15–0.2 of the §3.6 bound), docs/model.md, "Automatic Δt".
pub const DAMPING_RATE_DT: f64 = 0.2;

/// The largest stable Δt of one particle against every contact model in `models`, s; `None` when none bounds it:
/// the [`ParticleTimeStep::stable`] part of [`particle_time_steps`].
pub fn particle_time_step<'m>(
    models: impl IntoIterator<Item = &'m ContactModel>,
    particle: &ParticleInertia,
    max_impact_speed: f64,
) -> Option<f64> {
    particle_time_steps(models, particle, max_impact_speed).map(|bounds| bounds.stable)
}

/// The time-step bounds of one particle against every contact model in `models`; `None` when none bounds it.
///
/// The overlap-area law: the reference is (π/10)·sqrt(m/E) with the inscribed-circle mass m = π·r_in²·ρ (reference
/// §3.6; for round particles within a few percent of the mass itself, for elongated ones the bound the thesis asks
/// for); under the conservative formulation, whose stiffness is the thesis's times c/l ≤ 4R/r_in (chord c ≤ 2R,
/// l ≥ r_in/2), that bound times sqrt(r_in/(4R)) with R the reach. The stable bound is the smallest of the
/// reference, the flat-contact limit [`FLAT_CONTACT_OMEGA_DT`]/ω with ω = sqrt(2E·κ/m) (conservative: κ² for κ)
/// and the damping limit [`DAMPING_RATE_DT`]/(γ·κ·sqrt(2E/m)), κ the particle's
/// [`crate::shape::flat_contact_ratio`] and m its mass: two copies of the particle meeting face on (m⊥ = m/2,
/// stiffness E·c/l, damping γ·sqrt(E·m⊥)·c/l), its stiffest and most damped contact. A penetration law:
/// [`gc2d_contact::PenetrationLaw::max_time_step`] at `max_impact_speed` for the two partners that bound it, a flat
/// wall (m* = m, R* = R) and an equal particle (m* = m/2, R* = R/2), both parts the same.
pub fn particle_time_steps<'m>(
    models: impl IntoIterator<Item = &'m ContactModel>,
    particle: &ParticleInertia,
    max_impact_speed: f64,
) -> Option<ParticleTimeStep> {
    let p = particle;
    models
        .into_iter()
        .filter_map(|model| match model {
            ContactModel::OverlapArea(law) => {
                let e = law.elastic.e_modulus;
                let bound = max_stable_time_step_elongated(p.inscribed_radius, p.area_density, e);
                let kappa = p.flat_contact_ratio;
                let (reference, stiffness_ratio) = match law.elastic.formulation {
                    // Winkler: the thesis's normal stiffness; its rocking stiffness E·c³/(12 l) about the chord
                    // midpoint gives at most the normal frequency (docs/model.md, "Rocking of flat contacts").
                    AreaFormulation::Thesis | AreaFormulation::Winkler => (bound?, kappa),
                    AreaFormulation::Conservative => (bound? * conservative_time_step_factor(p), kappa * kappa),
                };
                let flat = FLAT_CONTACT_OMEGA_DT / (2.0 * e * stiffness_ratio / p.mass).sqrt();
                let damping = law
                    .damping
                    .map_or(f64::INFINITY, |d| DAMPING_RATE_DT / (d.gamma * kappa * (2.0 * e / p.mass).sqrt()));
                // A limit that is not a positive number (κ = 0, γ = 0, a massless particle) does not bind.
                let stable = [flat, damping].into_iter().filter(|dt| *dt > 0.0).fold(reference, f64::min);
                Some(ParticleTimeStep { stable, reference })
            }
            ContactModel::Penetration(law) => {
                let lever = p.contact_radius * p.contact_radius / p.inertia;
                let wall = PairProperties {
                    effective_radius: p.contact_radius,
                    effective_mass: p.mass,
                    tangential_mass: 1.0 / (1.0 / p.mass + lever),
                    rolling_inertia: p.inertia,
                };
                let twin = PairProperties {
                    effective_radius: 0.5 * p.contact_radius,
                    effective_mass: 0.5 * p.mass,
                    tangential_mass: 0.5 / (1.0 / p.mass + lever),
                    rolling_inertia: 0.5 * p.inertia,
                };
                let dt = [wall, twin]
                    .iter()
                    .filter_map(|pair| law.max_time_step(pair, max_impact_speed))
                    .reduce(f64::min)?;
                Some(ParticleTimeStep { stable: dt, reference: dt })
            }
        })
        .reduce(|a, b| ParticleTimeStep { stable: a.stable.min(b.stable), reference: a.reference.min(b.reference) })
}

/// sqrt(r_in/(4R)): the conservative area law's stiffness E·c²/l² is at most 4R/r_in times the thesis law's E·c/l
/// for a particle of inscribed radius r_in and reach R (1 when R is not a positive finite number).
fn conservative_time_step_factor(p: &ParticleInertia) -> f64 {
    let ratio = p.inscribed_radius / (4.0 * p.reach);
    if ratio > 0.0 && ratio.is_finite() { ratio.min(1.0).sqrt() } else { 1.0 }
}

/// The stable time step of the particles in `bodies`, each against the contact models its material can meet in
/// `interactions` ([`particle_time_step`]); `None` when there are no particles.
pub fn stable_time_step(
    bodies: &Bodies,
    interactions: &InteractionTable,
    max_impact_speed: f64,
) -> Option<TimeStepBound> {
    let models = interactions.models_per_material();
    bodies.particles().filter_map(|id| particle_bound(bodies, &models, id, max_impact_speed)).reduce(|x, y| {
        let refusal = x.refusal.min(y.refusal);
        let limiting = if y.dt.total_cmp(&x.dt).then(y.particle.cmp(&x.particle)).is_lt() { y } else { x };
        TimeStepBound { refusal, ..limiting }
    })
}

/// The time-step bound of particle `id` against the contact models its material meets (`models`, by material, as
/// [`InteractionTable::models_per_material`] gives them); `None` when it meets none.
fn particle_bound(
    bodies: &Bodies,
    models: &[Vec<&ContactModel>],
    id: BodyId,
    max_impact_speed: f64,
) -> Option<TimeStepBound> {
    let i = id.index();
    let scale = bodies.pose[i].scale;
    let inertia = ParticleInertia {
        inscribed_radius: bodies.inscribed_radius[i] * scale,
        area_density: bodies.mass[i] / bodies.area[i],
        mass: bodies.mass[i],
        inertia: 1.0 / bodies.inverse_inertia[i],
        contact_radius: bodies.contact_radius(i),
        reach: bodies.reach[i] * scale,
        flat_contact_ratio: match bodies.shape[i] {
            ShapeKind::Polygon => flat_contact_ratio(&bodies.body_vertices[bodies.vertices[i].range()], DVec2::ZERO),
            _ => 0.0,
        },
    };
    let models = models[bodies.material[i].index()].iter().copied();
    particle_time_steps(models, &inertia, max_impact_speed).map(|bounds| TimeStepBound {
        dt: bounds.stable,
        particle: id,
        refusal: bounds.reference,
    })
}

/// [`check_time_step`] for one particle just added to bodies that passed it: only the new particle can have lowered
/// the bound, so this costs one particle's bound instead of a pass over all (a source or an inlet inserting into a
/// World of a million particles checks in constant time).
pub fn check_added_particle_time_step(
    bodies: &Bodies,
    interactions: &InteractionTable,
    id: BodyId,
    dt: f64,
    limits: &SafetyLimits,
) -> Result<(), SafetyError> {
    let models = interactions.models_per_material();
    match particle_bound(bodies, &models, id, limits.max_impact_speed) {
        Some(bound) => refuse_above(bound, bodies, dt, limits),
        None => Ok(()),
    }
}

/// The error for `dt` above `bound`'s refusal bound, unless `limits` allow it.
fn refuse_above(bound: TimeStepBound, bodies: &Bodies, dt: f64, limits: &SafetyLimits) -> Result<(), SafetyError> {
    let TimeStepBound { dt: safe_dt, particle, refusal } = bound;
    if dt <= refusal || limits.allow_unsafe_time_step {
        return Ok(());
    }
    let i = particle.index();
    Err(SafetyError::UnsafeTimeStep {
        dt,
        safe_dt,
        particle: particle.0,
        inscribed_radius: bodies.inscribed_radius[i] * bodies.pose[i].scale,
    })
}

/// Refuses `dt` above the refusal bound (the §3.6 bound, [`TimeStepBound::refusal`]) unless `limits` allow it;
/// the error offers the stable bound.
pub fn check_time_step(
    bodies: &Bodies,
    interactions: &InteractionTable,
    dt: f64,
    limits: &SafetyLimits,
) -> Result<(), SafetyError> {
    match stable_time_step(bodies, interactions, limits.max_impact_speed) {
        Some(bound) => refuse_above(bound, bodies, dt, limits),
        None => Ok(()),
    }
}

/// Overlaps at most this fraction of the smaller particle's area count as touching at the start: bodies placed edge
/// to edge by a computed lattice may overlap by round-off.
pub const INITIAL_OVERLAP_TOLERANCE: f64 = 1e-12;

/// The deepest overlap between living bodies at their current poses, as (a, b, overlap over the smaller particle's
/// area), if it exceeds `tolerance` (see [`SafetyLimits::max_initial_overlap_fraction`]). Walls are not paired with
/// walls. Meant to run once before the first step: a sweep along x over the boxes sorted by their lower x bound, so it
/// allocates. A particle entirely outside the box of an inner-circle wall (a chamber, solid everywhere outside its
/// circle) lies wholly in its solid, an overlap of 100 %, though the two boxes do not meet.
pub fn deepest_initial_overlap(bodies: &Bodies, tolerance: f64) -> Option<(BodyId, BodyId, f64)> {
    let boxes: Vec<Aabb> = (0..bodies.len()).map(|i| bodies.aabb(i)).collect();
    let mut order: Vec<usize> = (0..bodies.len()).filter(|&i| bodies.alive[i]).collect();
    order.sort_by(|&i, &j| boxes[i].min.x.total_cmp(&boxes[j].min.x));
    let mut deepest: Option<(BodyId, BodyId, f64)> = None;
    for (k, &i) in order.iter().enumerate() {
        for &j in order[k + 1..].iter().take_while(|&&j| boxes[j].min.x <= boxes[i].max.x) {
            let both_walls = bodies.kind[i] == BodyKind::Wall && bodies.kind[j] == BodyKind::Wall;
            if both_walls || !boxes[i].overlaps(&boxes[j]) {
                continue;
            }
            let (a, b) = (BodyId(i.min(j) as u32), BodyId(i.max(j) as u32));
            let (particle, other) = if bodies.kind[a.index()] == BodyKind::Wall { (b, a) } else { (a, b) };
            let Some(geometry) = area_contact(bodies.shape_view(particle), bodies.shape_view(other)) else {
                continue;
            };
            let fraction = geometry.area / bodies.overlap_reference_area(i).min(bodies.overlap_reference_area(j));
            if fraction > tolerance && deepest.is_none_or(|d| fraction > d.2) {
                deepest = Some((a, b, fraction));
            }
        }
    }
    if tolerance >= 1.0 {
        return deepest;
    }
    let chambers = order.iter().filter(|&&i| bodies.shape[i] == ShapeKind::InnerCircle);
    for &chamber in chambers {
        let outside =
            order.iter().find(|&&i| bodies.kind[i] == BodyKind::Particle && !boxes[i].overlaps(&boxes[chamber]));
        if let Some(&particle) = outside
            && deepest.is_none_or(|d| 1.0 > d.2)
        {
            deepest = Some((BodyId(chamber.min(particle) as u32), BodyId(chamber.max(particle) as u32), 1.0));
        }
    }
    deepest
}

/// The largest distance a point of particle `i` travels in a step of `dt` at its current velocities,
/// (|v| + |ω|·R)·Δt with R the distance of its farthest point from the centroid (at the current scale).
pub fn step_travel(bodies: &Bodies, i: usize, dt: f64) -> f64 {
    travel_in_step(bodies.velocity[i], bodies.angular_velocity[i], bodies.reach[i] * bodies.pose[i].scale, dt)
}

/// (|v| + |ω|·R)·Δt: the largest distance a point at most `reach` R (m) from the centroid of a body moving at
/// `velocity` v and `angular_velocity` ω travels in a step of `dt`; the run's travel check, and the scene's check of
/// particles that start too fast for it.
#[inline]
pub fn travel_in_step(velocity: DVec2, angular_velocity: f64, reach: f64, dt: f64) -> f64 {
    (velocity.length() + angular_velocity.abs() * reach) * dt
}

/// The time step to suggest after a blow-up: a quarter of the current one, and never above the stable bound.
pub fn suggested_time_step(dt: f64, stable_dt: Option<f64>) -> f64 {
    let quarter = dt / 4.0;
    stable_dt.map_or(quarter, |safe| quarter.min(safe / 2.0))
}

#[cfg(test)]
mod message_tests {
    use super::*;

    /// An energy blow-up says the time only in the run's report, gives the energy in the scene's unit and names the
    /// particle with the most kinetic energy, which the run's report then names as the scene does (QA docs 17).
    #[test]
    fn an_energy_blow_up_names_its_most_energetic_particle_in_the_scenes_unit_without_the_time() {
        let error = SafetyError::EnergyJump {
            time: 0.0486,
            step: 486,
            gain: 0.8273,
            energy_unit: "J/m",
            most_energetic: Some((12, 0.25)),
            percent: 4400.0,
            suggested_dt: 4.414e-6,
        };
        assert_eq!(
            error.to_string(),
            "the simulation blew up: the energy rose by 8.273e-1 J/m more than the work done on the system explains \
             (4400 % of the run's energy scale); the energy balance does not say which bodies gained it, but the \
             particle with the most kinetic energy at the stop is body 12 (2.500e-1 J/m); reduce the time step (try \
             4.414e-6 s)"
        );
        assert_eq!(error.bodies(), [12]);
    }
}
