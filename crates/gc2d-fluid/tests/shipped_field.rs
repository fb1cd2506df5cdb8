//! The CFD field shipped with the scenes (scenes/fields/feedpipe_riser.vtk, OpenFOAM's turbulent riser flow): read
//! by the reader, and physically what its README says it is.

use gc2d_fluid::vtk::{DataLocation, VtkFile};
use gc2d_fluid::{Interpolation, Outside, SampledField};
use gc2d_geometry::DVec2;
use std::path::PathBuf;

const INLET_SPEED: f64 = 12.0;
const HALF_WIDTH: f64 = 0.03;

fn shipped() -> VtkFile {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/fields/feedpipe_riser.vtk");
    VtkFile::read(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn every_row_of_cells_carries_the_inlets_flux() {
    // Mass conservation of an incompressible flow: the mean of the cells' u_y across each row (cells of equal width)
    // equals the inlet's speed.
    let cells = shipped().velocity_samples("U", DataLocation::Cells).unwrap();
    let mut rows: std::collections::BTreeMap<i64, Vec<f64>> = Default::default();
    for (p, u) in cells.positions.iter().zip(&cells.velocities) {
        rows.entry((p[1] * 1e6).round() as i64).or_default().push(u.y);
    }
    assert_eq!(rows.len(), 100);
    for (y, speeds) in rows {
        assert_eq!(speeds.len(), 12);
        let mean = speeds.iter().sum::<f64>() / speeds.len() as f64;
        assert!((mean / INLET_SPEED - 1.0).abs() < 2e-3, "row at y = {} µm: mean {mean}", y);
    }
}

#[test]
fn the_walls_are_at_rest_and_the_profile_is_turbulent() {
    let file = shipped();
    let points = file.velocity_samples("U", DataLocation::Points).unwrap();
    for (p, u) in points.positions.iter().zip(&points.velocities) {
        let on_wall = (p[0].abs() - HALF_WIDTH).abs() < 1e-9;
        // The four corners, where foamToVTK averages a wall with the inlet or the outlet, are not at rest.
        if on_wall && p[1] > 1e-9 && p[1] < 1.0 - 1e-9 {
            assert_eq!(u.length(), 0.0, "wall point {p:?}");
        }
    }
    let field = SampledField::new(&points, Interpolation::Bilinear, Outside::Error).unwrap();
    // Near the top the flow has developed for 16 widths: flat across the core, 1 < axis/mean < 1.2 (laminar: 1.5).
    let axis = field.velocity(DVec2::new(0.0, 0.95)).unwrap();
    assert!(axis.x.abs() < 1e-3, "{axis}");
    let ratio = axis.y / INLET_SPEED;
    assert!(ratio > 1.0 && ratio < 1.2, "axis speed over mean {ratio}");
    // Symmetric about the axis.
    for x in [0.005, 0.015, 0.025] {
        let (left, right) = (field.velocity(DVec2::new(-x, 0.7)).unwrap(), field.velocity(DVec2::new(x, 0.7)).unwrap());
        assert!((left.y - right.y).abs() < 1e-3 * left.y, "{left} against {right}");
    }
}
