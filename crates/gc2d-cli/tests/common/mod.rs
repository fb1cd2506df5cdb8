//! What several test files of the command line share. Each test file is a crate of its own that uses a part of it.
#![allow(dead_code)]

use std::path::Path;

/// Writes `scenes/air.ron` into `dir`: one disk at rest in a fluid whose velocity is a VTK field named relative to the
/// scene, `fields/u.vtk` (a copy of gc2d-fluid's structured-points test file), Δt = 1e-4 s, 0.002 s long. For the
/// tests of files a scene reads from its own folder.
pub fn scene_with_a_vtk_field(dir: &Path) {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../gc2d-fluid/tests/data/structured_points.vtk");
    std::fs::create_dir_all(dir.join("scenes/fields")).unwrap();
    std::fs::copy(&data, dir.join("scenes/fields/u.vtk")).unwrap();
    let scene = "Scene(\n    run: (time_step_s: 1e-4, end_time_s: 0.002),\n    gravity: Constant(0.0),\n    \
        particles: [(shape: Disk(radius_m: 0.01), position_m: (0.5, 0.5))],\n    \
        fluid: (density_kg_m3: 1.2, field: Vtk(file: \"fields/u.vtk\", interpolation: Bilinear, outside: Nearest)),\n)\n";
    std::fs::write(dir.join("scenes/air.ron"), scene).unwrap();
}

/// A mill of 4 steel balls and one blade, 4 ms long at Δt = 5e-7 s with a frame (and a dump) every ms: the smallest
/// run the mill analysis reads, for the tests of its messages.
pub const FOUR_BALL_MILL: &str = r#"Scene(
    mass_model: SphereEquivalent,
    run: (time_step_s: 5e-7, end_time_s: 0.004, frames_per_second: 1000),
    materials: [(name: "steel", density_kg_m3: 7850, youngs_modulus_pa: 196.2e9, poisson_ratio: 0.3)],
    interactions: [(materials: ("steel", "steel"), law: Hertz(damping: Restitution(0.8)))],
    mill: (
        chamber_radius_m: 0.073,
        rotor: (rpm: 1700, hub_radius_m: 0.008, tip_radius_m: 0.058, blade_width_m: 0.008, arms_rad: [0.0]),
        balls: (count: 4, radius_m: 0.0025, speed_m_s: 1.0),
    ),
)"#;
