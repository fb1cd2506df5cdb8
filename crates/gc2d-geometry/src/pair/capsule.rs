//! A capsule wall (the core segment a–b swept by a disk of radius ρ: a stadium) against a disk or a polygon.
//!
//! Areas are exact, from the partition of the stadium K into the rectangle R = a–b ± ρ·n and the two half-disks
//! H_a, H_b beyond the end lines:
//!
//! - polygon: |P ∩ K| = |P ∩ R| (polygon clipping, [`overlap_polygon`]) + Σ |(P clipped to the half-plane of
//!   the end) ∩ D_end| (circle ∩ polygon);
//! - disk: |D ∩ K| = |D ∩ R| + Σ |D ∩ D_end ∩ half-plane|, where the lens D ∩ D_end is split by the two circles'
//!   radical line (on D_end's side of it the lens is D, on D's side it is D_end), so that each term is a circle
//!   intersected with a convex polygon: the circle's bounding square clipped by the end's half-plane and by the
//!   radical line.
//!
//! The chord comes from the crossings of the two outlines (segments and half circles); penetrations are exact
//! (closest points on the core segment; for a polygon crossed by the core, the separating axes of polygon and
//! segment, plus ρ).

use super::circle_polygon::{self, Part, walk};
use super::circles::{CirclePair, circle_pair, disk_disk_area_contact, disk_disk_penetration};
use super::{
    Crossings, Inner, admissible_polygon, area_contact_from_crossings, closest_on_segment, finite, line_circle,
    polygon_area, polygon_centroid, positive,
};
use crate::shape::{AreaContact, PairPenetration};
use crate::{DVec2, MAX_VERTICES, OverlapPolygon, cross, overlap_polygon};
use std::f64::consts::PI;

/// A non-degenerate capsule (a ≠ b): its axis, the unit normal on the axis's left, and the rectangle part.
struct Stadium {
    a: DVec2,
    b: DVec2,
    radius: f64,
    axis: DVec2,
    normal: DVec2,
    /// The rectangle a − ρn, b − ρn, b + ρn, a + ρn (counter-clockwise).
    rectangle: [DVec2; 4],
}

impl Stadium {
    fn new(a: DVec2, b: DVec2, radius: f64) -> Option<Self> {
        let axis = (b - a).try_normalize()?;
        let normal = axis.perp();
        let side = radius * normal;
        Some(Self { a, b, radius, axis, normal, rectangle: [a - side, b - side, b + side, a + side] })
    }

    /// The two ends: centre and outward axis direction.
    fn ends(&self) -> [(DVec2, DVec2); 2] {
        [(self.a, -self.axis), (self.b, self.axis)]
    }

    /// The two straight sides, each as (start, end, outward normal), counter-clockwise.
    fn sides(&self) -> [(DVec2, DVec2, DVec2); 2] {
        let [p0, p1, p2, p3] = self.rectangle;
        [(p0, p1, -self.normal), (p2, p3, self.normal)]
    }

    fn area(&self) -> f64 {
        2.0 * self.radius * (self.b - self.a).length() + PI * self.radius * self.radius
    }
}

/// Clips the polygon `points` to the closed half-plane {x : (x − origin)·direction ≥ 0} into `out`; returns the
/// number of vertices written (0 when nothing is left). `out` must hold `points.len() + 1` vertices.
fn clip_half_plane(points: &[DVec2], origin: DVec2, direction: DVec2, out: &mut [DVec2]) -> usize {
    let side = |p: DVec2| (p - origin).dot(direction);
    let mut len = 0;
    let mut push = |p: DVec2, len: &mut usize| {
        if let Some(slot) = out.get_mut(*len) {
            *slot = p;
            *len += 1;
        }
    };
    let Some(&last) = points.last() else { return 0 };
    let (mut p, mut sp) = (last, side(last));
    for &q in points {
        let sq = side(q);
        if sp >= 0.0 {
            push(p, &mut len);
            if sq < 0.0 {
                push(p + (q - p) * (sp / (sp - sq)), &mut len);
            }
        } else if sq > 0.0 {
            push(p + (q - p) * (sp / (sp - sq)), &mut len);
        }
        (p, sp) = (q, sq);
    }
    if len < 3 { 0 } else { len }
}

/// |D ∩ polygon| for a polygon that may be empty or degenerate (fewer than three vertices: 0).
fn circle_clipped_area(center: DVec2, radius: f64, polygon: &[DVec2]) -> f64 {
    if polygon.len() < 3 { 0.0 } else { walk(center, radius, polygon, Part::InsideCircle, &mut Crossings::new()) }
}

/// |D(center, radius) ∩ {(x − line_origin)·direction ≥ 0} ∩ {(x − cut_origin)·cut ≥ 0}|, exact: the circle's
/// bounding square (half-side 2r) clipped by both half-planes, intersected with the circle. A zero `cut` skips the
/// second half-plane.
fn circle_in_wedge(
    center: DVec2,
    radius: f64,
    line_origin: DVec2,
    direction: DVec2,
    cut_origin: DVec2,
    cut: DVec2,
) -> f64 {
    let h = 2.0 * radius;
    let square = [
        center + DVec2::new(-h, -h),
        center + DVec2::new(h, -h),
        center + DVec2::new(h, h),
        center + DVec2::new(-h, h),
    ];
    let (mut first, mut second) = ([DVec2::ZERO; 6], [DVec2::ZERO; 6]);
    let n = clip_half_plane(&square, line_origin, direction, &mut first);
    if n == 0 {
        return 0.0;
    }
    if cut == DVec2::ZERO {
        return circle_clipped_area(center, radius, &first[..n]);
    }
    let m = clip_half_plane(&first[..n], cut_origin, cut, &mut second);
    circle_clipped_area(center, radius, &second[..m])
}

/// |D ∩ H_end|: the disk (c, r) against the half-disk of radius ρ at `end` beyond its end line (outward `out`).
fn disk_half_disk_area(c: DVec2, r: f64, end: DVec2, rho: f64, out: DVec2) -> f64 {
    match circle_pair(c, r, end, rho) {
        CirclePair::Apart => 0.0,
        CirclePair::Nested => {
            let (center, radius) = if r <= rho { (c, r) } else { (end, rho) };
            circle_in_wedge(center, radius, end, out, end, DVec2::ZERO)
        }
        CirclePair::Crossing(crossing) => {
            // axis points from `end` towards c; the lens is D on end's side of the chord, D_end on c's side.
            let (axis, mid) = (crossing.axis, crossing.mid);
            circle_in_wedge(c, r, end, out, mid, -axis) + circle_in_wedge(end, rho, end, out, mid, axis)
        }
    }
}

/// Area of the intersection of the disk (`center`, `radius`) with the capsule (core a–b, `capsule_radius`), m²;
/// exact to rounding (see the module notes). 0 for non-finite or non-positive input.
pub fn disk_capsule_intersection_area(center: DVec2, radius: f64, a: DVec2, b: DVec2, capsule_radius: f64) -> f64 {
    if !(finite(center) && finite(a) && finite(b) && positive(radius) && positive(capsule_radius)) {
        return 0.0;
    }
    let Some(stadium) = Stadium::new(a, b, capsule_radius) else {
        return super::circles::lens_area(radius, capsule_radius, (center - a).length());
    };
    disk_stadium_area(center, radius, &stadium)
}

fn disk_stadium_area(center: DVec2, radius: f64, stadium: &Stadium) -> f64 {
    let mut area = circle_clipped_area(center, radius, &stadium.rectangle);
    for (end, out) in stadium.ends() {
        area += disk_half_disk_area(center, radius, end, stadium.radius, out);
    }
    area
}

/// Area of the intersection of the convex counter-clockwise polygon with the capsule (core a–b,
/// `capsule_radius`), m²; exact to rounding. 0 for non-finite or degenerate input.
pub fn polygon_capsule_intersection_area(polygon: &[DVec2], a: DVec2, b: DVec2, capsule_radius: f64) -> f64 {
    if !(admissible_polygon(polygon) && finite(a) && finite(b) && positive(capsule_radius)) {
        return 0.0;
    }
    let Some(stadium) = Stadium::new(a, b, capsule_radius) else {
        return circle_polygon::circle_polygon_intersection_area(a, capsule_radius, polygon);
    };
    polygon_stadium_area(polygon, &stadium)
}

fn polygon_stadium_area(polygon: &[DVec2], stadium: &Stadium) -> f64 {
    let mut overlap = OverlapPolygon::new();
    overlap_polygon(polygon, &stadium.rectangle, &mut overlap);
    let mut area = overlap.area();
    let mut clipped = [DVec2::ZERO; MAX_VERTICES + 1];
    for (end, out) in stadium.ends() {
        let n = clip_half_plane(polygon, end, out, &mut clipped);
        area += circle_clipped_area(end, stadium.radius, &clipped[..n]);
    }
    area
}

/// Area centroid of the overlap, of area `area` (> 0, as [`polygon_capsule_area_contact`] gives it), of the polygon
/// with the capsule (a, b, `rho`): the first moments of the same parts [`polygon_stadium_area`] sums (the polygon in
/// the rectangle, and beyond each end in its disk).
pub(crate) fn polygon_capsule_centroid(polygon: &[DVec2], a: DVec2, b: DVec2, rho: f64, area: f64) -> DVec2 {
    let Some(stadium) = Stadium::new(a, b, rho) else {
        return circle_polygon::disk_polygon_centroid(a, rho, polygon, area);
    };
    let mut overlap = OverlapPolygon::new();
    overlap_polygon(polygon, &stadium.rectangle, &mut overlap);
    let mut moment =
        if overlap.area() > 0.0 { overlap.area() * polygon_centroid(overlap.vertices()) } else { DVec2::ZERO };
    let mut clipped = [DVec2::ZERO; MAX_VERTICES + 1];
    for (end, out) in stadium.ends() {
        let n = clip_half_plane(polygon, end, out, &mut clipped);
        let part = circle_clipped_area(end, stadium.radius, &clipped[..n]);
        if part > 0.0 {
            moment += part * end + circle_polygon::disk_polygon_moment(end, stadium.radius, &clipped[..n]);
        }
    }
    moment / area
}

/// Crossings of the disk's outline with the stadium's, `entry` = the disk's counter-clockwise outline enters K.
fn disk_stadium_crossings(c: DVec2, r: f64, stadium: &Stadium, crossings: &mut Crossings) {
    let mut record = |p: DVec2, outward: DVec2| {
        let tangent = (p - c).perp();
        let along = tangent.dot(outward);
        if along != 0.0 {
            crossings.push(p, along < 0.0);
        }
    };
    for (start, end, outward) in stadium.sides() {
        if let Some((t1, t2)) = line_circle(start - c, end - start, r) {
            for t in [t1, t2] {
                if (0.0..=1.0).contains(&t) {
                    record(start + (end - start) * t, outward);
                }
            }
        }
    }
    for (center, out) in stadium.ends() {
        if let CirclePair::Crossing(crossing) = circle_pair(c, r, center, stadium.radius) {
            let (left, right) = crossing.points();
            for p in [left, right] {
                if (p - center).dot(out) > 0.0 {
                    record(p, (p - center) / stadium.radius);
                }
            }
        }
    }
}

/// Crossings of the polygon's outline with the stadium's, `entry` = the polygon's counter-clockwise outline enters
/// K. Parameters on the polygon's edges are half-open [0, 1), so a crossing at a vertex counts once.
fn polygon_stadium_crossings(polygon: &[DVec2], stadium: &Stadium, crossings: &mut Crossings) {
    let n = polygon.len();
    for k in 0..n {
        let (p, q) = (polygon[k], polygon[if k + 1 == n { 0 } else { k + 1 }]);
        let e = q - p;
        let mut record = |t: f64, outward: DVec2| {
            let along = e.dot(outward);
            if (0.0..1.0).contains(&t) && along != 0.0 {
                crossings.push(p + e * t, along < 0.0);
            }
        };
        for (start, end, outward) in stadium.sides() {
            let f = end - start;
            let denominator = cross(e, f);
            if denominator != 0.0 {
                let t = cross(start - p, f) / denominator;
                let v = cross(start - p, e) / denominator;
                if (0.0..=1.0).contains(&v) {
                    record(t, outward);
                }
            }
        }
        for (center, out) in stadium.ends() {
            if let Some((t1, t2)) = line_circle(p - center, e, stadium.radius) {
                for t in [t1, t2] {
                    let point = p + e * t;
                    if (point - center).dot(out) > 0.0 {
                        record(t, (point - center) / stadium.radius);
                    }
                }
            }
        }
    }
}

/// Disk i against capsule j for the area law.
pub(crate) fn disk_capsule_area_contact(c: DVec2, r: f64, a: DVec2, b: DVec2, rho: f64) -> Option<AreaContact> {
    if !(finite(c) && finite(a) && finite(b) && positive(r) && positive(rho)) {
        return None;
    }
    let Some(stadium) = Stadium::new(a, b, rho) else { return disk_disk_area_contact(c, r, a, rho) };
    if (c - closest_on_segment(c, a, b).0).length() >= r + rho {
        return None;
    }
    let area = disk_stadium_area(c, r, &stadium);
    if !positive(area) {
        return None;
    }
    let mut crossings = Crossings::new();
    disk_stadium_crossings(c, r, &stadium, &mut crossings);
    area_contact_from_crossings(area, crossings.as_slice(), || {
        let inner = if PI * r * r <= stadium.area() {
            Inner::Disk { center: c, radius: r }
        } else {
            Inner::Capsule { a, b, radius: rho }
        };
        (c - closest_on_segment(c, a, b).0, inner)
    })
}

/// Polygon i against capsule j for the area law.
pub(crate) fn polygon_capsule_area_contact(polygon: &[DVec2], a: DVec2, b: DVec2, rho: f64) -> Option<AreaContact> {
    if !(admissible_polygon(polygon) && finite(a) && finite(b) && positive(rho)) {
        return None;
    }
    let Some(stadium) = Stadium::new(a, b, rho) else {
        return circle_polygon::polygon_disk_area_contact(polygon, a, rho);
    };
    let area = polygon_stadium_area(polygon, &stadium);
    if !positive(area) {
        return None;
    }
    let mut crossings = Crossings::new();
    polygon_stadium_crossings(polygon, &stadium, &mut crossings);
    area_contact_from_crossings(area, crossings.as_slice(), || {
        let centroid = polygon_centroid(polygon);
        let inner = if polygon_area(polygon) <= stadium.area() {
            Inner::Polygon(polygon)
        } else {
            Inner::Capsule { a, b, radius: rho }
        };
        (centroid - closest_on_segment(centroid, a, b).0, inner)
    })
}

/// Disk i against capsule j: depth r + ρ − distance from the centre to the core segment, normal from the nearest
/// core point to the centre (the core's left normal when the centre lies on it); j's surface radius ρ on a cap,
/// ∞ on a side.
pub(crate) fn disk_capsule_penetration(c: DVec2, r: f64, a: DVec2, b: DVec2, rho: f64) -> Option<PairPenetration> {
    if !(finite(c) && finite(a) && finite(b) && positive(r) && positive(rho)) {
        return None;
    }
    if a == b {
        return disk_disk_penetration(c, r, a, rho);
    }
    let (q, t) = closest_on_segment(c, a, b);
    let on_cap = t <= 0.0 || t >= 1.0;
    let (distance, normal) = if on_cap {
        let offset = c - q;
        let distance = offset.length();
        (distance, if distance > 0.0 { offset / distance } else { (b - a).perp().normalize() })
    } else {
        // Off the side: the core's own normal and the distance to its line (no rounded foot point).
        side_distance(c, a, b)
    };
    PairPenetration::new(r + rho - distance, normal, c - r * normal, r, if on_cap { rho } else { f64::INFINITY })
}

/// Distance from `p` to the line through the segment s0–s1 (s0 ≠ s1) and the unit normal of that line pointing
/// towards `p` (the left normal when `p` lies on it).
fn side_distance(p: DVec2, s0: DVec2, s1: DVec2) -> (f64, DVec2) {
    let e = s1 - s0;
    let length = e.length();
    let side = cross(e, p - s0) / length;
    let left = e.perp() / length;
    if side >= 0.0 { (side, left) } else { (-side, -left) }
}

/// Polygon i against capsule j. Core segment apart from the polygon: depth ρ − their distance, normal from the
/// nearest core point to the nearest polygon point. Core crossing the polygon: the separating axis (the polygon's
/// edge normals and the core's normal) with the least overlap, depth = that overlap + ρ.
pub(crate) fn polygon_capsule_penetration(polygon: &[DVec2], a: DVec2, b: DVec2, rho: f64) -> Option<PairPenetration> {
    if !(admissible_polygon(polygon) && finite(a) && finite(b) && positive(rho)) {
        return None;
    }
    if a == b {
        return circle_polygon::disk_polygon_penetration(a, rho, polygon).map(PairPenetration::flipped);
    }
    let n = polygon.len();
    // Nearest points of polygon and core, assuming they do not cross: vertex–segment and end–edge candidates.
    let (mut best, mut on_polygon, mut on_core) = (f64::INFINITY, polygon[0], a);
    let (mut polygon_vertex, mut core_end, mut edge) = (true, true, 0);
    for k in 0..n {
        let (p, q) = (polygon[k], polygon[if k + 1 == n { 0 } else { k + 1 }]);
        let (point, t) = closest_on_segment(p, a, b);
        let distance = (p - point).length();
        if distance < best {
            (best, on_polygon, on_core) = (distance, p, point);
            (polygon_vertex, core_end) = (true, t <= 0.0 || t >= 1.0);
        }
        for end in [a, b] {
            let (point, t) = closest_on_segment(end, p, q);
            let distance = (end - point).length();
            if distance < best {
                (best, on_polygon, on_core) = (distance, point, end);
                (polygon_vertex, core_end, edge) = (t <= 0.0 || t >= 1.0, true, k);
            }
        }
    }
    let (core_depth, axis, kind) = least_overlap_axis(polygon, a, b);
    if core_depth <= 0.0 && best > 0.0 {
        // A flat feature on either side gives the normal exactly: the core's (polygon vertex off the core's side)
        // or the polygon edge's (core end off an edge); only vertex–end pairs take the difference of the points.
        let (best, normal) = if !core_end {
            side_distance(on_polygon, a, b)
        } else if !polygon_vertex {
            let (distance, towards_end) =
                side_distance(on_core, polygon[edge], polygon[if edge + 1 == n { 0 } else { edge + 1 }]);
            (distance, -towards_end)
        } else {
            (best, (on_polygon - on_core) / best)
        };
        let radius_i = if polygon_vertex { 0.0 } else { f64::INFINITY };
        let radius_j = if core_end { rho } else { f64::INFINITY };
        return PairPenetration::new(rho - best, normal, on_polygon, radius_i, radius_j);
    }
    // Crossing cores: the polygon moves along `axis` by core_depth + ρ.
    let depth = core_depth.max(0.0) + rho;
    let (on_i, radius_i, radius_j) = match kind {
        Axis::PolygonEdge => {
            // The deepest core end (the middle of the core when both are level), moved back to the polygon's edge.
            let (da, db) = (a.dot(axis), b.dot(axis));
            let deepest = if da > db {
                a
            } else if db > da {
                b
            } else {
                0.5 * (a + b)
            };
            let radius_j = if da == db { f64::INFINITY } else { rho };
            (deepest - core_depth.max(0.0) * axis, f64::INFINITY, radius_j)
        }
        Axis::CoreNormal => {
            let deepest =
                polygon.iter().copied().fold(polygon[0], |m, p| if p.dot(axis) < m.dot(axis) { p } else { m });
            (deepest, 0.0, f64::INFINITY)
        }
    };
    PairPenetration::new(depth, axis, on_i, radius_i, radius_j)
}

/// Which family a separating axis comes from.
#[derive(Clone, Copy)]
enum Axis {
    PolygonEdge,
    CoreNormal,
}

/// The axis u (unit, the direction the polygon must move) over the polygon's inward edge normals and ± the core's
/// normal with the least overlap max_core(u·x) − min_polygon(u·y); a negative overlap means the core and polygon
/// are apart.
fn least_overlap_axis(polygon: &[DVec2], a: DVec2, b: DVec2) -> (f64, DVec2, Axis) {
    let n = polygon.len();
    let lowest = |u: DVec2| polygon.iter().map(|p| p.dot(u)).fold(f64::INFINITY, f64::min);
    let mut best = (f64::INFINITY, DVec2::Y, Axis::PolygonEdge);
    for k in 0..n {
        let e = polygon[if k + 1 == n { 0 } else { k + 1 }] - polygon[k];
        let u = e.perp() / e.length();
        // Moving along the inward normal u, the polygon's edge k leads; the core must get below it.
        let overlap = a.dot(u).max(b.dot(u)) - polygon[k].dot(u);
        if overlap < best.0 {
            best = (overlap, u, Axis::PolygonEdge);
        }
    }
    let core_normal = (b - a).perp().normalize();
    for u in [core_normal, -core_normal] {
        let overlap = a.dot(u) - lowest(u);
        if overlap < best.0 {
            best = (overlap, u, Axis::CoreNormal);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn v(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    /// ∫ 2√(r² − s²) ds from s1 to s2: the area of a disk between two parallel lines.
    fn band(r: f64, s1: f64, s2: f64) -> f64 {
        let f = |s: f64| s * (r * r - s * s).sqrt() + r * r * (s / r).asin();
        f(s2) - f(s1)
    }

    #[test]
    fn a_ball_straddling_a_blade_takes_the_longer_side_as_chord() {
        let (a, b, rho) = (v(-1.0, 0.0), v(1.0, 0.0), 0.1);
        let (c, r) = (v(0.0, 0.05), 0.5);
        let contact = disk_capsule_area_contact(c, r, a, b, rho).unwrap();
        assert_relative_eq!(contact.area, band(r, -0.15, 0.05), max_relative = 1e-13);
        assert_relative_eq!(contact.normal, DVec2::Y, epsilon = 1e-15);
        assert_relative_eq!(contact.point, v(0.0, 0.1), epsilon = 1e-15);
        assert_relative_eq!(contact.chord_length, 2.0 * (r * r - 0.05f64 * 0.05).sqrt(), max_relative = 1e-14);
        let p = disk_capsule_penetration(c, r, a, b, rho).unwrap().penetration;
        assert_relative_eq!(p.depth, 0.55, max_relative = 1e-15);
        assert_eq!((p.normal, p.surface_radius_j), (DVec2::Y, f64::INFINITY));
    }

    #[test]
    fn a_ball_inside_a_blade_is_pushed_out_across_the_core() {
        let (a, b, rho) = (v(-1.0, 0.0), v(1.0, 0.0), 0.1);
        let contact = disk_capsule_area_contact(v(0.3, 0.02), 0.05, a, b, rho).unwrap();
        assert_relative_eq!(contact.area, PI * 0.05 * 0.05, max_relative = 1e-13);
        assert_relative_eq!(contact.normal, DVec2::Y, epsilon = 1e-14);
        assert_relative_eq!(contact.point, v(0.3, 0.02), epsilon = 1e-15);
        assert_relative_eq!(contact.chord_length, 0.1, max_relative = 1e-15);
    }

    #[test]
    fn a_ball_on_a_cap_meets_the_end_disk() {
        let (a, b, rho) = (v(-1.0, 0.0), v(1.0, 0.0), 0.1);
        let c = b + 0.2 * DVec2::from_angle(0.4);
        let contact = disk_capsule_area_contact(c, 0.15, a, b, rho).unwrap();
        assert_relative_eq!(contact.area, super::super::circles::lens_area(0.15, rho, 0.2), max_relative = 1e-13);
        assert_relative_eq!(contact.normal, DVec2::from_angle(0.4), epsilon = 1e-14);
        let p = disk_capsule_penetration(c, 0.15, a, b, rho).unwrap().penetration;
        assert_relative_eq!(p.depth, 0.05, max_relative = 1e-13);
        assert_eq!(p.surface_radius_j, rho);
    }

    #[test]
    fn a_square_crossed_by_the_core_is_pushed_along_the_least_overlap() {
        let (a, b, rho) = (v(-1.0, 0.0), v(1.0, 0.0), 0.1);
        let square = [v(-0.2, -0.05), v(0.2, -0.05), v(0.2, 0.35), v(-0.2, 0.35)];
        let p = polygon_capsule_penetration(&square, a, b, rho).unwrap().penetration;
        assert_relative_eq!(p.depth, 0.15, max_relative = 1e-14);
        assert_relative_eq!(p.normal, DVec2::Y, epsilon = 1e-15);
        assert_relative_eq!(p.point, v(0.0, 0.025), epsilon = 1e-15);
        assert_eq!(p.surface_radius_j, f64::INFINITY);
        let contact = polygon_capsule_area_contact(&square, a, b, rho).unwrap();
        assert_relative_eq!(contact.area, 0.06, max_relative = 1e-14);
        assert_relative_eq!(contact.normal, DVec2::Y, epsilon = 1e-15);
        assert_relative_eq!(contact.point, v(0.0, 0.1), epsilon = 1e-15);
        assert_relative_eq!(contact.chord_length, 0.4, max_relative = 1e-14);
        // The square's corner on the blade's side: a vertex contact.
        let tilted: Vec<DVec2> = square.iter().map(|&p| DVec2::from_angle(0.3).rotate(p) + v(0.1, 0.12)).collect();
        let q = polygon_capsule_penetration(&tilted, a, b, rho).unwrap();
        assert_eq!(q.surface_radius_i, 0.0);
        assert_relative_eq!(q.penetration.normal, DVec2::Y, epsilon = 1e-15);
    }

    #[test]
    fn a_blade_inside_a_polygon_overlaps_by_its_whole_area() {
        // The end half-disks lie inside the polygon with their centres on the clipping lines: each arc is exactly
        // half a turn, whatever side the rounding puts its end points on.
        let square = [v(-1.0, -1.0), v(1.0, -1.0), v(1.0, 1.0), v(-1.0, 1.0)];
        for (a, b) in [(v(-0.5, 0.0), v(0.5, 0.0)), (v(-0.3, -0.2), v(0.4, 0.35)), (v(0.1, 0.7), v(0.1, -0.6))] {
            let area = polygon_capsule_intersection_area(&square, a, b, 0.2);
            assert_relative_eq!(area, 0.4 * (b - a).length() + PI * 0.04, max_relative = 1e-14);
        }
    }

    #[test]
    fn degenerate_capsules_and_clipping() {
        assert_eq!(disk_capsule_intersection_area(v(0.0, 0.0), 1.0, v(0.5, 0.0), v(0.5, 0.0), 0.0), 0.0);
        assert_relative_eq!(
            disk_capsule_intersection_area(v(0.0, 0.0), 1.0, v(0.5, 0.0), v(0.5, 0.0), 0.2),
            PI * 0.04,
            max_relative = 1e-14
        );
        let mut out = [DVec2::ZERO; 5];
        let square = [v(0.0, 0.0), v(1.0, 0.0), v(1.0, 1.0), v(0.0, 1.0)];
        assert_eq!(clip_half_plane(&square, v(2.0, 0.0), DVec2::X, &mut out), 0);
        let n = clip_half_plane(&square, v(0.5, 0.0), DVec2::X, &mut out);
        assert_relative_eq!(polygon_area(&out[..n]), 0.5, max_relative = 1e-15);
    }
}
