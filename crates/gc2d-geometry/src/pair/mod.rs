//! Pair queries for every combination of [`ShapeView`](crate::ShapeView)s, one file per family of shape pairs:
//! two circles ([`circles`]), a circle and a convex polygon ([`circle_polygon`]), a capsule and a particle
//! ([`capsule`]), and two polygons ([`polygon_polygon`]). This module holds what they share: the circular-segment
//! area, line–circle crossings, and the chord rules of the overlap-area law (`docs/model.md`, “Contact geometry”),
//! restated for outlines that are not polygons.
//!
//! Everything here works on stack values and fixed buffers: nothing allocates, nothing panics.

pub mod capsule;
pub mod circle_polygon;
pub mod circles;
pub mod polygon_polygon;

use crate::overlap::DEGENERATE_CHORD_FRACTION;
use crate::shape::AreaContact;
use crate::{DVec2, MAX_VERTICES, cross};

/// A direction shorter than this fraction of the length it is compared with is treated as zero (as in the polygon
/// code's orientation fallback chain).
const NEGLIGIBLE_DIRECTION_FRACTION: f64 = 1e-9;

/// `x − sin x`, accurate to a few ulps also for small `x`, where the plain difference cancels: the area of a thin
/// circular segment is r²/2·(φ − sin φ) with φ ~ 1e-4 in a stiff contact.
pub(crate) fn x_minus_sin(x: f64) -> f64 {
    if x.abs() < 0.5 {
        let x2 = x * x;
        let mut term = x * x2 / 6.0;
        let mut sum = term;
        for k in 1..8 {
            term *= -x2 / (((2 * k + 2) * (2 * k + 3)) as f64);
            sum += term;
        }
        sum
    } else {
        x - x.sin()
    }
}

/// Area of the circular segment of a circle of `radius` cut off by a chord that subtends the arc angle `angle`
/// (radians, 0..=2π) at the centre: r²/2·(φ − sin φ). A full turn gives πr².
pub fn circular_segment_area(radius: f64, angle: f64) -> f64 {
    0.5 * radius * radius * x_minus_sin(angle)
}

/// The counter-clockwise angle swept by the ray from the origin as a point moves straight from `u` to `v` (both
/// relative to the origin), in (−π, π]; exact for a segment that does not pass through the origin.
#[inline]
pub(crate) fn subtended(u: DVec2, v: DVec2) -> f64 {
    cross(u, v).atan2(u.dot(v))
}

/// Where the line `p + t·e` crosses the circle of `radius` about the origin (`p` relative to the centre): the
/// parameters (t₁ ≤ t₂), or `None` when the line misses or only touches it. Computed from the line's distance `dl`
/// to the centre as t₀ ∓ √((r − dl)(r + dl))/|e|, which keeps the half-width of a shallow cut accurate.
pub(crate) fn line_circle(p: DVec2, e: DVec2, radius: f64) -> Option<(f64, f64)> {
    let length_squared = e.length_squared();
    if !positive(length_squared) {
        return None;
    }
    let length = length_squared.sqrt();
    let t0 = -p.dot(e) / length_squared;
    let dl = cross(e, p).abs() / length;
    if dl.is_nan() || dl >= radius {
        return None;
    }
    let s = ((radius - dl) * (radius + dl)).sqrt() / length;
    Some((t0 - s, t0 + s))
}

/// The point of segment a–b closest to `p`, and its parameter t ∈ [0, 1] (0 for a == b).
#[inline]
pub(crate) fn closest_on_segment(p: DVec2, a: DVec2, b: DVec2) -> (DVec2, f64) {
    let e = b - a;
    let length_squared = e.length_squared();
    if !positive(length_squared) {
        return (a, 0.0);
    }
    let t = ((p - a).dot(e) / length_squared).clamp(0.0, 1.0);
    (a + e * t, t)
}

/// True when `p` is a finite point.
#[inline]
pub(crate) fn finite(p: DVec2) -> bool {
    p.is_finite()
}

/// True when `radius` is a usable radius: finite and > 0.
#[inline]
pub(crate) fn positive(radius: f64) -> bool {
    radius.is_finite() && radius > 0.0
}

/// A polygon the pair queries accept: 3..=[`MAX_VERTICES`] finite vertices (convexity and orientation are the
/// caller's promise, as for [`contact_geometry`](crate::contact_geometry)).
pub(crate) fn admissible_polygon(points: &[DVec2]) -> bool {
    (3..=MAX_VERTICES).contains(&points.len()) && points.iter().all(|p| p.is_finite())
}

/// One point where body i's counter-clockwise outline crosses body j's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Crossing {
    pub(crate) point: DVec2,
    /// i's outline enters j here (it leaves j otherwise).
    pub(crate) entry: bool,
}

/// Room for the crossings of any admissible pair: a convex n-gon crosses a circle at most 2n times, and a capsule
/// outline (two segments, two half circles) at most 2(n + 2) times.
const CROSSINGS_CAP: usize = 2 * MAX_VERTICES + 8;

/// The crossings of two outlines, in a fixed stack buffer.
pub(crate) struct Crossings {
    items: [Crossing; CROSSINGS_CAP],
    len: usize,
}

impl Crossings {
    pub(crate) fn new() -> Self {
        Self { items: [Crossing { point: DVec2::ZERO, entry: false }; CROSSINGS_CAP], len: 0 }
    }

    /// Records a crossing; a full buffer (impossible for admissible convex input) drops it.
    pub(crate) fn push(&mut self, point: DVec2, entry: bool) {
        if let Some(slot) = self.items.get_mut(self.len) {
            *slot = Crossing { point, entry };
            self.len += 1;
        }
    }

    pub(crate) fn as_slice(&self) -> &[Crossing] {
        &self.items[..self.len]
    }

    /// The same crossings seen from the other body: every entry becomes an exit.
    pub(crate) fn flip(&mut self) {
        for item in &mut self.items[..self.len] {
            item.entry = !item.entry;
        }
    }
}

/// The shape the containment policy measures its chord on: the smaller of the two bodies, which is (all but)
/// the overlap when one body lies inside the other.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Inner<'a> {
    Disk { center: DVec2, radius: f64 },
    Polygon(&'a [DVec2]),
    Capsule { a: DVec2, b: DVec2, radius: f64 },
}

impl Inner<'_> {
    /// Centre of the shape and the extent (low, high) of its chord through that centre along `tangent` (unit).
    fn chord_through_centre(&self, tangent: DVec2) -> (DVec2, f64, f64) {
        match *self {
            Inner::Disk { center, radius } => (center, -radius, radius),
            Inner::Polygon(points) => {
                let center = polygon_centroid(points);
                let normal = tangent.perp();
                let (mut low, mut high) = (0.0f64, 0.0f64);
                let n = points.len();
                for k in 0..n {
                    let (p, q) = (points[k], points[if k + 1 == n { 0 } else { k + 1 }]);
                    let (dp, dq) = (normal.dot(p - center), normal.dot(q - center));
                    if (dp <= 0.0) != (dq <= 0.0) {
                        let at = tangent.dot(p + (q - p) * (dp / (dp - dq)) - center);
                        low = low.min(at);
                        high = high.max(at);
                    }
                }
                (center, low, high)
            }
            Inner::Capsule { a, b, radius } => {
                // Half-chord of the stadium through its centre: out through a side (ρ/β) or through a cap.
                let center = 0.5 * (a + b);
                let half_length = 0.5 * (b - a).length();
                let axis = (b - a).try_normalize().unwrap_or(DVec2::X);
                let (along, across) = (tangent.dot(axis).abs(), tangent.perp_dot(axis).abs());
                let reach = if across * half_length <= radius * along {
                    half_length * along
                        + (radius * radius - half_length * half_length * across * across).max(0.0).sqrt()
                } else {
                    radius / across
                };
                (center, -reach, reach)
            }
        }
    }
}

/// The area-law contact of body i with body j from the overlap `area` (> 0) and the crossings of their outlines,
/// following the polygon rules of `docs/model.md`:
///
/// - one entry and one exit: c1 = entry, c2 = exit, normal = perp(c2 − c1)/|c2 − c1| (= −∂A/∂x_i direction);
/// - more crossings: the two farthest apart, oriented so that the normal has a positive component along, in turn,
///   the area gradient perp(Σ exits − Σ entries), `away`, +y, +x (the first that is not negligible decides);
/// - none, or a chord shorter than 1e-9·√A: containment; the normal is unit(`away`) (+y when `away` is negligible)
///   and the chord is `inner`'s width across it, through `inner`'s centre.
///
/// `fallback` gives (`away`, `inner`) and is called only when a rule needs them (they cost O(n) for a polygon).
pub(crate) fn area_contact_from_crossings<'a>(
    area: f64,
    crossings: &[Crossing],
    fallback: impl Fn() -> (DVec2, Inner<'a>),
) -> Option<AreaContact> {
    if !(area.is_finite() && area > 0.0) {
        return None;
    }
    let min_chord = DEGENERATE_CHORD_FRACTION * area.sqrt();
    let entries = crossings.iter().filter(|c| c.entry).count();
    let chord = match crossings {
        [first, second] if entries == 1 => {
            let (entry, exit) = if first.entry { (first, second) } else { (second, first) };
            Some((entry.point, exit.point))
        }
        [] | [_] => None,
        _ => farthest_crossings(crossings, || fallback().0),
    }
    .filter(|(c1, c2)| (*c2 - *c1).length() > min_chord);
    let contact = match chord {
        Some((c1, c2)) => {
            let chord = c2 - c1;
            let chord_length = chord.length();
            AreaContact {
                area,
                chord_length,
                point: 0.5 * (c1 + c2),
                normal: chord.perp() / chord_length,
                centroid: None,
            }
        }
        None => {
            let (away, inner) = fallback();
            let normal =
                if away.length() > NEGLIGIBLE_DIRECTION_FRACTION * area.sqrt() { away.normalize() } else { DVec2::Y };
            // perp(tangent) = normal, so that normal = perp(c2 − c1)/|c2 − c1| as for every other kind.
            let tangent = DVec2::new(normal.y, -normal.x);
            let (center, low, high) = inner.chord_through_centre(tangent);
            let (c1, c2) = (center + low * tangent, center + high * tangent);
            AreaContact { area, chord_length: high - low, point: 0.5 * (c1 + c2), normal, centroid: None }
        }
    };
    (contact.normal.is_finite() && contact.point.is_finite() && contact.chord_length > 0.0).then_some(contact)
}

/// The two crossings farthest apart, ordered by the orientation chain of [`area_contact_from_crossings`].
fn farthest_crossings(crossings: &[Crossing], away: impl Fn() -> DVec2) -> Option<(DVec2, DVec2)> {
    let origin = crossings[0].point;
    let mut gradient_chord = DVec2::ZERO;
    let mut best: Option<(DVec2, DVec2)> = None;
    let mut best_distance = 0.0;
    for (k, c) in crossings.iter().enumerate() {
        if c.entry {
            gradient_chord -= c.point - origin;
        } else {
            gradient_chord += c.point - origin;
        }
        for d in &crossings[k + 1..] {
            let distance = d.point.distance_squared(c.point);
            if distance > best_distance {
                best_distance = distance;
                best = Some((c.point, d.point));
            }
        }
    }
    let (p, q) = best?;
    let chord = q - p;
    let negligible = NEGLIGIBLE_DIRECTION_FRACTION * chord.length();
    // (alignment of the candidate normal perp(chord) with a reference direction, that reference's length): a
    // reference decides when it is not negligible against the chord and the alignment not negligible against it.
    let decides =
        |(alignment, reference): (f64, f64)| reference > negligible && alignment.abs() > negligible * reference;
    let by_gradient = (chord.dot(gradient_chord), gradient_chord.length());
    let decisive = if decides(by_gradient) {
        Some(by_gradient)
    } else {
        let away = away();
        [(chord.perp().dot(away), away.length()), (chord.perp().y, 1.0), (chord.perp().x, 1.0)]
            .into_iter()
            .find(|&reference| decides(reference))
    };
    match decisive {
        Some((alignment, _)) if alignment < 0.0 => Some((q, p)),
        _ => Some((p, q)),
    }
}

pub(crate) use crate::overlap::centroid as polygon_centroid;

/// Area of a counter-clockwise polygon, summed relative to its first vertex.
pub(crate) fn polygon_area(points: &[DVec2]) -> f64 {
    let Some(&origin) = points.first() else { return 0.0 };
    let mut sum = 0.0;
    for pair in points[1..].windows(2) {
        sum += cross(pair[0] - origin, pair[1] - origin);
    }
    0.5 * sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn x_minus_sin_is_accurate_on_both_sides_of_the_series_switch() {
        for x in [1e-6, 1e-3, 0.1, 0.4999, 0.5, 1.0, 3.0, 6.2] {
            // Reference: the series summed in higher effective precision by many more terms.
            let mut term = x * x * x / 6.0;
            let mut sum = term;
            for k in 1..40 {
                term *= -x * x / (((2 * k + 2) * (2 * k + 3)) as f64);
                sum += term;
            }
            assert_relative_eq!(x_minus_sin(x), sum, max_relative = 1e-14);
        }
        assert_eq!(x_minus_sin(0.0), 0.0);
    }

    #[test]
    fn segment_of_a_full_turn_is_the_disk() {
        assert_relative_eq!(circular_segment_area(2.0, std::f64::consts::TAU), 4.0 * std::f64::consts::PI);
        assert_relative_eq!(circular_segment_area(1.0, std::f64::consts::PI), std::f64::consts::FRAC_PI_2);
    }
}
