//! What a built scene contains, for `gc2d-rs check` and for people reading a scene.

use crate::checks::number;
use gc2d_contact::{ImpactLaw, NormalSpring, PenetrationDamping, TangentialStiffness};
use gc2d_engine::{ContactModel, InteractionTable, MassModel, MaterialId};
use std::fmt;

/// One line per pair of materials (a ≤ b): `a–b: ` and the law with its parameters.
pub(crate) fn interaction_lines(names: &[String], table: &InteractionTable) -> Vec<String> {
    let mut lines = Vec::new();
    for a in 0..names.len() {
        for b in a..names.len() {
            let model = table.model(MaterialId(a as u16), MaterialId(b as u16));
            lines.push(format!("{}–{}: {}", names[a], names[b], describe(model)));
        }
    }
    lines
}

/// Where the power law e(v) = a/(v + b)^c exceeds 1 and the engine clips it to 1 (`ImpactLaw::restitution`), in
/// words after the formula; empty where it stays ≤ 1 at every speed. e(v) = 1 at v* = a^(1/c) − b; a fit such as
/// Reichardt's steel law reaches 1 only at v = 0.
fn clipping(a: f64, b: f64, c: f64) -> String {
    if c == 0.0 {
        return if a > 1.0 { " (above 1 at every speed: clipped to 1)".to_owned() } else { String::new() };
    }
    let crossing = a.powf(1.0 / c) - b;
    if c > 0.0 && crossing == f64::INFINITY {
        " (above 1 at every speed: clipped to 1)".to_owned()
    } else if c > 0.0 && crossing > 0.0 {
        format!(" (above 1 below {} m/s: clipped to 1 there)", significant(crossing))
    } else if c < 0.0 && a > 0.0 && crossing.is_finite() {
        format!(" (above 1 above {} m/s: clipped to 1 there)", significant(crossing.max(0.0)))
    } else {
        String::new()
    }
}

/// A contact model in words, with its parameters.
fn describe(model: &ContactModel) -> String {
    match model {
        ContactModel::OverlapArea(law) => {
            let mut text = format!("overlap area, E = {:e} N/m", law.elastic.e_modulus);
            match law.elastic.formulation {
                gc2d_contact::AreaFormulation::Thesis => {}
                gc2d_contact::AreaFormulation::Conservative => text += ", conservative",
                gc2d_contact::AreaFormulation::Winkler => text += ", Winkler",
            }
            if let Some(damping) = law.damping {
                text += &format!(", γ = {}", number(damping.gamma));
            }
            if let Some(friction) = law.friction {
                text += &format!(", μ = {}", number(friction.mu));
            }
            if let Some(cohesion) = law.cohesion {
                text += &format!(", k_coh = {:e} N/m", cohesion.k_coh);
            }
            text
        }
        ContactModel::Penetration(law) => {
            let mut text = match law.normal {
                NormalSpring::Linear { stiffness_n_m } => format!("linear spring, k = {stiffness_n_m:e} N/m"),
                NormalSpring::Hertz { effective_modulus_pa } => {
                    format!("Hertz, E* = {} Pa", six_digits(effective_modulus_pa))
                }
            };
            text += &match law.damping {
                None => ", undamped".to_owned(),
                Some(PenetrationDamping::DampingRatio(ratio)) => format!(", damping ratio D = {}", number(ratio)),
                Some(PenetrationDamping::Restitution(e)) => format!(", restitution e = {}", number(e)),
                Some(PenetrationDamping::VelocityDependent(ImpactLaw::SteelReichardt)) => {
                    ", restitution e(v) of steel (Reichardt)".to_owned()
                }
                Some(PenetrationDamping::VelocityDependent(ImpactLaw::PowerLaw { a, b, c })) => {
                    format!(", restitution e(v) = {}/(v + {})^{}{}", number(a), number(b), number(c), clipping(a, b, c))
                }
                Some(PenetrationDamping::VelocityDependent(ImpactLaw::Table(table))) => {
                    format!(", restitution e(v) from {} points", table.points().len())
                }
            };
            if let Some(friction) = law.tangential {
                text += &match friction.stiffness {
                    TangentialStiffness::CundallStrack { stiffness_ratio } => {
                        format!(", μ = {}, k_t/k_n = {stiffness_ratio:.4}", number(friction.mu))
                    }
                    TangentialStiffness::Mindlin { .. } => format!(", μ = {}, Mindlin", number(friction.mu)),
                };
            }
            if let Some(rolling) = law.rolling {
                text += &format!(", rolling μ_r = {}", number(rolling.mu_r));
            }
            if law.tensile_clamp {
                text += ", no pull (clamped)";
            }
            text
        }
    }
}

/// Counts and time-step facts of a built scene.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneSummary {
    /// The scene's name.
    pub name: String,
    /// Material names, in order (the first is the material of bodies that name none).
    pub materials: Vec<String>,
    /// The contact law of every pair of materials, one line each (`a–b: law`).
    pub interactions: Vec<String>,
    /// Wall bodies after the wall macros are expanded.
    pub wall_bodies: usize,
    /// Walls that vibrate, rotate or act as pistons.
    pub moving_walls: usize,
    /// How masses follow from shape and density.
    pub mass_model: MassModel,
    /// Particles at the start (explicit and from blocks).
    pub particles: usize,
    /// Their total mass: kg per metre of thickness, or kg with sphere-equivalent masses.
    pub particle_mass_kg_m: f64,
    /// Particles with a drag spring.
    pub drag_springs: usize,
    /// Particle sources.
    pub sources: usize,
    /// Inlets.
    pub inlets: usize,
    /// Insertions the sources and inlets attempt before the end time (a source skips an insertion when no free spot
    /// is found; an inlet postpones it).
    pub planned_insertions: u64,
    /// The scene's fluid: its description, and each particle kind's terminal speed and drag time; `None` without.
    pub fluid: Option<crate::build::fluid::FluidSummary>,
    /// The Δt the World runs with, s.
    pub time_step_s: f64,
    /// True when Δt was chosen automatically (the scene left `time_step_s` out).
    pub time_step_is_automatic: bool,
    /// The stable bound of the particles present or to be inserted, each against its stiffest contact law, s.
    pub stable_time_step_s: Option<f64>,
    /// The Δt above which the scene is refused (the §3.6 bound; between the stable bound and it a run goes on, and
    /// flat contacts may chatter), s.
    pub refusal_time_step_s: Option<f64>,
    /// The scene entry that sets the bound.
    pub limiting_entry: Option<String>,
    /// The impact speed a Hertz contact's bound is taken at, m/s (`Scene::max_impact_speed`).
    pub max_impact_speed_m_s: f64,
    /// End time, s.
    pub end_time_s: f64,
    /// `World::heap_bytes` of the World as built, before its first step: the body columns and the broadphase's
    /// per-body records of every body present at the start, bytes.
    pub heap_bytes_at_start: usize,
}

/// Box pairs per particle in a dense packing (a settled pile of 7-gons: 2.3, docs/performance.md, "Pile
/// throughput"); each holds a contact record whether or not the pair touches.
pub const BOX_PAIRS_PER_PARTICLE: f64 = 2.3;

/// Bytes per body that the World allocates only at its first step: the broadphase's four sorted endpoints (16 B
/// each) and its sweep scratch (8 B) (docs/performance.md, "Memory per particle").
pub const FIRST_STEP_BYTES_PER_BODY: usize = 4 * 16 + 8;

/// Heap bytes of one 7-gon particle's body columns and broadphase records with exact capacities (554 + 139 B,
/// docs/performance.md, "Memory per particle"), for particles that only sources insert.
pub const BODY_BYTES_OF_A_7_GON: usize = 554 + 139;

/// Bytes of one box pair: the pair list's entry (the engine's `PairEntry<PairContact>`: two body ids and the
/// contact record) and its slots in the open-addressing index (8 to 16 B; 16 taken).
pub fn bytes_per_box_pair() -> usize {
    std::mem::size_of::<gc2d_engine::broadphase::PairEntry<gc2d_engine::PairContact>>() + 16
}

/// Particle-steps per second of one core that run-time estimates use: 2 million, the dense 10,000-grain pile of
/// 7-gons on one thread, on the safe side of what it measures (docs/performance.md, "Quiet pairs" and "Sixteen cores
/// with the one-unit build": 3.2 M on the development machine, 1.3-2.3 M on a 16-core Xeon server; 1.3 M until
/// 2026-11, before the two-crossing walk and the release build optimised as one unit). Looser or smaller scenes run
/// faster, 100,000 grains slower.
pub const PARTICLE_STEPS_PER_SECOND: f64 = 2e6;

impl SceneSummary {
    /// The most particles the scene can hold: those at the start and every insertion its sources plan.
    pub fn most_particles(&self) -> u64 {
        self.particles as u64 + self.planned_insertions
    }

    /// A rough estimate of the World's heap memory at its fullest, bytes: the memory of the bodies as built
    /// ([`Self::heap_bytes_at_start`]), what the first step adds per body, the bodies sources insert (at the built
    /// ones' average, or a 7-gon's when none is built), and [`BOX_PAIRS_PER_PARTICLE`] box pairs per particle of
    /// [`bytes_per_box_pair`] each (a dense packing; a loose scene holds fewer).
    pub fn memory_estimate_bytes(&self) -> f64 {
        let bodies = self.particles + self.wall_bodies;
        let per_body = if self.particles > 0 {
            self.heap_bytes_at_start as f64 / bodies as f64
        } else {
            BODY_BYTES_OF_A_7_GON as f64
        };
        let most = self.most_particles() as f64;
        self.heap_bytes_at_start as f64
            + (bodies as f64 + self.planned_insertions as f64) * FIRST_STEP_BYTES_PER_BODY as f64
            + self.planned_insertions as f64 * per_body
            + most * BOX_PAIRS_PER_PARTICLE * bytes_per_box_pair() as f64
    }

    /// The particle-steps of the run: the steps times the mean particle count (sources filling the scene evenly
    /// from the start's count to [`Self::most_particles`]).
    pub fn particle_steps(&self) -> f64 {
        self.steps() as f64 * 0.5 * (self.particles as f64 + self.most_particles() as f64)
    }

    /// A rough estimate of the run time on one core, s: [`Self::particle_steps`] at [`PARTICLE_STEPS_PER_SECOND`].
    pub fn run_time_estimate_s(&self) -> f64 {
        self.particle_steps() / PARTICLE_STEPS_PER_SECOND
    }
}

/// `value` (≥ 0) with four significant digits, in fixed notation from 0.001 to 9999.5, else in scientific notation:
/// a speed or mass of any size stays readable (a 1.5 mm pellet's 1.3e-5 kg read "0.0000 kg" with four decimals).
fn significant(value: f64) -> String {
    if value == 0.0 || !value.is_finite() {
        return format!("{value}");
    }
    if !(1e-3..9999.5).contains(&value) {
        return format!("{value:.3e}");
    }
    let decimals = (3 - value.log10().floor() as i32).max(0) as usize;
    format!("{value:.decimals$}")
}

/// `value` with three significant digits (for values from 1 to 999.5).
fn three_digits(value: f64) -> String {
    let decimals = if value < 9.995 {
        2
    } else if value < 99.95 {
        1
    } else {
        0
    };
    format!("{value:.decimals$}")
}

/// Bytes in a unit a person reads (kB, MB, GB: powers of 1000), three significant digits.
fn human_bytes(bytes: f64) -> String {
    let (value, unit) = match bytes {
        b if b >= 1e9 => (b / 1e9, "GB"),
        b if b >= 1e6 => (b / 1e6, "MB"),
        b if b >= 1e3 => (b / 1e3, "kB"),
        b => (b, "B"),
    };
    format!("{} {unit}", three_digits(value))
}

/// A duration in the largest unit that keeps it above 1 (s, min, h, days), three significant digits.
fn human_duration(seconds: f64) -> String {
    let (value, unit) = match seconds {
        s if s >= 86_400.0 => (s / 86_400.0, "days"),
        s if s >= 3_600.0 => (s / 3_600.0, "h"),
        s if s >= 60.0 => (s / 60.0, "min"),
        s => (s, "s"),
    };
    format!("{} {unit}", three_digits(value))
}

impl SceneSummary {
    /// Steps to reach the end time.
    pub fn steps(&self) -> u64 {
        let steps = (self.end_time_s / self.time_step_s).round();
        if steps.is_finite() && steps >= 0.0 { steps as u64 } else { 0 }
    }
}

impl fmt::Display for SceneSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "scene `{}`", self.name)?;
        writeln!(f, "  materials: {}", self.materials.join(", "))?;
        for line in &self.interactions {
            writeln!(f, "    {line}")?;
        }
        writeln!(f, "  walls: {} ({} moving)", counted(self.wall_bodies as u64, "body", "bodies"), self.moving_walls)?;
        let (unit, model) = match self.mass_model {
            MassModel::PerUnitThickness => ("kg/m", "per unit thickness"),
            MassModel::SphereEquivalent => ("kg", "sphere-equivalent"),
        };
        writeln!(
            f,
            "  particles: {} at the start ({} {unit}, masses {model}), {} with a drag spring",
            self.particles,
            significant(self.particle_mass_kg_m),
            self.drag_springs
        )?;
        writeln!(
            f,
            "  sources: {}, inlets: {} (up to {})",
            self.sources,
            self.inlets,
            counted(self.planned_insertions, "insertion", "insertions")
        )?;
        if let Some(fluid) = &self.fluid {
            writeln!(f, "  fluid: {}", fluid.description)?;
            for scale in &fluid.scales {
                let speed = scale.terminal_speed_m_s;
                let motion = match speed {
                    f64::INFINITY => "falls freely (no drag: the fluid's density or drag coefficient is 0)".to_owned(),
                    f64::NEG_INFINITY => "rises freely (no drag: the drag coefficient is 0)".to_owned(),
                    s if s > 0.0 => format!("sinks at {} m/s", significant(s)),
                    s if s < 0.0 => format!("rises at {} m/s", significant(-s)),
                    _ => "floats".to_owned(),
                };
                writeln!(
                    f,
                    "    {}: {motion} in still fluid (terminal speed), drag relaxation time {:.3e} s",
                    scale.entry, scale.relaxation_time_s
                )?;
            }
            for scale in fluid.too_fast_for(self.time_step_s) {
                writeln!(
                    f,
                    "    warning: the drag on `{}` relaxes within {:.1} time steps (fewer than {}): its velocity \
                     will be inaccurate; use a smaller run.time_step_s",
                    scale.entry,
                    scale.relaxation_time_s / self.time_step_s,
                    crate::build::fluid::DRAG_STEPS_PER_RELAXATION_TIME
                )?;
            }
        }
        let how = if self.time_step_is_automatic { "automatic" } else { "given" };
        write!(f, "  time step: {:.3e} s ({how})", self.time_step_s)?;
        match (&self.stable_time_step_s, &self.limiting_entry) {
            (Some(bound), Some(entry)) => writeln!(f, ", stable bound {bound:.3e} s set by `{entry}`")?,
            _ => writeln!(f, ", no particles to bound it")?,
        }
        writeln!(
            f,
            "  impacts expected up to {:.3} m/s (where a Hertz contact's bound is taken)",
            self.max_impact_speed_m_s
        )?;
        writeln!(f, "  end time: {} s ({} steps)", number(self.end_time_s), self.steps())?;
        writeln!(
            f,
            "  memory (rough estimate): {} for up to {} ({} B per box pair, {BOX_PAIRS_PER_PARTICLE} pairs \
             per particle as in a dense packing)",
            human_bytes(self.memory_estimate_bytes()),
            counted(self.most_particles(), "particle", "particles"),
            bytes_per_box_pair()
        )?;
        write!(
            f,
            "  run time (rough estimate for one core): {} ({} particle-steps at {} M/s, docs/performance.md)",
            human_duration(self.run_time_estimate_s()),
            // A rough estimate in whole particle-steps (half the sum of the start and most particles can be n.5).
            six_digits(self.particle_steps().round()),
            PARTICLE_STEPS_PER_SECOND / 1e6
        )
    }
}

/// `count` with its noun, singular for one: "1 body", "3 bodies".
fn counted(count: u64, one: &str, many: &str) -> String {
    format!("{count} {}", if count == 1 { one } else { many })
}

/// A derived number (E* from E and ν, an estimate of particle-steps) to six significant digits: 1.07802e11, not the
/// 1.0780219780219778e11 of its last bit.
fn six_digits(x: f64) -> String {
    crate::checks::significant_digits(x, 6)
}

#[cfg(test)]
mod tests {
    use super::{clipping, six_digits};
    use gc2d_contact::ImpactLaw;

    /// Steel's E* = E/(2(1 − ν²)) was printed with all 17 digits of its last bit.
    #[test]
    fn derived_moduli_are_printed_to_six_digits() {
        assert_eq!(six_digits(1.0780219780219778e11), "1.07802e11");
        assert_eq!(six_digits(1e5), "100000");
        assert_eq!(six_digits(2.5e-3), "0.0025");
    }

    /// The summary says where a fitted e(v) exceeds 1, at the speed where the engine's clipped law reaches 1.
    #[test]
    fn a_power_law_above_one_is_reported_where_it_is_clipped() {
        let (a, b, c) = ImpactLaw::STEEL_REICHARDT;
        assert_eq!(clipping(a, b, c), "", "Reichardt's steel law reaches 1 only at v = 0");
        assert_eq!(clipping(0.7, 0.5, 0.3), "");
        assert_eq!(clipping(0.0, 0.5, -0.3), "");
        let text = clipping(1.2, 0.5, 0.3);
        assert_eq!(text, " (above 1 below 1.336 m/s: clipped to 1 there)");
        let law = ImpactLaw::PowerLaw { a: 1.2, b: 0.5, c: 0.3 };
        assert_eq!(law.restitution(1.336), 1.0);
        assert!(law.restitution(1.337) < 1.0);
        assert_eq!(clipping(0.5, 0.5, -0.5), " (above 1 above 3.500 m/s: clipped to 1 there)");
        assert_eq!(clipping(2.0, 0.5, -0.5), " (above 1 above 0 m/s: clipped to 1 there)");
        assert_eq!(clipping(1.5, 0.5, 0.0), " (above 1 at every speed: clipped to 1)");
        assert_eq!(clipping(1e300, 1.0, 1e-300), " (above 1 at every speed: clipped to 1)");
    }
}
