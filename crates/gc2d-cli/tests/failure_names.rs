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

/// Thirty-three hexagons dropped into a box with a time step far above their bound (allowed explicitly): the energy
/// balance stops the run within a few hundred steps.
const BLOW_UP_SCENE: &str = "Scene(
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
    // QA docs 17: the time was given twice, the energy in J for a per-unit-thickness scene, and no body was named.
    let stderr = failure(BLOW_UP_SCENE);
    assert!(stderr.contains("The run stopped at t = "), "{stderr}");
    assert_eq!(stderr.matches("t = ").count(), 1, "{stderr}");
    assert!(stderr.contains("the simulation blew up: the energy rose by "), "{stderr}");
    assert!(stderr.contains(" J/m more than the work done on the system explains"), "{stderr}");
    assert!(stderr.contains("the particle with the most kinetic energy at the stop is body "), "{stderr}");
    assert!(stderr.contains(" is `blocks[0] #"), "{stderr}");
}
