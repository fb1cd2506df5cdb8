//! Two convex polygons: the overlap-area contact is [`contact_geometry`] unchanged; the penetration is derived
//! from it.

use crate::DVec2;
use crate::shape::{AreaContact, PairPenetration};
use crate::{OverlapGeometry, contact_geometry, contact_geometry_with_centroid};

/// Polygon i against polygon j for the area law: [`contact_geometry`] reduced to [`AreaContact`] (bitwise the same
/// area, chord length, point and normal).
pub(crate) fn area_contact(a: &[DVec2], b: &[DVec2]) -> Option<AreaContact> {
    contact_geometry(a, b).map(AreaContact::from)
}

/// [`area_contact`] with the overlap polygon's centroid.
pub(crate) fn area_contact_with_centroid(a: &[DVec2], b: &[DVec2]) -> Option<AreaContact> {
    contact_geometry_with_centroid(a, b).map(AreaContact::from)
}

impl From<OverlapGeometry> for AreaContact {
    /// The polygon contact reduced to what every pair reports (bitwise the same fields).
    fn from(g: OverlapGeometry) -> Self {
        AreaContact {
            area: g.area,
            chord_length: g.chord_length,
            point: g.point,
            normal: g.normal,
            centroid: g.centroid,
        }
    }
}

/// Polygon i against polygon j for the penetration laws, defined from the area law: the overlap seen as a flat
/// contact of width |c1c2|, so depth = A/|c1c2|, normal = the chord normal, point = the chord midpoint, and both
/// surface radii ∞. (Two convex polygons have no curvature at a contact; a Hertz law needs its radius from
/// elsewhere, e.g. the particles' equivalent radii.)
pub(crate) fn penetration(a: &[DVec2], b: &[DVec2]) -> Option<PairPenetration> {
    let g = contact_geometry(a, b)?;
    PairPenetration::at(g.area / g.chord_length, g.normal, g.point, f64::INFINITY, f64::INFINITY)
}
