//! Bilinear interpolation on a rectilinear lattice of nodes (feedpipe.md §4.3, Eqs. 3.66–3.68): rows of nodes
//! parallel to x and y, spacings free along each axis.

use gc2d_geometry::DVec2;
use serde::{Deserialize, Serialize};

/// Nodes at every (xs[i], ys[j]) with their velocities.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(crate) struct Lattice {
    xs: Vec<f64>,
    ys: Vec<f64>,
    /// Velocity of node (i, j) at `i + xs.len() * j`, m/s.
    values: Vec<DVec2>,
}

/// Why nodes do not form a lattice.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct NotALattice {
    /// Distinct x and y coordinates and nodes found.
    pub columns: usize,
    /// Distinct y coordinates.
    pub rows: usize,
    /// Nodes.
    pub nodes: usize,
}

impl Lattice {
    /// The lattice of `nodes`, or why they are not one: at least two distinct x and y, and exactly one node at
    /// each (x, y) pair. Coordinates closer than `tolerance` are one.
    pub fn new(nodes: &[DVec2], velocities: &[DVec2], tolerance: f64) -> Result<Lattice, NotALattice> {
        let xs = distinct(nodes.iter().map(|p| p.x), tolerance);
        let ys = distinct(nodes.iter().map(|p| p.y), tolerance);
        let fail = NotALattice { columns: xs.len(), rows: ys.len(), nodes: nodes.len() };
        if xs.len() < 2 || ys.len() < 2 || xs.len() * ys.len() != nodes.len() {
            return Err(fail);
        }
        let mut values = vec![DVec2::ZERO; nodes.len()];
        let mut filled = vec![false; nodes.len()];
        for (p, v) in nodes.iter().zip(velocities) {
            let i = xs.partition_point(|&x| x <= p.x + tolerance) - 1;
            let j = ys.partition_point(|&y| y <= p.y + tolerance) - 1;
            let at = i + xs.len() * j;
            if filled[at] {
                return Err(fail);
            }
            filled[at] = true;
            values[at] = *v;
        }
        Ok(Lattice { xs, ys, values })
    }

    /// Whether `p` lies on the lattice's rectangle (its edges included).
    pub fn contains(&self, p: DVec2) -> bool {
        (self.xs[0]..=self.xs[self.xs.len() - 1]).contains(&p.x)
            && (self.ys[0]..=self.ys[self.ys.len() - 1]).contains(&p.y)
    }

    /// The point of the lattice's rectangle nearest to `p`.
    pub fn clamp(&self, p: DVec2) -> DVec2 {
        DVec2::new(p.x.clamp(self.xs[0], self.xs[self.xs.len() - 1]), p.y.clamp(self.ys[0], self.ys[self.ys.len() - 1]))
    }

    /// The bilinear interpolant at `p`, which must lie on the rectangle.
    pub fn interpolate(&self, p: DVec2) -> DVec2 {
        let nx = self.xs.len();
        let i = (self.xs.partition_point(|&x| x <= p.x).max(1) - 1).min(nx - 2);
        let j = (self.ys.partition_point(|&y| y <= p.y).max(1) - 1).min(self.ys.len() - 2);
        let (x1, x2, y1, y2) = (self.xs[i], self.xs[i + 1], self.ys[j], self.ys[j + 1]);
        let (a, b) = ((x2 - p.x) / (x2 - x1), (p.x - x1) / (x2 - x1));
        let v = |i: usize, j: usize| self.values[i + nx * j];
        let lower = a * v(i, j) + b * v(i + 1, j);
        let upper = a * v(i, j + 1) + b * v(i + 1, j + 1);
        ((y2 - p.y) * lower + (p.y - y1) * upper) / (y2 - y1)
    }
}

/// The distinct values, ascending, values within `tolerance` of a kept one counted as it.
fn distinct(values: impl Iterator<Item = f64>, tolerance: f64) -> Vec<f64> {
    let mut sorted: Vec<f64> = values.collect();
    sorted.sort_by(f64::total_cmp);
    let mut kept: Vec<f64> = Vec::new();
    for v in sorted {
        if kept.last().is_none_or(|&k| v - k > tolerance) {
            kept.push(v);
        }
    }
    kept
}
