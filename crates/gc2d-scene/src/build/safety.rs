//! Load-time safety: the stable time step of the scene's particles (including those its sources will insert) and
//! the overlap of the initial bodies (reference §3.6, §10.4).

use crate::checks::{number, significant_digits};
use crate::error::MAX_REPORTED_ERRORS;
use crate::error::{ErrorKind, SceneError};
use crate::schema::GridType;
use crate::spans::field_path;
use gc2d_engine::safety::{ParticleInertia, particle_time_steps, travel_in_step};
use gc2d_engine::{BodyShape, ContactModel, MassModel, ParticleRecipe, ShapeKind, shape_view};
use gc2d_geometry::{Aabb, DVec2, MassProperties, Pose, area_contact};
use rand_chacha::ChaCha8Rng;

/// Shapes drawn per source to estimate the smallest particle it will insert.
pub const SOURCE_SAMPLES: usize = 256;

/// Fraction of the stable bound used when the scene leaves Δt out. 0.15, not 0.25: at a quarter of the bound the
/// contact damping of dense packings (γ = 0.5 silo, γ = 0.75 pile) makes wall and floor forces alternate from step
/// to step (period-2 chatter), at 0.15 they do not (docs/model.md, "Automatic Δt").
pub const AUTOMATIC_TIME_STEP_FRACTION: f64 = 0.15;

/// Shortest time step a scene may give or get, s: a femtosecond, the step of molecular dynamics (the engine itself
/// needs Δt⁵/120 to be a normal f64, about 1.5e-61 s).
pub(crate) const MIN_TIME_STEP_S: f64 = 1e-15;

/// Δt when the scene leaves it out and has no particles to bound it (gc2d's default `DELTA_T`), s.
pub const FALLBACK_TIME_STEP: f64 = 1e-4;

/// The particle that limits the time step.
#[derive(Debug, Clone, PartialEq)]
pub struct TimeStepBound {
    /// The largest stable Δt, s (the engine's [`gc2d_engine::safety::ParticleTimeStep::stable`]).
    pub time_step: f64,
    /// The Δt chosen when the scene leaves it out: [`AUTOMATIC_TIME_STEP_FRACTION`] of the reference bound, never
    /// above the stable one ([`gc2d_engine::safety::ParticleTimeStep::automatic`]), s; the smallest over the
    /// particles, which need not be the one that sets `time_step`.
    pub automatic_time_step: f64,
    /// The Δt above which the scene is refused, s: the smallest reference bound (for the overlap-area law the §3.6
    /// bound, [`gc2d_engine::safety::ParticleTimeStep::reference`]).
    pub refusal_time_step: f64,
    /// The inscribed radius r of the limiting particle, m.
    pub inscribed_radius: f64,
    /// Field path of the scene entry it comes from.
    pub path: String,
}

impl TimeStepBound {
    /// The bound for one particle of shape `shape` and density `density` under `mass_model` against the contact
    /// `models` its material meets (the engine's [`particle_time_step`]), `None` for unusable values.
    pub fn of(
        shape: &BodyShape,
        density: f64,
        mass_model: MassModel,
        models: &[&ContactModel],
        max_impact_speed: f64,
        path: &str,
    ) -> Option<Self> {
        let mass = mass_model.mass_properties(shape, density);
        let inertia = ParticleInertia {
            inscribed_radius: shape.inscribed_radius(),
            area_density: area_density(mass_model, shape, density),
            mass: mass.mass,
            inertia: mass.inertia,
            contact_radius: shape.equivalent_radius(),
            reach: shape.reach(),
            flat_contact_ratio: shape.flat_contact_ratio(),
        };
        particle_time_steps(models.iter().copied(), &inertia, max_impact_speed).map(|bounds| Self {
            time_step: bounds.stable,
            automatic_time_step: bounds.automatic(AUTOMATIC_TIME_STEP_FRACTION),
            refusal_time_step: bounds.reference,
            inscribed_radius: inertia.inscribed_radius,
            path: path.to_owned(),
        })
    }

    /// The bound of a drag spring of `stiffness` K (N/m) pulling at the point `arm` (m, from the centroid) of a
    /// particle of mass m and moment of inertia I: the spring and the effective mass 1/(1/m + |arm|²/I) at the point
    /// it pulls form an oscillator, bounded as a penetration law's contact spring is, Δt ≤ (π/10)·sqrt(m_eff/K).
    /// `None` for a spring without stiffness.
    pub fn of_drag_spring(
        mass: MassProperties,
        arm: DVec2,
        stiffness: f64,
        inscribed_radius: f64,
        path: &str,
    ) -> Option<Self> {
        let effective_mass = 1.0 / (1.0 / mass.mass + arm.length_squared() / mass.inertia);
        let time_step = std::f64::consts::PI / 10.0 * (effective_mass / stiffness).sqrt();
        (time_step > 0.0 && time_step.is_finite()).then(|| Self {
            time_step,
            automatic_time_step: AUTOMATIC_TIME_STEP_FRACTION * time_step,
            refusal_time_step: time_step,
            inscribed_radius,
            path: path.to_owned(),
        })
    }

    /// The smaller of two bounds (the first on ties).
    pub fn min(a: Option<Self>, b: Option<Self>) -> Option<Self> {
        match (a, b) {
            (Some(a), Some(b)) => Some(Self::smaller(a, b)),
            (a, b) => a.or(b),
        }
    }

    /// The bound (and its particle) with the smaller `time_step`, the first on ties, with the smaller of the two
    /// automatic and refusal time steps.
    pub fn smaller(a: Self, b: Self) -> Self {
        let automatic_time_step = a.automatic_time_step.min(b.automatic_time_step);
        let refusal_time_step = a.refusal_time_step.min(b.refusal_time_step);
        let limiting = if b.time_step < a.time_step { b } else { a };
        Self { automatic_time_step, refusal_time_step, ..limiting }
    }

    /// The bound of the smallest of [`SOURCE_SAMPLES`] shapes drawn from a source's recipe.
    pub fn of_source(
        recipe: &ParticleRecipe,
        density: f64,
        mass_model: MassModel,
        models: &[&ContactModel],
        max_impact_speed: f64,
        path: &str,
        rng: &mut ChaCha8Rng,
    ) -> Option<Self> {
        (0..SOURCE_SAMPLES)
            .filter_map(|_| recipe.draw(rng).ok())
            .filter_map(|(shape, _)| Self::of(&shape, density, mass_model, models, max_impact_speed, path))
            .reduce(Self::smaller)
    }
}

/// A particle's mass per area of its shape, kg/m²: the density itself per unit thickness, m/A for sphere-equivalent
/// masses (what the engine's time-step bound reads from a particle).
fn area_density(mass_model: MassModel, shape: &BodyShape, density: f64) -> f64 {
    match mass_model {
        MassModel::PerUnitThickness => density,
        MassModel::SphereEquivalent => mass_model.mass_properties(shape, density).mass / shape.area(),
    }
}

/// The time step to run with: the scene's, refused above the refusal bound and otherwise kept (between the stable
/// and the refusal bound flat contacts may chatter), or an automatic one.
pub fn choose_time_step(
    requested: Option<f64>,
    bound: Option<&TimeStepBound>,
    allow_unsafe: bool,
) -> Result<f64, SceneError> {
    let Some(dt) = requested else {
        let Some(bound) = bound else { return Ok(FALLBACK_TIME_STEP) };
        let dt = round_down_to_two_digits(bound.automatic_time_step);
        if dt < MIN_TIME_STEP_S {
            return Err(SceneError::new(
                ErrorKind::TimeStep,
                bound.path.as_str(),
                format!(
                    "its particles (inscribed radius {:.3e} m) need a time step of {dt:.3e} s, below the shortest a \
                     scene may have ({MIN_TIME_STEP_S:e} s)",
                    bound.inscribed_radius
                ),
            )
            .with_help("check the units of its size (metres) and of the materials' Young's moduli and densities"));
        }
        return Ok(dt);
    };
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(SceneError::value("run.time_step_s", format!("{dt}: must be a positive finite number of seconds")));
    }
    match bound {
        Some(bound) if dt > bound.refusal_time_step && !allow_unsafe => Err(SceneError::new(
            ErrorKind::TimeStep,
            "run.time_step_s",
            format!(
                "time step {dt:.3e} s is above {:.3e} s, where the integrator fails; the stable bound is {:.3e} s, \
                 set by the particle that limits it (inscribed radius {:.3e} m, from `{}`) against the stiffest \
                 contact law its material meets",
                bound.refusal_time_step, bound.time_step, bound.inscribed_radius, bound.path
            ),
        )
        .with_help(format!(
            "use a time step of at most {:.3e} s, leave `time_step_s` out to get one chosen, or set \
             `allow_unsafe_time_step: true`",
            bound.time_step
        ))
        .with_label("too large")),
        _ => Ok(dt),
    }
}

/// A `run.checkpoint_interval_s` of `interval` shorter than the time step `time_step` (`automatic`: chosen by the
/// build): it would write a checkpoint at every step, and a unit slip such as 1e-9 fills the disk. `None` for no
/// interval or one of at least a step.
pub(crate) fn checkpoints_below_the_step(interval: Option<f64>, time_step: f64, automatic: bool) -> Option<SceneError> {
    let interval = interval.filter(|&interval| interval < time_step)?;
    let chosen = if automatic { " (chosen from the particles, as `time_step_s` is left out)" } else { "" };
    Some(
        SceneError::value(
            "run.checkpoint_interval_s",
            format!(
                "{} s is shorter than the time step, {} s{chosen}: a checkpoint would be written at every step",
                number(interval),
                number(time_step)
            ),
        )
        .with_label("shorter than a step")
        .with_help(format!(
            "give at least the time step, {} s (the unit is seconds of simulated time), or leave the field out for no \
             periodic checkpoints",
            number(time_step)
        )),
    )
}

/// x rounded down to two significant digits (x > 0).
fn round_down_to_two_digits(x: f64) -> f64 {
    let unit = 10f64.powf(x.log10().floor() - 1.0);
    let rounded = (x / unit).floor() * unit;
    if rounded > 0.0 && rounded <= x { rounded } else { x }
}

/// The first error `check` finds for each scene entry among `particles` (a block's many particles give one).
fn first_per_entry(
    particles: &[super::PlannedParticle],
    check: impl Fn(&super::PlannedParticle) -> Option<SceneError>,
) -> Vec<SceneError> {
    let mut reported: Vec<&str> = Vec::new();
    let mut errors = Vec::new();
    for p in particles {
        if reported.contains(&p.path.as_str()) {
            continue;
        }
        if let Some(error) = check(p) {
            reported.push(&p.path);
            errors.push(error);
        }
    }
    errors
}

/// Particles whose size and density give no usable mass or moment of inertia (zero, infinite or not a number: a
/// radius of 1e-300 m or 1e300 m), one error per scene entry. Such a particle blew up at the first step with advice to
/// reduce the time step, which cannot help, and `check` reported its scene as having "no particles to bound" Δt.
pub(crate) fn unusable_masses(particles: &[super::PlannedParticle], mass_model: MassModel) -> Vec<SceneError> {
    first_per_entry(particles, |p| {
        let mass = mass_model.mass_properties(&p.shape, p.density);
        let usable = |x: f64| x.is_finite() && x > 0.0;
        (!(usable(mass.mass) && usable(mass.inertia))).then(|| {
            SceneError::value(
                &p.path,
                format!(
                    "its size ({:.3e} m across) and density give a mass of {:e} and a moment of inertia of {:e}, \
                     not positive finite numbers: the engine cannot move it",
                    2.0 * p.shape.reach(),
                    mass.mass,
                    mass.inertia
                ),
            )
            .with_help("check the units of the size (metres) and of the material's density")
        })
    })
}

/// Particles that start so fast that their first step of `time_step` would move a point of them further than
/// `max_travel_fraction` of their inscribed radius, the run's travel limit (`SafetyLimits::max_travel_fraction`): the
/// run would stop at step 1, so `check` refuses them, one error per scene entry.
pub(crate) fn too_fast_at_start(
    particles: &[super::PlannedParticle],
    time_step: f64,
    max_travel_fraction: f64,
) -> Vec<SceneError> {
    first_per_entry(particles, |p| {
        let travel = travel_in_step(p.velocity, p.angular_velocity, p.shape.reach(), time_step);
        let limit = max_travel_fraction * p.shape.inscribed_radius();
        (travel > limit).then(|| {
            SceneError::value(
                &p.path,
                format!(
                    "it starts at {} m/s{} and would move {:.3e} m in its first step of {:.3e} s, more than its \
                     inscribed radius of {:.3e} m: it could pass through a wall or a particle unseen, and the run would \
                     stop at that step",
                    crate::checks::number(p.velocity.length()),
                    spin_words(p.angular_velocity, Some(p.shape.reach())),
                    travel,
                    time_step,
                    p.shape.inscribed_radius()
                ),
            )
            .with_help(format!("start it slower, or use a time step below {:.3e} s", time_step * limit / travel))
        })
    })
}

/// " spinning at ω rad/s" (with the surface speed ω·`reach` where the reach is known) for a spinning body, else
/// nothing: a spin alone moves the body's outermost points, and a message that named only the speed blamed a
/// particle at rest for the travel of its spin.
fn spin_words(angular_velocity: f64, reach: Option<f64>) -> String {
    match (angular_velocity, reach) {
        (0.0, _) => String::new(),
        (omega, Some(reach)) => format!(
            " spinning at {} rad/s (`angular_velocity_rad_s`; its outermost point at {:.3e} m/s)",
            crate::checks::number(omega),
            omega.abs() * reach
        ),
        (omega, None) => format!(" spinning at {} rad/s", crate::checks::number(omega)),
    }
}

/// Inlets whose particles enter so fast that their first step of `time_step` would move a point of them further than
/// `max_travel_fraction` of their inscribed radius (the run's travel limit, as [`too_fast_at_start`] for the particles
/// present at the start): the run would stop at the step of the first insertion. Judged on [`SOURCE_SAMPLES`] shapes
/// drawn from each inlet's recipe (the worst of them), one error per inlet at its `velocity_m_s`.
pub(crate) fn inlets_too_fast(
    inlets: &[gc2d_engine::Inlet],
    time_step: f64,
    max_travel_fraction: f64,
    rng: &mut ChaCha8Rng,
) -> Vec<SceneError> {
    let mut errors = Vec::new();
    for (i, inlet) in inlets.iter().enumerate() {
        let worst = (0..SOURCE_SAMPLES)
            .filter_map(|_| inlet.recipe.draw(rng).ok())
            .map(|(shape, _)| {
                let travel = travel_in_step(inlet.velocity, inlet.angular_velocity, shape.reach(), time_step);
                (travel, max_travel_fraction * shape.inscribed_radius())
            })
            .max_by(|a, b| (a.0 / a.1).total_cmp(&(b.0 / b.1)));
        if let Some((travel, limit)) = worst
            && travel > limit
        {
            errors.push(
                SceneError::value(
                    format!("inlets[{i}].velocity_m_s"),
                    format!(
                        "its particles enter at {} m/s{} and would move {travel:.3e} m in their first step of \
                         {time_step:.3e} s, more than the inscribed radius of the smallest ({limit:.3e} m): they could \
                         pass through a wall or a particle unseen, and the run would stop at the first insertion",
                        crate::checks::number(inlet.velocity.length()),
                        spin_words(inlet.angular_velocity, None),
                    ),
                )
                .with_label("too fast")
                .with_help(format!("feed them slower, or use a time step below {:.3e} s", time_step * limit / travel)),
            );
        }
    }
    errors
}

/// Particles whose centroid starts outside the run's `domain` (the engine removes them at the first step, before they
/// move), one error per scene entry.
pub(crate) fn outside_domain(particles: &[super::PlannedParticle], domain: Aabb) -> Vec<SceneError> {
    first_per_entry(particles, |p| {
        let at = p.pose.position;
        (!domain.contains(at)).then(|| {
            SceneError::value(
                &p.path,
                format!(
                    "it starts at ({}, {}) m, outside `run.domain` (x {} to {} m, y {} to {} m): the run would remove it \
                     at the first step",
                    crate::checks::number(at.x),
                    crate::checks::number(at.y),
                    crate::checks::number(domain.min.x),
                    crate::checks::number(domain.max.x),
                    crate::checks::number(domain.min.y),
                    crate::checks::number(domain.max.y),
                ),
            )
            .with_help("move it inside the domain, or widen `run.domain`")
        })
    })
}

/// A body placed for the overlap check.
pub struct PlacedBody<'a> {
    /// Its outline.
    pub shape: &'a BodyShape,
    /// Where it is.
    pub pose: Pose,
    /// True for walls (walls may overlap each other).
    pub is_wall: bool,
    /// Field path of its scene entry.
    pub path: &'a str,
}

/// A block's lattice, for the one error its overlapping neighbours give (see [`overlap_errors`]).
pub struct BlockGrid {
    /// The block's entry, `blocks[i]`: the path its particles carry.
    pub path: String,
    /// `grid_spacing_m`, (Δx, Δy).
    pub spacing: [f64; 2],
    /// The grid type, whose scatter (`RectGauss`, …) may bring neighbours together at any spacing.
    pub grid: GridType,
}

/// Overlaps between particles, and between particles and walls, larger than `max_fraction` of the smaller
/// particle's area (a particle outside a chamber, an inner-circle wall, overlaps it by its whole area), and walls that
/// lie exactly on each other. Two particles of one block of `blocks` that overlap give a single error at the block's
/// `grid_spacing_m` (its spacing against its particles' size), and the block's particles are not looked at further.
/// Returns at most [`MAX_REPORTED_ERRORS`] errors and the number of further ones found. Sweeps the bodies sorted by
/// their lower x bound, so the cost is O(N log N) plus the pairs whose boxes overlap.
pub fn overlap_errors(bodies: &[PlacedBody], max_fraction: f64, blocks: &[BlockGrid]) -> (Vec<SceneError>, usize) {
    // Each body's name as the run's outputs give it (`walls[0] #1`, `blocks[0] #17`): made only for an error.
    let names = std::cell::OnceCell::new();
    let name = |k: usize| -> String { names.get_or_init(|| super::numbered(bodies.iter().map(|b| b.path)))[k].clone() };
    let world: Vec<Vec<DVec2>> =
        bodies.iter().map(|b| b.shape.body_points().iter().map(|v| b.pose.apply(*v)).collect()).collect();
    let view =
        |k: usize| shape_view(bodies[k].shape.kind(), &world[k], bodies[k].shape.radius() * bodies[k].pose.scale);
    let boxes: Vec<Aabb> = (0..bodies.len()).map(|k| view(k).aabb()).collect();
    let mut order: Vec<usize> = (0..bodies.len()).collect();
    order.sort_by(|&a, &b| boxes[a].min.x.total_cmp(&boxes[b].min.x).then(a.cmp(&b)));
    let mut active: Vec<usize> = Vec::new();
    // The particles of blocks already reported as overlapping their neighbours.
    let mut excluded = vec![false; bodies.len()];
    let mut report = Report::default();
    for &i in &order {
        active.retain(|&j| boxes[j].max.x >= boxes[i].min.x && !excluded[j]);
        if excluded[i] {
            continue;
        }
        for &j in &active {
            let (a, b) = (i.min(j), i.max(j));
            if bodies[a].is_wall && bodies[b].is_wall {
                if coincide(&bodies[a], &world[a], &bodies[b], &world[b]) {
                    report.add(|| coinciding_walls_error(&bodies[b], [name(a), name(b)]));
                }
                continue;
            }
            if excluded[j] || !boxes[a].overlaps(&boxes[b]) {
                continue;
            }
            let (particle, other) = if bodies[a].is_wall { (b, a) } else { (a, b) };
            let Some(contact) = area_contact(view(particle), view(other)) else { continue };
            let particle_areas = [a, b].into_iter().filter(|&k| !bodies[k].is_wall).map(|k| bodies[k].shape.area());
            let smaller = particle_areas.fold(f64::INFINITY, f64::min);
            let fraction = contact.area / smaller;
            if fraction <= max_fraction {
                continue;
            }
            let block =
                blocks.iter().find(|g| !bodies[a].is_wall && g.path == bodies[a].path && g.path == bodies[b].path);
            let Some(block) = block else {
                report.add(|| {
                    overlap_error([&bodies[a], &bodies[b]], [name(a), name(b)], contact.point, fraction, max_fraction)
                });
                continue;
            };
            // Its neighbours overlap: one error for the block, whose particles are then left out.
            let members: Vec<usize> = (0..bodies.len()).filter(|&k| bodies[k].path == block.path).collect();
            let size = members.iter().fold(DVec2::ZERO, |size, &k| size.max(boxes[k].max - boxes[k].min));
            for &k in &members {
                excluded[k] = true;
            }
            let example = format!(
                "`{}` and `{}` by {} % of the smaller one's area at ({:.4}, {:.4}) m",
                name(b),
                name(a),
                percent(100.0 * fraction),
                contact.point.x,
                contact.point.y
            );
            report.add(|| block_overlap_error(block, size, &example));
            break;
        }
        if !excluded[i] {
            active.push(i);
        }
    }
    // An inner-circle wall (a chamber) is solid everywhere outside its circle: a particle entirely outside its box
    // lies wholly in that solid, though the boxes do not meet.
    if max_fraction >= 1.0 {
        return (report.errors, report.omitted);
    }
    let chambers = (0..bodies.len()).filter(|&k| bodies[k].is_wall && bodies[k].shape.kind() == ShapeKind::InnerCircle);
    for chamber in chambers {
        for particle in
            (0..bodies.len()).filter(|&k| !bodies[k].is_wall && !excluded[k] && !boxes[k].overlaps(&boxes[chamber]))
        {
            let (a, b) = (chamber.min(particle), chamber.max(particle));
            let at = bodies[particle].pose.position;
            report.add(|| overlap_error([&bodies[a], &bodies[b]], [name(a), name(b)], at, 1.0, max_fraction));
        }
    }
    (report.errors, report.omitted)
}

/// The first [`MAX_REPORTED_ERRORS`] errors found, and a count of the others (which are never made).
#[derive(Default)]
struct Report {
    errors: Vec<SceneError>,
    omitted: usize,
}

impl Report {
    fn add(&mut self, error: impl FnOnce() -> SceneError) {
        if self.errors.len() < MAX_REPORTED_ERRORS {
            self.errors.push(error());
        } else {
            self.omitted += 1;
        }
    }
}

/// The error at `block`'s `grid_spacing_m` where two of its neighbouring particles overlap (`example` names them):
/// its spacing against `size`, the largest width and height of its particles, which a spacing of at least that keeps
/// apart on a `Rect` or `Fcc` grid.
fn block_overlap_error(block: &BlockGrid, size: DVec2, example: &str) -> SceneError {
    let [dx, dy] = block.spacing;
    let fits = format!("({}, {})", two_digits_up(size.x), two_digits_up(size.y));
    let help = match block.grid {
        GridType::Rect | GridType::Fcc => {
            format!("use a grid spacing of at least {fits} m (the particles' width and height), or smaller particles")
        }
        scattered => format!(
            "a `{scattered:?}` grid moves each particle by up to half a spacing, so that neighbours may meet at any \
             spacing: use a `Rect` or `Fcc` grid with a spacing of at least {fits} m (the particles' width and height), \
             or smaller particles"
        ),
    };
    SceneError::new(
        ErrorKind::Overlap,
        field_path(&block.path, "grid_spacing_m"),
        format!(
            "neighbouring particles of this block overlap ({example}): its grid spacing is ({}, {}) m and its \
             particles are up to {} m wide and {} m high. Bodies must not overlap at the start beyond round-off: the run would \
             refuse them before its first step",
            number(dx),
            number(dy),
            significant_digits(size.x, 3),
            significant_digits(size.y, 3)
        ),
    )
    .with_help(help)
    .with_label("neighbours overlap")
}

/// True when two walls have the same outline at the same place (the same kind, radius and points, to round-off):
/// a particle touching one touches both, at twice the stiffness.
fn coincide(a: &PlacedBody, points_a: &[DVec2], b: &PlacedBody, points_b: &[DVec2]) -> bool {
    let size = points_a.iter().chain(points_b).map(|p| p.abs().max_element()).fold(a.shape.radius(), f64::max);
    let close = |x: DVec2, y: DVec2| (x - y).abs().max_element() <= 1e-12 * size;
    a.shape.kind() == b.shape.kind()
        && (a.shape.radius() * a.pose.scale - b.shape.radius() * b.pose.scale).abs() <= 1e-12 * size
        && points_a.len() == points_b.len()
        && points_a.iter().all(|&p| points_b.iter().any(|&q| close(p, q)))
}

/// The error at wall `b`'s entry where it lies exactly on wall `a`; `names` are the two walls' names, a's first.
fn coinciding_walls_error(b: &PlacedBody, names: [String; 2]) -> SceneError {
    let [a_name, b_name] = names;
    SceneError::value(
        b.path,
        format!(
            "this wall (`{b_name}`) lies exactly on `{a_name}`: a particle touching one touches both, and feels twice \
             the contact stiffness and damping"
        ),
    )
    .with_help("give each wall once (a mill's `rotor.arms_rad` lists each blade's angle once)")
    .with_label("given twice")
}

/// `x` (> 0) rounded up to two significant digits and written short: a spacing at least as large.
fn two_digits_up(x: f64) -> String {
    let unit = 10f64.powf(x.log10().floor() - 1.0);
    // A width computed as 0.006000000000000001 asks for 0.006, not 0.0061.
    let up = (x / unit - 1e-9).ceil() * unit;
    significant_digits(if up >= x && up.is_finite() { up } else { x }, 2)
}

/// A percentage to two decimals, or to three significant digits below 0.01 %.
fn percent(p: f64) -> String {
    if p >= 0.01 { format!("{p:.2}") } else { format!("{p:.2e}") }
}

/// The error at the entry of body b of `pair` (a, b) where the two overlap by `fraction` of the smaller particle's
/// area, more than `limit`; `names` are their names as the run's outputs give them, a's first.
fn overlap_error(pair: [&PlacedBody; 2], names: [String; 2], at: DVec2, fraction: f64, limit: f64) -> SceneError {
    let [a, b] = pair;
    let [a_name, b_name] = names;
    let what = if a.is_wall || b.is_wall { "a particle and a wall" } else { "two particles" };
    SceneError::new(
        ErrorKind::Overlap,
        b.path,
        format!(
            "{what} overlap by {} % of the smaller particle's area at ({:.4}, {:.4}) m: `{b_name}` and `{a_name}`. \
             Bodies must not overlap at the start beyond round-off ({} of the smaller area): the run would refuse \
             them before its first step, since an overlap at the start has no place in the energy ledger and its \
             damping would kick the bodies apart",
            percent(100.0 * fraction),
            at.x,
            at.y,
            crate::checks::number(limit)
        ),
    )
    .with_help("move them apart (for blocks: a larger grid spacing or smaller particles)")
    .with_label("overlaps")
}

#[cfg(test)]
mod tests {
    use super::*;
    use gc2d_geometry::square;

    #[test]
    fn automatic_time_steps_round_down_to_two_digits() {
        assert_eq!(round_down_to_two_digits(8.15e-6), 8.1e-6);
        assert!((round_down_to_two_digits(1.0e-5) - 1.0e-5).abs() < 1e-20);
        assert!(round_down_to_two_digits(9.99e-7) <= 9.99e-7);
        let bound = TimeStepBound {
            time_step: 1.63e-5,
            automatic_time_step: AUTOMATIC_TIME_STEP_FRACTION * 1.63e-5,
            refusal_time_step: 1.63e-5,
            inscribed_radius: 1e-3,
            path: "p".into(),
        };
        assert_eq!(choose_time_step(None, Some(&bound), false).unwrap(), 2.4e-6);
        assert_eq!(choose_time_step(None, None, false).unwrap(), FALLBACK_TIME_STEP);
        assert_eq!(choose_time_step(Some(2e-6), Some(&bound), false).unwrap(), 2e-6);
        assert_eq!(choose_time_step(Some(2e-5), Some(&bound), false).unwrap_err().kind(), ErrorKind::TimeStep);
        assert_eq!(choose_time_step(Some(2e-5), Some(&bound), true).unwrap(), 2e-5);
    }

    #[test]
    fn overlaps_are_measured_against_the_smaller_particle() {
        let big = square(0.02).unwrap();
        let small = square(0.01).unwrap();
        let (big, small) = (BodyShape::from(big), BodyShape::from(small));
        let body = |shape, x: f64, is_wall, path| PlacedBody {
            shape,
            pose: Pose::new(DVec2::new(x, 0.0), 0.0),
            is_wall,
            path,
        };
        // The small square sticks 1 mm into the big one: overlap 1e-5 m² = 10 % of the small square.
        let bodies = [body(&big, 0.0, false, "a"), body(&small, 0.014, false, "b")];
        let errors = overlap_errors(&bodies, 0.05, &[]).0;
        assert_eq!(errors.len(), 1);
        assert!(errors[0].message().contains("10.00 %"), "{}", errors[0].message());
        assert!(overlap_errors(&bodies, 0.11, &[]).0.is_empty());
        // Walls never count against each other.
        let walls = [body(&big, 0.0, true, "a"), body(&small, 0.014, true, "b")];
        assert!(overlap_errors(&walls, 0.0, &[]).0.is_empty());
    }
}
