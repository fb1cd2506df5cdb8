//! Distance and closest features of two convex polygons: Lin's closest-feature walk in 2D (reference §4.3).
//!
//! Each polygon is a ring of alternating vertices and edges. Edge `i` runs from vertex `i` to vertex `(i + 1) % n`
//! with the polygon on its left. The Voronoi region of an edge is the outer half-strip between the perpendiculars at
//! its end points; that of a vertex is the wedge between the perpendiculars to its two edges. Given a feature pair,
//! the walk computes the closest points of the two features and checks each against the other feature's region;
//! when a check fails it steps to the neighbouring feature across the violated boundary and repeats. When both pass,
//! the two points are mutually closest and their distance is the polygons' distance (Abb. 2.16).
//!
//! Warm-started from the previous step's features, the walk usually stops in its first pass. Contact — a closest
//! point inside the other polygon (footnote 11) or features that meet — hands over to the `contact` module, which
//! finds a crossing pair of edges near the contact and falls back to an exhaustive search; a walk that exceeds its
//! iteration cap falls back to that search too. Nothing here allocates or panics.

mod contact;
mod segments;

use crate::{DVec2, cross, cyclic_next, cyclic_previous, farthest_along, vertex_mean};
use serde::{Deserialize, Serialize};

/// A feature of a polygon's boundary ring. The index is a byte (polygons have at most
/// [`MAX_VERTICES`](crate::MAX_VERTICES) vertices), so that the engine's warm start of every pair takes 4 bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Feature {
    /// Vertex `i`.
    Vertex(u8),
    /// Edge `i`, from vertex `i` to vertex `(i + 1) % n`, the polygon on its left.
    Edge(u8),
}

const _: () = assert!(crate::MAX_VERTICES <= 256, "feature indices are bytes");

impl Feature {
    /// Vertex `i` (< [`MAX_VERTICES`](crate::MAX_VERTICES)).
    #[inline]
    pub fn vertex(i: usize) -> Self {
        Feature::Vertex(i as u8)
    }

    /// Edge `i` (< [`MAX_VERTICES`](crate::MAX_VERTICES)).
    #[inline]
    pub fn edge(i: usize) -> Self {
        Feature::Edge(i as u8)
    }

    /// The vertex or edge index.
    #[inline]
    pub fn index(self) -> usize {
        match self {
            Feature::Vertex(i) | Feature::Edge(i) => usize::from(i),
        }
    }
}

/// One feature of each polygon: what the engine stores per contact to warm-start the next step's query.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct FeaturePair {
    /// Feature of the first polygon.
    pub a: Feature,
    /// Feature of the second polygon.
    pub b: Feature,
}

impl FeaturePair {
    /// True when both indices exist on polygons with `n_a` and `n_b` vertices.
    fn fits(&self, n_a: usize, n_b: usize) -> bool {
        self.a.index() < n_a && self.b.index() < n_b
    }
}

/// The result of [`closest_features`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Separation {
    /// Distance between the polygons, ≥ 0; exactly 0.0 when they touch or interpenetrate.
    pub distance: f64,
    /// Closest point on `a`. When the polygons touch or overlap: a point of `a` inside or on `b`.
    pub point_a: DVec2,
    /// Closest point on `b`. When the polygons overlap it equals `point_a`.
    pub point_b: DVec2,
    /// The features carrying the two points (for overlaps: a crossing edge pair or a vertex and its nearest edge).
    pub features: FeaturePair,
    /// Feature pairs the walk examined, counting a contact search or the exhaustive fallback as one more
    /// (1 = the start pair was already closest).
    pub passes: u32,
    /// True when the interiors overlap: the walk's worst case of reference §4.3 footnote 11.
    pub penetrating: bool,
}

/// Distance, closest points and closest features of two convex polygons given as world-frame counter-clockwise
/// vertex slices (3 to [`MAX_VERTICES`](crate::MAX_VERTICES) vertices, validated convex as by
/// [`ConvexPolygon::new`](crate::ConvexPolygon::new)).
///
/// `warm_start` is the previous step's [`Separation::features`]; `None` (or out-of-range indices) starts from the
/// vertices most extreme towards each other along the line between the vertex means. Overlapping polygons report
/// distance 0 with `penetrating` set. An empty slice yields an infinite distance.
pub fn closest_features(a: &[DVec2], b: &[DVec2], warm_start: Option<FeaturePair>) -> Separation {
    if a.is_empty() || b.is_empty() {
        return Separation::undefined();
    }
    let start = match warm_start {
        Some(pair) if pair.fits(a.len(), b.len()) => pair,
        _ => cold_start(a, b),
    };
    // A persisting overlap: the stored pair still crosses with `a` leaving `b`, so nothing needs to move.
    if let (Feature::Edge(i), Feature::Edge(j)) = (start.a, start.b) {
        if let Some(crossing) = contact::proper_crossing(a, i.into(), b, j.into()).filter(|c| c.a_leaves_b) {
            return crossing.separation(1);
        }
    }
    walk(a, b, start)
}

impl Separation {
    /// The answer for an empty polygon: nothing to measure, never in contact.
    fn undefined() -> Self {
        let vertex = Feature::vertex(0);
        Self {
            distance: f64::INFINITY,
            point_a: DVec2::ZERO,
            point_b: DVec2::ZERO,
            features: FeaturePair { a: vertex, b: vertex },
            passes: 0,
            penetrating: false,
        }
    }

    /// Polygons apart (or touching) with mutually closest points `point_a`, `point_b` at `distance`.
    fn apart(point_a: DVec2, point_b: DVec2, distance: f64, features: FeaturePair, passes: u32) -> Self {
        Self { distance, point_a, point_b, features, passes, penetrating: false }
    }

    /// Overlapping polygons, witnessed by a point common to both.
    fn overlapping(point: DVec2, features: FeaturePair, passes: u32) -> Self {
        Self { distance: 0.0, point_a: point, point_b: point, features, passes, penetrating: true }
    }
}

/// Start pair without history: the vertex of `a` furthest towards `b` and the vertex of `b` furthest towards `a`,
/// measured along the line between the vertex means (lowest index on ties).
fn cold_start(a: &[DVec2], b: &[DVec2]) -> FeaturePair {
    let axis = vertex_mean(b) - vertex_mean(a);
    let (a_front, _) = farthest_along(a, axis);
    let (b_front, _) = farthest_along(b, -axis);
    FeaturePair { a: Feature::vertex(a_front), b: Feature::vertex(b_front) }
}

/// Most passes before the walk gives up: twice the number of features of both rings. A converging walk moves
/// monotonically around each ring and needs at most one pass per feature; only cycling on degenerate input hits this.
fn pass_cap(n_a: usize, n_b: usize) -> u32 {
    (2 * (n_a + n_b) + 2) as u32
}

/// What one pass of the walk decided.
enum Step {
    /// Both closest points lie in the other feature's Voronoi region: they realise the distance.
    Closest { point_a: DVec2, point_b: DVec2, distance: f64 },
    /// Replace the feature of `a` by this neighbour.
    MoveA(Feature),
    /// Replace the feature of `b` by this neighbour.
    MoveB(Feature),
    /// The features meet, or a closest point lies inside the other polygon: the distance is 0. The edges name where.
    Contact { edge_a: usize, edge_b: usize },
}

impl Step {
    /// The same decision with the roles of the two polygons exchanged.
    fn swapped(self) -> Self {
        match self {
            Step::Closest { point_a, point_b, distance } => {
                Step::Closest { point_a: point_b, point_b: point_a, distance }
            }
            Step::MoveA(f) => Step::MoveB(f),
            Step::MoveB(f) => Step::MoveA(f),
            Step::Contact { edge_a, edge_b } => Step::Contact { edge_a: edge_b, edge_b: edge_a },
        }
    }
}

/// The feature walk (reference §4.3, steps 1–7).
fn walk(a: &[DVec2], b: &[DVec2], start: FeaturePair) -> Separation {
    let cap = pass_cap(a.len(), b.len());
    let (mut fa, mut fb) = (start.a, start.b);
    for pass in 1..=cap {
        let step = match (fa, fb) {
            (Feature::Vertex(i), Feature::Vertex(j)) => vertex_vertex(a, i.into(), b, j.into()),
            (Feature::Vertex(i), Feature::Edge(j)) => vertex_edge(a, i.into(), b, j.into()),
            (Feature::Edge(i), Feature::Vertex(j)) => vertex_edge(b, j.into(), a, i.into()).swapped(),
            (Feature::Edge(i), Feature::Edge(j)) => edge_edge(a, i.into(), b, j.into()),
        };
        match step {
            Step::Closest { point_a, point_b, distance } => {
                let features = FeaturePair { a: fa, b: fb };
                return Separation::apart(point_a, point_b, distance, features, pass);
            }
            Step::MoveA(f) => fa = f,
            Step::MoveB(f) => fb = f,
            Step::Contact { edge_a, edge_b } => return contact::resolve(a, b, edge_a, edge_b, pass + 1),
        }
    }
    contact::exhaustive(a, b, cap + 1)
}

/// Checks the direction `towards` (from vertex `i` of `poly` to a point) against the vertex's wedge and names the
/// neighbouring edge across a violated boundary. A direction passing both tests lies in the vertex's normal cone,
/// which meets the polygon only at the vertex, so no inside test is needed here.
#[inline]
fn leave_vertex_region(poly: &[DVec2], i: usize, towards: DVec2) -> Option<Feature> {
    let n = poly.len();
    let v = poly[i];
    if towards.dot(poly[cyclic_next(i, n)] - v) > 0.0 {
        return Some(Feature::edge(i));
    }
    let i_prev = cyclic_previous(i, n);
    if towards.dot(v - poly[i_prev]) < 0.0 {
        return Some(Feature::edge(i_prev));
    }
    None
}

/// Where a point lies relative to an edge's Voronoi region.
enum EdgeRegion {
    /// Inside the half-strip (boundaries count as inside), with the perpendicular from the point to the edge.
    Inside(Perpendicular),
    /// Outside, across the boundary shared with this neighbouring feature.
    Leave(Feature),
    /// In the closed polygon itself; the edge is the one nearest to the point.
    InPolygon(usize),
}

/// The perpendicular from a point in an edge's region down to the edge.
struct Perpendicular {
    /// Where it meets the edge.
    foot: DVec2,
    /// Its length: the point's distance from the edge.
    length: f64,
    /// Its direction from the point to the edge, scaled by the edge length.
    direction: DVec2,
}

/// Checks `x` against the half-strip of edge `i` of `poly`. A point behind the edge's line (footnote 11) is either
/// outside another edge — step to the edge it is furthest outside of, as in Lin's local-minimum escape — or inside
/// the polygon. A point exactly on the edge counts as inside the polygon, so touching is reported as contact.
#[inline]
fn edge_region(poly: &[DVec2], i: usize, x: DVec2) -> EdgeRegion {
    let i_next = cyclic_next(i, poly.len());
    let (v0, v1) = (poly[i], poly[i_next]);
    let d = v1 - v0;
    let offset = x - v0;
    let along = offset.dot(d);
    if along < 0.0 {
        return EdgeRegion::Leave(Feature::vertex(i));
    }
    let length_squared = d.length_squared();
    if along > length_squared {
        return EdgeRegion::Leave(Feature::vertex(i_next));
    }
    let outward = cross(offset, d);
    if outward > 0.0 {
        // Division and square root are independent, so their latencies overlap.
        return EdgeRegion::Inside(Perpendicular {
            foot: v0 + d * (along / length_squared),
            length: outward / length_squared.sqrt(),
            direction: d.perp(),
        });
    }
    if outward == 0.0 {
        return EdgeRegion::InPolygon(i);
    }
    match contact::most_exposed_edge(poly, x) {
        (k, exposure) if exposure > 0.0 => EdgeRegion::Leave(Feature::edge(k)),
        (k, _) => EdgeRegion::InPolygon(k),
    }
}

fn vertex_vertex(a: &[DVec2], i: usize, b: &[DVec2], j: usize) -> Step {
    let (p, q) = (a[i], b[j]);
    if p == q {
        return Step::Contact { edge_a: i, edge_b: j };
    }
    if let Some(f) = leave_vertex_region(a, i, q - p) {
        return Step::MoveA(f);
    }
    if let Some(f) = leave_vertex_region(b, j, p - q) {
        return Step::MoveB(f);
    }
    Step::Closest { point_a: p, point_b: q, distance: (p - q).length() }
}

/// Vertex `i` of `p_poly` against edge `j` of `q_poly`, decided in (vertex polygon, edge polygon) order.
fn vertex_edge(p_poly: &[DVec2], i: usize, q_poly: &[DVec2], j: usize) -> Step {
    let p = p_poly[i];
    let perpendicular = match edge_region(q_poly, j, p) {
        EdgeRegion::Inside(perpendicular) => perpendicular,
        EdgeRegion::Leave(f) => return Step::MoveB(f),
        EdgeRegion::InPolygon(k) => return Step::Contact { edge_a: i, edge_b: k },
    };
    // The foot is seen from the vertex along the perpendicular's direction: test that instead of the foot itself.
    if let Some(f) = leave_vertex_region(p_poly, i, perpendicular.direction) {
        return Step::MoveA(f);
    }
    Step::Closest { point_a: p, point_b: perpendicular.foot, distance: perpendicular.length }
}

fn edge_edge(a: &[DVec2], i: usize, b: &[DVec2], j: usize) -> Step {
    let (p0, p1) = (a[i], a[cyclic_next(i, a.len())]);
    let (q0, q1) = (b[j], b[cyclic_next(j, b.len())]);
    if segments::meet(p0, p1, q0, q1) {
        return Step::Contact { edge_a: i, edge_b: j };
    }
    let (pa, pb) = segments::closest_between(p0, p1, q0, q1);
    match edge_region(a, i, pb) {
        EdgeRegion::Inside(_) => {}
        EdgeRegion::Leave(f) => return Step::MoveA(f),
        EdgeRegion::InPolygon(k) => return Step::Contact { edge_a: k, edge_b: j },
    }
    match edge_region(b, j, pa) {
        EdgeRegion::Inside(_) => {}
        EdgeRegion::Leave(f) => return Step::MoveB(f),
        EdgeRegion::InPolygon(k) => return Step::Contact { edge_a: i, edge_b: k },
    }
    Step::Closest { point_a: pa, point_b: pb, distance: (pa - pb).length() }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    fn v(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    fn rectangle(x0: f64, y0: f64, x1: f64, y1: f64) -> [DVec2; 4] {
        [v(x0, y0), v(x1, y0), v(x1, y1), v(x0, y1)]
    }

    /// Every feature of a polygon with `n` vertices.
    fn features(n: usize) -> impl Iterator<Item = Feature> {
        (0..n).flat_map(|i| [Feature::vertex(i), Feature::edge(i)])
    }

    /// The answer from a cold start and from every possible warm start, all of which must agree on the distance
    /// and the penetration flag.
    fn all_starts(a: &[DVec2], b: &[DVec2]) -> Vec<Separation> {
        let mut results = vec![closest_features(a, b, None)];
        for fa in features(a.len()) {
            for fb in features(b.len()) {
                results.push(closest_features(a, b, Some(FeaturePair { a: fa, b: fb })));
            }
        }
        let cold = results[0];
        for r in &results {
            assert!((r.distance - cold.distance).abs() <= 1e-15, "{r:?} vs cold {cold:?}");
            assert_eq!(r.penetrating, cold.penetrating, "{r:?} vs cold {cold:?}");
            assert!(r.passes <= pass_cap(a.len(), b.len()) + 2);
        }
        results
    }

    #[test]
    fn vertex_facing_edge_gives_its_height() {
        let a = rectangle(0.0, 0.0, 1.0, 1.0);
        let b = [v(0.3, 1.25), v(1.0, 2.0), v(0.0, 2.0)];
        for r in all_starts(&a, &b) {
            assert_eq!(r.distance, 0.25);
            assert_eq!(r.features, FeaturePair { a: Feature::edge(2), b: Feature::vertex(0) });
            assert!((r.point_a - v(0.3, 1.0)).length() < 1e-15);
            assert_eq!(r.point_b, v(0.3, 1.25));
        }
    }

    #[test]
    fn vertex_facing_vertex_gives_corner_distance() {
        let a = rectangle(0.0, 0.0, 1.0, 1.0);
        let b = rectangle(4.0, 5.0, 5.0, 6.0);
        for r in all_starts(&a, &b) {
            assert_eq!(r.distance, 5.0);
            assert_eq!(r.features, FeaturePair { a: Feature::vertex(2), b: Feature::vertex(0) });
        }
    }

    #[test]
    fn parallel_edges_facing_each_other_give_the_gap() {
        let a = rectangle(0.0, 0.0, 1.0, 1.0);
        let b = rectangle(1.5, 0.25, 2.5, 1.25);
        for r in all_starts(&a, &b) {
            assert_eq!(r.distance, 0.5);
            assert!(!r.penetrating);
            assert_eq!(r.point_a.x, 1.0);
            assert_eq!(r.point_b.x, 1.5);
            assert_eq!(r.point_a.y, r.point_b.y);
            assert!((0.25..=1.0).contains(&r.point_a.y));
        }
        let warm = FeaturePair { a: Feature::edge(1), b: Feature::edge(3) };
        let r = closest_features(&a, &b, Some(warm));
        assert_eq!((r.point_a, r.point_b, r.features, r.passes), (v(1.0, 0.625), v(1.5, 0.625), warm, 1));
    }

    #[test]
    fn vertex_exactly_on_edge_touches_without_penetrating() {
        let a = rectangle(0.0, 0.0, 1.0, 1.0);
        let b = [v(0.5, 1.0), v(1.0, 2.0), v(0.0, 2.0)];
        for r in all_starts(&a, &b) {
            assert_eq!(r.distance, 0.0);
            assert!(!r.penetrating);
            assert_eq!(r.point_a, v(0.5, 1.0));
        }
    }

    #[test]
    fn edge_sharing_rectangles_touch_without_penetrating() {
        let a = rectangle(0.0, 0.0, 1.0, 1.0);
        for b in [rectangle(1.0, 0.0, 2.0, 1.0), rectangle(1.0, 0.5, 2.0, 1.5), rectangle(1.0, 1.0, 2.0, 2.0)] {
            for r in all_starts(&a, &b) {
                assert_eq!(r.distance, 0.0);
                assert!(!r.penetrating);
                assert_eq!(r.point_a.x, 1.0);
            }
        }
    }

    #[test]
    fn collinear_overlap_without_crossing_is_penetrating() {
        // Stacked rectangles overlapping by half: boundaries meet only at vertices and along collinear edges.
        let a = rectangle(0.0, 0.0, 2.0, 2.0);
        let b = rectangle(1.0, 0.0, 3.0, 2.0);
        for r in all_starts(&a, &b) {
            assert_eq!(r.distance, 0.0);
            assert!(r.penetrating);
            assert_eq!(r.point_a, r.point_b);
            assert!((1.0..=2.0).contains(&r.point_a.x) && (0.0..=2.0).contains(&r.point_a.y));
        }
    }

    #[test]
    fn identical_polygons_penetrate() {
        let a = [v(0.0, 0.0), v(2.0, -0.5), v(3.0, 1.0), v(1.0, 2.5), v(-0.5, 1.0)];
        for r in all_starts(&a, &a) {
            assert_eq!(r.distance, 0.0);
            assert!(r.penetrating);
            assert!(!r.distance.is_nan() && r.point_a.is_finite());
        }
        let cold = closest_features(&a, &a, None);
        assert_eq!(cold.features, FeaturePair { a: Feature::vertex(0), b: Feature::edge(0) });
        assert_eq!(cold.point_a, a[0]);
    }

    #[test]
    fn polygon_inside_another_penetrates_with_an_inner_vertex_as_witness() {
        let outer = rectangle(0.0, 0.0, 4.0, 4.0);
        let inner = [v(1.0, 1.0), v(2.0, 1.5), v(1.5, 2.0)];
        for (a, b) in [(&outer[..], &inner[..]), (&inner[..], &outer[..])] {
            for r in all_starts(a, b) {
                assert_eq!(r.distance, 0.0);
                assert!(r.penetrating);
                assert!(inner.contains(&r.point_a));
                assert_eq!(r.point_a, r.point_b);
            }
        }
        // The inner vertex furthest from the outer boundary: (2, 1.5) lies 1.5 from the bottom edge.
        let r = closest_features(&inner, &outer, None);
        assert_eq!(r.point_a, v(2.0, 1.5));
        assert_eq!(r.features, FeaturePair { a: Feature::vertex(1), b: Feature::edge(0) });
    }

    #[test]
    fn corner_poking_into_an_edge_reports_the_crossing_where_a_leaves_b() {
        let a = [v(0.0, 0.0), v(1.0, 0.0), v(0.5, 1.1)];
        let b = rectangle(-1.0, 1.0, 2.0, 2.0);
        for r in all_starts(&a, &b) {
            assert!(r.penetrating);
            // Edge 1 climbs into b, edge 2 comes back out through b's bottom edge at x = 0.5 − 0.5/11.
            assert_eq!(r.features, FeaturePair { a: Feature::edge(2), b: Feature::edge(0) });
            assert!((r.point_a - v(0.5 - 0.5 / 11.0, 1.0)).length() < 1e-15);
        }
    }

    #[test]
    fn warm_start_on_the_crossing_needs_one_pass() {
        let a = [v(0.0, 0.0), v(1.0, 0.0), v(0.5, 1.1)];
        let b = rectangle(-1.0, 1.0, 2.0, 2.0);
        let first = closest_features(&a, &b, None);
        let again = closest_features(&a, &b, Some(first.features));
        assert_eq!(again.passes, 1);
        assert_eq!(again.point_a, first.point_a);
    }

    #[test]
    fn out_of_range_warm_start_falls_back_to_cold_start() {
        let a = rectangle(0.0, 0.0, 1.0, 1.0);
        let b = rectangle(3.0, 0.0, 4.0, 1.0);
        let cold = closest_features(&a, &b, None);
        let stale = closest_features(&a, &b, Some(FeaturePair { a: Feature::edge(9), b: Feature::vertex(4) }));
        assert_eq!(cold, stale);
        assert_eq!(cold.distance, 2.0);
    }

    #[test]
    fn exhaustive_search_agrees_with_the_walk() {
        let square = rectangle(0.0, 0.0, 1.0, 1.0);
        let heptagon: Vec<DVec2> =
            (0..7).map(|k| v(2.5, 0.3) + DVec2::from_angle(0.4 + k as f64 * TAU / 7.0) * 0.9).collect();
        let triangle = [v(0.3, 1.25), v(1.0, 2.0), v(0.0, 2.0)];
        let far_square = rectangle(4.0, 5.0, 5.0, 6.0);
        for (a, b) in [(&square[..], &heptagon[..]), (&square, &triangle), (&heptagon, &far_square)] {
            let walked = closest_features(a, b, None);
            let searched = contact::exhaustive(a, b, 1);
            assert!(!searched.penetrating && searched.distance > 0.0);
            assert!((walked.distance - searched.distance).abs() <= 1e-15);
            assert!((walked.point_a - searched.point_a).length() <= 1e-15);
            assert!((walked.point_b - searched.point_b).length() <= 1e-15);
            assert_eq!(walked.features, searched.features);
        }
    }

    #[test]
    fn empty_polygon_is_infinitely_far() {
        let a = rectangle(0.0, 0.0, 1.0, 1.0);
        assert_eq!(closest_features(&a, &[], None).distance, f64::INFINITY);
        assert_eq!(closest_features(&[], &a, None).distance, f64::INFINITY);
    }
}
