//! Where a loaded field is defined: the union of the mesh's cells seen from above (each cell as the convex hull of
//! its points' x and y), or the convex hull of all nodes when the file has no cells with an area.

use super::grid::BucketGrid;
use gc2d_geometry::DVec2;
use serde::{Deserialize, Serialize};

/// Convex polygons whose union is the field's domain, each kept as its edges' lines, with a grid over their
/// bounding boxes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(crate) struct Domain {
    /// Per edge, the unit inward normal n and the offset n·a of a point a on it: inside is n·p ≥ offset − tolerance.
    edges: Vec<(DVec2, f64)>,
    /// Polygon `i`'s edges are `edges[offsets[i]..offsets[i + 1]]`.
    offsets: Vec<usize>,
    /// Each polygon's bounding box.
    boxes: Vec<(DVec2, DVec2)>,
    grid: BucketGrid,
    /// How far outside an edge a point may lie and still count as on it, m (round-off of the mesh's coordinates).
    tolerance: f64,
}

impl Domain {
    /// The domain of cells given as lists of points; `fallback` (the nodes) gives the hull used when no cell has an
    /// area. `scale` is the mesh's size, for the tolerance.
    pub fn new(cells: impl Iterator<Item = Vec<DVec2>>, fallback: &[DVec2], scale: f64) -> Domain {
        let mut domain = Domain {
            edges: Vec::new(),
            offsets: vec![0],
            boxes: Vec::new(),
            grid: BucketGrid::new(&[], 2.0),
            tolerance: 1e-9 * scale,
        };
        for cell in cells {
            domain.push(convex_hull(cell));
        }
        if domain.boxes.is_empty() {
            domain.push(convex_hull(fallback.to_vec()));
        }
        domain.grid = BucketGrid::new(&domain.boxes, 2.0);
        domain
    }

    /// Adds a convex polygon (counter-clockwise, at least three corners; a degenerate one is left out).
    fn push(&mut self, hull: Vec<DVec2>) {
        if hull.len() < 3 {
            return;
        }
        let lo = hull.iter().fold(DVec2::splat(f64::INFINITY), |a, p| a.min(*p));
        let hi = hull.iter().fold(DVec2::splat(f64::NEG_INFINITY), |a, p| a.max(*p));
        self.boxes.push((lo, hi));
        for (k, &a) in hull.iter().enumerate() {
            let normal = (hull[(k + 1) % hull.len()] - a).perp().normalize();
            self.edges.push((normal, normal.dot(a)));
        }
        self.offsets.push(self.edges.len());
    }

    /// Whether `p` lies in a cell (its boundary included).
    pub fn contains(&self, p: DVec2) -> bool {
        if self.boxes.is_empty() {
            return false;
        }
        let (i, j) = self.grid.clamped_cell(p);
        let t = self.tolerance;
        self.grid.bucket(i, j).iter().any(|&c| {
            let c = c as usize;
            let (lo, hi) = self.boxes[c];
            p.x >= lo.x - t
                && p.y >= lo.y - t
                && p.x <= hi.x + t
                && p.y <= hi.y + t
                && self.edges[self.offsets[c]..self.offsets[c + 1]].iter().all(|&(n, offset)| n.dot(p) >= offset - t)
        })
    }
}

/// The convex hull of `points` counter-clockwise without repeated or collinear points (Andrew's monotone chain);
/// fewer than three points where they have no area.
fn convex_hull(mut points: Vec<DVec2>) -> Vec<DVec2> {
    points.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    points.dedup();
    if points.len() < 3 {
        return Vec::new();
    }
    let mut hull: Vec<DVec2> = Vec::with_capacity(2 * points.len());
    for pass in 0..2 {
        let start = hull.len();
        for n in 0..points.len() {
            let p = if pass == 0 { points[n] } else { points[points.len() - 1 - n] };
            while hull.len() >= start + 2
                && (hull[hull.len() - 1] - hull[hull.len() - 2]).perp_dot(p - hull[hull.len() - 2]) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    if hull.len() < 3 { Vec::new() } else { hull }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_drops_inner_repeated_and_collinear_points() {
        let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.5), (0.5, 0.0), (1.0, 1.0)];
        let hull = convex_hull(square.iter().map(|&(x, y)| DVec2::new(x, y)).collect());
        assert_eq!(hull, vec![DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(0.0, 1.0)]);
        assert!(convex_hull(vec![DVec2::ZERO, DVec2::X, DVec2::X * 2.0]).is_empty());
    }

    #[test]
    fn an_l_shaped_mesh_excludes_its_notch() {
        let quad = |x: f64, y: f64| {
            vec![DVec2::new(x, y), DVec2::new(x + 1.0, y), DVec2::new(x + 1.0, y + 1.0), DVec2::new(x, y + 1.0)]
        };
        let domain = Domain::new([quad(0.0, 0.0), quad(1.0, 0.0), quad(0.0, 1.0)].into_iter(), &[], 2.0);
        assert!(domain.contains(DVec2::new(0.5, 0.5)));
        assert!(domain.contains(DVec2::new(1.0, 1.0)), "a shared corner");
        assert!(domain.contains(DVec2::new(2.0, 0.3)), "on the outer boundary");
        assert!(!domain.contains(DVec2::new(1.5, 1.5)), "the notch");
        assert!(!domain.contains(DVec2::new(2.0 + 1e-6, 0.3)));
    }
}
