//! Shared steps of the regression tests: load a scene from `tests/scenes/`, run it to its end time, and time it.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use gc2d_engine::World;
use gc2d_scene::Scene;

/// Path of a scene file in this crate's `scenes/` directory.
pub fn scene_path(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes").join(file)
}

/// Builds the scene and runs it to its `run.end_time_s`; returns the World and the wall-clock time of the run.
pub fn run_scene(file: &str) -> (World, Duration) {
    let scene = Scene::from_path(scene_path(file)).unwrap_or_else(|e| panic!("cannot load {file}: {e:?}"));
    let mut world = scene.build().unwrap_or_else(|e| panic!("cannot build {file}: {e:?}"));
    let start = Instant::now();
    world.run_until(scene.run.end_time_s).unwrap_or_else(|e| panic!("{file} stopped: {e:?}"));
    (world, start.elapsed())
}

/// Sum of m·g over the particles alive in the World, N per unit thickness.
pub fn particle_weight(world: &World) -> f64 {
    let bodies = world.bodies();
    world.gravity() * bodies.particles().map(|id| bodies.mass[id.index()]).sum::<f64>()
}
