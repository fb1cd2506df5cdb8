//! The reference problems of the convergence study: small Worlds with a known answer (analytic, or a run at a very
//! small Δt), each measured by a few error metrics (reference §6.1, §6.2, §3.6).
//!
//! Material: E = 1e7 N/m and ρ = 5000 kg/m² (the thesis's production values, §2.14). Every World allows time steps
//! above the §3.6 bound, because the sweep goes past it on purpose; the engine's blow-up checks stay on.

use gc2d_contact::{ContactLaw, CundallStrack, NormalDamping, NormalElastic};
use gc2d_engine::schedules::GravitySchedule;
use gc2d_engine::{BodyId, Integrator, InteractionTable, MassModel, SafetyLimits, World, WorldConfig};
use gc2d_geometry::{ConvexPolygon, DVec2, Pose, rectangle, regular_polygon, square};
use std::f64::consts::PI;

/// Young's modulus of every problem, N/m.
const E_MODULUS: f64 = 1e7;
/// Area density of every problem, kg/m².
const DENSITY: f64 = 5000.0;
/// g of the incline, m/s².
const G: f64 = 9.81;

/// What an error metric compares with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Against {
    /// A closed-form answer (conservation law or analytic solution).
    Analytic,
    /// The same problem run with Gear c₀ = 3/16 at a very small Δt.
    Reference,
}

/// One error measure of a problem.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Metric {
    /// Short name, used in file names and CSV columns.
    pub id: &'static str,
    /// What the number is, for tables and figure titles.
    pub label: &'static str,
    /// Whether the answer is analytic or the reference run.
    pub against: Against,
}

/// What a run observed: problem-specific numbers that [`Problem::errors`] turns into the metrics' errors.
pub type Observation = Vec<f64>;

/// A reference problem: how to run it at a given Δt and how to score a run.
pub struct Problem {
    /// Short name, used in file names.
    pub id: &'static str,
    /// One-line description.
    pub title: &'static str,
    /// The error metrics; the first is the primary one (fits, instability, figures).
    pub metrics: &'static [Metric],
    /// The §3.6 bound (π/10)·sqrt(m/E) of the problem's particles, s.
    pub time_step_bound: f64,
    /// Simulated time of one run, s.
    pub run_time: f64,
    /// The metric (index into `metrics`) and the error above which a run counts as unstable: a relative error of
    /// order one, the answer is lost. For the oscillator it is the energy error beyond 10 E_osc, since a phase
    /// error can reach the amplitude and the energy can swing by several E_osc without any instability.
    pub instability: (usize, f64),
    /// The reference run's Δt as a fraction of the bound (full study; the quick study uses five times it). Smaller
    /// for problems whose error is only first order in Δt.
    pub reference_fraction: f64,
    simulate: fn(Integrator, f64) -> Result<Observation, String>,
    errors: fn(&Observation, &Observation) -> Vec<f64>,
}

impl Problem {
    /// Runs the problem with `integrator` at time step `dt`; `Err` with the engine's message when the run stopped.
    pub fn simulate(&self, integrator: Integrator, dt: f64) -> Result<Observation, String> {
        (self.simulate)(integrator, dt)
    }

    /// The errors of `observed`, one per metric, given the reference run's observation.
    pub fn errors(&self, observed: &Observation, reference: &Observation) -> Vec<f64> {
        (self.errors)(observed, reference)
    }
}

/// All problems of the study, in report order.
pub fn all_problems() -> Vec<Problem> {
    vec![elastic_head_on(), elastic_oblique(), damped_squares(), incline(), clamped_oscillator()]
}

fn contact_law(gamma: f64, mu: f64) -> ContactLaw {
    ContactLaw {
        elastic: NormalElastic::thesis(E_MODULUS),
        damping: (gamma > 0.0).then_some(NormalDamping { gamma }),
        friction: (mu > 0.0).then_some(CundallStrack { mu }),
        cohesion: None,
    }
}

/// The engine's blow-up checks, with time steps above the bound allowed.
fn study_limits() -> SafetyLimits {
    SafetyLimits { allow_unsafe_time_step: true, ..SafetyLimits::default() }
}

fn new_world(integrator: Integrator, dt: f64, law: ContactLaw, g: f64) -> Result<World, String> {
    new_world_with(integrator, dt, law, g, study_limits())
}

fn new_world_with(
    integrator: Integrator,
    dt: f64,
    law: ContactLaw,
    g: f64,
    safety: SafetyLimits,
) -> Result<World, String> {
    let config = WorldConfig {
        time_step: dt,
        integrator,
        interactions: InteractionTable::uniform(law),
        mass_model: MassModel::PerUnitThickness,
        gravity: GravitySchedule::constant(g),
        heating: None,
        safety,
        domain: None,
        seed: 1,
    };
    World::new(config).map_err(|e| e.to_string())
}

fn add(world: &mut World, shape: &ConvexPolygon, position: DVec2, velocity: DVec2) -> Result<BodyId, String> {
    world.add_particle(shape, Pose::new(position, 0.0), DENSITY, velocity, 0.0).map_err(|e| e.to_string())
}

fn run_until(world: &mut World, t_end: f64) -> Result<(), String> {
    world.run_until(t_end).map_err(|e| format!("t = {:.4e} s: {e}", world.time()))
}

/// The §3.6 bound of a World's particles (the refusal bound; the stable bound the engine offers also covers flat
/// contacts and is lower).
fn bound_of(world: &World) -> f64 {
    let config = world.config();
    gc2d_engine::safety::stable_time_step(world.bodies(), &config.interactions, config.safety.max_impact_speed)
        .map_or(f64::NAN, |bound| bound.refusal)
}

fn kinetic(world: &World) -> f64 {
    let b = world.bodies();
    b.particles()
        .map(|id| {
            let i = id.index();
            0.5 * b.mass[i] * b.velocity[i].length_squared() + 0.5 * b.inertia[i] * b.angular_velocity[i].powi(2)
        })
        .sum()
}

fn momentum(world: &World) -> DVec2 {
    let b = world.bodies();
    b.particles().map(|id| b.mass[id.index()] * b.velocity[id.index()]).sum()
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

// ---------------------------------------------------------------------------------------------------------------
// Two 64-gons, elastic (§6.2): γ = 0, μ = 0, g = 0, u = ±0.5 m/s.

/// Circumradius of the 64-gons, m.
const DISK_RADIUS: f64 = 0.005;
/// Approach speed of each 64-gon, m/s (§6.2).
const DISK_SPEED: f64 = 0.5;
/// Gap between the 64-gons along x at t = 0, m.
const DISK_GAP: f64 = 1e-4;
/// Simulated time: approach (0.1 ms), contact (0.64 ms) and free flight after it.
const DISK_RUN_TIME: f64 = 1.5e-3;

/// Two 64-gons at ±0.5 m/s whose centres are offset by `impact` (the impact parameter b) across the motion.
/// Observation: [KE_after/KE_before, |ΔP|/(m·u), v₁ₓ, v₁ᵧ, ω₁].
fn simulate_disks(integrator: Integrator, dt: f64, impact: f64) -> Result<Observation, String> {
    let mut world = new_world(integrator, dt, contact_law(0.0, 0.0), 0.0)?;
    let shape = regular_polygon(64, DISK_RADIUS).map_err(|e| e.to_string())?;
    // Centres at x = ±½(sqrt(D² − b²) + gap): first touch after the same 0.1 ms for every impact parameter.
    let diameter = 2.0 * DISK_RADIUS;
    let x = 0.5 * ((diameter * diameter - impact * impact).sqrt() + DISK_GAP);
    let a = add(&mut world, &shape, DVec2::new(-x, -0.5 * impact), DVec2::new(DISK_SPEED, 0.0))?;
    add(&mut world, &shape, DVec2::new(x, 0.5 * impact), DVec2::new(-DISK_SPEED, 0.0))?;
    let (kinetic_before, momentum_before) = (kinetic(&world), momentum(&world));
    run_until(&mut world, DISK_RUN_TIME)?;
    if world.contacts().next().is_some() {
        return Err("the 64-gons still touch at the end of the run".into());
    }
    let mass = world.bodies().mass[a.index()];
    let v = world.bodies().velocity[a.index()];
    Ok(vec![
        kinetic(&world) / kinetic_before,
        (momentum(&world) - momentum_before).length() / (mass * DISK_SPEED),
        v.x,
        v.y,
        world.bodies().angular_velocity[a.index()],
    ])
}

fn disk_bound() -> f64 {
    let mut world = new_world(Integrator::default(), 1e-6, contact_law(0.0, 0.0), 0.0).expect("valid");
    let shape = regular_polygon(64, DISK_RADIUS).expect("valid 64-gon");
    add(&mut world, &shape, DVec2::ZERO, DVec2::ZERO).expect("valid particle");
    bound_of(&world)
}

const MOMENTUM: Metric = Metric { id: "momentum", label: "|ΔP|/(m·u), momentum change", against: Against::Analytic };

/// Head-on elastic collision of two 64-gons: the kinetic energy must come back exactly (a conservative central
/// force), momentum is conserved.
pub fn elastic_head_on() -> Problem {
    const METRICS: &[Metric] =
        &[Metric { id: "kinetic_energy", label: "|KE_after/KE_before − 1|", against: Against::Analytic }, MOMENTUM];
    Problem {
        id: "elastic_head_on",
        title: "Elastic head-on collision of two 64-gons (R = 5 mm, ±0.5 m/s, γ = μ = g = 0)",
        metrics: METRICS,
        time_step_bound: disk_bound(),
        run_time: DISK_RUN_TIME,
        instability: (0, 1.0),
        reference_fraction: 1e-3,
        simulate: |integrator, dt| simulate_disks(integrator, dt, 0.0),
        errors: |o, _| vec![(o[0] - 1.0).abs(), o[1]],
    }
}

/// Elastic collision of two 64-gons with impact parameter b = R (b/D = 0.5): the corners spin the polygons up
/// (Abb. 2.30), and the area force is not exactly conservative for a rotating pair, so the kinetic energy after the
/// collision is compared with the reference run.
pub fn elastic_oblique() -> Problem {
    const METRICS: &[Metric] = &[
        Metric { id: "kinetic_energy", label: "|KE_after − KE_ref|/KE_before", against: Against::Reference },
        Metric { id: "velocity", label: "|v₁ − v₁,ref|/u, outgoing velocity", against: Against::Reference },
        MOMENTUM,
    ];
    Problem {
        id: "elastic_oblique",
        title: "Elastic oblique collision of two 64-gons, impact parameter b = R (γ = μ = g = 0)",
        metrics: METRICS,
        time_step_bound: disk_bound(),
        run_time: DISK_RUN_TIME,
        instability: (0, 1.0),
        reference_fraction: 1e-3,
        simulate: |integrator, dt| simulate_disks(integrator, dt, DISK_RADIUS),
        errors: |o, r| {
            let dv = DVec2::new(o[2] - r[2], o[3] - r[3]).length() / DISK_SPEED;
            vec![(o[0] - r[0]).abs(), dv, o[1]]
        },
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Two squares edge to edge, damped (§6.0 setup B, §6.2 inelastic).

/// Side of the squares, m.
const SQUARE_SIDE: f64 = 0.01;
/// Simulated time of the squares' collision: approach (0.1 ms), contact (≈ 0.25 ms) and free flight, s.
const SQUARE_RUN_TIME: f64 = 1e-3;
/// Damping constant of the inelastic collision (Abb. 2.7).
const SQUARE_GAMMA: f64 = 0.3;

/// Head-on squares at ±0.5 m/s, edge to edge. Observation: [restitution, |ΔP|/(m·u)].
fn simulate_squares(integrator: Integrator, dt: f64) -> Result<Observation, String> {
    let mut world = new_world(integrator, dt, contact_law(SQUARE_GAMMA, 0.0), 0.0)?;
    let shape = square(SQUARE_SIDE).map_err(|e| e.to_string())?;
    let x = 0.5 * (SQUARE_SIDE + 1e-4);
    let a = add(&mut world, &shape, DVec2::new(-x, 0.0), DVec2::new(DISK_SPEED, 0.0))?;
    let b = add(&mut world, &shape, DVec2::new(x, 0.0), DVec2::new(-DISK_SPEED, 0.0))?;
    let momentum_before = momentum(&world);
    run_until(&mut world, SQUARE_RUN_TIME)?;
    if world.contacts().next().is_some() {
        return Err("the squares still touch at the end of the run".into());
    }
    let bodies = world.bodies();
    let restitution = (bodies.velocity[b.index()] - bodies.velocity[a.index()]).x / (2.0 * DISK_SPEED);
    let mass = bodies.mass[a.index()];
    Ok(vec![restitution, (momentum(&world) - momentum_before).length() / (mass * DISK_SPEED)])
}

/// Damped head-on collision of two 1 cm squares edge to edge (γ = 0.3): the restitution coefficient against the
/// reference run.
pub fn damped_squares() -> Problem {
    const METRICS: &[Metric] =
        &[Metric { id: "restitution", label: "|e − e_ref|/e_ref, restitution", against: Against::Reference }, MOMENTUM];
    let bound = {
        let mut world = new_world(Integrator::default(), 1e-6, contact_law(0.0, 0.0), 0.0).expect("valid");
        add(&mut world, &square(SQUARE_SIDE).expect("valid square"), DVec2::ZERO, DVec2::ZERO).expect("valid");
        bound_of(&world)
    };
    Problem {
        id: "damped_squares",
        title: "Damped head-on collision of two 1 cm squares edge to edge (γ = 0.3, ±0.5 m/s)",
        metrics: METRICS,
        time_step_bound: bound,
        run_time: SQUARE_RUN_TIME,
        instability: (0, 1.0),
        reference_fraction: 1e-4,
        simulate: simulate_squares,
        errors: |o, r| vec![relative(o[0], r[0]), o[1]],
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Block sliding down an incline (§6.1).

/// The block: 40 mm × 4 mm (flat, so that it does not rock; see docs/model.md "Validation of the engine").
const BLOCK: DVec2 = DVec2::new(0.04, 0.004);
/// Incline angle, rad (30°), above the friction angle arctan 0.3 = 16.7°.
const INCLINE_ANGLE: f64 = PI / 6.0;
/// Friction coefficient of the incline.
const INCLINE_MU: f64 = 0.3;
/// Damping of the incline contact (the thesis's default).
const INCLINE_GAMMA: f64 = 0.5;
/// The position is measured at this time, s.
const INCLINE_TIME: f64 = 0.05;

fn incline_world(integrator: Integrator, dt: f64) -> Result<(World, BodyId), String> {
    let mut world = new_world(integrator, dt, contact_law(INCLINE_GAMMA, INCLINE_MU), G)?;
    let uphill = DVec2::from_angle(INCLINE_ANGLE);
    let normal = uphill.perp();
    let thickness = 0.02;
    let floor = rectangle(0.5, thickness).map_err(|e| e.to_string())?;
    world.add_wall(&floor, Pose::new(-0.5 * thickness * normal, INCLINE_ANGLE), DVec2::ZERO, Default::default());
    let shape = rectangle(BLOCK.x, BLOCK.y).map_err(|e| e.to_string())?;
    let pose = Pose::new(0.5 * BLOCK.y * normal, INCLINE_ANGLE);
    let block = world.add_particle(&shape, pose, DENSITY, DVec2::ZERO, 0.0).map_err(|e| e.to_string())?;
    Ok((world, block))
}

/// The analytic distance slid from rest in time t: ½·g·(sin Θ − μ cos Θ)·t².
pub fn incline_analytic_distance(t: f64) -> f64 {
    0.5 * G * (INCLINE_ANGLE.sin() - INCLINE_MU * INCLINE_ANGLE.cos()) * t * t
}

/// Observation: [distance slid down the slope s, downhill velocity v, time t] at the end of the run; t lies within
/// Δt/2 of T, so every comparison is made at the run's own t.
fn simulate_incline(integrator: Integrator, dt: f64) -> Result<Observation, String> {
    let (mut world, block) = incline_world(integrator, dt)?;
    let start = world.bodies().pose[block.index()].position;
    run_until(&mut world, INCLINE_TIME)?;
    let downhill = -DVec2::from_angle(INCLINE_ANGLE);
    let bodies = world.bodies();
    Ok(vec![
        (bodies.pose[block.index()].position - start).dot(downhill),
        bodies.velocity[block.index()].dot(downhill),
        world.time(),
    ])
}

/// The reference's distance at time `t` near its own end time: s_ref + v_ref·δ + ½a·δ², δ = t − t_ref, with the
/// analytic acceleration (exact enough for |δ| ≤ Δt/2).
fn incline_reference_distance(reference: &Observation, t: f64) -> f64 {
    let delta = t - reference[2];
    reference[0] + reference[1] * delta + 0.5 * 2.0 * incline_analytic_distance(1.0) * delta * delta
}

/// A 40 × 4 mm block released at rest on a 30° incline with μ = 0.3 (γ = 0.5): the distance slid at T = 0.05 s.
pub fn incline() -> Problem {
    const METRICS: &[Metric] = &[
        Metric { id: "position", label: "|s(T) − s_ref(T)|/s_ref(T), distance slid", against: Against::Reference },
        Metric {
            id: "position_analytic",
            label: "|s(T) − ½g(sin Θ − μ cos Θ)T²|/(½g(sin Θ − μ cos Θ)T²)",
            against: Against::Analytic,
        },
    ];
    let bound = incline_world(Integrator::default(), 1e-6).map(|(w, _)| bound_of(&w)).unwrap_or(f64::NAN);
    Problem {
        id: "incline",
        title: "Block (40 × 4 mm) sliding down a 30° incline, μ = 0.3, γ = 0.5, distance at T = 0.05 s",
        metrics: METRICS,
        time_step_bound: bound,
        run_time: INCLINE_TIME,
        // A distance off by 10 % is a broken run: the block's flat contact rocks at the Nyquist frequency and slides
        // differently (docs/model.md, "Validation of the engine"), without any engine check firing.
        instability: (0, 0.1),
        reference_fraction: 1e-3,
        simulate: simulate_incline,
        errors: |o, r| {
            vec![relative(o[0], incline_reference_distance(r, o[2])), relative(o[0], incline_analytic_distance(o[2]))]
        },
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Harmonic contact oscillator: a square clamped between two walls (permanent contact, γ = 0).

/// Initial overlap of the square with each wall, m.
const CLAMP_OVERLAP: f64 = 1e-5;
/// Oscillation amplitude as a fraction of the overlap: the square never leaves either wall, even when an integrator
/// near its stability limit inflates the amplitude (Verlet's by 1/sqrt(1 − (ωΔt)²/4), 3.2× at ωΔt = 1.9).
const CLAMP_AMPLITUDE_FRACTION: f64 = 0.2;
/// Periods before the measurement. The square starts at its equilibrium with its largest speed and is back there
/// after whole periods, where the position is first-order sensitive to a phase error.
const CLAMP_PERIODS: f64 = 50.0;
/// Steps after which the oscillator's propagation error is measured (Gear's start-up transient has decayed).
const CLAMP_START_UP_STEPS: usize = 10;

/// Stiffness of an edge-on wall contact with frozen arm l: F = E·A/l = (E·s/l)·h.
fn edge_stiffness(length: f64) -> f64 {
    E_MODULUS * SQUARE_SIDE / length
}

/// The nominal (l = s/2 − h₀) angular frequency of the clamped square, rad/s.
fn clamp_nominal_omega() -> f64 {
    let mass = DENSITY * SQUARE_SIDE * SQUARE_SIDE;
    (2.0 * edge_stiffness(0.5 * SQUARE_SIDE - CLAMP_OVERLAP) / mass).sqrt()
}

/// A 1 cm square between a floor and a ceiling, overlapping each by h₀ = 10 µm, started at y = 0 with
/// v₀ = 0.2·h₀·ω upwards and g = 0. The forces cancel at t = 0, so the engine's free-flight start (a = 0) is right
/// to leading order. The arms l of both contacts freeze at the first step (decision D1), at overlaps h₀ ∓ v₀Δt, so
/// the stiffnesses differ from run to run by O(Δt); all energies and exact solutions therefore use the run's own
/// frozen stiffnesses k_b, k_t: ω² = (k_b + k_t)/m, equilibrium y_e = h₀(k_t − k_b)/(k_b + k_t), and the model's
/// energy E = ½mv² + ½k_b h_b² + ½k_t h_t² (exact for the linear edge contact, A = s·h).
///
/// Gear's derivatives 3..5 start at zero (the engine's free-flight seed) while the true jerk is −ω²v₀, which costs
/// an O(Δt²) energy and phase offset in the first steps (see docs/validation.md). The propagation error is measured
/// separately from it: the exact solution y(t) = y_e + (y_s − y_e) cos ω(t − t_s) + (v_s/ω) sin ω(t − t_s) starts
/// from the run's own state (y_s, v_s) after [`CLAMP_START_UP_STEPS`] steps.
///
/// Observation: [y(T), y_exact(T), largest |E − E₀|/E_osc over the last period, |Ē_last − Ē_second|/E_osc,
/// amplitude], at T = 50 nominal periods, with E₀ the energy of the initial condition, E_osc = ½mv₀² and Ē
/// the mean energy over a period (the second one, and the last one).
fn simulate_clamped(integrator: Integrator, dt: f64) -> Result<Observation, String> {
    // The ledger takes its initial total before any contact is evaluated, so it books the elastic energy of the
    // pre-loaded overlaps (k·h₀², 25 times the oscillation energy) as a gain at the first step; its energy-jump
    // check would judge the set-up, not the integrator. Instability is judged by the energy error instead.
    let limits =
        SafetyLimits { max_energy_gain_fraction: f64::INFINITY, max_initial_overlap_fraction: 1.0, ..study_limits() };
    let mut world = new_world_with(integrator, dt, contact_law(0.0, 0.0), 0.0, limits)?;
    let thickness = 0.01;
    let wall = rectangle(0.1, thickness).map_err(|e| e.to_string())?;
    let offset = 0.5 * SQUARE_SIDE - CLAMP_OVERLAP + 0.5 * thickness;
    for y in [-offset, offset] {
        world.add_wall(&wall, Pose::new(DVec2::new(0.0, y), 0.0), DVec2::ZERO, Default::default());
    }
    let omega_nominal = clamp_nominal_omega();
    let v0 = CLAMP_AMPLITUDE_FRACTION * CLAMP_OVERLAP * omega_nominal;
    let shape = square(SQUARE_SIDE).map_err(|e| e.to_string())?;
    let id = add(&mut world, &shape, DVec2::ZERO, DVec2::new(0.0, v0))?;
    let mass = world.bodies().mass[id.index()];
    let period = 2.0 * PI / omega_nominal;
    let t_end = CLAMP_PERIODS * period;
    let step = |world: &mut World| world.step().map_err(|e| format!("t = {:.4e} s: {e}", world.time()));
    step(&mut world)?;
    // The arms frozen at the first step: the contact with the floor (below) and with the ceiling.
    let (mut l_bottom, mut l_top) = (f64::NAN, f64::NAN);
    for (a, b, contact) in world.contacts() {
        let wall = if a == id { b } else { a };
        let length = contact.state.overlap_area().constants.map_or(f64::NAN, |k| k.length);
        if world.bodies().pose[wall.index()].position.y < 0.0 {
            l_bottom = length;
        } else {
            l_top = length;
        }
    }
    let (k_b, k_t) = (edge_stiffness(l_bottom), edge_stiffness(l_top));
    let omega = ((k_b + k_t) / mass).sqrt();
    let y_equilibrium = CLAMP_OVERLAP * (k_t - k_b) / (k_b + k_t);
    let energy_at = |y: f64, v: f64| {
        let (h_b, h_t) = (CLAMP_OVERLAP - y, CLAMP_OVERLAP + y);
        0.5 * mass * v * v + 0.5 * k_b * h_b.max(0.0).powi(2) + 0.5 * k_t * h_t.max(0.0).powi(2)
    };
    let state = |world: &World| (world.bodies().pose[id.index()].position.y, world.bodies().velocity[id.index()].y);
    let e0 = energy_at(0.0, v0);
    for _ in 1..CLAMP_START_UP_STEPS {
        step(&mut world)?;
    }
    let t_start = world.time();
    let (y_start, v_start) = state(&world);
    let oscillation_energy = 0.5 * mass * v0 * v0;
    let (mut second, mut last) = ((0.0, 0usize), (0.0, 0usize));
    let mut energy_error = 0.0_f64;
    while world.time() + 0.5 * dt < t_end {
        step(&mut world)?;
        let (y, v) = state(&world);
        let e = energy_at(y, v);
        let t = world.time();
        if t > t_start + period && t <= t_start + 2.0 * period {
            second = (second.0 + e, second.1 + 1);
        }
        if t > t_end - period {
            last = (last.0 + e, last.1 + 1);
            energy_error = energy_error.max((e - e0).abs() / oscillation_energy);
        }
    }
    let mean = |(sum, n): (f64, usize)| sum / n as f64;
    let drift = (mean(last) - mean(second)).abs() / oscillation_energy;
    let phase = omega * (world.time() - t_start);
    let (y, _) = state(&world);
    let y_exact = y_equilibrium + (y_start - y_equilibrium) * phase.cos() + v_start / omega * phase.sin();
    Ok(vec![y, y_exact, energy_error, drift, v0 / omega_nominal])
}

/// The clamped square: a linear contact oscillator with an analytic solution, run for 50 periods. Its run ends within
/// Δt/2 of T, so it is compared only with the exact solution at the run's own end time, not with a reference run.
pub fn clamped_oscillator() -> Problem {
    const METRICS: &[Metric] = &[
        Metric {
            id: "position",
            label: "|y(T) − y_exact(T)|/amplitude, from the state after 10 steps",
            against: Against::Analytic,
        },
        Metric { id: "energy", label: "max |E − E₀|/E_osc over the last period", against: Against::Analytic },
        Metric { id: "energy_drift", label: "|Ē_last − Ē_second|/E_osc, energy drift", against: Against::Analytic },
    ];
    let bound = {
        let mut world = new_world(Integrator::default(), 1e-6, contact_law(0.0, 0.0), 0.0).expect("valid");
        add(&mut world, &square(SQUARE_SIDE).expect("valid square"), DVec2::ZERO, DVec2::ZERO).expect("valid");
        bound_of(&world)
    };
    Problem {
        id: "clamped_oscillator",
        title: "Harmonic contact oscillator: 1 cm square clamped between two walls, γ = 0, 50 periods",
        metrics: METRICS,
        time_step_bound: bound,
        run_time: CLAMP_PERIODS * 2.0 * PI / clamp_nominal_omega(),
        // Near its limit ωΔt = 2 Verlet's energy error is large but bounded (the conserved modified energy has the
        // factor 1 − (ωΔt)²/4: 7.5 E_osc at ωΔt = 1.9), so an energy error of 10 E_osc marks instability.
        instability: (1, 10.0),
        reference_fraction: 1e-3,
        simulate: simulate_clamped,
        errors: |o, _| vec![(o[0] - o[1]).abs() / o[4], o[2], o[3]],
    }
}
