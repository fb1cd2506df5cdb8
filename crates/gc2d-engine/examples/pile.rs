//! The main job until the command line lands: a poured pile (reference §8.3). The thesis's 7-gons (semi-axes
//! 1.75 mm ± 25 %, E = 10⁷ N/m, γ = 0.75, μ = 0.6, Δt = 2·10⁻⁶ s) fall from a drop source through a funnel onto a
//! floor between two side walls and build a heap.
//!
//! ```sh
//! cargo run --release -p gc2d-engine --example pile
//! ```
//!
//! It pours about 360 particles in 0.8 s and lets them come to rest until t = 1 s (500,000 steps, about a minute on
//! a current core; the World is below its parallel threshold, so a second core does not help).
//! Every `REPORT_EVERY` steps it prints time, particles, contacts, kinetic energy and the energy ledger's balance
//! error; at the end the particle count, the pile height, the run time and the throughput.

use gc2d_bench::piles::add_container;
use gc2d_bench::thesis_material;
use gc2d_engine::{DropHeight, DropSource, MaterialId, ParticleRecipe, TimeWindow, WallMotion, World};
use gc2d_geometry::{DVec2, Pose, rectangle};
use std::time::Instant;

/// Width of the box, m (the floor runs from x = 0 to x = BOX_WIDTH).
const BOX_WIDTH: f64 = 0.3;
/// Height of the box's side walls, m.
const BOX_HEIGHT: f64 = 0.2;
/// Height of the funnel's outlet above the floor, m.
const FUNNEL_OUTLET_HEIGHT: f64 = 0.08;
/// Width of the funnel's outlet, m: about seven particle diameters, so that it passes more than the source pours
/// (Beverloo's law gives some 700 particles/s) and does not clog.
const FUNNEL_OUTLET: f64 = 0.025;
/// Length and thickness of each funnel wall, m, and its tilt against the horizontal.
const FUNNEL_WALL: (f64, f64, f64) = (0.07, 0.003, std::f64::consts::FRAC_PI_3);
/// Height of the drop source above the floor, m (just above the funnel's rim, 0.141 m).
const SOURCE_HEIGHT: f64 = 0.15;
/// Width of the drop source, m: a particle dropped from rest needs some 30 ms to clear its spot, so the line holds
/// about twenty spots to keep up with the insertions.
const SOURCE_WIDTH: f64 = 0.07;
/// Time between two insertions, s, and the end of pouring.
const INSERTION_INTERVAL: f64 = 2.2e-3;
const POURING_ENDS: f64 = 0.8;
/// End of the run, s.
const END_TIME: f64 = 1.0;
/// Steps between two progress lines (0.05 s).
const REPORT_EVERY: u64 = 25_000;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut world = World::new(thesis_material::thesis_config(7))?;
    add_container(&mut world, BOX_WIDTH, BOX_HEIGHT);
    add_funnel(&mut world)?;
    world.add_source(DropSource {
        position: DVec2::new(0.5 * BOX_WIDTH, SOURCE_HEIGHT),
        width: SOURCE_WIDTH,
        height: DropHeight::Absolute,
        window: TimeWindow::new(0.0, POURING_ENDS),
        interval: INSERTION_INTERVAL,
        recipe: ParticleRecipe::Polygon(thesis_material::thesis_recipe()),
        density: thesis_material::DENSITY,
        material: MaterialId::default(),
    })?;

    println!("    t/s  particles  contacts  kinetic/J  balance error/J");
    let started = Instant::now();
    let mut particle_steps = 0u64;
    while world.time() < END_TIME - 0.5 * world.time_step() {
        world.step()?;
        particle_steps += world.bodies().particles().count() as u64;
        if world.steps() % REPORT_EVERY == 0 {
            let ledger = world.ledger();
            println!(
                "  {:.3}  {:9}  {:8}  {:9.3e}  {:+15.3e}",
                world.time(),
                world.bodies().particles().count(),
                world.stats().contacts,
                ledger.kinetic(),
                ledger.balance_error()
            );
        }
    }
    let seconds = started.elapsed().as_secs_f64();
    let particles = world.bodies().particles().count();
    println!(
        "done: {particles} particles ({} insertions skipped: no free spot), pile height {:.4} m ({} particles \
         still in the funnel), {seconds:.1} s run time, {:.2e} particle-steps/s",
        world.stats().insertions_skipped,
        pile_height(&world),
        in_funnel(&world),
        particle_steps as f64 / seconds
    );
    Ok(())
}

/// Two walls tilted `FUNNEL_WALL.2` against the horizontal, whose lower inner corners leave `FUNNEL_OUTLET` between
/// them at `FUNNEL_OUTLET_HEIGHT`, centred over the floor.
fn add_funnel(world: &mut World) -> Result<(), Box<dyn std::error::Error>> {
    let (length, thickness, tilt) = FUNNEL_WALL;
    let wall = rectangle(length, thickness)?;
    let centre = 0.5 * BOX_WIDTH;
    for side in [-1.0, 1.0] {
        // The wall's long axis points up and away from the centre; its lower end sits at the outlet's edge.
        let axis = DVec2::new(side * tilt.cos(), tilt.sin());
        let lower_end = DVec2::new(centre + side * 0.5 * FUNNEL_OUTLET, FUNNEL_OUTLET_HEIGHT);
        let angle = if side > 0.0 { tilt } else { std::f64::consts::PI - tilt };
        let pose = Pose::new(lower_end + 0.5 * length * axis, angle);
        world.add_wall(&wall, pose, DVec2::ZERO, WallMotion::Static);
    }
    Ok(())
}

/// Top of the highest particle below the funnel's outlet, m above the floor.
fn pile_height(world: &World) -> f64 {
    let b = world.bodies();
    b.particles().map(|id| b.aabb(id.index()).max.y).filter(|&top| top < FUNNEL_OUTLET_HEIGHT).fold(0.0, f64::max)
}

/// Particles whose centre is at or above the funnel's outlet.
fn in_funnel(world: &World) -> usize {
    let b = world.bodies();
    b.particles().filter(|id| b.pose[id.index()].position.y >= FUNNEL_OUTLET_HEIGHT).count()
}
