//! Two circles: disk–disk (the lens) and disk–inner circle (the part of the disk outside a chamber's circle).
//!
//! Both overlaps are bounded by two circular arcs that meet at the circles' two crossing points, so both are sums
//! of two circular segments on either side of the common chord; computing them that way (rather than πr² − lens,
//! or with `acos`) keeps a 1e-8 overlap of millimetre disks accurate to ~1e-10 relative.

use super::{Crossing, Inner, area_contact_from_crossings, circular_segment_area, finite, positive};
use crate::DVec2;
use crate::shape::{AreaContact, PairPenetration};
use std::f64::consts::PI;

/// How two circles (1 and 2) lie to each other.
pub(crate) enum CirclePair {
    /// No common interior point (touching included): d ≥ r1 + r2, or non-finite input.
    Apart,
    /// One disk inside the other (touching from inside and concentric included): d ≤ |r1 − r2|.
    Nested,
    /// The outlines cross at two points.
    Crossing(CircleCrossing),
}

/// Two crossing circles: their common chord and the half-angles it subtends at each centre.
pub(crate) struct CircleCrossing {
    /// Unit vector from centre 2 towards centre 1.
    pub(crate) axis: DVec2,
    /// Midpoint of the common chord.
    pub(crate) mid: DVec2,
    /// Half the chord length.
    pub(crate) half_chord: f64,
    /// Half-angle at centre 1 of the arc of circle 1 on circle 2's side of the chord (inside circle 2).
    pub(crate) half_angle_1: f64,
    /// Half-angle at centre 1 of the arc of circle 1 on the far side of the chord (outside circle 2): π − the
    /// former, computed directly so that it keeps its digits when small.
    pub(crate) half_angle_1_far: f64,
    /// Half-angle at centre 2 of the arc of circle 2 inside circle 1.
    pub(crate) half_angle_2: f64,
}

impl CircleCrossing {
    /// The crossing point on the left of `axis` (perp side) and the one on its right.
    pub(crate) fn points(&self) -> (DVec2, DVec2) {
        let side = self.half_chord * self.axis.perp();
        (self.mid + side, self.mid - side)
    }
}

/// r1 + r2 − d, summed as r_small − (d − r_big): near touching both differences are exact (Sterbenz), so a 1e-9
/// overlap of a 5 mm disk at 0.1 m keeps all its digits, where the plain sum would round r1 + r2 first.
pub(crate) fn external_gap(d: f64, r1: f64, r2: f64) -> f64 {
    let (big, small) = if r1 >= r2 { (r1, r2) } else { (r2, r1) };
    small - (d - big)
}

/// d − |r1 − r2|, summed as (d − r_big) + r_small for the same reason (a disk against a chamber's wall).
pub(crate) fn internal_gap(d: f64, r1: f64, r2: f64) -> f64 {
    let (big, small) = if r1 >= r2 { (r1, r2) } else { (r2, r1) };
    (d - big) + small
}

/// Classifies circles (c1, r1) and (c2, r2). The chord's half-length comes from Heron's product
/// (r1 + r2 + d)(r2 − r1 + d)(r1 − r2 + d)(r1 + r2 − d), whose small factor in a shallow contact is the depth itself.
pub(crate) fn circle_pair(c1: DVec2, r1: f64, c2: DVec2, r2: f64) -> CirclePair {
    let d = (c1 - c2).length();
    if d.is_nan() || d >= r1 + r2 {
        return CirclePair::Apart;
    }
    if d <= (r1 - r2).abs() {
        return CirclePair::Nested;
    }
    let axis = (c1 - c2) / d;
    let (big, small) = if r1 >= r2 { (r1, r2) } else { (r2, r1) };
    let heron = (r1 + r2 + d) * (d + (big - small)) * internal_gap(d, r1, r2) * external_gap(d, r1, r2);
    let half_chord = heron.max(0.0).sqrt() / (2.0 * d);
    // Signed distances from each centre to the chord, towards the other centre.
    let x2 = 0.5 * (d + (r2 - r1) * (r2 + r1) / d);
    let x1 = 0.5 * (d + (r1 - r2) * (r1 + r2) / d);
    CirclePair::Crossing(CircleCrossing {
        axis,
        mid: c2 + x2 * axis,
        half_chord,
        half_angle_1: half_chord.atan2(x1),
        half_angle_1_far: half_chord.atan2(-x1),
        half_angle_2: half_chord.atan2(x2),
    })
}

/// Area of the intersection of two disks of radii `r1`, `r2` whose centres are `distance` apart (the lens), m²:
/// 0 when they are apart (or the input is not finite and positive), π·min(r1, r2)² when one lies inside the other.
///
/// Computed as the two circular segments on either side of the common chord, each r²/2·(φ − sin φ) with a series
/// for small φ, so that shallow overlaps keep their relative precision.
pub fn lens_area(r1: f64, r2: f64, distance: f64) -> f64 {
    if !(positive(r1) && positive(r2) && distance.is_finite()) {
        return 0.0;
    }
    match circle_pair(DVec2::new(distance.abs(), 0.0), r1, DVec2::ZERO, r2) {
        CirclePair::Apart => 0.0,
        CirclePair::Nested => PI * r1.min(r2).powi(2),
        CirclePair::Crossing(c) => lens_of(&c, r1, r2),
    }
}

fn lens_of(c: &CircleCrossing, r1: f64, r2: f64) -> f64 {
    circular_segment_area(r1, 2.0 * c.half_angle_1) + circular_segment_area(r2, 2.0 * c.half_angle_2)
}

/// Area of the part of disk 1 (radius `r1`) outside circle 2 (radius `r2`) for crossing circles:
/// the segment of disk 1 beyond the chord minus the segment of disk 2 beyond it.
fn outside_of(c: &CircleCrossing, r1: f64, r2: f64) -> f64 {
    (circular_segment_area(r1, 2.0 * c.half_angle_1_far) - circular_segment_area(r2, 2.0 * c.half_angle_2)).max(0.0)
}

/// Area of the part of the disk (`center`, `radius`) that lies outside the circle (`chamber_center`,
/// `chamber_radius`), m²: πr² − lens, computed without that cancellation. 0 for non-finite or non-positive input.
pub fn disk_outside_circle_area(center: DVec2, radius: f64, chamber_center: DVec2, chamber_radius: f64) -> f64 {
    if !(finite(center) && finite(chamber_center) && positive(radius) && positive(chamber_radius)) {
        return 0.0;
    }
    match circle_pair(center, radius, chamber_center, chamber_radius) {
        CirclePair::Apart => PI * radius * radius,
        CirclePair::Nested => PI * (radius * radius - chamber_radius * chamber_radius).max(0.0),
        CirclePair::Crossing(c) => outside_of(&c, radius, chamber_radius),
    }
}

/// Disk i against disk j: the lens and the chord through the two crossing points, normal along ci − cj.
pub(crate) fn disk_disk_area_contact(ci: DVec2, ri: f64, cj: DVec2, rj: f64) -> Option<AreaContact> {
    if !(finite(ci) && finite(cj) && positive(ri) && positive(rj)) {
        return None;
    }
    let smaller =
        if ri <= rj { Inner::Disk { center: ci, radius: ri } } else { Inner::Disk { center: cj, radius: rj } };
    match circle_pair(ci, ri, cj, rj) {
        CirclePair::Apart => None,
        CirclePair::Nested => area_contact_from_crossings(PI * ri.min(rj).powi(2), &[], || (ci - cj, smaller)),
        CirclePair::Crossing(c) => {
            // Walking i counter-clockwise, it enters j at the crossing on the left of the axis j → i.
            let (left, right) = c.points();
            let crossings = [Crossing { point: left, entry: true }, Crossing { point: right, entry: false }];
            area_contact_from_crossings(lens_of(&c, ri, rj), &crossings, || (ci - cj, smaller))
        }
    }
}

/// Disk i inside a chamber j (solid outside the circle): the part of the disk outside the circle and the chord
/// through the crossing points; the normal points from the wall towards the chamber's centre. A disk entirely in
/// the solid (or around the whole chamber) is a containment, pushed towards the centre along c_j − c_i.
pub(crate) fn disk_inner_area_contact(ci: DVec2, ri: f64, cj: DVec2, rj: f64) -> Option<AreaContact> {
    if !(finite(ci) && finite(cj) && positive(ri) && positive(rj)) {
        return None;
    }
    let disk = Inner::Disk { center: ci, radius: ri };
    match circle_pair(ci, ri, cj, rj) {
        CirclePair::Apart => area_contact_from_crossings(PI * ri * ri, &[], || (cj - ci, disk)),
        CirclePair::Nested if ri <= rj => None,
        CirclePair::Nested => area_contact_from_crossings(PI * (ri * ri - rj * rj), &[], || (cj - ci, disk)),
        CirclePair::Crossing(c) => {
            // Walking i counter-clockwise, it enters the solid at the crossing on the right of the axis j → i.
            let (left, right) = c.points();
            let crossings = [Crossing { point: right, entry: true }, Crossing { point: left, entry: false }];
            area_contact_from_crossings(outside_of(&c, ri, rj), &crossings, || (cj - ci, disk))
        }
    }
}

/// Disk i against disk j: depth ri + rj − |ci − cj|, normal along ci − cj (+y for coincident centres).
pub(crate) fn disk_disk_penetration(ci: DVec2, ri: f64, cj: DVec2, rj: f64) -> Option<PairPenetration> {
    if !(finite(ci) && finite(cj) && positive(ri) && positive(rj)) {
        return None;
    }
    let offset = ci - cj;
    let distance = offset.length();
    let normal = if distance > 0.0 { offset / distance } else { DVec2::Y };
    PairPenetration::new(external_gap(distance, ri, rj), normal, ci - ri * normal, ri, rj)
}

/// Disk i inside a chamber j: depth |ci − cj| + ri − R, normal towards the chamber's centre (+y when concentric),
/// j's surface radius −R (concave).
pub(crate) fn disk_inner_penetration(ci: DVec2, ri: f64, cj: DVec2, rj: f64) -> Option<PairPenetration> {
    if !(finite(ci) && finite(cj) && positive(ri) && positive(rj)) {
        return None;
    }
    let offset = cj - ci;
    let distance = offset.length();
    let normal = if distance > 0.0 { offset / distance } else { DVec2::Y };
    PairPenetration::new((distance - rj) + ri, normal, ci - ri * normal, ri, -rj)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// The textbook lens formula (fine away from shallow overlaps).
    fn textbook_lens(r1: f64, r2: f64, d: f64) -> f64 {
        let a1 = r1 * r1 * ((d * d + r1 * r1 - r2 * r2) / (2.0 * d * r1)).acos();
        let a2 = r2 * r2 * ((d * d + r2 * r2 - r1 * r1) / (2.0 * d * r2)).acos();
        let k = 0.5 * ((-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2)).sqrt();
        a1 + a2 - k
    }

    #[test]
    fn lens_matches_the_textbook_formula_and_its_limits() {
        for (r1, r2, d) in [(1.0, 1.0, 1.0), (1.0, 0.5, 1.2), (2.0, 0.3, 1.9), (0.3, 2.0, 1.75), (1.0, 1.0, 0.01)] {
            assert_relative_eq!(lens_area(r1, r2, d), textbook_lens(r1, r2, d), max_relative = 1e-12);
        }
        assert_eq!(lens_area(1.0, 1.0, 2.0), 0.0);
        assert_relative_eq!(lens_area(1.0, 0.5, 0.5), PI * 0.25);
        assert_eq!(lens_area(1.0, f64::NAN, 0.5), 0.0);
        // Shallow: two equal circles overlapping by δ: A ≈ (4/3)·√r·δ^{3/2}·… ; compare with the series of the exact
        // formula, A = 2r²(θ − sinθcosθ) with cos θ = 1 − δ/(2r).
        let (r, delta) = (1.75e-3, 1e-11);
        let theta = (1.0f64 - delta / (2.0 * r)).acos();
        let exact_series = 2.0 * r * r * (2.0 * theta).powi(3) / 12.0 * (1.0 - (2.0 * theta).powi(2) / 20.0);
        assert_relative_eq!(lens_area(r, r, 2.0 * r - delta), exact_series, max_relative = 1e-5);
    }

    #[test]
    fn disk_disk_contact_is_along_the_centre_line() {
        let c = disk_disk_area_contact(DVec2::new(0.0, 1.5), 1.0, DVec2::ZERO, 1.0).unwrap();
        assert_relative_eq!(c.normal, DVec2::Y, epsilon = 1e-15);
        assert_relative_eq!(c.point, DVec2::new(0.0, 0.75), epsilon = 1e-15);
        assert_relative_eq!(c.chord_length, 2.0 * (1.0f64 - 0.75 * 0.75).sqrt(), max_relative = 1e-14);
        assert_relative_eq!(c.area, textbook_lens(1.0, 1.0, 1.5), max_relative = 1e-12);
        assert!(disk_disk_area_contact(DVec2::new(0.0, 2.0), 1.0, DVec2::ZERO, 1.0).is_none());
        let p = disk_disk_penetration(DVec2::new(0.0, 1.5), 1.0, DVec2::ZERO, 1.0).unwrap().penetration;
        assert_eq!((p.depth, p.normal, p.point, p.surface_radius_j), (0.5, DVec2::Y, DVec2::new(0.0, 0.75), 1.0));
    }

    #[test]
    fn a_disk_in_a_chamber_is_pushed_towards_the_centre() {
        let chamber = (DVec2::new(0.2, -0.1), 1.0);
        let ci = chamber.0 + DVec2::new(0.85, 0.0);
        let c = disk_inner_area_contact(ci, 0.2, chamber.0, chamber.1).unwrap();
        assert_relative_eq!(c.normal, -DVec2::X, epsilon = 1e-15);
        assert_relative_eq!(c.area, PI * 0.04 - textbook_lens(0.2, 1.0, 0.85), max_relative = 1e-12);
        assert!(disk_inner_area_contact(chamber.0 + DVec2::new(0.79, 0.0), 0.2, chamber.0, chamber.1).is_none());
        let escaped = disk_inner_area_contact(chamber.0 + DVec2::new(0.0, 1.5), 0.2, chamber.0, chamber.1).unwrap();
        assert_relative_eq!(escaped.area, PI * 0.04);
        assert_relative_eq!(escaped.normal, -DVec2::Y);
        assert_relative_eq!(escaped.chord_length, 0.4);
        let p = disk_inner_penetration(ci, 0.2, chamber.0, chamber.1).unwrap().penetration;
        assert_relative_eq!(p.depth, 0.05, max_relative = 1e-12);
        assert_eq!((p.normal, p.surface_radius_j), (-DVec2::X, -1.0));
        assert_relative_eq!(p.point, chamber.0 + DVec2::new(1.025, 0.0), epsilon = 1e-15);
    }
}
