//! A checkpoint compared with the scene a run is resumed with (`Scene::compare_with_checkpoint`): the same scene
//! continues it whatever a resumed run may change, and an edit that the checkpoint's World would silently ignore is
//! named by the scene's field or object.

mod common;

use common::FULL_SCENE;
use gc2d_scene::Scene;
use std::path::PathBuf;

fn bundled(name: &str) -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes").join(name);
    std::fs::read_to_string(path).unwrap()
}

/// The differences of the scene `text` with `from` replaced by `to` from a checkpoint of `text` after `steps` steps.
fn differences_after_edit(text: &str, steps: u32, from: &str, to: &str) -> Vec<String> {
    assert!(text.contains(from), "the scene has no `{from}`");
    let mut world = Scene::from_str(text, "scene.ron").unwrap().build().unwrap();
    for _ in 0..steps {
        world.step().unwrap();
    }
    let edited = Scene::from_str(&text.replace(from, to), "edited.ron").unwrap();
    edited.compare_with_checkpoint(&world).unwrap().differences
}

#[test]
fn the_same_scene_continues_its_checkpoint_with_another_seed_end_and_cadence() {
    let edits = [
        ("seed: 7", "seed: 8"),
        ("end_time_s: 0.01", "end_time_s: 0.5"),
        ("frames_per_second: 200", "frames_per_second: 10"),
        ("name: \"full\"", "name: \"full, continued\""),
    ];
    for (from, to) in edits {
        let differences = differences_after_edit(FULL_SCENE, 20, from, to);
        assert!(differences.is_empty(), "`{to}` does not continue the run: {differences:?}");
    }
}

#[test]
fn an_edit_the_checkpoint_would_ignore_is_named_by_its_field() {
    let cases = [
        ("time_step_s: 2e-6", "time_step_s: 1e-6", "run.time_step_s: Δt is 1e-6 s with the scene, 2e-6 s in the"),
        ("max_overlap_fraction: 0.05", "max_overlap_fraction: 0.06", "run.max_overlap_fraction: 0.06 with the scene"),
        ("y_range_m: (-1.0, 1.0)), max", "y_range_m: (-1.0, 2.0)), max", "run.domain: x -1 to 3.5 m, y -1 to 2 m"),
        ("from_m_s2: 9.81", "from_m_s2: 9.8", "gravity"),
        ("amplitude: 0.01", "amplitude: 0.02", "heating"),
        (
            "(name: \"lead\", density_kg_m2: 20000, gamma: 0.75)",
            "(name: \"lead\", density_kg_m2: 20000, gamma: 0.5)",
            "materials or interactions: `sand–lead: ",
        ),
        ("density_kg_m2: 20000", "density_kg_m2: 21000", "particles[2]: its mass differs"),
        ("position_m: (0.0, -0.005)", "position_m: (0.0, -0.006)", "walls[0]: its place or motion differs"),
        ("frequency_hz: 20, waveform", "frequency_hz: 21, waveform", "walls[2]: its place or motion differs"),
        (
            "Square(side_m: 0.02), position_m: (0.6",
            "Square(side_m: 0.03), position_m: (0.6",
            "walls[2]: its shape differs",
        ),
        ("force_n: 10", "force_n: 11", "walls[3]: its place or motion differs"),
        ("speed_m_s: 0.01, window_s: (0.0, 1.0)", "speed_m_s: 0.02, window_s: (0.0, 1.0)", "drag springs differ"),
        ("interval_s: 0.001", "interval_s: 0.002", "sources[0]: it differs"),
    ];
    for (from, to, expected) in cases {
        let differences = differences_after_edit(FULL_SCENE, 20, from, to);
        assert!(differences.iter().any(|d| d.contains(expected)), "`{to}`: {differences:?} names no `{expected}`");
    }
}

#[test]
fn a_mill_or_feed_pipe_edit_is_named() {
    let mill = bundled("mill.ron");
    let differences = differences_after_edit(&mill, 5, "rpm: 1700", "rpm: 1600");
    assert!(differences.iter().any(|d| d.contains("mill.rotor")), "{differences:?}");
    let pipe = bundled("feedpipe.ron");
    for (from, to, expected) in [
        ("rate_per_s: 200", "rate_per_s: 300", "inlets[0] (feed): it differs"),
        ("from_m: (0.03, 1.0)", "from_m: (0.03, 1.1)", "outlets[0] (top): it differs"),
        ("centre_speed_m_s: 16.0", "centre_speed_m_s: 15.0", "fluid: the fluid differs"),
    ] {
        let differences = differences_after_edit(&pipe, 5, from, to);
        assert!(differences.iter().any(|d| d.contains(expected)), "`{to}`: {differences:?} names no `{expected}`");
    }
}

#[test]
fn another_scene_altogether_is_told_by_its_bodies() {
    let world = Scene::from_str(&bundled("pile.ron"), "pile.ron").unwrap().build().unwrap();
    let mill = Scene::from_str(&bundled("mill.ron"), "mill.ron").unwrap();
    let differences = mill.compare_with_checkpoint(&world).unwrap().differences;
    assert!(differences.iter().any(|d| d.starts_with("walls: ")), "{differences:?}");
}

#[test]
fn an_edit_that_changes_the_automatic_time_step_is_named_before_the_time_step() {
    // QA docs: an edited Young's modulus was told as "run.time_step_s: Δt is … with the scene", its consequence.
    let pile = bundled("pile.ron");
    let differences = differences_after_edit(&pile, 5, "youngs_modulus_n_m: 1e7", "youngs_modulus_n_m: 2e7");
    assert!(differences.len() >= 2, "{differences:?}");
    assert!(differences[0].starts_with("materials or interactions: "), "{differences:?}");
    let last = differences.last().unwrap();
    assert!(
        last.starts_with("run.time_step_s: Δt is ")
            && last.ends_with("(automatic: it follows from the materials and shapes)"),
        "{differences:?}"
    );
}
