//! Shared steps of the regression tests: load a scene from `tests/scenes/`, run it to its end time, and time it.
#![allow(dead_code)] // each test file uses its own subset of these helpers

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

/// The directory [`RUN_DIR_VARIABLE`] names, if set. A relative path is taken from the workspace root, where the
/// README's commands run: cargo starts the tests in this crate's directory, which would otherwise turn `runs` into
/// `tests/runs`.
fn run_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(std::env::var_os(RUN_DIR_VARIABLE)?);
    let workspace = Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the tests crate lies in the workspace");
    Some(if dir.is_absolute() { dir } else { workspace.join(dir) })
}

/// The thesis-sized scenes take hours: they are best run with `gc2d-rs run` (progress bar, checkpoints, resume) and
/// then measured here. If [`RUN_DIR_VARIABLE`] is set, loads that run's final checkpoint and checks it reached the
/// scene's end time (the returned duration is zero); otherwise runs the scene like [`run_scene`].
pub fn run_or_load_scene(file: &str) -> (World, Duration) {
    let Some(dir) = run_dir() else { return run_scene(file) };
    let stem = Path::new(file).file_stem().expect("a scene file name");
    let world = load_finished_run(&dir.join(stem), &load_scene(file));
    (world, Duration::ZERO)
}

/// The final checkpoint of the `gc2d-rs run` output directory `run`, which must have been made from `scene` (its
/// `scene.ron` equals it in everything but the seed and the name) and have reached the scene's end time.
fn load_finished_run(run: &Path, scene: &Scene) -> World {
    check_made_from(run, scene);
    let end = scene.run.end_time_s;
    let checkpoint = run.join("final.ckpt");
    let world = World::load_checkpoint_file(&checkpoint)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", checkpoint.display()));
    assert!(
        world.time() >= end - 0.5 * world.time_step(),
        "{} stops at t = {} s, before the scene's end time {end} s: resume it with `gc2d-rs run --resume`",
        checkpoint.display(),
        world.time()
    );
    world
}

/// The members of an ensemble of a thesis-sized scene: with [`RUN_DIR_VARIABLE`] set, the final checkpoint of every
/// directory in it whose name starts with the scene's stem (`sandpile_thesis`, `sandpile_thesis_seed2`, … made with
/// `gc2d-rs run SCENE --seed N --out DIR/sandpile_thesis_seedN`), and of every run directory inside such a directory
/// that has none itself (the points of a sweep, `DIR/sandpile_thesis/seed=N` made by `sweeps/sandpile_thesis.ron`),
/// each checked to have reached the scene's end time, in name order; otherwise the scene run once with its own seed.
/// Each member comes with its path below the run directory.
pub fn run_or_load_ensemble(file: &str) -> Vec<(String, World)> {
    let Some(dir) = run_dir() else {
        return vec![(file.to_owned(), run_scene(file).0)];
    };
    let stem = Path::new(file).file_stem().expect("a scene file name").to_string_lossy().into_owned();
    let entries = |folder: &Path| -> Vec<PathBuf> {
        std::fs::read_dir(folder)
            .unwrap_or_else(|e| panic!("cannot list {} ({RUN_DIR_VARIABLE}): {e}", folder.display()))
            .filter_map(|entry| entry.ok().map(|e| e.path()))
            .collect()
    };
    let finished = |path: &PathBuf| path.join("final.ckpt").is_file();
    let mut members: Vec<PathBuf> = Vec::new();
    for path in entries(&dir) {
        if !path.file_name().is_some_and(|name| name.to_string_lossy().starts_with(&stem)) {
            continue;
        }
        if finished(&path) {
            members.push(path);
        } else if path.is_dir() {
            members.extend(entries(&path).into_iter().filter(finished));
        }
    }
    members.sort();
    assert!(!members.is_empty(), "no {stem}*/final.ckpt or {stem}*/*/final.ckpt in {}", dir.display());
    let scene = load_scene(file);
    members
        .into_iter()
        .map(|member| {
            let name = member.strip_prefix(&dir).unwrap_or(&member).display().to_string();
            (name, load_finished_run(&member, &scene))
        })
        .collect()
}

/// Refuses a run directory whose `scene.ron` (the copy `gc2d-rs run` writes) differs from `scene` in anything but
/// the seed and the name (which only names outputs), naming the first differing line: a run of an older version of
/// a scene must not be measured against the current one's targets, nor mixed into its ensemble.
fn check_made_from(run: &Path, scene: &Scene) {
    let copy = run.join("scene.ron");
    let used = Scene::from_path(&copy)
        .unwrap_or_else(|e| panic!("cannot read {} (the scene the run was made from): {e:?}", copy.display()));
    let comparable = |s: &Scene| {
        let mut s = s.clone();
        s.source = None;
        s.run.seed = 0;
        s.name.clear();
        s.to_ron_string().expect("a scene serializes")
    };
    let (used, current) = (comparable(&used), comparable(scene));
    if let Some((line, (a, b))) = used.lines().zip(current.lines()).enumerate().find(|(_, (a, b))| a != b) {
        panic!(
            "{} was made from another version of the scene: line {} of its normalized text is `{}`, the current \
             scene has `{}`; run it again",
            run.display(),
            line + 1,
            a.trim(),
            b.trim()
        );
    }
    assert_eq!(used.lines().count(), current.lines().count(), "{} was made from another scene", copy.display());
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
