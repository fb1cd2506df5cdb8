//! Where a loaded field is defined: the union of the mesh's cells seen from above (each cell as the convex hull of
//! its points' x and y), or the convex hull of all nodes when the file has no cells with an area.

use super::grid::BucketGrid;
use gc2d_geometry::DVec2;
use serde::{Deserialize, Serialize};

/// Convex polygons (counter-clockwise) whose union is the field's domain, with a grid over their bounding boxes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(crate) struct Domain {
    vertices: Vec<DVec2>,
    /// Polygon `i` is `vertices[offsets[i]..offsets[i + 1]]`.
    offsets: Vec<usize>,
    grid: BucketGrid,
    /// How far outside an edge a point may lie and still count as on it, m (round-off of the mesh's coordinates).
    tolerance: f64,
}

impl Domain {
    /// The domain of cells given as lists of points; `fallback` (the nodes) gives the hull used when no cell has an
    /// area. `scale` is the mesh's size, for the tolerance.
    pub fn new(cells: impl Iterator<Item = Vec<DVec2>>, fallback: &[DVec2], scale: f64) -> Domain {
        let mut vertices = Vec::new();
        let mut offsets = vec![0];
        let mut boxes = Vec::new();
        let mut push = |hull: Vec<DVec2>, vertices: &mut Vec<DVec2>, offsets: &mut Vec<usize>| {
            if hull.len() >= 3 {
                let lo = hull.iter().fold(DVec2::splat(f64::INFINITY), |a, p| a.min(*p));
                let hi = hull.iter().fold(DVec2::splat(f64::NEG_INFINITY), |a, p| a.max(*p));
                boxes.push((lo, hi));
                vertices.extend(hull);
                offsets.push(vertices.len());
            }
        };
        for cell in cells {
            push(convex_hull(cell), &mut vertices, &mut offsets);
        }
        if offsets.len() == 1 {
            push(convex_hull(fallback.to_vec()), &mut vertices, &mut offsets);
        }
        let grid = BucketGrid::new(&boxes, 2.0);
        Domain { vertices, offsets, grid, tolerance: 1e-9 * scale }
    }

    /// Whether `p` lies in a cell (its boundary included).
    pub fn contains(&self, p: DVec2) -> bool {
        if self.offsets.len() == 1 {
            return false;
        }
        let (i, j) = self.grid.clamped_cell(p);
        self.grid.bucket(i, j).iter().any(|&c| {
            let poly = &self.vertices[self.offsets[c as usize]..self.offsets[c as usize + 1]];
            (0..poly.len()).all(|k| {
                let a = poly[k];
                let edge = poly[(k + 1) % poly.len()] - a;
                edge.perp_dot(p - a) >= -self.tolerance * edge.length()
            })
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
