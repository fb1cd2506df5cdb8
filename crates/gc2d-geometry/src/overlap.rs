//! Overlap of two convex polygons: the overlap area A and the contact chord c1c2 (reference §2.3, §2.4, §4.4, D10).
//!
//! gc2d's normal force is proportional to the overlap area A (eq. 2.20). It acts at the midpoint of the chord c1c2
//! joining the two points where the outlines cross, perpendicular to the chord. With c1 the point where `a`'s
//! counter-clockwise outline enters `b` and c2 where it leaves, the overlap is bounded by `a`'s chain c1→c2 and `b`'s
//! chain c2→c1, and the normal `perp(c2 − c1)/|c2 − c1|` (perp(v) = (−v.y, v.x)) points from `b` towards `a`. It is
//! also −∂A/∂x_a / |∂A/∂x_a|: moving `a` along it shrinks the overlap fastest, at the rate |c2 − c1|.
//!
//! Where the outlines cross exactly twice, properly (almost every contact of a pile), the overlap is built from
//! its two crossings (module `two_crossings`); every other overlap by Sutherland–Hodgman clipping of `a` by the
//! edges of `b` that face it (module `clip`), in fixed stack buffers sized by the vertex counts. See `docs/model.md`
//! (“Contact geometry”) for the tie rule and the policies for degenerate, deep and contained overlaps.

mod clip;
mod facing;
mod two_crossings;

use crate::{DVec2, Feature, FeaturePair, MAX_VERTICES, cross, cyclic_next};
use clip::{Label, Ring, RingVertex};
use facing::Facing;
use two_crossings::{TwoCrossings, two_crossings, two_crossings_from_exit};

/// A chord shorter than this fraction of √A carries no direction: the overlap is treated as a containment.
/// A genuine chord is that short only when `a`'s outline barely leaves `b` (or the reverse), i.e. one polygon is
/// all but inside the other; rounding noise on an exact touch is many orders of magnitude smaller.
pub const DEGENERATE_CHORD_FRACTION: f64 = 1e-9;

/// A direction (area gradient, centroid offset) shorter than this fraction of the length it is compared with is
/// treated as zero, and the next rule of the orientation fallback chain decides.
const NEGLIGIBLE_DIRECTION_FRACTION: f64 = 1e-9;

/// How the chord ends c1 and c2 of a [`OverlapGeometry`] were found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactKind {
    /// The outlines cross at exactly two points, each a proper crossing of two edges: the normal DEM contact.
    Crossing,
    /// Two crossings, at least one of them fixed by the tie rule: collinear overlapping edges, or a vertex of one
    /// outline exactly on the other's edge line.
    Degenerate,
    /// A deep overlap whose outlines cross more than twice: c1, c2 are the two crossings farthest apart.
    MultipleCrossings,
    /// One polygon inside the other (or identical): no usable crossings. The normal runs along
    /// centroid(a) − centroid(b) (+y when they coincide) and the chord is the overlap's width across it, through
    /// the overlap centroid.
    Contained,
}

/// Result of intersecting polygon `a` (body i) with polygon `b` (body j).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OverlapGeometry {
    /// Overlap area A in m² (per unit thickness), > 0.
    pub area: f64,
    /// Where `a`'s outline, walked counter-clockwise, enters `b`.
    pub c1: DVec2,
    /// Where `a`'s outline leaves `b`.
    pub c2: DVec2,
    /// Midpoint of c1c2: the force application point s_ij (reference §2.4).
    pub point: DVec2,
    /// Unit vector perpendicular to c1c2, pointing from `b` towards `a`: the repulsive force on `a` is along +normal.
    pub normal: DVec2,
    /// |c2 − c1| in m.
    pub chord_length: f64,
    /// How c1 and c2 were found.
    pub kind: ContactKind,
    /// Area centroid of the overlap polygon, m: computed by [`contact_geometry_with_centroid`] for the Winkler
    /// formulation of the overlap-area law, `None` from [`contact_geometry`] (which spends nothing on it).
    pub centroid: Option<DVec2>,
}

/// The intersection polygon of two convex polygons, counter-clockwise, in a fixed buffer (no heap).
#[derive(Debug, Clone)]
pub struct OverlapPolygon {
    vertices: [DVec2; 2 * MAX_VERTICES],
    len: usize,
    area: f64,
}

impl OverlapPolygon {
    /// An empty overlap (no vertices, zero area), ready to be filled by [`overlap_polygon`].
    pub fn new() -> Self {
        Self { vertices: [DVec2::ZERO; 2 * MAX_VERTICES], len: 0, area: 0.0 }
    }

    /// The vertices, counter-clockwise; empty when the interiors do not overlap.
    pub fn vertices(&self) -> &[DVec2] {
        &self.vertices[..self.len]
    }

    /// The area in m²; zero when the interiors do not overlap.
    pub fn area(&self) -> f64 {
        self.area
    }
}

impl Default for OverlapPolygon {
    fn default() -> Self {
        Self::new()
    }
}

/// Overlap area and contact chord of polygon `a` (body i) with polygon `b` (body j).
///
/// Both are world-frame, counter-clockwise, validated convex vertex slices of 3..=[`MAX_VERTICES`] vertices.
/// Returns `None` when the interiors do not overlap (A = 0, including mere touching) or the input is out of range.
/// Never allocates, never panics, never returns NaN for finite input.
pub fn contact_geometry(a: &[DVec2], b: &[DVec2]) -> Option<OverlapGeometry> {
    contact_geometry_from_exit(a, b, false, &mut None)
}

/// [`contact_geometry`] with the overlap polygon's area centroid in [`OverlapGeometry::centroid`] (bitwise the same
/// other fields), for laws that apply the elastic force at the centroid (docs/model.md, "Rocking of flat contacts").
pub fn contact_geometry_with_centroid(a: &[DVec2], b: &[DVec2]) -> Option<OverlapGeometry> {
    contact_geometry_from_exit(a, b, true, &mut None)
}

/// [`contact_geometry`], or [`contact_geometry_with_centroid`] where `with_centroid`, found first from `exit`, the
/// edges of `a` and `b` on which `a`'s outline left `b` in the last step, and `exit` updated to this step's where the
/// overlap is a plain two-crossing one (else left as it was). A persisting contact's crossings are found from last
/// step's instead of among all facing edges, and wherever the full search walks the contact it is the same bit for
/// bit; the full search leaves to the clipper a few exact ties away from the crossings (a vertex exactly on an edge
/// line, equal vertex means) that the walk from `exit` may still take, to round-off the clipper's answer
/// (docs/model.md, "Contact geometry"; docs/performance.md, "Overlaps from the last exit").
pub fn contact_geometry_from_exit(
    a: &[DVec2],
    b: &[DVec2],
    with_centroid: bool,
    exit: &mut Option<FeaturePair>,
) -> Option<OverlapGeometry> {
    let total = checked_total_vertices(a, b)?;
    if let Some(FeaturePair { a: Feature::Edge(edge_of_a), b: Feature::Edge(edge_of_b) }) = *exit
        && let Some(overlap) = two_crossings_from_exit(a, b, usize::from(edge_of_a), usize::from(edge_of_b))
    {
        return Some(two_crossing_contact(&overlap, with_centroid, exit));
    }
    match total {
        0..=16 => contact_with_capacity::<16>(a, b, with_centroid, exit),
        17..=32 => contact_with_capacity::<32>(a, b, with_centroid, exit),
        33..=64 => contact_with_capacity::<64>(a, b, with_centroid, exit),
        _ => contact_with_capacity::<128>(a, b, with_centroid, exit),
    }
}

/// Writes the intersection polygon of `a` and `b` (same input rules as [`contact_geometry`]) into `out`, which is
/// left empty when the interiors do not overlap.
pub fn overlap_polygon(a: &[DVec2], b: &[DVec2], out: &mut OverlapPolygon) {
    out.len = 0;
    out.area = 0.0;
    match checked_total_vertices(a, b) {
        None => {}
        Some(0..=16) => overlap_with_capacity::<16>(a, b, out),
        Some(17..=32) => overlap_with_capacity::<32>(a, b, out),
        Some(33..=64) => overlap_with_capacity::<64>(a, b, out),
        Some(_) => overlap_with_capacity::<128>(a, b, out),
    }
}

/// `a.len() + b.len()` when both polygons have an admissible vertex count. The sum bounds the overlap's vertex count
/// (each clip adds at most one vertex), so it picks the smallest stack buffer that fits.
fn checked_total_vertices(a: &[DVec2], b: &[DVec2]) -> Option<usize> {
    let admissible = |p: &[DVec2]| (3..=MAX_VERTICES).contains(&p.len());
    (admissible(a) && admissible(b)).then_some(a.len() + b.len())
}

fn overlap_with_capacity<const CAP: usize>(a: &[DVec2], b: &[DVec2], out: &mut OverlapPolygon) {
    let Some(facing) = Facing::of(a, b) else { return };
    if let Some(overlap) = two_crossings(a, b, &facing) {
        let mut len = 0;
        overlap.for_each_vertex(|vertex| {
            if let Some(slot) = out.vertices.get_mut(len) {
                *slot = vertex;
                len += 1;
            }
        });
        out.len = len;
        out.area = overlap.area();
        return;
    }
    let (mut first, mut second) = (Ring::<CAP>::new(), Ring::<CAP>::new());
    let Some(ring) = clip::clip(a, b, &facing, &mut first, &mut second) else { return };
    let area = 0.5 * ring.twice_area();
    if positive_area(area) {
        for (slot, vertex) in out.vertices.iter_mut().zip(ring.vertices()) {
            *slot = vertex.point;
        }
        out.len = ring.vertices().len();
        out.area = area;
    }
}

/// A finite, positive area: non-finite input (infinite coordinates) can give a NaN or infinite one, which is no
/// contact.
fn positive_area(area: f64) -> bool {
    area.is_finite() && area > 0.0
}

/// The two-crossing walk where it applies (almost every contact), else the clipper.
fn contact_with_capacity<const CAP: usize>(
    a: &[DVec2],
    b: &[DVec2],
    with_centroid: bool,
    exit: &mut Option<FeaturePair>,
) -> Option<OverlapGeometry> {
    let facing = Facing::of(a, b)?;
    if let Some(overlap) = two_crossings(a, b, &facing) {
        return Some(two_crossing_contact(&overlap, with_centroid, exit));
    }
    let (mut first, mut second) = (Ring::<CAP>::new(), Ring::<CAP>::new());
    let ring = clip::clip(a, b, &facing, &mut first, &mut second)?;
    let area = 0.5 * ring.twice_area();
    if !positive_area(area) {
        return None;
    }
    let contact = contact_from_overlap(ring.vertices(), area, a, b);
    Some(OverlapGeometry { centroid: with_centroid.then(|| ring_centroid(ring.vertices())), ..contact })
}

/// The contact of a two-crossing overlap: a plain crossing whose chord runs from the entry c1 to the exit c2; sets
/// `exit` to the edges of c2.
fn two_crossing_contact(
    overlap: &TwoCrossings,
    with_centroid: bool,
    exit: &mut Option<FeaturePair>,
) -> OverlapGeometry {
    let (edge_of_a, edge_of_b) = overlap.exit_edges();
    *exit = Some(FeaturePair { a: Feature::edge(edge_of_a), b: Feature::edge(edge_of_b) });
    let (c1, c2) = (overlap.c1(), overlap.c2());
    let chord = c2 - c1;
    let chord_length = chord.length();
    OverlapGeometry {
        area: overlap.area(),
        c1,
        c2,
        point: 0.5 * (c1 + c2),
        normal: chord.perp() / chord_length,
        chord_length,
        kind: ContactKind::Crossing,
        centroid: with_centroid.then(|| overlap.centroid()),
    }
}

/// The chord rules of `docs/model.md`, applied to the labelled overlap polygon.
fn contact_from_overlap(ring: &[RingVertex], area: f64, a: &[DVec2], b: &[DVec2]) -> OverlapGeometry {
    let (mut any_b, mut shared) = (false, 0);
    for vertex in ring {
        any_b |= vertex.edge == Label::B;
        shared += usize::from(vertex.edge == Label::Shared);
    }
    // a's outline inside the closed polygon b (tie rule: b's boundary counts as inside). When a lies inside b and
    // touches it along shared edges, a's outline leaves b's boundary where it stops being shared, so only its
    // strictly interior edges count.
    let strictly_inside = !any_b && shared > 0 && shared < ring.len();
    let on_a = |k: usize| match ring[k].edge {
        Label::A => true,
        Label::Shared => !strictly_inside,
        Label::B => false,
    };
    let runs = Runs::of(ring.len(), on_a);
    let min_chord = DEGENERATE_CHORD_FRACTION * area.sqrt();
    let crossing = match runs.count {
        0 => None,
        1 => Some((ring[runs.first_entry].point, ring[runs.first_exit].point)),
        _ => farthest_crossings(ring, on_a, a, b),
    }
    .filter(|(c1, c2)| (*c2 - *c1).length() > min_chord);
    let Some((c1, c2)) = crossing else {
        return contained_contact(ring, area, a, b);
    };
    let kind = if runs.count > 1 {
        ContactKind::MultipleCrossings
    } else if shared > 0 || ring[runs.first_entry].tied || ring[runs.first_exit].tied {
        ContactKind::Degenerate
    } else {
        ContactKind::Crossing
    };
    let chord = c2 - c1;
    let chord_length = chord.length();
    OverlapGeometry {
        area,
        c1,
        c2,
        point: 0.5 * (c1 + c2),
        normal: chord.perp() / chord_length,
        chord_length,
        kind,
        centroid: None,
    }
}

/// The runs of consecutive edges of a cyclic ring for which `on_a` holds: how many, and when there is exactly one,
/// the vertex where it starts (the entry into `b`) and the vertex where it ends (the exit).
struct Runs {
    count: usize,
    first_entry: usize,
    first_exit: usize,
}

impl Runs {
    fn of(len: usize, on_a: impl Fn(usize) -> bool) -> Self {
        let mut runs = Runs { count: 0, first_entry: 0, first_exit: 0 };
        let mut previous = on_a(len - 1);
        for k in 0..len {
            let current = on_a(k);
            if current && !previous {
                if runs.count == 0 {
                    runs.first_entry = k;
                }
                runs.count += 1;
            } else if previous && !current {
                runs.first_exit = k;
            }
            previous = current;
        }
        runs
    }
}

/// Deep-overlap policy: the two crossings (entries or exits) farthest apart, ordered so that the normal has a
/// positive component along, in turn, the area gradient −∂A/∂x_a = perp(Σ exits − Σ entries), centroid(a) −
/// centroid(b), +y, +x: the first of these that is not negligible decides.
fn farthest_crossings(
    ring: &[RingVertex],
    on_a: impl Fn(usize) -> bool,
    a: &[DVec2],
    b: &[DVec2],
) -> Option<(DVec2, DVec2)> {
    let n = ring.len();
    let is_crossing = |k: usize| on_a(k) != on_a(if k == 0 { n - 1 } else { k - 1 });
    let origin = ring[0].point;
    let mut gradient_chord = DVec2::ZERO;
    let mut best: Option<(DVec2, DVec2)> = None;
    let mut best_distance = 0.0;
    for k in (0..n).filter(|&k| is_crossing(k)) {
        let p = ring[k].point;
        if on_a(k) {
            gradient_chord -= p - origin;
        } else {
            gradient_chord += p - origin;
        }
        for l in (k + 1..n).filter(|&l| is_crossing(l)) {
            let distance = ring[l].point.distance_squared(p);
            if distance > best_distance {
                best_distance = distance;
                best = Some((p, ring[l].point));
            }
        }
    }
    let (p, q) = best?;
    let chord = q - p;
    let length = chord.length();
    let centroid_offset = centroid(a) - centroid(b);
    let negligible = NEGLIGIBLE_DIRECTION_FRACTION * length;
    // (alignment of the candidate normal perp(chord) with a reference vector, that vector's length): a length vector
    // (area gradient, centroid offset) counts only when it is not negligible against the chord.
    let references = [
        (chord.dot(gradient_chord), gradient_chord.length()),
        (chord.perp().dot(centroid_offset), centroid_offset.length()),
    ]
    .into_iter()
    .filter(|&(_, reference)| reference > negligible)
    .chain([(chord.perp().y, 1.0), (chord.perp().x, 1.0)]);
    let decisive = references.into_iter().find(|&(alignment, reference)| alignment.abs() > negligible * reference);
    match decisive {
        Some((alignment, _)) if alignment < 0.0 => Some((q, p)),
        _ => Some((p, q)),
    }
}

/// Containment policy: normal along centroid(a) − centroid(b) (+y when they coincide within
/// [`NEGLIGIBLE_DIRECTION_FRACTION`]·√A); chord = the overlap's width across the normal, through its centroid.
fn contained_contact(ring: &[RingVertex], area: f64, a: &[DVec2], b: &[DVec2]) -> OverlapGeometry {
    let offset = centroid(a) - centroid(b);
    let normal =
        if offset.length() > NEGLIGIBLE_DIRECTION_FRACTION * area.sqrt() { offset.normalize() } else { DVec2::Y };
    // Chord direction t with perp(t) = normal, so that normal = perp(c2 − c1)/|c2 − c1| as for every other kind.
    let tangent = DVec2::new(normal.y, -normal.x);
    let center = ring_centroid(ring);
    let (mut low, mut high) = (0.0f64, 0.0f64);
    let n = ring.len();
    for k in 0..n {
        let (p, q) = (ring[k].point, ring[cyclic_next(k, n)].point);
        let (dp, dq) = (normal.dot(p - center), normal.dot(q - center));
        if (dp <= 0.0) != (dq <= 0.0) {
            let at = tangent.dot(p + (q - p) * (dp / (dp - dq)) - center);
            low = low.min(at);
            high = high.max(at);
        }
    }
    let (c1, c2) = (center + low * tangent, center + high * tangent);
    OverlapGeometry {
        area,
        c1,
        c2,
        point: 0.5 * (c1 + c2),
        normal,
        chord_length: high - low,
        kind: ContactKind::Contained,
        centroid: None,
    }
}

/// Area centroid of the overlap polygon: [`centroid`] of its points, read in place.
fn ring_centroid(ring: &[RingVertex]) -> DVec2 {
    centroid_of_vertices(ring.len(), |k| ring[k].point)
}

/// Area centroid of a counter-clockwise polygon (vertex mean for a degenerate one), summed relative to its first
/// vertex for precision.
pub(crate) fn centroid(points: &[DVec2]) -> DVec2 {
    centroid_of_vertices(points.len(), |k| points[k])
}

/// Area centroid of the counter-clockwise polygon of `len` (≥ 1) vertices `vertex(0..len)`.
#[inline]
fn centroid_of_vertices(len: usize, vertex: impl Fn(usize) -> DVec2) -> DVec2 {
    let origin = vertex(0);
    let mut twice_area = 0.0;
    let mut weighted = DVec2::ZERO;
    for k in 1..len.saturating_sub(1) {
        let (p, q) = (vertex(k) - origin, vertex(k + 1) - origin);
        let c = cross(p, q);
        twice_area += c;
        weighted += (p + q) * c;
    }
    if twice_area > 0.0 {
        origin + weighted / (3.0 * twice_area)
    } else {
        (0..len).map(&vertex).sum::<DVec2>() / len as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use std::f64::consts::PI;

    fn v(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    /// Counter-clockwise axis-aligned rectangle [x0, x1] × [y0, y1].
    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> [DVec2; 4] {
        [v(x0, y0), v(x1, y0), v(x1, y1), v(x0, y1)]
    }

    fn regular(n: usize, radius: f64, center: DVec2, phase: f64) -> Vec<DVec2> {
        (0..n)
            .map(|i| {
                let phi = phase + 2.0 * PI * i as f64 / n as f64;
                center + radius * v(phi.cos(), phi.sin())
            })
            .collect()
    }

    #[test]
    fn a_above_b_pushes_a_up_with_the_chord_across_the_contact() {
        let h = 1e-3;
        let a = rect(0.25, -h, 0.75, 0.5 - h);
        let b = rect(0.0, -1.0, 1.0, 0.0);
        let c = contact_geometry(&a, &b).unwrap();
        assert_relative_eq!(c.area, 0.5 * h, max_relative = 1e-12);
        assert_eq!((c.c1, c.c2), (v(0.25, 0.0), v(0.75, 0.0)));
        assert_eq!(c.normal, DVec2::Y);
        assert_eq!(c.point, v(0.5, 0.0));
        assert_eq!(c.chord_length, 0.5);
        assert_eq!(c.kind, ContactKind::Crossing);
        // Swapping the bodies swaps the chord ends and flips the normal.
        let d = contact_geometry(&b, &a).unwrap();
        assert_eq!((d.c1, d.c2, d.normal), (c.c2, c.c1, -DVec2::Y));
    }

    #[test]
    fn separated_and_touching_pairs_have_no_contact() {
        let b = rect(0.0, -1.0, 1.0, 0.0);
        assert!(contact_geometry(&rect(2.0, 0.5, 3.0, 1.0), &b).is_none());
        // Edge on edge, same width (a stacked column of rectangles) and wider.
        assert!(contact_geometry(&rect(0.0, 0.0, 1.0, 1.0), &b).is_none());
        assert!(contact_geometry(&rect(-0.5, 0.0, 1.5, 1.0), &b).is_none());
        // Corner on corner, and a corner on an edge from outside.
        assert!(contact_geometry(&rect(1.0, 0.0, 2.0, 1.0), &b).is_none());
        assert!(contact_geometry(&[v(0.5, 0.0), v(1.0, 1.0), v(0.0, 1.0)], &b).is_none());
        assert!(contact_geometry(&b, &[v(0.5, 0.0), v(1.0, 1.0), v(0.0, 1.0)]).is_none());
        let mut empty = OverlapPolygon::new();
        overlap_polygon(&rect(0.0, 0.0, 1.0, 1.0), &b, &mut empty);
        assert!(empty.vertices().is_empty() && empty.area() == 0.0);
    }

    #[test]
    fn out_of_range_and_non_finite_input_gives_no_contact() {
        let b = rect(0.0, 0.0, 1.0, 1.0);
        assert!(contact_geometry(&b[..2], &b).is_none());
        assert!(contact_geometry(&regular(65, 1.0, DVec2::ZERO, 0.0), &b).is_none());
        let nan = [v(f64::NAN, 0.0), v(1.0, 0.0), v(0.5, 1.0)];
        assert!(contact_geometry(&nan, &b).is_none());
        assert!(contact_geometry(&b, &nan).is_none());
        let infinite = [v(0.0, 0.0), v(f64::INFINITY, 0.0), v(0.5, 1.0)];
        assert!(contact_geometry(&infinite, &b).is_none_or(|c| c.area.is_finite() && c.normal.is_finite()));
    }

    #[test]
    fn stacked_columns_take_the_shared_extent_as_chord() {
        // Same-width rectangles pressed together: the side edges are collinear and overlap.
        let h = 0.125;
        let a = rect(0.0, -h, 1.0, 1.0 - h);
        let b = rect(0.0, -1.0, 1.0, 0.0);
        let c = contact_geometry(&a, &b).unwrap();
        assert_eq!(c.area, h);
        assert_eq!((c.c1, c.c2), (v(0.0, 0.0), v(1.0, 0.0)));
        assert_eq!(c.normal, DVec2::Y);
        assert_eq!(c.kind, ContactKind::Degenerate);
        let d = contact_geometry(&b, &a).unwrap();
        assert_eq!((d.c1, d.c2, d.normal, d.kind), (v(1.0, -h), v(0.0, -h), -DVec2::Y, ContactKind::Degenerate));
        // One side flush, the other not.
        let e = contact_geometry(&rect(0.0, -h, 0.5, 1.0 - h), &b).unwrap();
        assert_eq!((e.c1, e.c2, e.normal, e.kind), (v(0.0, 0.0), v(0.5, 0.0), DVec2::Y, ContactKind::Degenerate));
    }

    #[test]
    fn a_crossing_through_a_vertex_is_resolved_by_the_tie_rule() {
        // A diamond whose lower-left edge passes exactly through b's top-left corner (0, 0).
        let h = 0.25;
        let a = [v(h, -h), v(h + 1.0, 1.0 - h), v(h, 2.0 - h), v(h - 1.0, 1.0 - h)];
        let b = rect(0.0, -1.0, 1.0, 0.0);
        let c = contact_geometry(&a, &b).unwrap();
        assert_eq!(c.area, h * h);
        assert_eq!((c.c1, c.c2), (v(0.0, 0.0), v(2.0 * h, 0.0)));
        assert_eq!(c.normal, DVec2::Y);
        assert_eq!(c.kind, ContactKind::Degenerate);
        // A vertex of a exactly on b's edge, the rest of a inside: containment, no crossing.
        let tip_on_edge = [v(0.5, 0.0), v(0.4, -0.5), v(0.6, -0.5)];
        let t = contact_geometry(&[tip_on_edge[0], tip_on_edge[1], tip_on_edge[2]], &b).unwrap();
        assert_eq!(t.kind, ContactKind::Contained);
        assert_relative_eq!(t.area, 0.05, max_relative = 1e-14);
    }

    #[test]
    fn identical_polygons_are_contained_with_the_fixed_axis_normal() {
        let a = regular(7, 1.0, v(3.0, -2.0), 0.3);
        let c = contact_geometry(&a, &a).unwrap();
        assert_eq!(c.kind, ContactKind::Contained);
        assert_relative_eq!(c.area, 3.5 * (2.0 * PI / 7.0).sin(), max_relative = 1e-12);
        assert_eq!(c.normal, DVec2::Y);
        // The chord is the horizontal width through the centroid, walked so that perp(c2 − c1) = +y: rightwards.
        assert!(c.c2.x > c.c1.x);
        assert_relative_eq!(c.c1.y, -2.0, epsilon = 1e-12);
        assert_relative_eq!(c.c2.y, -2.0, epsilon = 1e-12);
        assert!(c.c1.x < 3.0 && 3.0 < c.c2.x);
        assert_relative_eq!(c.chord_length, (c.c2 - c.c1).length(), max_relative = 1e-12);
        // Both ends lie on the outline: on an edge line, and inside every other edge's half-plane.
        for end in [c.c1, c.c2] {
            let sides = (0..7).map(|k| cross(a[(k + 1) % 7] - a[k], end - a[k]));
            assert!(sides.clone().all(|s| s > -1e-12) && sides.map(f64::abs).any(|s| s < 1e-12));
        }
    }

    #[test]
    fn a_polygon_inside_the_other_is_pushed_along_the_centroid_offset() {
        let small = rect(0.0, 0.0, 0.2, 0.1);
        let big = rect(-1.0, -2.0, 1.0, 0.5);
        for (a, b, sign) in [(&small, &big, 1.0), (&big, &small, -1.0)] {
            let c = contact_geometry(a, b).unwrap();
            assert_eq!(c.kind, ContactKind::Contained);
            assert_relative_eq!(c.area, 0.02, max_relative = 1e-12);
            let offset = sign * (v(0.1, 0.05) - v(0.0, -0.75));
            assert_relative_eq!(c.normal, offset.normalize(), epsilon = 1e-12);
            // Width of the small rectangle across the normal, through its centre.
            assert_relative_eq!(c.point, v(0.1, 0.05), epsilon = 1e-12);
            assert_relative_eq!(c.normal.dot(c.c2 - c.c1), 0.0, epsilon = 1e-12);
            let half_width = (0.1 / c.normal.y.abs()).min(0.05 / c.normal.x.abs());
            assert_relative_eq!(c.chord_length, 2.0 * half_width, max_relative = 1e-12);
            assert_relative_eq!(c.normal.perp_dot(c.c2 - c.c1), -c.chord_length, max_relative = 1e-12);
        }
    }

    #[test]
    fn a_polygon_inside_the_other_along_a_shared_edge_is_pushed_out_through_it() {
        let small = rect(0.0, 0.0, 0.5, 0.5);
        let big = rect(-1.0, 0.0, 1.0, 2.0);
        let c = contact_geometry(&small, &big).unwrap();
        assert_eq!((c.c1, c.c2, c.normal, c.kind), (v(0.5, 0.0), v(0.0, 0.0), -DVec2::Y, ContactKind::Degenerate));
        let d = contact_geometry(&big, &small).unwrap();
        assert_eq!((d.c1, d.c2, d.normal, d.kind), (v(0.0, 0.0), v(0.5, 0.0), DVec2::Y, ContactKind::Degenerate));
        assert_eq!((c.area, d.area), (0.25, 0.25));
    }

    #[test]
    fn a_hexagram_takes_a_diameter_of_the_inner_hexagon() {
        let radius = 1.0;
        let up = regular(3, radius, DVec2::ZERO, PI / 2.0);
        let down = regular(3, radius, DVec2::ZERO, -PI / 2.0);
        let c = contact_geometry(&up, &down).unwrap();
        assert_eq!(c.kind, ContactKind::MultipleCrossings);
        let triangle_area = 3.0 * 3f64.sqrt() / 4.0 * radius * radius;
        assert_relative_eq!(c.area, 2.0 / 3.0 * triangle_area, max_relative = 1e-12);
        // The hexagon's vertices are the six crossings, at distance radius/√3 from the centre; c1, c2 are opposite.
        assert_relative_eq!(c.chord_length, 2.0 * radius / 3f64.sqrt(), max_relative = 1e-12);
        assert_relative_eq!(c.point, DVec2::ZERO, epsilon = 1e-12);
        assert_relative_eq!(c.c1.length(), radius / 3f64.sqrt(), max_relative = 1e-12);
        // Symmetric: no area gradient and coincident centroids, so the fixed +y orientation decides.
        assert!(c.normal.y > 0.0);
        assert_relative_eq!(c.normal.length(), 1.0, max_relative = 1e-14);
        assert_relative_eq!(c.normal.dot(c.c2 - c.c1), 0.0, epsilon = 1e-12);
    }

    #[test]
    fn an_asymmetric_deep_overlap_is_oriented_along_the_area_gradient() {
        let up = regular(3, 1.0, v(0.05, 0.2), PI / 2.0 + 0.02);
        let down = regular(3, 1.0, DVec2::ZERO, -PI / 2.0);
        let c = contact_geometry(&up, &down).unwrap();
        assert_eq!(c.kind, ContactKind::MultipleCrossings);
        let step = 1e-7;
        let area_at = |shift: DVec2| {
            let moved: Vec<DVec2> = up.iter().map(|&p| p + shift).collect();
            contact_geometry(&moved, &down).unwrap().area
        };
        let gradient =
            v(area_at(v(step, 0.0)) - area_at(v(-step, 0.0)), area_at(v(0.0, step)) - area_at(v(0.0, -step)))
                / (2.0 * step);
        assert!(c.normal.dot(-gradient) > 0.0);
    }

    #[test]
    fn overlap_polygon_is_the_counter_clockwise_intersection() {
        let a = rect(0.0, 0.0, 2.0, 2.0);
        let b = rect(1.0, 1.0, 3.0, 3.0);
        let mut out = OverlapPolygon::new();
        overlap_polygon(&a, &b, &mut out);
        assert_eq!(out.area(), 1.0);
        let mut corners = out.vertices().to_vec();
        corners.sort_by(|p, q| p.x.total_cmp(&q.x).then(p.y.total_cmp(&q.y)));
        assert_eq!(corners, [v(1.0, 1.0), v(1.0, 2.0), v(2.0, 1.0), v(2.0, 2.0)]);
        let c = contact_geometry(&a, &b).unwrap();
        assert_eq!((c.c1, c.c2, c.kind), (v(2.0, 1.0), v(1.0, 2.0), ContactKind::Crossing));
        assert_relative_eq!(c.normal, v(-1.0, -1.0).normalize(), epsilon = 1e-15);
    }
}
