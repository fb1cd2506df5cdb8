//! The legacy VTK reader: every supported structure read from a file, and broken files refused with a message
//! naming the file, the line and what was expected.

use gc2d_fluid::vtk::{DataLocation, DatasetKind, VtkError, VtkFile};
use std::path::PathBuf;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name)
}

fn read(name: &str) -> VtkFile {
    VtkFile::read(&data(name)).unwrap_or_else(|e| panic!("{e}"))
}

/// The bilinear test field of tests/data/README.md.
fn u(x: f64, y: f64) -> [f64; 2] {
    [1.0 + 2.0 * x + 3.0 * y + 4.0 * x * y, -0.5 + x - y + 0.25 * x * y]
}

/// Asserts that every sample's velocity is the test field at its position.
fn assert_test_field(file: &VtkFile, location: DataLocation) {
    let samples = file.velocity_samples("U", location).unwrap();
    assert_eq!(samples.positions.len(), samples.velocities.len());
    for (p, v) in samples.positions.iter().zip(&samples.velocities) {
        let expected = u(p[0], p[1]);
        assert!((v.x - expected[0]).abs() < 1e-6 && (v.y - expected[1]).abs() < 1e-6, "{p:?}: {v}");
    }
}

#[test]
fn reads_the_thesis_layout_with_point_and_cell_data() {
    let file = read("feedpipe_unstructured.vtk");
    assert_eq!(file.dataset, DatasetKind::UnstructuredGrid);
    assert_eq!(file.title, "feedpipe_unstructured");
    assert_eq!((file.points.len(), file.cells.len()), (24, 6));
    assert_eq!(file.cells.cell(4), &[5, 6, 10, 9, 17, 18, 22, 21]);
    let names = |loc| file.data(loc).iter().map(|a| (a.name.clone(), a.components)).collect::<Vec<_>>();
    assert_eq!(names(DataLocation::Cells), [("cellID".into(), 1), ("p".into(), 1), ("U".into(), 3)]);
    assert_eq!(names(DataLocation::Points), [("p".into(), 1), ("U".into(), 3)]);
    assert_test_field(&file, DataLocation::Points);
    // The cell data sit at the cell centres (the mean of the 8 points): cell 4 spans x 0.5..1, y 0.25..1.
    let cells = file.velocity_samples("U", DataLocation::Cells).unwrap();
    assert_eq!(cells.positions[4], [0.75, 0.625, 0.05]);
    assert_test_field(&file, DataLocation::Cells);
}

#[test]
fn reads_structured_points_rectilinear_and_structured_grids_and_polydata() {
    let sp = read("structured_points.vtk");
    assert_eq!(sp.dataset, DatasetKind::StructuredPoints);
    assert_eq!((sp.points.len(), sp.cells.len()), (9, 4));
    assert_eq!(sp.points[5], [1.0, 0.5, 0.0]);
    assert_eq!(sp.cells.cell(3), &[4, 5, 8, 7]);
    assert_test_field(&sp, DataLocation::Points);

    let rg = read("rectilinear_grid.vtk");
    assert_eq!(rg.dataset, DatasetKind::RectilinearGrid);
    assert_eq!((rg.points.len(), rg.cells.len()), (24, 6));
    assert_eq!(rg.points[3 * 4 + 2], [0.4, -1.0, 0.01]);
    assert_test_field(&rg, DataLocation::Points);

    let sg = read("structured_grid.vtk");
    assert_eq!(sg.dataset, DatasetKind::StructuredGrid);
    assert_eq!((sg.points.len(), sg.cells.len()), (6, 2));
    assert_test_field(&sg, DataLocation::Points);

    let pd = read("polydata.vtk");
    assert_eq!(pd.dataset, DatasetKind::PolyData);
    assert_eq!(pd.cells.len(), 2);
    assert_eq!(pd.cells.cell(1), &[1, 4, 2]);
    assert_test_field(&pd, DataLocation::Points);
}

#[test]
fn reads_a_real_foam_to_vtk_export_with_its_time_value() {
    let file = read("foam_cavity.vtk");
    assert_eq!(file.dataset, DatasetKind::UnstructuredGrid);
    assert_eq!(file.time_value, Some(0.05));
    assert_eq!((file.points.len(), file.cells.len()), (40, 12));
    let samples = file.velocity_samples("U", DataLocation::Points).unwrap();
    // The lid's inner nodes move at 1 m/s; point 17 is (0.05, 0.1, 0).
    assert_eq!(samples.positions[17], [0.05, 0.1, 0.0]);
    assert_eq!((samples.velocities[17].x, samples.velocities[17].y), (1.0, 0.0));
}

#[test]
fn reads_vtk_5_1_offsets_and_connectivity() {
    let text = "# vtk DataFile Version 5.1\nnew cells\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n\
                0 0 0 1 0 0 1 1 0 0 1 0\nCELLS 2 4\nOFFSETS vtktypeint64\n0 4\nCONNECTIVITY vtktypeint64\n\
                0 1 2 3\nCELL_TYPES 1\n9\nPOINT_DATA 4\nVECTORS U float\n1 0 0 1 0 0 1 0 0 1 0 0\n";
    let file = VtkFile::parse(text.as_bytes(), "new.vtk").unwrap();
    assert_eq!(file.cells.len(), 1);
    assert_eq!(file.cells.cell(0), &[0, 1, 2, 3]);
}

/// A good file with one change; the message must name the file and the line and say what it expected.
fn refused(name: &str, from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(data(name)).unwrap();
    assert!(text.contains(from), "{from}");
    let broken = text.replacen(from, to, 1);
    match VtkFile::parse(broken.as_bytes(), "broken.vtk") {
        Ok(_) => panic!("accepted {from} -> {to}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn broken_files_are_refused_with_located_messages() {
    let f = "feedpipe_unstructured.vtk";
    let cases = [
        (f, "# vtk DataFile", "# vtx DataFile", "broken.vtk, line 1: expected `# vtk DataFile Version x.y`"),
        (f, "ASCII", "BINARY", "broken.vtk, line 3: binary VTK is not read"),
        (f, "DATASET UNSTRUCTURED_GRID", "DATASET UNSTRUCTURED", "line 4: expected STRUCTURED_POINTS"),
        (f, "POINTS 24 float", "POINTS 24 real", "line 5: expected the data type of POINTS"),
        (f, "0.5 0.25 0", "0.5 x 0", "line 7: expected POINTS: number 17 of 72 (a number), found `x`"),
        (f, "0.5 0.25 0", "0.5 nan 0", "line 7: expected POINTS: number 17 of 72, found the non-finite `nan`"),
        (f, "8 5 6 10 9 17 18 22 21", "8 5 6 10 9 17 18 22 24", "line 14: a cell names point 24, but there are 24"),
        (f, "CELLS 6 54", "CELLS 6 55", "line 21: expected CELLS: entry 55 of 55 (a count), found `CELL_TYPES`"),
        (f, "8 2 3 7 6 14 15 19 18", "9 2 3 7 6 14 15 19 18", "line 14: CELLS 6 54: cell 6 of 6 needs more entries"),
        (
            f,
            "CELL_TYPES 6\n12 12 12 12 12 12",
            "CELL_TYPES 5\n12 12 12 12 12",
            "line 21: CELL_TYPES 5, but CELLS (line 14) has 6 cells",
        ),
        (f, "CELL_DATA 6", "CELL_DATA 7", "line 23: CELL_DATA 7, but the dataset has 6 cells"),
        (f, "POINT_DATA 24", "POINT_DATA 23", "POINT_DATA 23, but the dataset has 24 points"),
        (f, "p 1 6 float", "p 1 5 float", "FIELD array p has 5 tuples, but the section has 6 values"),
        (
            f,
            "FIELD attributes 2",
            "FIELD attributes 3",
            "expected the name of a FIELD array, found the end of the file",
        ),
        (f, "POINT_DATA 24", "POINTS_DATA 24", "expected SCALARS, COLOR_SCALARS"),
        (f, "POINTS 24 float", "POINTS 99999999999999 float", "line 5: POINTS: the counts ask for more numbers"),
        ("structured_points.vtk", "SPACING 0.5 0.5 1\n", "", "expected SPACING in a STRUCTURED_POINTS dataset"),
        (
            "rectilinear_grid.vtk",
            "Y_COORDINATES 4 float",
            "Y_COORDINATES 3 float",
            "line 9: expected FIELD, DIMENSIONS",
        ),
        (
            "rectilinear_grid.vtk",
            "Y_COORDINATES 4 float",
            "Y_COORDINATES 3 float",
            "found `2` (a number where a keyword",
        ),
        (
            "rectilinear_grid.vtk",
            "DIMENSIONS 3 4 2",
            "DIMENSIONS 3 5 2",
            "line 8: Y_COORDINATES has 4 values, DIMENSIONS (line 5) says 5",
        ),
        (
            "structured_grid.vtk",
            "DIMENSIONS 3 2 1",
            "DIMENSIONS 3 3 1",
            "line 6: POINTS has 6 points, DIMENSIONS 3 3 1",
        ),
        ("polydata.vtk", "POLYGONS 2 9", "CELLS 2 9", "line 7: CELLS does not belong in a POLYDATA dataset"),
    ];
    for (file, from, to, expected) in cases {
        let message = refused(file, from, to);
        assert!(message.starts_with("broken.vtk, line "), "{message}");
        assert!(message.contains(expected), "{from} -> {to}:\n  got      {message}\n  expected {expected}");
    }
}

#[test]
fn a_truncated_file_is_refused_at_its_last_line() {
    let text = std::fs::read_to_string(data("feedpipe_unstructured.vtk")).unwrap();
    let cut = &text[..text.len() - 30];
    let lines = cut.lines().count();
    let message = VtkFile::parse(cut.as_bytes(), "cut.vtk").unwrap_err().to_string();
    assert!(message.starts_with(&format!("cut.vtk, line {lines}: expected FIELD array U: number ")), "{message}");
    assert!(message.ends_with("found the end of the file"), "{message}");
}

#[test]
fn a_missing_or_wrong_velocity_array_is_named() {
    let file = read("feedpipe_unstructured.vtk");
    let e = file.velocity_samples("V", DataLocation::Points).unwrap_err().to_string();
    assert!(e.contains("expected a POINT_DATA array named V; found p, U"), "{e}");
    assert!(e.contains("line 32"), "{e}");
    let e = file.velocity_samples("p", DataLocation::Cells).unwrap_err().to_string();
    assert!(e.contains("array p has 1 components; a velocity needs 2 or 3"), "{e}");
    let e = VtkFile::read(&data("absent.vtk")).unwrap_err();
    assert!(matches!(e, VtkError::Io { .. }) && e.to_string().contains("absent.vtk: cannot read"), "{e}");
}
