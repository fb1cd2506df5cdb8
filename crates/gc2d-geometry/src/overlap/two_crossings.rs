//! The overlap of a plain contact, built from its two crossings instead of by clipping (reference §4.4: "walking
//! both rings from the first crossing").
//!
//! In almost every contact of a granular pile the outlines cross exactly twice, properly: `a`'s outline enters `b`
//! at c1 and leaves it at c2. The overlap is then `a`'s chain c1 → c2 (the vertices of `a` between them) and `b`'s
//! chain c2 → c1. Each edge of `a` that faces `b` is cut by the facing edge lines of `b` (Cyrus–Beck: the piece of
//! a segment inside a convex polygon lies between its last entry into and its first exit from the half-planes),
//! which finds both crossings, the edges of `a` and `b` they lie on, and so both chains, with a few side tests per
//! facing vertex and none of the clipper's copying.
//!
//! Anything else goes to the clipper, which resolves it by the policies of `docs/model.md`: a vertex exactly on
//! an edge line or a crossing exactly through a vertex (the tie rule), more than two crossings, none (containment
//! or no overlap), and a chord too short to carry a direction. Where the walk applies, the clipper would give the
//! same overlap up to round-off and call it [`ContactKind::Crossing`](super::ContactKind::Crossing) too (the tests
//! below hold them to each other).

use super::facing::Facing;
use super::{DEGENERATE_CHORD_FRACTION, positive_area};
use crate::{DVec2, cross, cyclic_next, cyclic_previous};

/// The most edges of `b` that may face `a` for the walk; a contact facing more goes to the clipper. 12 takes in
/// whole grains of up to 12 corners, which face a long wall whole: along t = mean(a) − mean(b), from a grain to the
/// middle of a wall far along it, every vertex of the grain reaches beyond the wall's far end.
const MAX_FACING_EDGES: usize = 12;

/// A point where `a`'s outline crosses `b`'s: on `a`'s edge `edge_of_a` (from vertex `edge_of_a` to the next) and
/// on `b`'s edge `edge_of_b`.
#[derive(Clone, Copy)]
struct Crossing {
    point: DVec2,
    edge_of_a: usize,
    edge_of_b: usize,
}

/// The overlap of a two-crossing contact of `a` with `b`: c1, the vertices of `a` inside `b`, c2, the vertices of
/// `b` inside `a`, counter-clockwise. Its area is positive and its chord long enough to carry a direction.
pub(crate) struct TwoCrossings<'p> {
    a: &'p [DVec2],
    b: &'p [DVec2],
    entry: Crossing,
    exit: Crossing,
    /// Twice the signed area, summed relative to c1 (as the clipper's ring sums relative to its first vertex).
    twice_area: f64,
    /// Σ (p + q) × cross(p, q) over the fan's triangles (p, q relative to c1): the centroid's numerator.
    weighted: DVec2,
}

impl TwoCrossings<'_> {
    /// Where `a`'s outline enters `b`.
    pub(crate) fn c1(&self) -> DVec2 {
        self.entry.point
    }

    /// Where `a`'s outline leaves `b`.
    pub(crate) fn c2(&self) -> DVec2 {
        self.exit.point
    }

    /// The overlap area, m².
    pub(crate) fn area(&self) -> f64 {
        0.5 * self.twice_area
    }

    /// The overlap's area centroid.
    pub(crate) fn centroid(&self) -> DVec2 {
        self.entry.point + self.weighted / (3.0 * self.twice_area)
    }

    /// The edges on which `a`'s outline leaves `b`: the warm start of [`two_crossings_from_exit`] in the next step.
    pub(crate) fn exit_edges(&self) -> (usize, usize) {
        (self.exit.edge_of_a, self.exit.edge_of_b)
    }

    /// Calls `visit` with the overlap's vertices, counter-clockwise, starting at c1.
    pub(crate) fn for_each_vertex(&self, mut visit: impl FnMut(DVec2)) {
        visit(self.entry.point);
        for_each_after(self.a, self.entry.edge_of_a, self.exit.edge_of_a, &mut visit);
        visit(self.exit.point);
        for_each_after(self.b, self.exit.edge_of_b, self.entry.edge_of_b, &mut visit);
    }

    /// Sums `twice_area` and `weighted` over the fan of triangles from c1. Always inlined (see `proper_crossing`).
    #[inline(always)]
    fn sum_moments(&mut self) {
        let origin = self.entry.point;
        let (mut twice_area, mut weighted) = (0.0, DVec2::ZERO);
        let mut previous = DVec2::ZERO;
        self.for_each_vertex(|p| {
            let current = p - origin;
            let c = cross(previous, current);
            twice_area += c;
            weighted += (previous + current) * c;
            previous = current;
        });
        (self.twice_area, self.weighted) = (twice_area, weighted);
    }
}

/// Calls `visit` with the vertices after `from` up to and including `to`, cyclically; none when `from == to`.
fn for_each_after(points: &[DVec2], from: usize, to: usize, visit: &mut impl FnMut(DVec2)) {
    let mut k = from;
    while k != to {
        k = cyclic_next(k, points.len());
        visit(points[k]);
    }
}

/// The two-crossing overlap of `a` and `b` (counter-clockwise convex polygons not separated by `facing`), or
/// `None` where the contact is anything else and the clipper must decide: ties, more or fewer than two crossings,
/// an area that is not positive or a chord too short to carry a direction.
///
/// Only the facing parts are looked at: `a`'s vertices that reach no farther than `b` along t (a contiguous run
/// around `a`'s bottom vertex) with the edges on either side, against the lines of `b`'s edges that reach `a`
/// (around `b`'s top vertex). Each vertex is tested against each of those lines once, and each edge of `a` is cut
/// by them from its two ends' sides (Cyrus–Beck: the piece of a segment inside a convex polygon lies between its
/// last entry into and its first exit from the half-planes).
pub(crate) fn two_crossings<'p>(a: &'p [DVec2], b: &'p [DVec2], facing: &Facing) -> Option<TwoCrossings<'p>> {
    if !facing.reduced {
        return None;
    }
    let t = facing.towards;
    let edges_of_a = facing_edges(a, facing.bottom, |p| p.dot(t) <= facing.top_b);
    let edges_of_b = facing_edges(b, facing.top, |p| p.dot(t) >= facing.bottom_a);
    let (n, m) = (a.len(), b.len());
    let line_count = edges_of_b.count;
    if line_count > MAX_FACING_EDGES {
        return None;
    }
    // The lines are b's facing edges, walked again for each vertex rather than kept in an array of
    // MAX_FACING_EDGES: zeroing that array (384 bytes, a call of memset) cost more than the few edges walked again.
    let sides_of = |p: DVec2, sides: &mut [f64; MAX_FACING_EDGES]| {
        let mut j = edges_of_b.first;
        for side in &mut sides[..line_count] {
            let after = cyclic_next(j, m);
            *side = cross(b[after] - b[j], p - b[j]);
            j = after;
        }
    };
    let (mut entry, mut exit) = (None, None);
    let mut i = edges_of_a.first;
    let (mut p_sides, mut q_sides) = ([0.0; MAX_FACING_EDGES], [0.0; MAX_FACING_EDGES]);
    sides_of(a[i], &mut p_sides);
    for _ in 0..edges_of_a.count {
        let after = cyclic_next(i, n);
        sides_of(a[after], &mut q_sides);
        if let Some(piece) = cut(&p_sides[..line_count], &q_sides[..line_count])? {
            let (p, q) = (a[i], a[after]);
            let at = |t: f64| p + (q - p) * t;
            let edge_of_b = |line: usize| (edges_of_b.first + line) % m;
            // A second entry or exit means more than two crossings: the clipper's case.
            if let Some(line) = piece.entry_line {
                first_only(&mut entry, Crossing { point: at(piece.entry), edge_of_a: i, edge_of_b: edge_of_b(line) })?;
            }
            if let Some(line) = piece.exit_line {
                first_only(&mut exit, Crossing { point: at(piece.exit), edge_of_a: i, edge_of_b: edge_of_b(line) })?;
            }
        }
        p_sides = q_sides;
        i = after;
    }
    let (entry, exit) = (entry?, exit?);
    if exit.edge_of_b == entry.edge_of_b {
        // On one edge of b the chain from c2 runs forwards to c1 (no vertex of b inside a), unless it goes round
        // all of b, which only a deep overlap does.
        let j = exit.edge_of_b;
        if (entry.point - exit.point).dot(b[cyclic_next(j, m)] - b[j]) <= 0.0 {
            return None;
        }
    }
    ring_between(a, b, entry, exit)
}

/// The two-crossing overlap of `a` and `b` found from the crossing where `a`'s outline left `b` in the last step
/// (edge `exit_a` of `a`, edge `exit_b` of `b`), or `None` where it is not found so and the full search must decide
/// ([`two_crossings`]). Where both find it, both give it bit for bit: the same crossings of the same edges, computed
/// alike. (The full walk also gives up on exact ties away from the crossings, which this one does not look at.)
///
/// The crossing must still be a proper one with `a` leaving `b`. From it, `a`'s vertices strictly inside `b` are
/// walked back and `b`'s strictly inside `a` forward, which ends each chain at the edge of the other crossing, and
/// that must be a proper crossing with `a` entering `b`. The ring c1, `a`'s chain, c2, `b`'s chain then lies in
/// `a ∩ b`, is simple (each chain's inside lies strictly inside the other polygon), and has `a` beyond its `a`-chain
/// and `b` beyond its `b`-chain, which makes it, where its area is positive, the whole of `a ∩ b`: the outlines cross
/// nowhere else. The side tests run over whole outlines without early exits, whose branches the processor could not
/// foresee (docs/performance.md, "Overlaps from the last exit"), but for one first test of the edge that usually
/// decides a vertex outside ([`strictly_inside`]).
pub(crate) fn two_crossings_from_exit<'p>(
    a: &'p [DVec2],
    b: &'p [DVec2],
    exit_a: usize,
    exit_b: usize,
) -> Option<TwoCrossings<'p>> {
    let (n, m) = (a.len(), b.len());
    if exit_a >= n || exit_b >= m {
        return None;
    }
    let exit = proper_crossing(a, exit_a, b, exit_b, Passage::Leaving)?;
    // The vertex of `a` that ends its chain lies beyond `b`'s edge of the entry, which is mostly the edge of the exit
    // (no vertex of `b` inside `a`); the vertex that ends `b`'s chain lies beyond `a`'s edge of the entry.
    let mut entry_a = exit_a;
    while strictly_inside(b, a[entry_a], exit_b) {
        entry_a = cyclic_previous(entry_a, n);
        if entry_a == exit_a {
            return None;
        }
    }
    let mut entry_b = exit_b;
    while strictly_inside(a, b[cyclic_next(entry_b, m)], entry_a) {
        entry_b = cyclic_next(entry_b, m);
        if entry_b == exit_b {
            return None;
        }
    }
    let entry = proper_crossing(a, entry_a, b, entry_b, Passage::Entering)?;
    // With no vertex between them on one outline, the chain along that edge must run forwards from one crossing to
    // the other (the other way round it would be the whole outline).
    if entry_a == exit_a && (exit.point - entry.point).dot(a[cyclic_next(entry_a, n)] - a[entry_a]) <= 0.0 {
        return None;
    }
    if entry_b == exit_b && (entry.point - exit.point).dot(b[cyclic_next(entry_b, m)] - b[entry_b]) <= 0.0 {
        return None;
    }
    ring_between(a, b, entry, exit)
}

/// The overlap bounded by `a`'s chain from `entry` to `exit` and `b`'s chain back, with its moments summed, where its
/// area is positive and its chord long enough to carry a direction. Always inlined, as its two callers' ends were.
#[inline(always)]
fn ring_between<'p>(a: &'p [DVec2], b: &'p [DVec2], entry: Crossing, exit: Crossing) -> Option<TwoCrossings<'p>> {
    let mut overlap = TwoCrossings { a, b, entry, exit, twice_area: 0.0, weighted: DVec2::ZERO };
    overlap.sum_moments();
    let area = overlap.area();
    let chord_carries_a_direction = (exit.point - entry.point).length() > DEGENERATE_CHORD_FRACTION * area.sqrt();
    (positive_area(area) && chord_carries_a_direction).then_some(overlap)
}

/// Which way `a`'s outline passes `b`'s at a crossing.
#[derive(Clone, Copy, PartialEq)]
enum Passage {
    Entering,
    Leaving,
}

/// The crossing of `a`'s edge `i` with `b`'s edge `j` where each edge's ends lie strictly on both sides of the
/// other's line and `a` passes into or out of `b` as `passage` says; else `None`. The point is computed as the full
/// walk computes it, from the sides of `a`'s ends to `b`'s edge line. Always inlined, as is `sum_moments`: left to the
/// compiler both were calls, and the dense 10,000-grain 7-gon pile ran 4 % slower (docs/performance.md, "Overlaps
/// from the last exit").
#[inline(always)]
fn proper_crossing(a: &[DVec2], i: usize, b: &[DVec2], j: usize, passage: Passage) -> Option<Crossing> {
    let (p, q) = (a[i], a[cyclic_next(i, a.len())]);
    let (start, end) = (b[j], b[cyclic_next(j, b.len())]);
    let edge_of_b = end - start;
    let (side_p, side_q) = (cross(edge_of_b, p - start), cross(edge_of_b, q - start));
    let (side_start, side_end) = (cross(q - p, start - p), cross(q - p, end - p));
    let crosses = match passage {
        Passage::Entering => (side_p < 0.0) & (side_q > 0.0) & (side_start > 0.0) & (side_end < 0.0),
        Passage::Leaving => (side_p > 0.0) & (side_q < 0.0) & (side_start < 0.0) & (side_end > 0.0),
    };
    crosses.then(|| Crossing { point: p + (q - p) * (side_p / (side_p - side_q)), edge_of_a: i, edge_of_b: j })
}

/// Whether `p` lies strictly inside the counter-clockwise convex polygon `points` (every side test positive; a NaN
/// is not). The edge `likely_outside` (from vertex `likely_outside` to the next) is tested first, and alone where `p`
/// is beyond it: the walks from an exit mostly end on a vertex beyond the other polygon's crossed edge, and that one
/// test instead of a whole outline's took 7 % off the dense 7-gon pile's instructions (docs/performance.md,
/// "The walk's last vertex tested against the crossed edge first"). The answer is the same with any `likely_outside`:
/// the edge is tested again with the others.
fn strictly_inside(points: &[DVec2], p: DVec2, likely_outside: usize) -> bool {
    let inner_side = |start: DVec2, end: DVec2| cross(end - start, p - start) > 0.0;
    if !inner_side(points[likely_outside], points[cyclic_next(likely_outside, points.len())]) {
        return false;
    }
    let mut inside = true;
    let mut start = points[points.len() - 1];
    for &end in points {
        inside &= inner_side(start, end);
        start = end;
    }
    inside
}

/// A run of consecutive edges of a polygon: `count` edges from edge `first` (from vertex `first` to the next) on.
struct EdgeRun {
    first: usize,
    count: usize,
}

/// The edges with at least one end among the vertices for which `facing` holds, which are consecutive around
/// `start` (a polygon's vertices on one side of a line are; `start` must be one of them): all edges when every
/// vertex faces.
fn facing_edges(points: &[DVec2], start: usize, facing: impl Fn(DVec2) -> bool) -> EdgeRun {
    let len = points.len();
    let mut first = start;
    loop {
        let before = cyclic_previous(first, len);
        if before == start {
            return EdgeRun { first: start, count: len };
        }
        if !facing(points[before]) {
            break;
        }
        first = before;
    }
    let mut last = start;
    while facing(points[cyclic_next(last, len)]) {
        last = cyclic_next(last, len);
    }
    // From the edge ending at the first facing vertex to the one starting at the last.
    EdgeRun { first: cyclic_previous(first, len), count: cyclic_distance(first, last, len) + 2 }
}

/// Where one edge of `a` lies inside `b`: its parameters of entry and exit and the facing lines it crosses there
/// (`None` where the edge starts or ends inside `b`).
struct EdgePiece {
    entry: f64,
    entry_line: Option<usize>,
    exit: f64,
    exit_line: Option<usize>,
}

/// The piece inside all facing lines of the edge whose ends have the sides `p_sides` and `q_sides` (Cyrus–Beck):
/// `Some(None)` when it misses them, `None` when a side is exactly zero (or NaN) or the piece shrinks to a point
/// (ties, for the clipper).
fn cut(p_sides: &[f64], q_sides: &[f64]) -> Option<Option<EdgePiece>> {
    let mut piece = EdgePiece { entry: 0.0, entry_line: None, exit: 1.0, exit_line: None };
    for (line, (&sp, &sq)) in p_sides.iter().zip(q_sides).enumerate() {
        // Exactly on a line (or NaN): the tie rule decides.
        if !(sp.abs() > 0.0 && sq.abs() > 0.0) {
            return None;
        }
        if sp < 0.0 && sq < 0.0 {
            return Some(None);
        }
        // The same parameter as the clipper's crossing p + (q − p)·sp/(sp − sq).
        let crossing = || sp / (sp - sq);
        if sp < 0.0 {
            let t = crossing();
            if t == piece.entry {
                return None;
            }
            if t > piece.entry {
                (piece.entry, piece.entry_line) = (t, Some(line));
            }
        } else if sq < 0.0 {
            let t = crossing();
            if t == piece.exit {
                return None;
            }
            if t < piece.exit {
                (piece.exit, piece.exit_line) = (t, Some(line));
            }
        }
    }
    match piece.entry.partial_cmp(&piece.exit)? {
        std::cmp::Ordering::Less => Some(Some(piece)),
        std::cmp::Ordering::Equal => None,
        std::cmp::Ordering::Greater => Some(None),
    }
}

/// Stores `crossing` in the empty `slot`; `None` when the slot already holds one.
fn first_only(slot: &mut Option<Crossing>, crossing: Crossing) -> Option<()> {
    slot.is_none().then(|| *slot = Some(crossing))
}

/// How many steps forward from `from` to `to` around a polygon of `len` vertices.
fn cyclic_distance(from: usize, to: usize, len: usize) -> usize {
    if to >= from { to - from } else { to + len - from }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::overlap::clip::{self, Ring};
    use crate::overlap::contact_from_overlap;
    use crate::{ContactKind, ConvexPolygon, Feature, FeaturePair, OverlapGeometry, Pose, contact_geometry};
    use proptest::prelude::*;
    use proptest::strategy::ValueTree;
    use proptest::test_runner::RngSeed;
    use std::f64::consts::PI;

    fn v(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    fn walk(a: &[DVec2], b: &[DVec2]) -> Option<(f64, DVec2, DVec2)> {
        let facing = Facing::of(a, b)?;
        let overlap = two_crossings(a, b, &facing)?;
        Some((overlap.area(), overlap.c1(), overlap.c2()))
    }

    /// The clipper's contact alone, for comparison.
    fn clipped(a: &[DVec2], b: &[DVec2]) -> Option<OverlapGeometry> {
        let facing = Facing::of(a, b)?;
        let (mut first, mut second) = (Ring::<64>::new(), Ring::<64>::new());
        let ring = clip::clip(a, b, &facing, &mut first, &mut second)?;
        let area = 0.5 * ring.twice_area();
        (area > 0.0).then(|| contact_from_overlap(ring.vertices(), area, a, b))
    }

    #[test]
    fn a_corner_pressed_into_an_edge_is_walked() {
        let b = [v(0.0, -1.0), v(1.0, -1.0), v(1.0, 0.0), v(0.0, 0.0)];
        let h = 0.01;
        // A triangle whose lower corner dips h below b's top edge: the overlap is the triangle's tip.
        let a = [v(0.5, -h), v(0.5 + 0.3, 0.5), v(0.5 - 0.2, 0.5)];
        let (area, c1, c2) = walk(&a, &b).expect("a plain two-crossing contact");
        let (left, right) = (0.5 - 0.2 * h / (0.5 + h), 0.5 + 0.3 * h / (0.5 + h));
        assert!((area - 0.5 * (right - left) * h).abs() < 1e-15);
        assert!((c1 - v(left, 0.0)).length() < 1e-15 && (c2 - v(right, 0.0)).length() < 1e-15);
        // b's corner inside a: the overlap's vertices come from b.
        let c = contact_geometry(&b, &a).unwrap();
        assert_eq!(c.kind, ContactKind::Crossing);
        assert!((c.area - area).abs() < 1e-15);
    }

    #[test]
    fn two_vertices_of_each_inside_the_other() {
        // Two squares side by side, one tilted a little, pressed 1 % of their size into each other.
        let b = [v(-0.5, -0.5), v(0.5, -0.5), v(0.5, 0.5), v(-0.5, 0.5)];
        let a = b.map(|p| Pose::new(v(0.99, 0.02), 0.05).apply(p));
        let (area, c1, c2) = walk(&a, &b).expect("walked");
        let reference = clipped(&a, &b).unwrap();
        assert!((area - reference.area).abs() <= 1e-14 * reference.area);
        assert!((c1 - reference.c1).length() < 1e-15 && (c2 - reference.c2).length() < 1e-15);
    }

    #[test]
    fn ties_and_deep_overlaps_are_left_to_the_clipper() {
        let b = [v(0.0, -1.0), v(1.0, -1.0), v(1.0, 0.0), v(0.0, 0.0)];
        // A vertex exactly on b's top edge line.
        assert!(walk(&[v(0.5, 0.0), v(0.9, 0.5), v(0.1, 0.5)], &b).is_none());
        // Edges along b's: stacked columns.
        assert!(walk(&[v(0.0, -0.1), v(1.0, -0.1), v(1.0, 0.9), v(0.0, 0.9)], &b).is_none());
        // Identical polygons (equal vertex means), one inside the other, and six crossings (a hexagram).
        assert!(walk(&b, &b).is_none());
        assert!(walk(&[v(0.4, -0.6), v(0.6, -0.6), v(0.5, -0.4)], &b).is_none());
        let triangle = |phase: f64| {
            [0.0, 1.0, 2.0].map(|k: f64| v((phase + k * 2.0 * PI / 3.0).cos(), (phase + k * 2.0 * PI / 3.0).sin()))
        };
        assert!(walk(&triangle(PI / 2.0), &triangle(-PI / 2.0)).is_none());
    }

    /// A random convex polygon of 3–12 vertices on an ellipse of semi-axis `size`, centred at the origin.
    fn outline(size: f64) -> impl Strategy<Value = Vec<DVec2>> {
        (prop::collection::vec(0.0..1.0f64, 3..=12), 0.3..1.0f64).prop_filter_map("degenerate", move |(f, aspect)| {
            let mut angles: Vec<f64> = f.iter().map(|f| 2.0 * PI * f).collect();
            angles.sort_by(f64::total_cmp);
            let points: Vec<DVec2> = angles.iter().map(|phi| size * v(phi.cos(), aspect * phi.sin())).collect();
            let (body, _) = ConvexPolygon::new(&points).ok()?;
            (body.inscribed_radius() > 0.05 * size).then(|| body.vertices().to_vec())
        })
    }

    /// `b` moved along `direction` from far away until it touches `a`, then `depth` farther.
    fn pressed_together(a: &[DVec2], b: &[DVec2], direction: DVec2, depth: f64) -> Vec<DVec2> {
        let at = |distance: f64| b.iter().map(|&p| p + direction * distance).collect::<Vec<_>>();
        let (mut inside, mut apart) = (0.0, 10.0);
        for _ in 0..80 {
            let middle = 0.5 * (inside + apart);
            if contact_geometry(a, &at(middle)).is_some() {
                inside = middle;
            } else {
                apart = middle;
            }
        }
        at(apart - depth)
    }

    /// `cases` cases from a fixed seed, so that every run tests the same pairs.
    fn seeded(cases: u32, seed: u64) -> ProptestConfig {
        ProptestConfig { rng_seed: RngSeed::Fixed(seed), ..ProptestConfig::with_cases(cases) }
    }

    proptest! {
        #![proptest_config(seeded(3000, 0x6c2d_0002))]

        /// Shallow to moderately deep contacts of random polygons, 7 cm from the origin as in a pile: where the walk
        /// applies it gives the clipper's area and chord to round-off, and the clipper calls the contact a plain
        /// crossing. It applies to nearly all of them (checked below).
        #[test]
        fn the_walk_agrees_with_the_clipper(
            a in outline(1.0), b in outline(1.0), angle in 0.0..2.0 * PI, turn in 0.0..2.0 * PI,
            depth in prop_oneof![1e-9..1e-6f64, 1e-6..1e-3f64, 1e-3..0.3f64],
        ) {
            let size = 1.75e-3;
            let place = |points: &[DVec2], pose: Pose| points.iter().map(|&p| pose.apply(p * size)).collect::<Vec<_>>();
            let a = place(&a, Pose::new(v(0.07, 0.05), 0.0));
            let b = place(&b, Pose::new(v(0.07, 0.05), turn));
            let b = pressed_together(&a, &b, v(angle.cos(), angle.sin()), depth * size);
            let Some((area, c1, c2)) = walk(&a, &b) else { return Ok(()) };
            let reference = clipped(&a, &b).expect("the clipper finds the overlap too");
            prop_assert_eq!(reference.kind, ContactKind::Crossing);
            // Coordinates near 0.1 m carry ~1e-17 m of rounding each: slivers get the floor of `tests/overlap.rs`.
            let area_tolerance = 1e-9 * reference.area + 1e-13 * size * size;
            prop_assert!((area - reference.area).abs() <= area_tolerance, "{area} vs {}", reference.area);
            // Where the edges cross at a shallow angle the crossing point is ill-conditioned along the edge.
            let tolerance = 1e-9 * size;
            prop_assert!((c1 - reference.c1).length() <= tolerance && (c2 - reference.c2).length() <= tolerance);
        }
    }

    proptest! {
        #![proptest_config(seeded(1000, 0x6c2d_0003))]

        /// The walk from an exit finds the full walk's overlap from the full walk's own exit, and from any other pair
        /// of edges it finds that overlap, bit for bit, or nothing: never another polygon, also where the contact is deep
        /// enough for more crossings (which the full walk leaves to the clipper).
        #[test]
        fn the_walk_from_any_exit_gives_the_full_walks_overlap_or_nothing(
            a in outline(1.0), b in outline(1.0), angle in 0.0..2.0 * PI, turn in 0.0..2.0 * PI,
            depth in prop_oneof![1e-9..1e-6f64, 1e-6..1e-3f64, 1e-3..0.3f64, 0.3..1.0f64],
        ) {
            let b: Vec<DVec2> = b.iter().map(|&p| Pose::new(DVec2::ZERO, turn).apply(p)).collect();
            let b = pressed_together(&a, &b, v(angle.cos(), angle.sin()), depth);
            let full = Facing::of(&a, &b).and_then(|facing| two_crossings(&a, &b, &facing));
            let bits = |o: &TwoCrossings| {
                [o.c1().x, o.c1().y, o.c2().x, o.c2().y, o.area(), o.centroid().x, o.centroid().y].map(f64::to_bits)
            };
            if let Some(full) = &full {
                let (exit_a, exit_b) = full.exit_edges();
                let warm = two_crossings_from_exit(&a, &b, exit_a, exit_b);
                prop_assert_eq!(warm.map(|o| bits(&o)), Some(bits(full)));
            }
            for (exit_a, exit_b) in (0..a.len()).flat_map(|i| (0..b.len()).map(move |j| (i, j))) {
                if let Some(warm) = two_crossings_from_exit(&a, &b, exit_a, exit_b) {
                    prop_assert_eq!(Some(bits(&warm)), full.as_ref().map(bits), "from edges {} and {}", exit_a, exit_b);
                }
            }
        }
    }

    proptest! {
        #![proptest_config(seeded(2000, 0x6c2d_0004))]

        /// The edge tested first changes nothing: `strictly_inside` is every side test positive, whichever edge it
        /// starts from, for points inside, outside, on the outline's edges, at its vertices and NaN.
        #[test]
        fn the_edge_tested_first_does_not_change_the_answer(
            polygon in outline(1.0), x in -1.2..1.2f64, y in -1.2..1.2f64, edge in 0usize..12, along in 0.0..1.0f64,
        ) {
            let n = polygon.len();
            let on_edge = polygon[edge % n] + (polygon[cyclic_next(edge % n, n)] - polygon[edge % n]) * along;
            for p in [v(x, y), on_edge, polygon[edge % n], DVec2::NAN] {
                let mut start = polygon[n - 1];
                let mut every_side_positive = true;
                for &end in &polygon {
                    every_side_positive &= cross(end - start, p - start) > 0.0;
                    start = end;
                }
                for first in 0..n {
                    prop_assert_eq!(strictly_inside(&polygon, p, first), every_side_positive, "{:?} from edge {}", p, first);
                }
            }
        }
    }

    /// Deep overlaps with more than two crossings, and ties, are found from no edge: the clipper keeps them.
    #[test]
    fn the_walk_from_an_exit_leaves_ties_and_many_crossings_alone() {
        let triangle = |phase: f64| {
            [0.0, 1.0, 2.0].map(|k: f64| v((phase + k * 2.0 * PI / 3.0).cos(), (phase + k * 2.0 * PI / 3.0).sin()))
        };
        let square = [v(0.0, -1.0), v(1.0, -1.0), v(1.0, 0.0), v(0.0, 0.0)];
        let diamond = [v(0.5, -1.2), v(1.2, -0.5), v(0.5, 0.2), v(-0.2, -0.5)];
        let on_the_line = [v(0.2, 0.0), v(0.8, -0.3), v(0.9, 0.5)];
        let cases: [(&[DVec2], &[DVec2]); 4] = [
            (&triangle(PI / 2.0), &triangle(-PI / 2.0)),
            (&diamond, &square),
            (&square, &diamond),
            (&on_the_line, &square),
        ];
        for (a, b) in cases {
            for (i, j) in (0..a.len()).flat_map(|i| (0..b.len()).map(move |j| (i, j))) {
                assert!(two_crossings_from_exit(a, b, i, j).is_none(), "{a:?} from edges {i} and {j}");
            }
        }
    }

    /// A contact that persists, one grain turning and sliding against another by small steps: the overlap found
    /// from the last step's exit is the one found without it, bit for bit, at every step, and the warm walk finds
    /// it at all but the steps where the crossings moved to other edges.
    #[test]
    fn a_persisting_contact_is_found_from_its_last_exit() {
        let heptagon: Vec<DVec2> = (0..7).map(|k| 1e-3 * v((k as f64 * 0.9).cos(), (k as f64 * 0.9).sin())).collect();
        let heptagon = ConvexPolygon::new(&heptagon).unwrap().0.vertices().to_vec();
        let mut exit = None;
        let (mut found, mut warm) = (0, 0);
        for step in 0..2000 {
            let s = step as f64;
            let a: Vec<DVec2> = heptagon.iter().map(|&p| Pose::new(v(0.1, 0.1), 0.2).apply(p)).collect();
            let pose = Pose::new(v(0.1 + 5e-4 * (1e-3 * s).cos(), 0.1 + 1.6e-3 + 1e-4 * (3e-3 * s).sin()), 1e-3 * s);
            let b: Vec<DVec2> = heptagon.iter().map(|&p| pose.apply(p)).collect();
            let hint = exit;
            let from_exit = super::super::contact_geometry_from_exit(&a, &b, true, &mut exit);
            assert_eq!(from_exit, super::super::contact_geometry_with_centroid(&a, &b), "step {step}");
            found += usize::from(from_exit.is_some());
            if let Some(FeaturePair { a: Feature::Edge(i), b: Feature::Edge(j) }) = hint {
                warm += usize::from(two_crossings_from_exit(&a, &b, i.into(), j.into()).is_some());
            }
        }
        assert!(found > 1900 && warm + 20 >= found, "found {found} times, {warm} from the last exit");
    }

    /// A grain against a wall 80 times longer than it (a silo's side wall), in either order: along the line between
    /// the vertex means every vertex of the grain faces the wall, and the walk still applies and agrees with the
    /// clipper.
    #[test]
    fn a_grain_against_a_long_wall_is_walked() {
        let mut runner = proptest::test_runner::TestRunner::new_with_rng(
            ProptestConfig::default(),
            proptest::test_runner::TestRng::deterministic_rng(proptest::test_runner::RngAlgorithm::ChaCha),
        );
        let size = 2.5e-3;
        let wall = [v(-0.0225, 0.0), v(-0.02, 0.0), v(-0.02, 0.4), v(-0.0225, 0.4)];
        let strategy = (outline(size), -0.19..0.19f64, 0.0..2.0 * PI, 1e-6..0.1f64, -1.0..1.0f64);
        let mut walked = 0;
        for case in 0..1000 {
            let (grain, along, turn, depth, slope) = strategy.new_tree(&mut runner).unwrap().current();
            let grain: Vec<DVec2> = grain.iter().map(|&p| Pose::new(v(-0.02, 0.2 + along), turn).apply(p)).collect();
            let grain = pressed_together(&wall, &grain, v(1.0, slope).normalize(), depth * size);
            let (a, b) = if case % 2 == 0 { (&wall[..], &grain[..]) } else { (&grain[..], &wall[..]) };
            let Some((area, c1, c2)) = walk(a, b) else { continue };
            walked += 1;
            let reference = clipped(a, b).expect("the clipper finds the overlap too");
            assert_eq!(reference.kind, ContactKind::Crossing);
            assert!((area - reference.area).abs() <= 1e-9 * reference.area + 1e-13 * size * size);
            assert!((c1 - reference.c1).length() <= 1e-9 * size && (c2 - reference.c2).length() <= 1e-9 * size);
        }
        assert!(walked >= 990, "walked {walked} of 1000");
    }

    /// The walk takes the contacts of a pile: shallow ones, between polygons of gc2d's sizes and shapes.
    #[test]
    fn the_walk_takes_almost_every_shallow_contact() {
        let mut runner = proptest::test_runner::TestRunner::new_with_rng(
            ProptestConfig::default(),
            proptest::test_runner::TestRng::deterministic_rng(proptest::test_runner::RngAlgorithm::ChaCha),
        );
        let strategy = (outline(1.0), outline(1.0), 0.0..2.0 * PI, 0.0..2.0 * PI, 1e-6..1e-2f64);
        let (mut walked, mut crossings) = (0, 0);
        for _ in 0..2000 {
            let (a, b, angle, turn, depth) = strategy.new_tree(&mut runner).unwrap().current();
            let b: Vec<DVec2> = b.iter().map(|&p| Pose::new(DVec2::ZERO, turn).apply(p)).collect();
            let b = pressed_together(&a, &b, v(angle.cos(), angle.sin()), depth);
            if clipped(&a, &b).is_some_and(|c| c.kind == ContactKind::Crossing) {
                crossings += 1;
                walked += usize::from(walk(&a, &b).is_some());
            }
        }
        assert!(crossings > 1900, "{crossings} plain crossings");
        assert!(walked as f64 >= 0.99 * crossings as f64, "walked {walked} of {crossings}");
    }
}
