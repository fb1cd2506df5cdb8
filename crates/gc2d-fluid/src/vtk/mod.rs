//! A reader of legacy ASCII VTK files as OpenFOAM's `foamToVTK -legacy -ascii` writes them (feedpipe.md §4.2, §5.5).
//!
//! It reads the five dataset structures (STRUCTURED_POINTS, STRUCTURED_GRID, RECTILINEAR_GRID, POLYDATA,
//! UNSTRUCTURED_GRID), the dataset's own FIELD block (foamToVTK's `TimeValue`), POINT_DATA and CELL_DATA with their
//! SCALARS, COLOR_SCALARS, LOOKUP_TABLE, VECTORS, NORMALS, TEXTURE_COORDINATES, TENSORS and FIELD arrays, and cell
//! lists in both the classic layout and VTK 5.1's OFFSETS/CONNECTIVITY. Every number is read as f64. Binary files,
//! the FIELD dataset structure and METADATA blocks are refused with a message saying so.
//!
//! Anything malformed gives a [`VtkError`] naming the file, the line and what was expected; the reader never panics
//! and allocates no more than the file's size warrants, whatever counts the file claims. Why this is not `vtkio`:
//! docs/model.md, section "Fluid".

mod parse;
mod tokens;

use crate::sampled::FieldSamples;
use gc2d_geometry::DVec2;
use std::path::Path;

/// A malformed or unreadable VTK file.
#[derive(Debug, thiserror::Error)]
pub enum VtkError {
    /// The file could not be read.
    #[error("{file}: cannot read the file: {source}")]
    Io {
        /// The file's name as given.
        file: String,
        /// What the system said.
        source: std::io::Error,
    },
    /// The file is not what a legacy ASCII VTK file must be, or lacks what was asked of it.
    #[error("{file}, line {line}: {message}")]
    Syntax {
        /// The file's name as given.
        file: String,
        /// The line (from 1) where the problem was found.
        line: usize,
        /// What was expected and what was found.
        message: String,
    },
}

/// The dataset structure a file declares after `DATASET`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DatasetKind {
    /// A regular lattice given by DIMENSIONS, ORIGIN and SPACING.
    StructuredPoints,
    /// A curvilinear lattice: DIMENSIONS and POINTS.
    StructuredGrid,
    /// A lattice with its own X, Y and Z coordinates.
    RectilinearGrid,
    /// Points with vertices, lines, polygons and triangle strips.
    PolyData,
    /// Points and cells of any type (foamToVTK's mesh).
    UnstructuredGrid,
}

impl DatasetKind {
    /// The keyword the file uses.
    pub fn keyword(self) -> &'static str {
        match self {
            DatasetKind::StructuredPoints => "STRUCTURED_POINTS",
            DatasetKind::StructuredGrid => "STRUCTURED_GRID",
            DatasetKind::RectilinearGrid => "RECTILINEAR_GRID",
            DatasetKind::PolyData => "POLYDATA",
            DatasetKind::UnstructuredGrid => "UNSTRUCTURED_GRID",
        }
    }
}

/// Cells as lists of point indices: cell `i` is `indices[offsets[i]..offsets[i + 1]]`.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Cells {
    /// Where each cell's indices start in `indices`, and one past the last cell's end.
    pub offsets: Vec<usize>,
    /// The point indices of all cells, one after the other.
    pub indices: Vec<usize>,
}

impl Cells {
    /// The number of cells.
    pub fn len(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// Whether there are no cells.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The point indices of cell `i` (`i < len()`).
    pub fn cell(&self, i: usize) -> &[usize] {
        &self.indices[self.offsets[i]..self.offsets[i + 1]]
    }
}

/// One data array of a POINT_DATA or CELL_DATA section (or of the dataset's FIELD block): `components` numbers per
/// point or cell, one point or cell after the other.
#[derive(Debug, Clone, PartialEq)]
pub struct DataArray {
    /// The array's name (`U`, `p`, ...).
    pub name: String,
    /// Numbers per point or cell (3 for VECTORS).
    pub components: usize,
    /// The numbers, `components` per point or cell.
    pub values: Vec<f64>,
    /// The line where the array's header stands.
    pub line: usize,
}

/// Where a data array lives.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum DataLocation {
    /// POINT_DATA: values at the mesh's nodes (foamToVTK interpolates them from the cells).
    Points,
    /// CELL_DATA: values of the cells (OpenFOAM's own solution), placed at the cell centres, the mean of each
    /// cell's points.
    Cells,
}

/// The contents of a legacy VTK file, with implicit points and cells of the structured datasets made explicit.
#[derive(Debug, Clone, PartialEq)]
pub struct VtkFile {
    /// The file's name, for messages.
    pub source: String,
    /// The title line (foamToVTK writes the case name).
    pub title: String,
    /// The dataset structure.
    pub dataset: DatasetKind,
    /// The points (x, y, z), m. For the structured datasets, in VTK's order: x fastest, then y, then z.
    pub points: Vec<[f64; 3]>,
    /// The cells. For the structured datasets, the lattice's cells (hexahedra, quads or segments).
    pub cells: Cells,
    /// The arrays of POINT_DATA.
    pub point_data: Vec<DataArray>,
    /// The arrays of CELL_DATA.
    pub cell_data: Vec<DataArray>,
    /// The `TimeValue` of the dataset's FIELD block (foamToVTK writes the snapshot's time there), s.
    pub time_value: Option<f64>,
    /// The line of the POINT_DATA and CELL_DATA headers, for messages (the last line where a section is absent).
    section_lines: [usize; 2],
}

impl VtkFile {
    /// Reads and parses the file at `path`.
    pub fn read(path: &Path) -> Result<VtkFile, VtkError> {
        let file = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|source| VtkError::Io { file: file.clone(), source })?;
        VtkFile::parse(&bytes, &file)
    }

    /// Parses the bytes of a file; `file` names it in messages.
    pub fn parse(bytes: &[u8], file: &str) -> Result<VtkFile, VtkError> {
        parse::parse(bytes, file)
    }

    /// The arrays at `location`.
    pub fn data(&self, location: DataLocation) -> &[DataArray] {
        match location {
            DataLocation::Points => &self.point_data,
            DataLocation::Cells => &self.cell_data,
        }
    }

    /// The velocity array `name` (OpenFOAM's is `U`) at `location` as samples for a [`crate::SampledField`]: the
    /// x and y components at the points or at the cell centres (a third component is dropped), with the mesh's
    /// cells as the field's domain.
    pub fn velocity_samples(&self, name: &str, location: DataLocation) -> Result<FieldSamples, VtkError> {
        let section = match location {
            DataLocation::Points => ("POINT_DATA", self.section_lines[0]),
            DataLocation::Cells => ("CELL_DATA", self.section_lines[1]),
        };
        let arrays = self.data(location);
        let Some(array) = arrays.iter().find(|a| a.name == name) else {
            let names: Vec<&str> = arrays.iter().map(|a| a.name.as_str()).collect();
            let found = if names.is_empty() { "none".to_string() } else { names.join(", ") };
            return Err(self.error(section.1, format!("expected a {} array named {name}; found {found}", section.0)));
        };
        if !(2..=3).contains(&array.components) {
            return Err(self.error(
                array.line,
                format!("array {name} has {} components; a velocity needs 2 or 3", array.components),
            ));
        }
        let velocities: Vec<DVec2> =
            array.values.chunks_exact(array.components).map(|v| DVec2::new(v[0], v[1])).collect();
        let positions = match location {
            DataLocation::Points => self.points.clone(),
            DataLocation::Cells => (0..self.cells.len()).map(|i| self.cell_centre(i)).collect(),
        };
        Ok(FieldSamples {
            source: self.source.clone(),
            positions,
            velocities,
            mesh_points: self.points.clone(),
            cells: self.cells.clone(),
        })
    }

    /// The mean of cell `i`'s points (for a hexahedron or a quad with straight edges, a parallelogram's centre).
    fn cell_centre(&self, i: usize) -> [f64; 3] {
        let cell = self.cells.cell(i);
        let mut sum = [0.0; 3];
        for &p in cell {
            for (s, c) in sum.iter_mut().zip(self.points[p]) {
                *s += c;
            }
        }
        let n = cell.len().max(1) as f64;
        sum.map(|s| s / n)
    }

    fn error(&self, line: usize, message: String) -> VtkError {
        VtkError::Syntax { file: self.source.clone(), line, message }
    }
}
