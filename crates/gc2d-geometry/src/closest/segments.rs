//! Closest points and contact of two line segments: the per-feature geometry of the walk (reference §4.3 step 1).

use crate::{DVec2, cross};

/// The point of segment `q0`–`q1` closest to `p`; exactly an end point when the projection falls outside.
#[inline]
pub(super) fn closest_on_segment(p: DVec2, q0: DVec2, q1: DVec2) -> DVec2 {
    let d = q1 - q0;
    let along = (p - q0).dot(d);
    if along <= 0.0 {
        return q0;
    }
    let length_squared = d.length_squared();
    if along >= length_squared {
        return q1;
    }
    q0 + d * (along / length_squared)
}

/// Closest points (on `p0`–`p1`, on `q0`–`q1`) of two segments that do not meet.
///
/// Disjoint segments in the plane have a closest pair with at least one end point, so the nearest of the four
/// end-point projections is taken (first in the order p0, p1, q0, q1 on ties). Exactly parallel segments whose
/// projections overlap have a whole interval of closest pairs; the midpoint of that interval is taken instead, so
/// the answer does not depend on which end point happened to win (footnote 10: parallel edges).
pub(super) fn closest_between(p0: DVec2, p1: DVec2, q0: DVec2, q1: DVec2) -> (DVec2, DVec2) {
    let candidates = [
        (p0, closest_on_segment(p0, q0, q1)),
        (p1, closest_on_segment(p1, q0, q1)),
        (closest_on_segment(q0, p0, p1), q0),
        (closest_on_segment(q1, p0, p1), q1),
    ];
    let mut best = candidates[0];
    let mut best_squared = best.0.distance_squared(best.1);
    for &(pa, pb) in &candidates[1..] {
        let squared = pa.distance_squared(pb);
        if squared < best_squared {
            best = (pa, pb);
            best_squared = squared;
        }
    }
    let (dp, dq) = (p1 - p0, q1 - q0);
    let length_squared = dp.length_squared();
    if cross(dp, dq) == 0.0 && length_squared > 0.0 {
        let s0 = (q0 - p0).dot(dp) / length_squared;
        let s1 = (q1 - p0).dot(dp) / length_squared;
        let low = s0.min(s1).max(0.0);
        let high = s0.max(s1).min(1.0);
        if low < high {
            let pa = p0 + dp * (0.5 * (low + high));
            return (pa, closest_on_segment(pa, q0, q1));
        }
    }
    best
}

/// True when the closed segments `p0`–`p1` and `q0`–`q1` have a point in common (crossing, touching at an end
/// point, or overlapping collinearly).
pub(super) fn meet(p0: DVec2, p1: DVec2, q0: DVec2, q1: DVec2) -> bool {
    let (dp, dq) = (p1 - p0, q1 - q0);
    let q0_side = cross(dp, q0 - p0);
    let q1_side = cross(dp, q1 - p0);
    let p0_side = cross(dq, p0 - q0);
    let p1_side = cross(dq, p1 - q0);
    if !(straddle(q0_side, q1_side) && straddle(p0_side, p1_side)) {
        return false;
    }
    if q0_side != 0.0 || q1_side != 0.0 || p0_side != 0.0 || p1_side != 0.0 {
        return true;
    }
    // Collinear: the segments meet when their extents along the common line overlap.
    let along_q0 = (q0 - p0).dot(dp);
    let along_q1 = (q1 - p0).dot(dp);
    along_q0.max(along_q1) >= 0.0 && along_q0.min(along_q1) <= dp.length_squared()
}

/// True when the two values do not lie strictly on the same side of zero.
#[inline]
fn straddle(x: f64, y: f64) -> bool {
    !(x > 0.0 && y > 0.0 || x < 0.0 && y < 0.0)
}
