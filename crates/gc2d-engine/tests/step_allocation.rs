//! A warm `World::step` allocates nothing (preamble: the hot paths must not allocate), on the sequential path and on
//! the rayon path.
//!
//! The counting allocator (`gc2d-alloc-count`) is installed in this test binary only. Its process-wide count includes
//! every thread, so that allocations made by rayon's workers count too; the file therefore holds a single test, which
//! measures the two paths one after the other while no other test of this binary runs.

use gc2d_alloc_count::{CountingAllocator, process_allocations};
use gc2d_bench::thesis_material;
use gc2d_engine::{WallMotion, World};
use gc2d_geometry::{DVec2, Pose, rectangle, square};

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

/// `columns` × `rows` squares of 3.5 mm (the size of the thesis's pile particles) stacked like bricks in a box of
/// floor and side walls, 1 µm apart and at rest, with the thesis's pile material: within a millisecond every square
/// rests on the ones below, and the contacts persist.
fn brick_stack(columns: usize, rows: usize) -> World {
    let config = thesis_material::thesis_config(1);
    let mut world = World::new(config).unwrap();
    let side = 3.5e-3;
    let gap = 1e-6;
    let pitch = side + gap;
    let width = (columns as f64 + 0.5) * pitch + gap;
    let floor = rectangle(width + 0.02, 0.01).unwrap();
    world.add_wall(&floor, Pose::new(DVec2::new(0.5 * width, -0.005), 0.0), DVec2::ZERO, WallMotion::Static);
    let height = rows as f64 * pitch + 0.01;
    let wall = rectangle(0.01, height).unwrap();
    for x in [-0.005, width + 0.005] {
        world.add_wall(&wall, Pose::new(DVec2::new(x, 0.5 * height), 0.0), DVec2::ZERO, WallMotion::Static);
    }
    let brick = square(side).unwrap();
    for k in 0..columns * rows {
        let (column, row) = (k % columns, k / columns);
        // Odd rows shifted by half a brick, so every brick rests on two below.
        let x = gap + (column as f64 + 0.5 + 0.5 * (row % 2) as f64) * pitch;
        let position = DVec2::new(x, (row as f64 + 0.5) * pitch + gap);
        world.add_particle(&brick, Pose::new(position, 0.0), 5000.0, DVec2::ZERO, 0.0).unwrap();
    }
    world
}

/// Steps `world` until its contacts are in full swing (2,500 steps, 5 ms: every brick has landed and the pair list has reached its size), then counts the
/// allocations of the next 200 steps. Returns (allocations, contacts after the warm-up).
fn allocations_of_warm_steps(world: &mut World) -> (usize, usize) {
    for _ in 0..2_500 {
        world.step().unwrap();
    }
    let contacts = world.stats().contacts;
    let before = process_allocations();
    for _ in 0..200 {
        world.step().unwrap();
    }
    (process_allocations() - before, contacts)
}

#[test]
fn warm_steps_allocate_nothing_on_the_sequential_and_the_rayon_path() {
    // 120 particles: below the World's parallel threshold, every stage runs on the calling thread.
    let mut small = brick_stack(12, 10);
    let (sequential, contacts) = allocations_of_warm_steps(&mut small);
    assert!(contacts > 200, "the test must exercise contacts, got {contacts}");
    assert_eq!(sequential, 0, "a warm sequential step allocated");

    // 1,000 particles on a 2-thread pool: the predictor, the transform, the narrowphase and the corrector all run as
    // rayon tasks. The pool is built (and its threads started) before counting.
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
    let mut large = brick_stack(40, 25);
    let (parallel, contacts) = pool.install(|| allocations_of_warm_steps(&mut large));
    assert!(contacts > 800, "the test must exercise contacts, got {contacts}");
    assert_eq!(parallel, 0, "a warm parallel step allocated");
}
