//! Energy of elastic angular polygons under the two formulations of the overlap-area law (issue 19, item 1).
//!
//! The thesis law F = E·A/l is not the gradient of a potential: single collisions of two regular 7-gons change the
//! kinetic energy by several percent depending on their orientations, and a gas of 7-gons drifts. The conservative
//! formulation F = E·A·c/l², the gradient of W = E·A²/(2l²), keeps the energy of every collision and of the gas up
//! to the integrator's error. Numbers in docs/validation.md, "Energy of the overlap-area law".

mod common;

use common::{E_THESIS, RHO_THESIS, add_box, config, kinetic_change_over_one_contact, law, step, world};
use gc2d_contact::{AreaFormulation, ContactLaw, NormalElastic};
use gc2d_engine::World;
use gc2d_geometry::{Aabb, AngleMode, DVec2, Pose, ellipse_polygon, regular_polygon};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::TAU;

/// Circumradius of the 7-gons, m.
const RADIUS: f64 = 5e-3;
/// Fraction of the §3.6 bound the runs use (never above the stable bound): the scene format's automatic Δt.
const AUTOMATIC_FRACTION: f64 = 0.15;

/// The elastic, frictionless law of the issue with the given formulation.
fn elastic(formulation: AreaFormulation) -> ContactLaw {
    ContactLaw { elastic: NormalElastic { e_modulus: E_THESIS, formulation }, ..law(E_THESIS, 0.0, 0.0) }
}

/// The World that `build` makes for a time step, built with `fraction_of_automatic` times the automatic time step
/// of its particles.
fn with_automatic_time_step(build: impl Fn(f64) -> World, fraction_of_automatic: f64) -> World {
    let probe = build(1.0);
    let bounds = gc2d_engine::safety::stable_time_step(probe.bodies(), &probe.config().interactions, 1.0)
        .expect("particles bound the time step");
    build((AUTOMATIC_FRACTION * bounds.refusal).min(bounds.dt) * fraction_of_automatic)
}

/// The relative change of the kinetic energy over one head-on collision of two regular 7-gons at 0.5 m/s, turned
/// by `angles`, with impact parameter `offset`.
fn collision(formulation: AreaFormulation, angles: (f64, f64), offset: f64) -> f64 {
    let shape = regular_polygon(7, RADIUS).unwrap();
    let build = |dt| {
        let mut world = world(config(dt, elastic(formulation), 0.0));
        let gap = 2.0 * RADIUS + 1e-4;
        for (x, angle, v) in [(-0.5 * gap, angles.0, 0.25), (0.5 * gap, angles.1, -0.25)] {
            let pose = Pose::new(DVec2::new(x, offset * x.signum()), angle);
            world.add_particle(&shape, pose, RHO_THESIS, DVec2::new(v, 0.0), 0.0).unwrap();
        }
        world
    };
    kinetic_change_over_one_contact(&mut with_automatic_time_step(build, 1.0))
}

/// Over a grid of orientations and two impact parameters, the conservative law keeps the kinetic energy of every
/// collision to 1e-4, while the thesis law changes it by percents (measured: −17.6 % to +0.6 %).
#[test]
fn single_collisions_of_7_gons_keep_their_energy_only_under_the_conservative_law() {
    let sector = TAU / 7.0;
    let (mut thesis_min, mut thesis_max, mut conservative_worst) = (f64::INFINITY, f64::NEG_INFINITY, 0.0_f64);
    for a in 0..5 {
        for b in 0..5 {
            for offset in [0.0, 0.3 * RADIUS] {
                let angles = (a as f64 * sector / 5.0, b as f64 * sector / 5.0);
                let thesis = collision(AreaFormulation::Thesis, angles, offset);
                thesis_min = thesis_min.min(thesis);
                thesis_max = thesis_max.max(thesis);
                conservative_worst =
                    conservative_worst.max(collision(AreaFormulation::Conservative, angles, offset).abs());
            }
        }
    }
    println!("thesis {thesis_min:+.3e} .. {thesis_max:+.3e}, conservative worst {conservative_worst:.2e}");
    assert!(conservative_worst < 1e-4, "conservative law changed a collision's energy by {conservative_worst:e}");
    assert!(thesis_min < -0.02, "the thesis law's spread is expected to reach a few percent ({thesis_min:e})");
}

/// A gas of `count` random RAND1 7-gons (circumradius 5 mm ± 10 %) in a closed box covering a quarter of it,
/// E = 1e7 N/m, ρ = 5000 kg/m², γ = μ = 0, g = 0, speeds uniform in 0.2–0.8 m/s in random directions.
fn gas(formulation: AreaFormulation, count: usize, fraction_of_automatic: f64) -> World {
    let build = |dt| {
        let mut world = world(config(dt, elastic(formulation), 0.0));
        let mut rng = ChaCha8Rng::seed_from_u64(19);
        let particle_area = 3.5 * RADIUS * RADIUS * (TAU / 7.0).sin();
        let side = (count as f64 * particle_area / 0.25).sqrt();
        let columns = (count as f64).sqrt().ceil() as usize;
        let spacing = side / columns as f64;
        assert!(spacing > 2.2 * 1.1 * RADIUS, "the lattice must not overlap");
        add_box(&mut world, Aabb { min: DVec2::ZERO, max: DVec2::splat(side) }, 0.01);
        for k in 0..count {
            let size = RADIUS * rng.random_range(0.9..1.1);
            let shape = ellipse_polygon(7, size, size, AngleMode::Rand1, &mut rng).unwrap();
            let centre = DVec2::new((k % columns) as f64 + 0.5, (k / columns) as f64 + 0.5) * spacing;
            let pose = Pose::new(centre, rng.random_range(0.0..TAU));
            let velocity = DVec2::from_angle(rng.random_range(0.0..TAU)) * rng.random_range(0.2..0.8);
            world.add_particle(&shape, pose, RHO_THESIS, velocity, 0.0).unwrap();
        }
        world
    };
    with_automatic_time_step(build, fraction_of_automatic)
}

/// The relative change of the total energy (kinetic + stored in contacts) after `steps` steps.
fn drift(world: &mut World, steps: u64) -> f64 {
    step(world);
    let start = world.ledger().initial_total;
    for _ in 1..steps {
        step(world);
    }
    world.ledger().total() / start - 1.0
}

/// CI-sized gas: 200 7-gons for 3·10^4 steps at the automatic Δt of each law (0.074 s conservative, 0.18 s thesis;
/// a few collisions per particle). The conservative law keeps the energy within 10^-4 (measured +4.4e-7); the
/// thesis law gains more than 0.5 % in the same number of steps (measured +1.27 %).
#[test]
fn a_7_gon_gas_keeps_its_energy_under_the_conservative_law() {
    let conservative = drift(&mut gas(AreaFormulation::Conservative, 200, 1.0), 30_000);
    let thesis = drift(&mut gas(AreaFormulation::Thesis, 200, 1.0), 30_000);
    println!("3e4 steps: conservative {conservative:+.3e}, thesis {thesis:+.3e}");
    assert!(conservative.abs() < 1e-4, "conservative drift {conservative:e}");
    assert!(thesis > 5e-3, "thesis drift {thesis:e}");
}

/// The run: 10^5 steps at the automatic Δt. The conservative law keeps the energy within 0.5 %.
#[test]
#[ignore = "about 20 s in release; the CI-sized run is a_7_gon_gas_keeps_its_energy_under_the_conservative_law"]
fn a_7_gon_gas_keeps_its_energy_over_10_to_the_5_steps() {
    for (formulation, fraction) in [
        (AreaFormulation::Conservative, 1.0),
        (AreaFormulation::Thesis, 1.0),
        (AreaFormulation::Conservative, 0.25),
        (AreaFormulation::Thesis, 0.25),
    ] {
        let mut world = gas(formulation, 200, fraction);
        let steps = (100_000.0 / fraction) as u64;
        let change = drift(&mut world, steps);
        let ledger = world.ledger();
        println!(
            "{formulation:?} at {fraction} x automatic dt = {:.3e} s, {steps} steps ({:.3} s): energy {change:+.4e}, \
             opening residual {:+.4e} J of {:.4} J, balance error {:+.3e} J",
            world.config().time_step,
            world.time(),
            ledger.opening_residual,
            ledger.initial_total,
            ledger.balance_error()
        );
        if formulation == AreaFormulation::Conservative {
            assert!(change.abs() < 5e-3, "conservative drift {change:e}");
        }
    }
}
