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

#[test]
fn a_stopped_run_names_the_bodies_by_their_scene_entries() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("throw.ron");
    std::fs::write(&scene, SCENE).unwrap();
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
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("body 1 is `particles[0]`"), "{stderr}");
}
