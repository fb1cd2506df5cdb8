//! A velocity field sampled at the nodes of a mesh (a loaded CFD export), interpolated bilinearly on a lattice or
//! by Shepard's method on any point cloud, with the mesh's z-layers merged.

mod domain;
mod grid;
mod lattice;
mod shepard;

pub use grid::MAX_NEIGHBOURS;

use crate::field::{Outside, OutsideField};
use crate::vtk::Cells;
use domain::Domain;
use gc2d_geometry::DVec2;
use lattice::Lattice;
use serde::{Deserialize, Serialize};
use shepard::ShepardCloud;

/// Velocities at positions, with the mesh they came from: what [`crate::vtk::VtkFile::velocity_samples`] reads and
/// [`SampledField::new`] interpolates. Tests and tools may fill one by hand.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldSamples {
    /// Where the samples came from (a file name), for messages.
    pub source: String,
    /// Sample positions (x, y, z), m; z is dropped (the field lives in the x-y plane).
    pub positions: Vec<[f64; 3]>,
    /// Velocity (x, y) at each position, m/s.
    pub velocities: Vec<DVec2>,
    /// The mesh's points, which `cells` index, m.
    pub mesh_points: Vec<[f64; 3]>,
    /// The mesh's cells; their outlines seen from above make the field's domain. Without cells with an area, the
    /// domain is the convex hull of the positions.
    pub cells: Cells,
}

/// How a sampled field is interpolated between its nodes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Interpolation {
    /// Bilinear on a rectilinear lattice (feedpipe.md §4.3): exact for any field a + b·x + c·y + d·x·y. The merged
    /// nodes must form a lattice (rows parallel to x and y, spacings free), else [`SampledField::new`] refuses.
    Bilinear,
    /// Shepard's inverse-distance weighting (feedpipe.md §4.4) over the `neighbours` nearest nodes with weights
    /// h^−`power`; the thesis uses 4 neighbours and power 2 ([`Interpolation::SHEPARD_THESIS`]). Any point cloud.
    Shepard {
        /// The exponent p of the weights h^−p (> 0).
        power: f64,
        /// How many nearest nodes are weighted (1 to [`MAX_NEIGHBOURS`]).
        neighbours: usize,
    },
}

impl Interpolation {
    /// The thesis's Shepard settings: the 4 nearest nodes, power 2.
    pub const SHEPARD_THESIS: Interpolation = Interpolation::Shepard { power: 2.0, neighbours: 4 };
}

/// Why samples cannot make a field.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SampledError {
    /// No samples at all.
    #[error("{file}: no velocity samples")]
    Empty {
        /// Where the samples came from.
        file: String,
    },
    /// Positions and velocities differ in number.
    #[error("{file}: {positions} positions but {velocities} velocities")]
    Mismatch {
        /// Where the samples came from.
        file: String,
        /// Positions given.
        positions: usize,
        /// Velocities given.
        velocities: usize,
    },
    /// A position or velocity is not finite.
    #[error("{file}: sample {index} has a non-finite position or velocity")]
    NonFinite {
        /// Where the samples came from.
        file: String,
        /// The sample's index.
        index: usize,
    },
    /// Bilinear interpolation was asked of nodes that are no lattice.
    #[error(
        "{file}: bilinear interpolation needs the nodes on a rectilinear lattice, but the {nodes} distinct (x, y) \
         nodes have {columns} distinct x and {rows} distinct y (use Shepard's method for this mesh)"
    )]
    NotALattice {
        /// Where the samples came from.
        file: String,
        /// Distinct x found.
        columns: usize,
        /// Distinct y found.
        rows: usize,
        /// Nodes after merging the z-layers.
        nodes: usize,
    },
    /// Shepard's power or neighbour count is out of range.
    #[error(
        "{file}: Shepard's power must be > 0 and finite and its neighbours 1 to {MAX_NEIGHBOURS}, not {power} and {neighbours}"
    )]
    Shepard {
        /// Where the samples came from.
        file: String,
        /// The power given.
        power: f64,
        /// The neighbour count given.
        neighbours: usize,
    },
}

/// The interpolator of a sampled field.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
enum Interpolator {
    Bilinear(Lattice),
    Shepard(Box<ShepardCloud>),
}

/// A velocity field interpolated from samples at a mesh's nodes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SampledField {
    source: String,
    outside: Outside,
    nodes: usize,
    interpolator: Interpolator,
}

impl SampledField {
    /// The field of `samples`: the z-layers merged ([`merge_layers`]), the domain made from the cells, and the
    /// interpolator set up; `outside` says what points off the mesh get.
    pub fn new(samples: &FieldSamples, interpolation: Interpolation, outside: Outside) -> Result<Self, SampledError> {
        let file = samples.source.clone();
        if samples.positions.len() != samples.velocities.len() {
            return Err(SampledError::Mismatch {
                file,
                positions: samples.positions.len(),
                velocities: samples.velocities.len(),
            });
        }
        if samples.positions.is_empty() {
            return Err(SampledError::Empty { file });
        }
        let bad = samples
            .positions
            .iter()
            .zip(&samples.velocities)
            .position(|(p, v)| !(p.iter().all(|c| c.is_finite()) && v.is_finite()));
        if let Some(index) = bad {
            return Err(SampledError::NonFinite { file, index });
        }
        let (nodes, velocities, scale) = merge_layers(&samples.positions, &samples.velocities);
        let tolerance = 1e-9 * scale;
        let node_count = nodes.len();
        let interpolator = match interpolation {
            Interpolation::Bilinear => match Lattice::new(&nodes, &velocities, tolerance) {
                Ok(lattice) => Interpolator::Bilinear(lattice),
                Err(e) => {
                    return Err(SampledError::NotALattice { file, columns: e.columns, rows: e.rows, nodes: e.nodes });
                }
            },
            Interpolation::Shepard { power, neighbours } => {
                if !(power > 0.0 && power.is_finite() && (1..=MAX_NEIGHBOURS).contains(&neighbours)) {
                    return Err(SampledError::Shepard { file, power, neighbours });
                }
                let points = &samples.mesh_points;
                let cells = (0..samples.cells.len()).map(|c| {
                    samples
                        .cells
                        .cell(c)
                        .iter()
                        .filter_map(|&i| points.get(i))
                        .map(|p| DVec2::new(p[0], p[1]))
                        .collect()
                });
                let domain = Domain::new(cells, &nodes, scale);
                Interpolator::Shepard(Box::new(ShepardCloud::new(nodes, velocities, domain, power, neighbours)))
            }
        };
        Ok(SampledField { source: file, outside, nodes: node_count, interpolator })
    }

    /// Clears the file name ([`crate::FluidField::same_flow`]).
    pub(crate) fn forget_source(&mut self) {
        self.source.clear();
    }

    /// Where the samples came from (a file name), for messages.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// The number of distinct (x, y) nodes after merging the z-layers.
    pub fn node_count(&self) -> usize {
        self.nodes
    }

    /// The velocity at `x`, m/s: interpolated inside the mesh, and outside it as [`Outside`] says.
    pub fn velocity(&self, x: DVec2) -> Result<DVec2, OutsideField> {
        let inside = match &self.interpolator {
            Interpolator::Bilinear(lattice) => lattice.contains(x),
            Interpolator::Shepard(cloud) => cloud.domain.contains(x),
        };
        if inside {
            return Ok(match &self.interpolator {
                Interpolator::Bilinear(lattice) => lattice.interpolate(x),
                Interpolator::Shepard(cloud) => cloud.interpolate(x),
            });
        }
        match self.outside {
            Outside::Zero => Ok(DVec2::ZERO),
            Outside::Nearest => Ok(match &self.interpolator {
                Interpolator::Bilinear(lattice) => lattice.interpolate(lattice.clamp(x)),
                Interpolator::Shepard(cloud) => cloud.nearest_node(x),
            }),
            Outside::Error => Err(OutsideField { file: self.source.clone(), position: x }),
        }
    }
}

/// Merges samples that share (x, y) (the two z-layers of a one-cell-thick 2D OpenFOAM mesh, feedpipe.md §4.2
/// and §4.4 pitfall a): one node per (x, y), its velocity the mean of the merged samples'. Positions count as equal
/// where x and y agree after rounding to 1e-9 of the mesh's larger extent. Returns the nodes (in the order of their
/// first sample), their velocities and that extent (m; 1 for a single point).
pub fn merge_layers(positions: &[[f64; 3]], velocities: &[DVec2]) -> (Vec<DVec2>, Vec<DVec2>, f64) {
    let xy: Vec<DVec2> = positions.iter().map(|p| DVec2::new(p[0], p[1])).collect();
    let lo = xy.iter().fold(DVec2::splat(f64::INFINITY), |a, p| a.min(*p));
    let hi = xy.iter().fold(DVec2::splat(f64::NEG_INFINITY), |a, p| a.max(*p));
    let extent = (hi - lo).max_element();
    let scale = if extent > 0.0 { extent } else { 1.0 };
    let step = 1e-9 * scale;
    let key = |p: DVec2| {
        let q = ((p - lo) / step).round();
        (q.x as i64, q.y as i64)
    };
    let mut order: Vec<usize> = (0..xy.len()).collect();
    order.sort_by_key(|&i| (key(xy[i]), i));
    // Each group (equal keys, in sample order) becomes one node, placed at its first sample.
    let mut groups: Vec<(usize, DVec2)> = Vec::new();
    let mut k = 0;
    while k < order.len() {
        let first = order[k];
        let mut sum = DVec2::ZERO;
        let mut n = 0;
        while k < order.len() && key(xy[order[k]]) == key(xy[first]) {
            sum += velocities[order[k]];
            n += 1;
            k += 1;
        }
        groups.push((first, sum / n as f64));
    }
    groups.sort_by_key(|g| g.0);
    let nodes = groups.iter().map(|g| xy[g.0]).collect();
    let merged = groups.iter().map(|g| g.1).collect();
    (nodes, merged, scale)
}
