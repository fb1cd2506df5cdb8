//! A run that the engine stops names the bodies as the scene does (issue 19 item 5): `particles[0]`, `walls[0]`, not
//! only the internal body ids.

use assert_cmd::Command;

/// A 1 cm square thrown at a floor at 80 m/s with a time step far above its bound (allowed explicitly): it moves more
/// than its own size per step, which the engine stops.
const SCENE: &str = "Scene(
    run: (time_step_s: 2e-4, end_time_s: 0.01, allow_unsafe_time_step: true),
    walls: [Wall(shape: Rectangle(width_m: 0.2, height_m: 0.01), position_m: (0, -0.005))],
    particles: [(shape: Square(side_m: 0.01), position_m: (0, 0.05), velocity_m_s: (0, -80))],
)
";

/// A 1 cm square a source drops with a time step of 20 ms (allowed explicitly): it falls further than its inscribed
/// radius in its second step, which the engine stops.
const SOURCE_SCENE: &str = "Scene(
    run: (time_step_s: 2e-2, end_time_s: 0.2, allow_unsafe_time_step: true),
    walls: [Wall(shape: Rectangle(width_m: 0.2, height_m: 0.01), position_m: (0, -0.5))],
    sources: [(position_m: (0, 0.05), width_m: 0, window_s: (0, 0.1), interval_s: 0.1,
               shape: (semi_axes_m: (0.005, 0.005), corners: 4))],
)
";

/// The stderr of a failed `gc2d-rs run` of `scene_text`.
fn failure(scene_text: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("throw.ron");
    std::fs::write(&scene, scene_text).unwrap();
    let output = Command::cargo_bin("gc2d-rs")
        .unwrap()
        .arg("run")
        .arg(&scene)
        .arg("--quiet")
        .arg("--out")
        .arg(dir.path().join("out"))
        .output()
        .unwrap();
    assert!(!output.status.success());
    String::from_utf8_lossy(&output.stderr).into_owned()
}

#[test]
fn a_stopped_run_names_the_bodies_by_their_scene_entries() {
    let stderr = failure(SCENE);
    assert!(stderr.contains("body 1 is `particles[0]`"), "{stderr}");
}

#[test]
fn a_particle_a_source_inserted_is_named_by_the_source() {
    let stderr = failure(SOURCE_SCENE);
    assert!(stderr.contains("body 1 is `sources[0] #0`"), "{stderr}");
}
