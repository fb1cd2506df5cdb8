//! What several test files of the command line share.

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
