//! The report of a run the engine stops for an energy blow-up (QA docs 17): the time once, the energy in the scene's
//! unit, and the particle with the most kinetic energy named as the scene does.

use assert_cmd::Command;

/// Thirty-three hexagons dropped into a box with a time step far above their bound (allowed explicitly): the energy
/// balance stops the run within a few hundred steps.
const SCENE: &str = "Scene(
    run: (end_time_s: 0.3, seed: 1, time_step_s: 1e-4, allow_unsafe_time_step: true),
    materials: [(name: \"sand\", gamma: 0.75, mu: 0.6)],
    walls: [Box(x_range_m: (-0.05, 0.05), y_range_m: (0.0, 0.1), thickness_m: 0.005)],
    blocks: [(
        x_range_m: (-0.04, 0.04), y_range_m: (0.01, 0.03), grid_spacing_m: (0.008, 0.008),
        shape: (semi_axes_m: (0.003, 0.003), corners: 6, orientation: Equal),
    )],
)
";

#[test]
fn an_energy_blow_up_gives_the_time_once_the_unit_per_thickness_and_the_most_energetic_particle() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("blow.ron");
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
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("The run stopped at t = "), "{stderr}");
    assert_eq!(stderr.matches("t = ").count(), 1, "{stderr}");
    assert!(stderr.contains("the simulation blew up: the energy rose by "), "{stderr}");
    assert!(stderr.contains(" J/m more than the work done on the system explains"), "{stderr}");
    assert!(stderr.contains("the particle with the most kinetic energy at the stop is body "), "{stderr}");
    assert!(stderr.contains(" is `blocks[0] #"), "{stderr}");
}
