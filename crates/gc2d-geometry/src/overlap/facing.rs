//! The sides of two convex polygons that face each other, found once per pair for both ways of intersecting them
//! (the two-crossing walk and the clipper).
//!
//! Along t = mean(a) − mean(b), `b` reaches at most `top_b` and `a` at least `bottom_a`. When `top_b ≤ bottom_a`
//! the line between them separates the polygons. Otherwise only the edges of `b` that reach above `bottom_a` can
//! bound the overlap: a ∩ b = a ∩ b ∩ {x·t ≥ bottom_a}, and the part of `b` in that half-plane is cut out by the
//! edges that reach into it. Likewise only the edges of `a` that reach below `top_b` can meet `b`. In a shallow
//! contact that leaves about half of each outline. With t = 0 (equal vertex means) nothing is left out.

use crate::{DVec2, farthest_along, vertex_mean};

/// Where `a` and `b` face each other along the line joining their vertex means.
pub(crate) struct Facing {
    /// t = mean(a) − mean(b).
    pub(crate) towards: DVec2,
    /// Index of `b`'s vertex farthest towards `a` (the first of equals).
    pub(crate) top: usize,
    /// The farthest `b` reaches towards `a`.
    pub(crate) top_b: f64,
    /// Index of `a`'s vertex farthest towards `b` (the first of equals).
    pub(crate) bottom: usize,
    /// The least `a` reaches towards `b`.
    pub(crate) bottom_a: f64,
    /// False when the vertex means coincide: every edge is used.
    pub(crate) reduced: bool,
}

impl Facing {
    /// The facing sides of `a` and `b`, or `None` when a line across t separates them.
    pub(crate) fn of(a: &[DVec2], b: &[DVec2]) -> Option<Self> {
        let towards = vertex_mean(a) - vertex_mean(b);
        let (top, top_b) = farthest_along(b, towards);
        let reduced = towards != DVec2::ZERO;
        let (bottom, bottom_a) = if reduced {
            // p·(−t) = −(p·t) exactly, so this is the least reach along t.
            let (bottom, reach_back) = farthest_along(a, -towards);
            (bottom, -reach_back)
        } else {
            (0, 0.0)
        };
        if reduced && top_b <= bottom_a {
            return None;
        }
        Some(Self { towards, top, top_b, bottom, bottom_a, reduced })
    }

    /// Whether `b`'s edge from `p` to `q` lies wholly below `a` and so cannot bound the overlap.
    pub(crate) fn skips_edge_of_b(&self, p: DVec2, q: DVec2) -> bool {
        self.reduced && p.dot(self.towards) < self.bottom_a && q.dot(self.towards) < self.bottom_a
    }
}
