//! The main job until the command line lands: 7-gons poured from a source onto a floor between two walls.
//!
//! Run with `cargo run --release -p gc2d-engine --example pile`. Prints progress and the energy ledger.

use gc2d_contact::{ContactLaw, CundallStrack, NormalDamping, NormalElastic};
use gc2d_engine::schedules::GravitySchedule;
use gc2d_engine::{DropHeight, DropSource, TimeWindow, WallMotion, World, WorldConfig};
use gc2d_geometry::{AngleMode, DVec2, Pose, Randomization, ShapeRecipe, rectangle};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let contact_law = ContactLaw {
        elastic: NormalElastic { e_modulus: 1e7 },
        damping: Some(NormalDamping { gamma: 0.75 }),
        friction: Some(CundallStrack { mu: 0.6 }),
        cohesion: None,
    };
    let config = WorldConfig {
        time_step: 2e-6,
        integrator: Default::default(),
        contact_law,
        gravity: GravitySchedule::constant(9.81),
        heating: None,
        safety: Default::default(),
        domain: None,
        seed: 7,
    };
    let mut world = World::new(config)?;
    let floor = rectangle(0.3, 0.01)?;
    world.add_wall(&floor, Pose::new(DVec2::new(0.0, -0.005), 0.0), DVec2::ZERO, WallMotion::Static);
    let side = rectangle(0.01, 0.2)?;
    for x in [-0.155, 0.155] {
        world.add_wall(&side, Pose::new(DVec2::new(x, 0.1), 0.0), DVec2::ZERO, WallMotion::Static);
    }
    world.add_source(DropSource {
        position: DVec2::new(0.0, 0.06),
        width: 0.04,
        height: DropHeight::Absolute,
        window: TimeWindow::new(0.0, 0.8),
        interval: 4e-3,
        recipe: ShapeRecipe {
            semi_axes: DVec2::splat(1.75e-3),
            size_variation: 0.25,
            size_randomization: Randomization::Equal,
            corners: 7,
            corner_variation: 0,
            corner_randomization: Randomization::Const,
            angle_mode: AngleMode::Rand1,
            rotation: 0.0,
            rotation_randomization: Randomization::Equal,
        },
        density: 5000.0,
    })?;
    let end_time = 1.1;
    let started = Instant::now();
    let mut particle_steps = 0u64;
    while world.time() < end_time {
        world.step()?;
        particle_steps += world.bodies().particles().count() as u64;
        if world.steps() % 25_000 == 0 {
            let ledger = world.ledger();
            println!(
                "t = {:.3} s  particles {:5}  contacts {:5}  kinetic {:.3e} J  balance error {:+.2e} J",
                world.time(),
                world.stats().inserted,
                world.stats().contacts,
                ledger.kinetic(),
                ledger.balance_error()
            );
        }
    }
    let elapsed = started.elapsed().as_secs_f64();
    let height = world
        .bodies()
        .particles()
        .map(|id| world.bodies().pose[id.index()].position.y)
        .fold(f64::NEG_INFINITY, f64::max);
    println!(
        "done: {} particles ({} insertions skipped: no free spot), pile top at {:.4} m, {:.1} s wall time, \
         {:.2e} particle-steps/s",
        world.stats().inserted,
        world.stats().insertions_skipped,
        height,
        elapsed,
        particle_steps as f64 / elapsed
    );
    Ok(())
}
