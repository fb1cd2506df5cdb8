//! A circle and a convex polygon: disk–polygon (either body as i) and polygon–inner circle.
//!
//! The overlap D ∩ P of a disk and a convex polygon is bounded by pieces of the polygon's edges inside the disk and
//! arcs of the circle inside the polygon; P \ D (a polygon poking out of a chamber) by the edge pieces outside the
//! disk and the same arcs. Both areas are, by Green's theorem, the area of the straight polygon through all piece
//! ends (crossing points and kept vertices) plus (inside) or minus (outside) one circular segment per arc. Summing
//! that polygon relative to a point of the region (for P \ D: each piece relative to its own exit point) and the
//! segments by r²/2·(φ − sin φ) with a series for small φ keeps 1e-9 m overlaps of millimetre disks at 0.1 m to
//! ~1e-9 relative (tests/pair_queries.rs, against 60-digit values); the usual sum of signed circle ∩ triangle areas
//! over a fan from the centre cancels there (sectors of size r² summing to an overlap of size 1e-12·r²).
//!
//! Each arc runs counter-clockwise from a point where the polygon's outline leaves the disk to the next point where
//! it enters it. Its angle φ is fixed by the two end points up to a whole turn, which matters only when the two
//! (nearly) coincide; the turn is then read from the angle the polygon's outside chain between them subtends at the
//! centre, which equals φ (the chain and the arc bound a piece of P \ D, which does not hold the centre), counted
//! cheaply in pseudo-angles. So φ ≈ 0 and φ ≈ 2π are told apart even when the two ends coincide.

use super::{
    Crossings, Inner, admissible_polygon, area_contact_from_crossings, circular_segment_area, finite, polygon_area,
    polygon_centroid, positive, subtended,
};
use crate::shape::{AreaContact, PairPenetration};
use crate::{DVec2, cross};
use std::f64::consts::{PI, TAU};

/// Which part of the polygon [`walk`] measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Part {
    /// P ∩ D.
    InsideCircle,
    /// P \ D.
    OutsideCircle,
}

/// Area of the part of the convex counter-clockwise polygon `polygon` inside (or outside) the circle, m². Records
/// every crossing of the outlines in `crossings`, with `entry` = the polygon's outline enters the disk there.
/// Input must be admissible and the radius positive (checked by the callers).
pub(crate) fn walk(center: DVec2, radius: f64, polygon: &[DVec2], part: Part, crossings: &mut Crossings) -> f64 {
    let keep_inside = part == Part::InsideCircle;
    let n = polygon.len();
    let radius_squared = radius * radius;
    let inside = |p: DVec2| (p - center).length_squared() < radius_squared;
    // P ∩ D is one convex region: one reference point in it. P \ D may fall apart into several pieces (a polygon
    // poking out of a chamber at several corners), each summed relative to its own exit point; the outside chain
    // before the walk's first exit belongs to the last piece and is moved onto that piece's origin at the end.
    let origin = match part {
        Part::InsideCircle => closest_boundary(center, polygon).clamped_point(center),
        Part::OutsideCircle => polygon[0],
    };
    let mut state = Walk {
        center,
        radius,
        origin,
        start_vertex: polygon[0],
        prefix: 0.0,
        keep_inside,
        twice_straight: 0.0,
        arcs: 0.0,
        chain: 0.0,
        open_exit: None,
        first_entry: None,
        crossed: false,
    };
    let mut in_p = inside(polygon[0]);
    for k in 0..n {
        let (p, q) = (polygon[k], polygon[if k + 1 == n { 0 } else { k + 1 }]);
        let in_q = inside(q);
        let e = q - p;
        let (t0, s) = line_parameters(p - center, e, radius);
        let at = |t: f64| p + e * t.clamp(0.0, 1.0);
        match (in_p, in_q) {
            (true, true) => state.inside_piece(p, q),
            (true, false) => {
                let exit = at(t0 + s);
                state.inside_piece(p, exit);
                state.exit(exit, crossings);
                state.outside_piece(exit, q);
            }
            (false, true) => {
                let entry = at(t0 - s);
                state.outside_piece(p, entry);
                state.entry(entry, crossings);
                state.inside_piece(entry, q);
            }
            (false, false) if s > 0.0 && t0 > 0.0 && t0 < 1.0 => {
                let (entry, exit) = (at(t0 - s), at(t0 + s));
                state.outside_piece(p, entry);
                state.entry(entry, crossings);
                state.inside_piece(entry, exit);
                state.exit(exit, crossings);
                state.outside_piece(exit, q);
            }
            (false, false) => state.outside_piece(p, q),
        }
        in_p = in_q;
    }
    state.finish()
}

/// The running sums of [`walk`].
struct Walk {
    center: DVec2,
    radius: f64,
    /// Reference point of the shoelace sum: a point of (or next to) the measured region; for P \ D the current
    /// piece's exit point.
    origin: DVec2,
    /// The walk's first vertex: the reference point of `prefix`.
    start_vertex: DVec2,
    /// For P \ D: twice the area swept (about `start_vertex`) by the outside chain before the first exit.
    prefix: f64,
    keep_inside: bool,
    /// Twice the area of the straight polygon through the piece ends (kept pieces and arc chords).
    twice_straight: f64,
    /// Circular segments, added (inside) or subtracted (outside).
    arcs: f64,
    /// Pseudo-angle ([`pseudo_turn`]) swept at the centre by the outside pieces since the last exit (or the start).
    chain: f64,
    /// The exit point whose arc is still open.
    open_exit: Option<DVec2>,
    /// The first entry of the walk, when it came before any exit, with the chain angle before it: it closes the
    /// arc of the walk's last exit.
    first_entry: Option<(DVec2, f64)>,
    crossed: bool,
}

impl Walk {
    fn inside_piece(&mut self, u: DVec2, v: DVec2) {
        if self.keep_inside {
            self.twice_straight += cross(u - self.origin, v - self.origin);
        }
    }

    fn outside_piece(&mut self, u: DVec2, v: DVec2) {
        self.chain += pseudo_turn(u - self.center, v - self.center);
        // Outside pieces follow an exit, or come before the walk's first exit (the prefix).
        if self.keep_inside {
        } else if self.open_exit.is_some() {
            self.twice_straight += cross(u - self.origin, v - self.origin);
        } else {
            self.prefix += cross(u - self.start_vertex, v - self.start_vertex);
        }
    }

    fn exit(&mut self, point: DVec2, crossings: &mut Crossings) {
        crossings.push(point, false);
        self.crossed = true;
        if !self.keep_inside {
            self.origin = point;
        }
        self.open_exit = Some(point);
        self.chain = 0.0;
    }

    fn entry(&mut self, point: DVec2, crossings: &mut Crossings) {
        crossings.push(point, true);
        self.crossed = true;
        if let Some(exit) = self.open_exit.take() {
            self.arc(exit, point, self.chain);
        } else if self.first_entry.is_none() {
            self.first_entry = Some((point, self.chain));
        }
    }

    /// The arc counter-clockwise from `exit` to `entry`, whose outside chain subtends `chain` (in pseudo-angle
    /// units, 4 per turn). The end points fix the angle up to a whole turn, which matters only when they (nearly)
    /// coincide: then the chain tells an empty arc (chain ≈ 0) from a full one (chain ≈ 4).
    fn arc(&mut self, exit: DVec2, entry: DVec2, chain: f64) {
        let direct = subtended(exit - self.center, entry - self.center);
        let mut angle = if direct < 0.0 { direct + TAU } else { direct };
        if angle > 1.5 * PI && chain < 2.0 {
            angle -= TAU;
        } else if angle < 0.5 * PI && chain > 2.0 {
            angle += TAU;
        }
        let angle = angle.clamp(0.0, TAU);
        let segment = circular_segment_area(self.radius, angle);
        let (u, v) = (exit - self.origin, entry - self.origin);
        if self.keep_inside {
            self.twice_straight += cross(u, v);
            self.arcs += segment;
        } else {
            self.twice_straight += cross(v, u);
            self.arcs -= segment;
        }
    }

    fn finish(mut self) -> f64 {
        if let (Some(exit), Some((entry, before))) = (self.open_exit.take(), self.first_entry) {
            self.arc(exit, entry, self.chain + before);
            if !self.keep_inside {
                // The chain before the first exit ran from the first vertex to `entry`: moved onto `exit` as origin.
                self.prefix -= cross(exit - self.start_vertex, entry - self.start_vertex);
            }
        }
        self.twice_straight += self.prefix;
        // No crossing and every vertex outside: the chain is the polygon's winding about the centre (0 or 4).
        if !self.crossed && self.chain > 2.0 {
            let disk = PI * self.radius * self.radius;
            self.arcs += if self.keep_inside { disk } else { -disk };
        }
        let area = 0.5 * self.twice_straight + self.arcs;
        if area.is_finite() { area.max(0.0) } else { 0.0 }
    }
}

/// A monotone stand-in for the polar angle of `v` (≠ 0), 0..4 per turn (the "diamond angle"): cheaper than
/// `atan2`, and enough to count the whole turns of an outside chain. p(−v) = p(v) + 2 (mod 4), so a step of less
/// than half a turn is a pseudo-step of less than 2.
fn pseudo_angle(v: DVec2) -> f64 {
    if v.y >= 0.0 {
        if v.x >= 0.0 { v.y / (v.x + v.y) } else { 1.0 - v.x / (v.y - v.x) }
    } else if v.x < 0.0 {
        2.0 - v.y / (-v.x - v.y)
    } else {
        3.0 + v.x / (v.x - v.y)
    }
}

/// The pseudo-angle swept from `u` to `v` (relative to the centre) by a straight step of less than half a turn,
/// in (−2, 2].
fn pseudo_turn(u: DVec2, v: DVec2) -> f64 {
    let step = pseudo_angle(v) - pseudo_angle(u);
    if step > 2.0 {
        step - 4.0
    } else if step <= -2.0 {
        step + 4.0
    } else {
        step
    }
}

/// For the line `p + t·e` (`p` relative to the circle's centre): the parameter t₀ of the point nearest the centre
/// and the half-width s of the chord in parameter units (0 when the line misses the circle), from the line's
/// distance dl as √((r − dl)(r + dl))/|e|.
fn line_parameters(p: DVec2, e: DVec2, radius: f64) -> (f64, f64) {
    let length_squared = e.length_squared();
    if !positive(length_squared) {
        return (0.0, 0.0);
    }
    let length = length_squared.sqrt();
    let dl = cross(e, p).abs() / length;
    let s = if dl < radius { ((radius - dl) * (radius + dl)).sqrt() / length } else { 0.0 };
    (-p.dot(e) / length_squared, s)
}

/// Where a point lies relative to a convex polygon's outline.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Boundary {
    /// The point of the outline nearest to the query point.
    pub(crate) point: DVec2,
    /// Distance from the query point to the outline, ≥ 0.
    pub(crate) distance: f64,
    /// The query point is inside the polygon or on its outline.
    pub(crate) inside: bool,
    /// The nearest outline point is a vertex (only for outside points).
    pub(crate) vertex: bool,
    /// Outward unit normal of the nearest edge (for inside points: the edge the point is pushed out through).
    pub(crate) edge_normal: DVec2,
}

impl Boundary {
    /// The nearest point of the closed polygon: the query point itself when inside.
    fn clamped_point(&self, query: DVec2) -> DVec2 {
        if self.inside { query } else { self.point }
    }
}

/// The nearest outline point of the convex counter-clockwise polygon to `c`. Inside (all edge sides ≥ 0), the
/// nearest outline point is the foot on the nearest edge line, which lies on that edge for a convex polygon.
pub(crate) fn closest_boundary(c: DVec2, polygon: &[DVec2]) -> Boundary {
    let n = polygon.len();
    let (mut inside, mut least_side, mut least_edge) = (true, f64::INFINITY, 0);
    for k in 0..n {
        let (p, q) = (polygon[k], polygon[if k + 1 == n { 0 } else { k + 1 }]);
        let e = q - p;
        let side = cross(e, c - p) / e.length();
        if side < 0.0 {
            inside = false;
        }
        if side < least_side {
            (least_side, least_edge) = (side, k);
        }
    }
    let edge_normal_of = |k: usize| {
        let e = polygon[if k + 1 == n { 0 } else { k + 1 }] - polygon[k];
        -e.perp() / e.length()
    };
    if inside {
        let edge_normal = edge_normal_of(least_edge);
        return Boundary {
            point: c + least_side * edge_normal,
            distance: least_side,
            inside,
            vertex: false,
            edge_normal,
        };
    }
    let (mut best, mut best_distance, mut best_vertex, mut best_edge) = (polygon[0], f64::INFINITY, true, 0);
    for k in 0..n {
        let (p, q) = (polygon[k], polygon[if k + 1 == n { 0 } else { k + 1 }]);
        let (point, t) = super::closest_on_segment(c, p, q);
        let distance = (c - point).length();
        if distance < best_distance {
            (best, best_distance, best_vertex, best_edge) = (point, distance, t <= 0.0 || t >= 1.0, k);
        }
    }
    if !best_vertex {
        // Off an edge's interior: the distance to its line (exact perpendicular, no rounded foot point).
        let (p, q) = (polygon[best_edge], polygon[if best_edge + 1 == n { 0 } else { best_edge + 1 }]);
        best_distance = -cross(q - p, c - p) / (q - p).length();
    }
    Boundary {
        point: best,
        distance: best_distance,
        inside,
        vertex: best_vertex,
        edge_normal: edge_normal_of(best_edge),
    }
}

/// The vertex farthest from `c` and its distance.
fn farthest_vertex(c: DVec2, polygon: &[DVec2]) -> (DVec2, f64) {
    polygon.iter().fold((polygon[0], -1.0), |(best, distance), &p| {
        let d = (p - c).length();
        if d > distance { (p, d) } else { (best, distance) }
    })
}

/// Area of the intersection of the disk (`center`, `radius`) with the convex counter-clockwise polygon `polygon`
/// (3..=[`MAX_VERTICES`](crate::MAX_VERTICES) world vertices), m²; exact to rounding, also for shallow overlaps.
/// 0 for non-finite or degenerate input. Allocation-free.
pub fn circle_polygon_intersection_area(center: DVec2, radius: f64, polygon: &[DVec2]) -> f64 {
    if !(finite(center) && positive(radius) && admissible_polygon(polygon)) {
        return 0.0;
    }
    walk(center, radius, polygon, Part::InsideCircle, &mut Crossings::new())
}

/// Area of the part of the convex counter-clockwise polygon outside the circle (`center`, `radius`), m²: what a
/// chamber's wall (solid outside the circle) overlaps. Computed directly, not as area(P) − area(P ∩ D), so that a
/// corner poking 1e-8 out of a chamber keeps its digits. 0 for non-finite or degenerate input.
pub fn polygon_outside_circle_area(polygon: &[DVec2], center: DVec2, radius: f64) -> f64 {
    if !(finite(center) && positive(radius) && admissible_polygon(polygon)) {
        return 0.0;
    }
    walk(center, radius, polygon, Part::OutsideCircle, &mut Crossings::new())
}

/// Area centroid of the intersection, of area `area` (> 0, as [`circle_polygon_intersection_area`] gives it), of the
/// disk (`center`, `radius`) with the convex counter-clockwise polygon.
pub(crate) fn disk_polygon_centroid(center: DVec2, radius: f64, polygon: &[DVec2], area: f64) -> DVec2 {
    center + disk_polygon_moment(center, radius, polygon) / area
}

/// Area centroid of the part, of area `area` (> 0, as [`polygon_outside_circle_area`] gives it), of the convex
/// counter-clockwise polygon outside the circle (`center`, `radius`): the first moment of the polygon less that of
/// its part inside the circle.
pub(crate) fn polygon_outside_circle_centroid(polygon: &[DVec2], center: DVec2, radius: f64, area: f64) -> DVec2 {
    let whole = polygon_area(polygon) * (polygon_centroid(polygon) - center);
    center + (whole - disk_polygon_moment(center, radius, polygon)) / area
}

/// First moment ∫∫ (x − `center`) dA of the disk ∩ polygon, m³, by a fan from the centre: a triangle for each piece
/// of an edge inside the disk and a circular sector for each piece outside. The fan cancels where the overlap is a
/// tiny part of the disk (the reason [`walk`] sums areas otherwise), but its absolute error, ~1e-16·r³, is far below
/// anything a contact's moment resolves; [`walk`]'s exact area divides it.
pub(crate) fn disk_polygon_moment(center: DVec2, radius: f64, polygon: &[DVec2]) -> DVec2 {
    let n = polygon.len();
    // Sector between the rays through `a` and `b` (relative to the centre, outside the disk, less than half a turn
    // apart): ∫ (r³/3)(cos θ, sin θ) dθ = −(r³/3)·perp(b̂ − â).
    let sector = |a: DVec2, b: DVec2| -(radius * radius * radius / 3.0) * (b.normalize() - a.normalize()).perp();
    let triangle = |u: DVec2, v: DVec2| cross(u, v) / 6.0 * (u + v);
    let mut moment = DVec2::ZERO;
    for k in 0..n {
        let (p, q) = (polygon[k] - center, polygon[if k + 1 == n { 0 } else { k + 1 }] - center);
        let e = q - p;
        let Some((t1, t2)) = super::line_circle(p, e, radius) else {
            moment += sector(p, q);
            continue;
        };
        let (enter, leave) = (t1.clamp(0.0, 1.0), t2.clamp(0.0, 1.0));
        let (u, v) = (p + e * enter, p + e * leave);
        if enter > 0.0 {
            moment += sector(p, u);
        }
        if leave > enter {
            moment += triangle(u, v);
        }
        if leave < 1.0 {
            moment += sector(v, q);
        }
    }
    moment
}

/// The smaller of a disk and a polygon, for the containment chord.
fn smaller<'a>(center: DVec2, radius: f64, polygon: &'a [DVec2]) -> Inner<'a> {
    if PI * radius * radius <= polygon_area(polygon) { Inner::Disk { center, radius } } else { Inner::Polygon(polygon) }
}

/// Disk i against polygon j: the exact overlap; the disk's outline enters the polygon where the polygon's leaves
/// the disk.
pub(crate) fn disk_polygon_area_contact(center: DVec2, radius: f64, polygon: &[DVec2]) -> Option<AreaContact> {
    if !(finite(center) && positive(radius) && admissible_polygon(polygon)) {
        return None;
    }
    let mut crossings = Crossings::new();
    let area = walk(center, radius, polygon, Part::InsideCircle, &mut crossings);
    if area <= 0.0 {
        return None;
    }
    crossings.flip();
    area_contact_from_crossings(area, crossings.as_slice(), || {
        (center - polygon_centroid(polygon), smaller(center, radius, polygon))
    })
}

/// Polygon i against disk j: the same overlap and crossings as [`disk_polygon_area_contact`], entries and exits
/// swapped.
pub(crate) fn polygon_disk_area_contact(polygon: &[DVec2], center: DVec2, radius: f64) -> Option<AreaContact> {
    if !(finite(center) && positive(radius) && admissible_polygon(polygon)) {
        return None;
    }
    let mut crossings = Crossings::new();
    let area = walk(center, radius, polygon, Part::InsideCircle, &mut crossings);
    if area <= 0.0 {
        return None;
    }
    area_contact_from_crossings(area, crossings.as_slice(), || {
        (polygon_centroid(polygon) - center, smaller(center, radius, polygon))
    })
}

/// Polygon i in a chamber j: the part of the polygon outside the circle; the polygon enters the solid where it
/// leaves the disk. Containment (the polygon wholly in the solid) pushes it towards the chamber's centre.
pub(crate) fn polygon_inner_area_contact(polygon: &[DVec2], center: DVec2, radius: f64) -> Option<AreaContact> {
    if !(finite(center) && positive(radius) && admissible_polygon(polygon)) {
        return None;
    }
    let mut crossings = Crossings::new();
    let area = walk(center, radius, polygon, Part::OutsideCircle, &mut crossings);
    if area <= 0.0 {
        return None;
    }
    crossings.flip();
    area_contact_from_crossings(area, crossings.as_slice(), || {
        (center - polygon_centroid(polygon), Inner::Polygon(polygon))
    })
}

/// Disk i against polygon j, exact: outside, depth r − distance to the nearest outline point (a vertex: surface
/// radius 0, an edge: ∞), normal from that point to the centre; centre inside (or on the outline), depth r + its
/// distance to the nearest edge, pushed out through that edge.
pub(crate) fn disk_polygon_penetration(center: DVec2, radius: f64, polygon: &[DVec2]) -> Option<PairPenetration> {
    if !(finite(center) && positive(radius) && admissible_polygon(polygon)) {
        return None;
    }
    let boundary = closest_boundary(center, polygon);
    if boundary.inside || !positive(boundary.distance) {
        let normal = boundary.edge_normal;
        let depth = radius + if boundary.inside { boundary.distance } else { 0.0 };
        return PairPenetration::new(depth, normal, center - radius * normal, radius, f64::INFINITY);
    }
    // Off an edge the normal is the edge's own (exactly perpendicular to it); off a vertex, towards the centre.
    let normal = if boundary.vertex { (center - boundary.point) / boundary.distance } else { boundary.edge_normal };
    let surface_radius = if boundary.vertex { 0.0 } else { f64::INFINITY };
    PairPenetration::new(radius - boundary.distance, normal, center - radius * normal, radius, surface_radius)
}

/// Polygon i in a chamber j: the vertex farthest from the centre decides (one contact per pair); depth = its
/// distance − R, normal towards the centre, j's surface radius −R, i's 0 (a vertex).
pub(crate) fn polygon_inner_penetration(polygon: &[DVec2], center: DVec2, radius: f64) -> Option<PairPenetration> {
    if !(finite(center) && positive(radius) && admissible_polygon(polygon)) {
        return None;
    }
    let (vertex, distance) = farthest_vertex(center, polygon);
    if !positive(distance) {
        return None;
    }
    PairPenetration::new(distance - radius, (center - vertex) / distance, vertex, 0.0, -radius)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn v(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> [DVec2; 4] {
        [v(x0, y0), v(x1, y0), v(x1, y1), v(x0, y1)]
    }

    /// The cap of height h of a circle of radius r.
    fn cap(r: f64, h: f64) -> f64 {
        let half_angle = ((r - h) / r).acos();
        circular_segment_area(r, 2.0 * half_angle)
    }

    #[test]
    fn a_disk_on_a_floor_overlaps_by_its_cap() {
        let (r, h) = (1.75e-3, 1e-9);
        let floor = rect(-1.0, -1.0, 1.0, 0.0);
        let center = v(0.07, r - h);
        let c = disk_polygon_area_contact(center, r, &floor).unwrap();
        assert_relative_eq!(c.area, cap(r, h), max_relative = 1e-6);
        assert_eq!(c.normal, DVec2::Y);
        assert_relative_eq!(c.point, v(0.07, 0.0), epsilon = 1e-15);
        assert_relative_eq!(c.chord_length, 2.0 * (2.0 * r * h - h * h).sqrt(), max_relative = 1e-6);
        let d = polygon_disk_area_contact(&floor, center, r).unwrap();
        assert_eq!((d.area, d.point, d.chord_length), (c.area, c.point, c.chord_length));
        assert_eq!(d.normal, -c.normal);
        let p = disk_polygon_penetration(center, r, &floor).unwrap().penetration;
        assert_relative_eq!(p.depth, h, max_relative = 1e-6);
        assert_eq!((p.normal, p.surface_radius_j), (DVec2::Y, f64::INFINITY));
    }

    #[test]
    fn containment_both_ways_and_a_cap_cut_off_a_contained_disk() {
        let square = rect(-1.0, -1.0, 1.0, 1.0);
        assert_relative_eq!(circle_polygon_intersection_area(v(0.1, 0.2), 0.5, &square), PI * 0.25);
        assert_relative_eq!(circle_polygon_intersection_area(v(0.0, 0.0), 10.0, &square), 4.0);
        assert_eq!(circle_polygon_intersection_area(v(3.0, 0.0), 1.0, &square), 0.0);
        // A disk poking a hair out through the right edge: all but a tiny cap.
        let (r, h) = (0.5, 1e-6);
        let area = circle_polygon_intersection_area(v(1.0 - r + h, 0.0), r, &square);
        assert_relative_eq!(PI * r * r - area, cap(r, h), max_relative = 1e-3);
        assert!(area < PI * r * r);
        // A corner poking out of a circle.
        let outside = polygon_outside_circle_area(&square, DVec2::ZERO, 2f64.sqrt() - 1e-3);
        assert!(outside > 0.0 && outside < 4.0 * 1e-5);
        assert_relative_eq!(
            outside + circle_polygon_intersection_area(DVec2::ZERO, 2f64.sqrt() - 1e-3, &square),
            4.0,
            max_relative = 1e-14
        );
    }

    #[test]
    fn a_disk_centre_inside_a_polygon_is_pushed_out_through_the_nearest_edge() {
        let square = rect(0.0, 0.0, 1.0, 1.0);
        let p = disk_polygon_penetration(v(0.9, 0.5), 0.2, &square).unwrap().penetration;
        assert_relative_eq!(p.depth, 0.3, max_relative = 1e-14);
        assert_eq!(p.normal, DVec2::X);
        assert_relative_eq!(p.point, v(0.85, 0.5), epsilon = 1e-15);
        // Off a corner: vertex contact.
        let q = disk_polygon_penetration(v(1.1, 1.1), 0.2, &square).unwrap().penetration;
        assert_relative_eq!(q.depth, 0.2 - 0.1 * 2f64.sqrt(), max_relative = 1e-12);
        assert_eq!(q.surface_radius_j, 0.0);
        assert!(disk_polygon_penetration(v(1.3, 0.5), 0.2, &square).is_none());
    }

    #[test]
    fn a_disk_across_a_strip_takes_the_farthest_crossing_pair() {
        // Four crossings: (±x_top, 0.05) and (±x_bottom, −0.05); the farthest pair is a diagonal, and the area
        // gradient (the overlap shrinks as the disk moves up) orients the normal upwards, as for polygons.
        let strip = rect(-1.0, -0.05, 1.0, 0.05);
        let (c, r) = (v(0.0, 0.01), 0.5);
        let a = disk_polygon_area_contact(c, r, &strip).unwrap();
        let (top, bottom) = ((r * r - 0.04f64 * 0.04).sqrt(), (r * r - 0.06f64 * 0.06).sqrt());
        assert_relative_eq!(a.chord_length, ((top + bottom).powi(2) + 0.01).sqrt(), max_relative = 1e-14);
        // Two diagonals tie; the first found is kept.
        assert_relative_eq!(a.point.x.abs(), 0.5 * (top - bottom), epsilon = 1e-15);
        assert_relative_eq!(a.point.y, 0.0, epsilon = 1e-15);
        assert!(a.normal.y > 0.99);
        let b = polygon_disk_area_contact(&strip, c, r).unwrap();
        assert_eq!((b.area, b.point, b.normal), (a.area, a.point, -a.normal));
    }
}
