//! Throughput of `World::step` on a settled dense pile of 10,000 exact disks (the engine issue's "dense pile of
//! 10,000 disks: particle-steps per second on 1 and 2 threads", reported in docs/performance.md).
//!
//! ```sh
//! cargo run --release -p gc2d-engine --example bench_disk_pile          # 10,000 disks (about 4 minutes)
//! cargo run --release -p gc2d-engine --example bench_disk_pile -- 2000  # another number of disks
//! ```
//!
//! The disks (radius 1 mm ± 20 %, drawn uniformly; glass density 2500 kg/m³ with sphere-equivalent masses) start
//! on a hexagonal lattice a little wider than the largest disk, in a box twice as wide as the settled pile is high,
//! and settle under gravity for `SETTLE_TIME` on two threads (not timed, but reported). They meet each other and the
//! walls by a linear spring with restitution 0.5 and Cundall–Strack friction μ = 0.5. The stiffness,
//! `STIFFNESS` = 2000 N/m, is far below glass's (as is usual in DEM, to afford a Δt that settles the pile in
//! minutes): in the settled 10,000-disk pile the deepest overlap is about 0.8 % of the smaller diameter. Δt is half
//! the engine's stable bound for the smallest disk (5.75 µs).
//!
//! While the pile settles, its kinetic energy and the deepest overlap of that step are printed every
//! `SETTLE_REPORT_INTERVAL`. Measured for 10,000 disks: the kinetic energy peaks near 10⁻² J in the first 0.1 s
//! while the lattice collapses, and has fallen to about 2·10⁻⁶ J (a few mm/s r.m.s.) by 0.35 s, where it levels off;
//! settling 0.4 s (69,554 steps) took 3.5 minutes on the shared two cores.
//!
//! Then, like `bench_pile`, after `WARM_STEPS` untimed steps the wall-clock and CPU time (of all threads) of about
//! `PARTICLE_STEPS_PER_RUN` particle-steps are measured on a rayon pool of 1 and of 2 threads. Printed per run:
//! particle-steps per wall-clock second, wall and CPU ns per particle-step, box pairs and contacts per disk.

#[path = "support/timing.rs"]
mod timing;

use gc2d_contact::{
    CundallStrack, NormalSpring, PenetrationDamping, PenetrationLaw, TangentialSpring, TangentialStiffness,
};
use gc2d_engine::safety::{ParticleInertia, particle_time_step};
use gc2d_engine::schedules::GravitySchedule;
use gc2d_engine::{
    BodyShape, ContactModel, Integrator, InteractionTable, MassModel, MaterialId, MaterialPair, SafetyLimits,
    WallMotion, World, WorldConfig,
};
use gc2d_geometry::{DVec2, Pose, rectangle};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;
use std::time::Instant;
use timing::{load_average, measure, pool, print_header};

/// Disks in the pile unless the command line names another count.
const DEFAULT_DISKS: usize = 10_000;
/// Mean disk radius, m.
const RADIUS: f64 = 1e-3;
/// Relative spread of the radii: uniform in `RADIUS`·(1 ± `SIZE_VARIATION`).
const SIZE_VARIATION: f64 = 0.2;
/// Density of glass, kg/m³.
const DENSITY: f64 = 2500.0;
/// Normal stiffness of the linear spring, N/m.
const STIFFNESS: f64 = 2000.0;
/// Coefficient of restitution of every impact.
const RESTITUTION: f64 = 0.5;
/// Coulomb friction coefficient.
const FRICTION: f64 = 0.5;
/// Δt as a fraction of the engine's stable bound for the smallest disk.
const TIME_STEP_FRACTION: f64 = 0.5;
/// Gap between neighbours on the start lattice beyond the largest diameter, m.
const LATTICE_GAP: f64 = 0.1e-3;
/// Packing fraction assumed when sizing the box for the settled pile.
const ASSUMED_PACKING: f64 = 0.82;
/// Simulated time the pile settles before it is measured, s.
const SETTLE_TIME: f64 = 0.4;
/// Interval of the kinetic-energy reports while the pile settles, s.
const SETTLE_REPORT_INTERVAL: f64 = 0.05;
/// Particle-steps per measurement: the step count is this divided by the number of disks.
const PARTICLE_STEPS_PER_RUN: u64 = 20_000_000;
/// Thickness of the box walls, m.
const WALL_THICKNESS: f64 = 0.01;
/// Seed of the radii.
const SEED: u64 = 10_000;

/// The contact law of every pair: linear spring `STIFFNESS`, restitution `RESTITUTION`, friction `FRICTION`.
fn contact_model() -> ContactModel {
    ContactModel::Penetration(PenetrationLaw {
        damping: Some(PenetrationDamping::Restitution(RESTITUTION)),
        tangential: Some(TangentialSpring {
            mu: FRICTION,
            stiffness: TangentialStiffness::CundallStrack { stiffness_ratio: CundallStrack::STIFFNESS_FACTOR },
            damping_ratio: 0.0,
        }),
        ..PenetrationLaw::elastic(NormalSpring::Linear { stiffness_n_m: STIFFNESS })
    })
}

/// `TIME_STEP_FRACTION` of the engine's stable Δt for the smallest disk, s.
fn time_step(model: &ContactModel) -> f64 {
    let radius = RADIUS * (1.0 - SIZE_VARIATION);
    let mass = DENSITY * 4.0 / 3.0 * PI * radius.powi(3);
    let inertia = ParticleInertia {
        inscribed_radius: radius,
        area_density: mass / (PI * radius * radius),
        mass,
        inertia: 0.4 * mass * radius * radius,
        contact_radius: radius,
        reach: radius,
        flat_contact_ratio: 0.0,
    };
    let bound = particle_time_step([model], &inertia, SafetyLimits::default().max_impact_speed);
    TIME_STEP_FRACTION * bound.expect("the linear spring bounds the time step")
}

/// `disks` disks on a hexagonal lattice in a box twice as wide as the settled pile will be high (floor and side walls
/// high enough for the lattice), at rest, under gravity.
fn pile(disks: usize) -> World {
    let model = contact_model();
    let config = WorldConfig {
        time_step: time_step(&model),
        integrator: Integrator::default(),
        interactions: InteractionTable::new(1, &[MaterialPair { a: MaterialId(0), b: MaterialId(0), model }])
            .expect("a complete table"),
        mass_model: MassModel::SphereEquivalent,
        gravity: GravitySchedule::constant(9.81),
        heating: None,
        safety: SafetyLimits::default(),
        domain: None,
        seed: SEED,
    };
    let mut world = World::new(config).expect("valid configuration");
    let mut rng = ChaCha8Rng::seed_from_u64(SEED);
    let radii: Vec<f64> =
        (0..disks).map(|_| RADIUS * (1.0 + rng.random_range(-SIZE_VARIATION..SIZE_VARIATION))).collect();
    let covered = radii.iter().map(|r| PI * r * r).sum::<f64>() / ASSUMED_PACKING;
    let width = (2.0 * covered).sqrt();
    let spacing = 2.0 * RADIUS * (1.0 + SIZE_VARIATION) + LATTICE_GAP;
    let columns = ((width - spacing) / spacing).floor() as usize;
    let row_height = spacing * 3f64.sqrt() / 2.0;
    let rows = disks.div_ceil(columns);
    let height = (rows as f64 + 1.0) * row_height;
    let t = WALL_THICKNESS;
    let floor = rectangle(width + 2.0 * t, t).expect("positive size");
    world.add_wall(&floor, Pose::new(DVec2::new(0.5 * width, -0.5 * t), 0.0), DVec2::ZERO, WallMotion::Static);
    let side = rectangle(t, height).expect("positive size");
    for x in [-0.5 * t, width + 0.5 * t] {
        world.add_wall(&side, Pose::new(DVec2::new(x, 0.5 * height), 0.0), DVec2::ZERO, WallMotion::Static);
    }
    for (k, &radius) in radii.iter().enumerate() {
        let (row, column) = (k / columns, k % columns);
        let shift = if row % 2 == 0 { 0.5 } else { 1.0 };
        let position = DVec2::new((column as f64 + shift) * spacing, (row as f64 + 0.5) * row_height + 0.5 * spacing);
        world
            .add_particle(BodyShape::Disk { radius }, Pose::new(position, 0.0), DENSITY, DVec2::ZERO, 0.0)
            .expect("finite pose");
    }
    world
}

fn main() {
    let disks = std::env::args().nth(1).map_or(DEFAULT_DISKS, |a| a.parse().expect("a number of disks"));
    println!("load average before: {}", load_average());
    let started = Instant::now();
    let mut world = pile(disks);
    let built = started.elapsed().as_secs_f64();
    pool(2).install(|| {
        let reports = (SETTLE_TIME / SETTLE_REPORT_INTERVAL).round() as u32;
        for report in 1..=reports {
            world.run_until(f64::from(report) * SETTLE_REPORT_INTERVAL).expect("the pile settles without blowing up");
            println!(
                "  t = {:.2} s: kinetic energy {:.3e} J, largest overlap {:.2} % of the smaller diameter",
                world.time(),
                world.ledger().kinetic(),
                100.0 * world.stats().max_overlap_fraction
            );
        }
    });
    println!(
        "built {disks} disks in {built:.1} s, settled {SETTLE_TIME} s ({} steps of {:.3e} s) in {:.1} s on 2 threads: \
         {} contacts, kinetic energy {:.3e} J, largest overlap {:.2} % of the smaller diameter",
        world.steps(),
        world.time_step(),
        started.elapsed().as_secs_f64() - built,
        world.stats().contacts,
        world.ledger().kinetic(),
        100.0 * world.stats().max_overlap_fraction,
    );
    println!();
    print_header("disk");
    for threads in [1, 2] {
        measure(&mut world, threads, PARTICLE_STEPS_PER_RUN / disks as u64).print();
    }
    println!("\nload average after: {}", load_average());
}
