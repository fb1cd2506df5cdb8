//! Shared steps of the regression tests: load a scene from `tests/scenes/`, run it to its end time, and time it.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use gc2d_engine::World;
use gc2d_scene::Scene;

/// Path of a scene file in this crate's `scenes/` directory.
pub fn scene_path(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes").join(file)
}

/// Reads a scene of this crate's `scenes/` directory, panicking with the diagnostic if it does not load.
fn load_scene(file: &str) -> Scene {
    Scene::from_path(scene_path(file)).unwrap_or_else(|e| panic!("cannot load {file}: {e:?}"))
}

/// Environment variable naming a directory of finished `gc2d-rs run` outputs: with it, [`run_or_load_scene`] reads
/// `<dir>/<scene stem>/final.ckpt` instead of running the scene again.
pub const RUN_DIR_VARIABLE: &str = "GC2D_REGRESSION_RUN_DIR";

/// The thesis-sized scenes take hours: they are best run with `gc2d-rs run` (progress bar, checkpoints, resume) and
/// then measured here. If [`RUN_DIR_VARIABLE`] is set, loads that run's final checkpoint and checks it reached the
/// scene's end time (the returned duration is zero); otherwise runs the scene like [`run_scene`].
pub fn run_or_load_scene(file: &str) -> (World, Duration) {
    let Some(dir) = std::env::var_os(RUN_DIR_VARIABLE) else { return run_scene(file) };
    let scene = load_scene(file);
    let stem = Path::new(file).file_stem().expect("a scene file name");
    let checkpoint = PathBuf::from(dir).join(stem).join("final.ckpt");
    let world = World::load_checkpoint_file(&checkpoint)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", checkpoint.display()));
    let end = scene.run.end_time_s;
    assert!(
        world.time() >= end - 0.5 * world.time_step(),
        "{} stops at t = {} s, before the scene's end time {end} s: resume it with `gc2d-rs run --resume`",
        checkpoint.display(),
        world.time()
    );
    (world, Duration::ZERO)
}

/// Builds the scene and runs it to its `run.end_time_s`; returns the World and the wall-clock time of the run.
pub fn run_scene(file: &str) -> (World, Duration) {
    let scene = load_scene(file);
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
