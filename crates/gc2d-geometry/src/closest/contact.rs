//! Touching and overlapping polygons: crossing edges near a contact, and the exhaustive O(n·m) answer that backs
//! up the walk (reference §4.3 step 7 and footnote 11, §10.4 degenerate contact geometry).
//!
//! An overlap is reported by a pair of edges whose interiors cross, preferring a crossing where the boundary of `a`
//! leaves `b`: two convex polygons in general position whose boundaries cross twice have exactly one such pair, so
//! warm and cold starts agree and the pair tracks the contact from step to step. Overlaps without a proper crossing
//! (one polygon inside the other, collinear edges of stacked rectangles, identical polygons) are reported by the
//! vertex deepest inside the other polygon.

use super::{Feature, FeaturePair, Separation, segments};
use crate::{DVec2, cross, cyclic_next, cyclic_previous};

/// Two edges whose interiors cross.
pub(super) struct Crossing {
    edge_a: usize,
    edge_b: usize,
    point: DVec2,
    /// The edge of `a` runs from inside `b` to outside: the boundary of `a` leaves `b` here.
    pub(super) a_leaves_b: bool,
}

impl Crossing {
    /// The overlap this crossing proves.
    pub(super) fn separation(&self, passes: u32) -> Separation {
        let features = FeaturePair { a: Feature::edge(self.edge_a), b: Feature::edge(self.edge_b) };
        Separation::overlapping(self.point, features, passes)
    }
}

/// The crossing of edge `i` of `a` and edge `j` of `b` when each edge has its end points strictly on opposite sides
/// of the other's line. Such a crossing means the interiors overlap.
#[inline]
pub(super) fn proper_crossing(a: &[DVec2], i: usize, b: &[DVec2], j: usize) -> Option<Crossing> {
    let (p0, p1) = (a[i], a[cyclic_next(i, a.len())]);
    let (q0, q1) = (b[j], b[cyclic_next(j, b.len())]);
    let dq = q1 - q0;
    let p0_inside = cross(dq, p0 - q0);
    let p1_inside = cross(dq, p1 - q0);
    if !strictly_opposite(p0_inside, p1_inside) {
        return None;
    }
    let dp = p1 - p0;
    if !strictly_opposite(cross(dp, q0 - p0), cross(dp, q1 - p0)) {
        return None;
    }
    let t = p0_inside / (p0_inside - p1_inside);
    Some(Crossing { edge_a: i, edge_b: j, point: p0 + dp * t, a_leaves_b: p0_inside > 0.0 })
}

#[inline]
fn strictly_opposite(x: f64, y: f64) -> bool {
    x > 0.0 && y < 0.0 || x < 0.0 && y > 0.0
}

/// The walk found contact near edge `edge_a` of `a` and edge `edge_b` of `b`: look for a crossing where `a` leaves
/// `b` among those edges and their ring neighbours (a 3 × 3 block), else answer exhaustively.
pub(super) fn resolve(a: &[DVec2], b: &[DVec2], edge_a: usize, edge_b: usize, passes: u32) -> Separation {
    let rows = [edge_a, cyclic_previous(edge_a, a.len()), cyclic_next(edge_a, a.len())];
    let columns = [edge_b, cyclic_previous(edge_b, b.len()), cyclic_next(edge_b, b.len())];
    for i in rows {
        for j in columns {
            if let Some(crossing) = proper_crossing(a, i, b, j).filter(|c| c.a_leaves_b) {
                return crossing.separation(passes);
            }
        }
    }
    exhaustive(a, b, passes + 1)
}

/// The first crossing where `a` leaves `b`, in index order, else the first crossing of any kind.
fn preferred_crossing(a: &[DVec2], b: &[DVec2]) -> Option<Crossing> {
    let mut entering = None;
    for i in 0..a.len() {
        for j in 0..b.len() {
            if let Some(crossing) = proper_crossing(a, i, b, j) {
                if crossing.a_leaves_b {
                    return Some(crossing);
                }
                entering.get_or_insert(crossing);
            }
        }
    }
    entering
}

/// The exact answer by exhaustive search, O(n·m): a crossing edge pair (lowest indices, leaving preferred), else
/// the deepest vertex when the interiors still overlap, else the nearest pair of edges.
pub(super) fn exhaustive(a: &[DVec2], b: &[DVec2], passes: u32) -> Separation {
    if let Some(crossing) = preferred_crossing(a, b) {
        return crossing.separation(passes);
    }
    if !has_separating_edge(a, b) && !has_separating_edge(b, a) {
        return deepest_vertex(a, b, passes);
    }
    nearest_edges(a, b, passes)
}

/// True when some edge line of `p` has all of `q` on or beyond it. For convex polygons the interiors are disjoint
/// exactly when such an edge exists in `p` or in `q` (separating-axis theorem in 2D).
fn has_separating_edge(p: &[DVec2], q: &[DVec2]) -> bool {
    (0..p.len()).any(|k| {
        let v = p[k];
        let d = p[cyclic_next(k, p.len())] - v;
        q.iter().all(|&w| cross(d, w - v) <= 0.0)
    })
}

/// The edge of `poly` that `x` lies furthest outside of, and that signed distance (negative: `x` is inside every
/// edge). Lowest index on ties.
pub(super) fn most_exposed_edge(poly: &[DVec2], x: DVec2) -> (usize, f64) {
    let mut best = (0, f64::NEG_INFINITY);
    for k in 0..poly.len() {
        let v = poly[k];
        let d = poly[cyclic_next(k, poly.len())] - v;
        let length = d.length();
        if length > 0.0 {
            let exposure = cross(x - v, d) / length;
            if exposure > best.1 {
                best = (k, exposure);
            }
        }
    }
    best
}

/// Overlap without crossing edges: the vertex (of `a` first, then `b`) lying deepest inside the other polygon,
/// paired with the other polygon's edge nearest to it.
fn deepest_vertex(a: &[DVec2], b: &[DVec2], passes: u32) -> Separation {
    let mut best_depth = f64::NEG_INFINITY;
    let mut best = (DVec2::ZERO, FeaturePair { a: Feature::vertex(0), b: Feature::vertex(0) });
    for (i, &v) in a.iter().enumerate() {
        let (k, exposure) = most_exposed_edge(b, v);
        if -exposure > best_depth {
            best_depth = -exposure;
            best = (v, FeaturePair { a: Feature::vertex(i), b: Feature::edge(k) });
        }
    }
    for (j, &w) in b.iter().enumerate() {
        let (k, exposure) = most_exposed_edge(a, w);
        if -exposure > best_depth {
            best_depth = -exposure;
            best = (w, FeaturePair { a: Feature::edge(k), b: Feature::vertex(j) });
        }
    }
    Separation::overlapping(best.0, best.1, passes)
}

/// Disjoint interiors: the closest pair over all edge pairs (first in index order on ties). Edges that meet give
/// distance exactly 0, with both points at the touching vertex.
fn nearest_edges(a: &[DVec2], b: &[DVec2], passes: u32) -> Separation {
    let mut best_squared = f64::INFINITY;
    let vertices = FeaturePair { a: Feature::vertex(0), b: Feature::vertex(0) };
    let mut best = Separation::apart(a[0], b[0], a[0].distance(b[0]), vertices, passes);
    for i in 0..a.len() {
        let i_next = cyclic_next(i, a.len());
        let (p0, p1) = (a[i], a[i_next]);
        for j in 0..b.len() {
            let j_next = cyclic_next(j, b.len());
            let (q0, q1) = (b[j], b[j_next]);
            let (mut pa, mut pb) = segments::closest_between(p0, p1, q0, q1);
            if segments::meet(p0, p1, q0, q1) {
                let vertex = if pa == p0 || pa == p1 { pa } else { pb };
                (pa, pb) = (vertex, vertex);
            }
            let squared = pa.distance_squared(pb);
            if squared < best_squared {
                best_squared = squared;
                let features =
                    FeaturePair { a: feature_at(pa, i, p0, i_next, p1), b: feature_at(pb, j, q0, j_next, q1) };
                best = Separation::apart(pa, pb, squared.sqrt(), features, passes);
            }
        }
    }
    best
}

/// The feature of edge `i` (from `v0`, vertex `i`, to `v1`, vertex `i_next`) that carries `x`.
fn feature_at(x: DVec2, i: usize, v0: DVec2, i_next: usize, v1: DVec2) -> Feature {
    if x == v0 {
        Feature::vertex(i)
    } else if x == v1 {
        Feature::vertex(i_next)
    } else {
        Feature::edge(i)
    }
}
