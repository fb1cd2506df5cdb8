//! Shapes as the narrowphase sees them, and the two shape-generic pair queries the contact laws read: the overlap
//! area with its contact chord (the gc2d overlap-area law) and the penetration depth with its normal and contact
//! point (linear spring and Hertz laws).
//!
//! Particles are convex polygons or exact disks; walls may also be capsules (rotor blades, rounded wall ends) and
//! inner circles (the boundary of a circular chamber, solid outside). Every query is a `match` on the two shapes,
//! like Box2D's pair table, into the per-family files of [`pair`](crate::pair). Body i is a particle; a wall given
//! as i is answered by swapping the bodies and flipping the normal, and two walls never interact (`None`).

use crate::pair::{capsule, circle_polygon, circles, polygon_polygon};
use crate::{Aabb, DVec2};

/// A body's outline in the world frame, as the narrowphase sees it. Lengths in m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ShapeView<'a> {
    /// A convex polygon: counter-clockwise world vertices, 3..=[`MAX_VERTICES`](crate::MAX_VERTICES), validated as
    /// by [`ConvexPolygon::new`](crate::ConvexPolygon::new). A particle or a wall.
    Polygon(&'a [DVec2]),
    /// An exact circle (its interior is the body). A particle, or a disk-shaped wall.
    Disk {
        /// Centre, m.
        center: DVec2,
        /// Radius, m, > 0.
        radius: f64,
    },
    /// The segment a–b swept by a disk of `radius` (a stadium): rotor blades, rounded wall ends. A wall only.
    /// `a == b` is allowed and is then a disk-shaped wall.
    Capsule {
        /// One end of the core segment, m.
        a: DVec2,
        /// The other end, m.
        b: DVec2,
        /// Radius of the rounding, m, > 0.
        radius: f64,
    },
    /// The boundary of a circular chamber: the solid is everything OUTSIDE the circle; particles stay inside. A
    /// wall only.
    InnerCircle {
        /// Centre, m.
        center: DVec2,
        /// Radius of the chamber, m, > 0.
        radius: f64,
    },
}

impl ShapeView<'_> {
    /// The axis-aligned bounding box for the broadphase. For an [`InnerCircle`](ShapeView::InnerCircle) it is the
    /// circle's bounding box, so that every particle inside the chamber pairs with it (its solid is unbounded).
    pub fn aabb(&self) -> Aabb {
        match *self {
            ShapeView::Polygon(points) => Aabb::of_points(points),
            ShapeView::Disk { center, radius } | ShapeView::InnerCircle { center, radius } => {
                Aabb { min: center - DVec2::splat(radius), max: center + DVec2::splat(radius) }
            }
            ShapeView::Capsule { a, b, radius } => {
                Aabb { min: a.min(b) - DVec2::splat(radius), max: a.max(b) + DVec2::splat(radius) }
            }
        }
    }

    /// How deep `point` lies inside the solid, m: its distance from the outline, positive inside (a polygon, disk or
    /// capsule; outside an [`InnerCircle`](ShapeView::InnerCircle)), zero on the outline, negative outside (for a
    /// polygon the distance from the nearest edge's line, which has the right sign). For the load-time checks (a drop
    /// line inside a wall), not for contacts.
    pub fn depth_of(&self, point: DVec2) -> f64 {
        match *self {
            ShapeView::Polygon(points) => points
                .iter()
                .zip(points.iter().cycle().skip(1))
                .map(|(&a, &b)| (b - a).perp_dot(point - a) / (b - a).length())
                .fold(f64::INFINITY, f64::min),
            ShapeView::Disk { center, radius } => radius - point.distance(center),
            ShapeView::Capsule { a, b, radius } => {
                let along = b - a;
                let t = if along == DVec2::ZERO { 0.0 } else { (point - a).dot(along) / along.length_squared() };
                radius - point.distance(a + t.clamp(0.0, 1.0) * along)
            }
            ShapeView::InnerCircle { center, radius } => point.distance(center) - radius,
        }
    }

    /// True for the shapes a particle may have (polygon, disk).
    fn is_particle_shape(&self) -> bool {
        matches!(self, ShapeView::Polygon(_) | ShapeView::Disk { .. })
    }
}

/// What the gc2d overlap-area law needs: today's polygon [`OverlapGeometry`](crate::OverlapGeometry) reduced to
/// the area, the chord c1c2 and the normal, for any pair of shapes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AreaContact {
    /// Overlap area A of the interiors (for an inner circle: of the particle with the solid outside it), m², > 0.
    pub area: f64,
    /// |c2 − c1|, m: the rate −dA/dh at which the overlap shrinks when i moves along the normal.
    pub chord_length: f64,
    /// Midpoint of the chord c1c2: the force application point, m.
    pub point: DVec2,
    /// Unit vector perpendicular to the chord, from j towards i: the repulsive force on i is along +normal.
    pub normal: DVec2,
    /// Area centroid of the overlap, m, where it was asked for and is computed ([`area_contact_with_centroid`]).
    /// `None` otherwise.
    pub centroid: Option<DVec2>,
}

/// What penetration laws (linear spring, Hertz) need.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Penetration {
    /// Penetration depth, m, > 0: how far i must move along `normal` to stop overlapping j.
    pub depth: f64,
    /// Unit vector from j towards i: the repulsive force on i is along +normal.
    pub normal: DVec2,
    /// Contact point: midway between the two surface points, which lie `depth` apart along the normal, m.
    pub point: DVec2,
    /// Curvature radius of j's outline at the contact, m: disk r, capsule cap r, capsule side or polygon edge
    /// `f64::INFINITY`, inner circle −R (concave), polygon vertex 0.0. With i's radius R_i the Hertz law's
    /// effective radius is 1/(1/R_i + 1/R_j).
    pub surface_radius_j: f64,
}

impl AreaContact {
    /// The same contact seen from the other body: the normal flips, everything else stays.
    fn flipped(self) -> Self {
        Self { normal: -self.normal, ..self }
    }
}

/// A penetration together with the curvature radius of i's outline at the contact, which the public result leaves
/// to the caller but swapping the bodies needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PairPenetration {
    pub(crate) penetration: Penetration,
    pub(crate) surface_radius_i: f64,
}

impl PairPenetration {
    /// The penetration from surface point `on_i` (the deepest point of i along −normal), depth and normal: the
    /// contact point is midway to j's surface point `on_i + depth·normal`. `None` unless all is finite and depth > 0.
    pub(crate) fn new(
        depth: f64,
        normal: DVec2,
        on_i: DVec2,
        surface_radius_i: f64,
        surface_radius_j: f64,
    ) -> Option<Self> {
        Self::at(depth, normal, on_i + 0.5 * depth * normal, surface_radius_i, surface_radius_j)
    }

    /// The penetration with its contact point given. `None` unless all is finite and depth > 0.
    pub(crate) fn at(
        depth: f64,
        normal: DVec2,
        point: DVec2,
        surface_radius_i: f64,
        surface_radius_j: f64,
    ) -> Option<Self> {
        let ok = depth.is_finite() && depth > 0.0 && normal.is_finite() && point.is_finite();
        ok.then_some(Self { penetration: Penetration { depth, normal, point, surface_radius_j }, surface_radius_i })
    }

    /// The same contact seen from the other body: normal flipped, surface radii swapped.
    pub(crate) fn flipped(self) -> Self {
        let p = self.penetration;
        Self {
            penetration: Penetration { normal: -p.normal, surface_radius_j: self.surface_radius_i, ..p },
            surface_radius_i: p.surface_radius_j,
        }
    }
}

/// Overlap area and contact chord of body i with body j, for the overlap-area law.
///
/// `i` is a particle shape (polygon or disk), `j` any shape; a wall given as `i` with a particle as `j` is answered
/// for the swapped pair with the normal flipped. Returns `None` when the interiors do not overlap (touching
/// included), for two walls, and for non-finite or degenerate input (radius ≤ 0, a polygon outside 3..=64
/// vertices). Never allocates or panics.
///
/// Polygon–polygon is [`contact_geometry`](crate::contact_geometry) unchanged. Every other pair is exact (areas to
/// rounding): see `docs/model.md` (“Shapes and pair queries”) for the chord rules of crossing, multi-crossing and
/// contained overlaps, which are those of the polygon code.
pub fn area_contact(i: ShapeView, j: ShapeView) -> Option<AreaContact> {
    use ShapeView::*;
    match (i, j) {
        (Polygon(a), Polygon(b)) => polygon_polygon::area_contact(a, b),
        (Disk { center: ci, radius: ri }, Disk { center: cj, radius: rj }) => {
            circles::disk_disk_area_contact(ci, ri, cj, rj)
        }
        (Disk { center, radius }, Polygon(b)) => circle_polygon::disk_polygon_area_contact(center, radius, b),
        (Polygon(a), Disk { center, radius }) => circle_polygon::polygon_disk_area_contact(a, center, radius),
        (Disk { center: ci, radius: ri }, InnerCircle { center, radius }) => {
            circles::disk_inner_area_contact(ci, ri, center, radius)
        }
        (Polygon(a), InnerCircle { center, radius }) => circle_polygon::polygon_inner_area_contact(a, center, radius),
        (Disk { center, radius: r }, Capsule { a, b, radius }) => {
            capsule::disk_capsule_area_contact(center, r, a, b, radius)
        }
        (Polygon(p), Capsule { a, b, radius }) => capsule::polygon_capsule_area_contact(p, a, b, radius),
        (Capsule { .. } | InnerCircle { .. }, _) if j.is_particle_shape() => {
            area_contact(j, i).map(AreaContact::flipped)
        }
        _ => None,
    }
}

/// [`area_contact`] with the overlap's area centroid in [`AreaContact::centroid`], for laws that apply the force at
/// the centroid (docs/model.md, "Rocking of flat contacts"). Computed for polygon–polygon (from the overlap polygon)
/// and for a polygon with a disk, in an inner circle or against a capsule (first moments, by a fan from the circles'
/// centres). `None` for two round outlines (disks, inner circles, a disk against a capsule), whose overlap is
/// symmetric about the chord's perpendicular bisector, so that the centroid projects on the chord midpoint.
pub fn area_contact_with_centroid(i: ShapeView, j: ShapeView) -> Option<AreaContact> {
    use ShapeView::*;
    if let (Polygon(a), Polygon(b)) = (i, j) {
        return polygon_polygon::area_contact_with_centroid(a, b);
    }
    // The pair's own area query has validated the input and measured the area the centroid divides by.
    let contact = area_contact(i, j)?;
    let area = contact.area;
    let centroid = match (i, j) {
        (Disk { center, radius }, Polygon(p)) | (Polygon(p), Disk { center, radius }) => {
            Some(circle_polygon::disk_polygon_centroid(center, radius, p, area))
        }
        (Polygon(p), InnerCircle { center, radius }) | (InnerCircle { center, radius }, Polygon(p)) => {
            Some(circle_polygon::polygon_outside_circle_centroid(p, center, radius, area))
        }
        (Polygon(p), Capsule { a, b, radius }) | (Capsule { a, b, radius }, Polygon(p)) => {
            Some(capsule::polygon_capsule_centroid(p, a, b, radius, area))
        }
        _ => None,
    };
    Some(AreaContact { centroid, ..contact })
}

/// Penetration depth, normal and contact point of body i with body j, for the penetration laws.
///
/// Same roles and `None` rules as [`area_contact`]. Exact for every pair with a disk or capsule (centre distances,
/// closest points on segments and polygons; a disk centre inside a polygon gives depth = r + its distance to the
/// outline, through the nearest edge), polygon–capsule by the separating axes of polygon and core segment. For
/// polygon–polygon it is defined from the area law: depth = A/|c1c2|, normal = chord normal, point = chord
/// midpoint, surface radius ∞ (the overlap as an equivalent flat contact). Polygon–inner circle takes the vertex
/// farthest outside. Never allocates or panics.
pub fn penetration(i: ShapeView, j: ShapeView) -> Option<Penetration> {
    pair_penetration(i, j).map(|p| p.penetration)
}

fn pair_penetration(i: ShapeView, j: ShapeView) -> Option<PairPenetration> {
    use ShapeView::*;
    match (i, j) {
        (Polygon(a), Polygon(b)) => polygon_polygon::penetration(a, b),
        (Disk { center: ci, radius: ri }, Disk { center: cj, radius: rj }) => {
            circles::disk_disk_penetration(ci, ri, cj, rj)
        }
        (Disk { center, radius }, Polygon(b)) => circle_polygon::disk_polygon_penetration(center, radius, b),
        (Polygon(a), Disk { center, radius }) => {
            circle_polygon::disk_polygon_penetration(center, radius, a).map(PairPenetration::flipped)
        }
        (Disk { center: ci, radius: ri }, InnerCircle { center, radius }) => {
            circles::disk_inner_penetration(ci, ri, center, radius)
        }
        (Polygon(a), InnerCircle { center, radius }) => circle_polygon::polygon_inner_penetration(a, center, radius),
        (Disk { center, radius: r }, Capsule { a, b, radius }) => {
            capsule::disk_capsule_penetration(center, r, a, b, radius)
        }
        (Polygon(p), Capsule { a, b, radius }) => capsule::polygon_capsule_penetration(p, a, b, radius),
        (Capsule { .. } | InnerCircle { .. }, _) if j.is_particle_shape() => {
            pair_penetration(j, i).map(PairPenetration::flipped)
        }
        _ => None,
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

    const SQUARE: [DVec2; 4] = [DVec2::new(0.0, 0.0), DVec2::new(1.0, 0.0), DVec2::new(1.0, 1.0), DVec2::new(0.0, 1.0)];

    fn disk(x: f64, y: f64, radius: f64) -> ShapeView<'static> {
        ShapeView::Disk { center: v(x, y), radius }
    }

    #[test]
    fn depths_are_distances_from_the_outline_positive_inside() {
        let square = ShapeView::Polygon(&SQUARE);
        assert_relative_eq!(square.depth_of(v(0.5, 0.5)), 0.5);
        assert_relative_eq!(square.depth_of(v(0.9, 0.2)), 0.1, epsilon = 1e-15);
        assert_eq!(square.depth_of(v(1.0, 0.5)), 0.0);
        assert!(square.depth_of(v(1.5, 0.5)) < 0.0);
        assert_relative_eq!(disk(0.0, 0.0, 1.0).depth_of(v(0.6, 0.0)), 0.4, epsilon = 1e-15);
        let blade = ShapeView::Capsule { a: v(0.0, 0.0), b: v(1.0, 0.0), radius: 0.2 };
        assert_relative_eq!(blade.depth_of(v(0.5, 0.15)), 0.05, epsilon = 1e-15);
        assert_relative_eq!(blade.depth_of(v(1.1, 0.0)), 0.1, epsilon = 1e-15);
        let dot = ShapeView::Capsule { a: v(0.0, 0.0), b: v(0.0, 0.0), radius: 0.2 };
        assert_relative_eq!(dot.depth_of(v(0.1, 0.0)), 0.1, epsilon = 1e-15);
        let chamber = ShapeView::InnerCircle { center: v(0.0, 0.0), radius: 1.0 };
        assert!(chamber.depth_of(v(0.5, 0.5)) < 0.0);
        assert_relative_eq!(chamber.depth_of(v(1.25, 0.0)), 0.25);
        // Inside exactly where parry2d-f64 says a convex polygon contains the point.
        let pentagon = [v(0.0, 0.0), v(2.0, 0.0), v(2.5, 1.0), v(1.0, 2.0), v(-0.5, 1.0)];
        let reference = parry2d_f64::shape::ConvexPolygon::from_convex_polyline_unmodified(pentagon.to_vec()).unwrap();
        for k in 0..400 {
            let p = v(-1.0 + 0.19 * (k % 20) as f64, -1.0 + 0.19 * (k / 20) as f64);
            let expected = parry2d_f64::query::PointQuery::contains_local_point(&reference, p);
            assert_eq!(ShapeView::Polygon(&pentagon).depth_of(p) > 0.0, expected, "{p}");
        }
    }

    #[test]
    fn touching_is_no_contact() {
        let square = ShapeView::Polygon(&SQUARE);
        for (i, j) in [
            (disk(0.0, 2.0, 1.0), disk(0.0, 0.0, 1.0)),
            (disk(0.5, 1.5, 0.5), square),
            (disk(2.0, 0.5, 1.0), square),
            (disk(0.0, 0.5, 0.5), ShapeView::InnerCircle { center: v(0.0, 0.0), radius: 1.0 }),
            (disk(0.5, 2.0, 0.5), ShapeView::Capsule { a: v(-1.0, 1.0), b: v(1.0, 1.0), radius: 0.5 }),
            (square, ShapeView::Capsule { a: v(-1.0, 2.0), b: v(2.0, 2.0), radius: 1.0 }),
        ] {
            assert!(area_contact(i, j).is_none(), "{i:?} {j:?}");
            assert!(penetration(i, j).is_none(), "{i:?} {j:?}");
        }
        // A square with its corners exactly on a chamber's circle: inside, no contact.
        let chamber = ShapeView::InnerCircle { center: v(0.5, 0.5), radius: 0.5f64.sqrt() };
        assert!(area_contact(square, chamber).is_none_or(|c| c.area < 1e-15));
    }

    #[test]
    fn coincident_and_exactly_placed_centres_stay_finite() {
        let square = ShapeView::Polygon(&SQUARE);
        // Coincident disks: containment, +y.
        let c = area_contact(disk(0.3, 0.3, 1.0), disk(0.3, 0.3, 0.5)).unwrap();
        assert_eq!(c.normal, DVec2::Y);
        assert_relative_eq!(c.area, PI * 0.25);
        assert_eq!(penetration(disk(0.3, 0.3, 1.0), disk(0.3, 0.3, 0.5)).unwrap().normal, DVec2::Y);
        // A disk centred on a polygon vertex and on an edge.
        for (x, y) in [(1.0, 1.0), (0.5, 0.0), (0.0, 0.25)] {
            let area = area_contact(disk(x, y, 0.1), square).unwrap();
            let expected = if x == 1.0 { PI * 0.01 / 4.0 } else { PI * 0.01 / 2.0 };
            assert_relative_eq!(area.area, expected, max_relative = 1e-12);
            let p = penetration(disk(x, y, 0.1), square).unwrap();
            assert_relative_eq!(p.depth, 0.1, max_relative = 1e-15);
            assert!(p.normal.is_finite() && (p.normal.length() - 1.0).abs() < 1e-15);
        }
        // A disk centred on a capsule's core and at a capsule's end point.
        let blade = ShapeView::Capsule { a: v(0.0, 0.0), b: v(1.0, 0.0), radius: 0.2 };
        for (x, y) in [(0.5, 0.0), (1.0, 0.0)] {
            let p = penetration(disk(x, y, 0.1), blade).unwrap();
            assert_relative_eq!(p.depth, 0.3, max_relative = 1e-15);
            assert!(area_contact(disk(x, y, 0.1), blade).is_some_and(|c| c.normal.is_finite()));
        }
        // A disk at a chamber's centre bigger than the chamber.
        let c = area_contact(disk(0.0, 0.0, 2.0), ShapeView::InnerCircle { center: v(0.0, 0.0), radius: 1.0 }).unwrap();
        assert_relative_eq!(c.area, 3.0 * PI, max_relative = 1e-14);
    }

    #[test]
    fn a_wall_given_first_is_answered_flipped() {
        let blade = ShapeView::Capsule { a: v(0.0, 0.0), b: v(1.0, 0.0), radius: 0.2 };
        let ball = disk(0.4, 0.25, 0.1);
        let (forward, backward) = (penetration(ball, blade).unwrap(), penetration(blade, ball).unwrap());
        assert_eq!(backward.normal, -forward.normal);
        assert_eq!((backward.depth, backward.point), (forward.depth, forward.point));
        assert_eq!((forward.surface_radius_j, backward.surface_radius_j), (f64::INFINITY, 0.1));
        let (a, b) = (area_contact(ball, blade).unwrap(), area_contact(blade, ball).unwrap());
        assert_eq!((b.area, b.point, b.chord_length, b.normal), (a.area, a.point, a.chord_length, -a.normal));
        let chamber = ShapeView::InnerCircle { center: v(0.0, 0.0), radius: 1.0 };
        let square = [v(0.5, 0.5), v(0.8, 0.5), v(0.8, 0.8), v(0.5, 0.8)];
        let p = penetration(chamber, ShapeView::Polygon(&square)).unwrap();
        assert_relative_eq!(p.depth, 0.8 * 2f64.sqrt() - 1.0, max_relative = 1e-14);
        assert_relative_eq!(p.normal, v(1.0, 1.0).normalize(), epsilon = 1e-15);
        assert_eq!(p.surface_radius_j, 0.0);
    }

    #[test]
    fn boxes_cover_the_shapes() {
        assert_eq!(disk(1.0, 2.0, 0.5).aabb(), Aabb { min: v(0.5, 1.5), max: v(1.5, 2.5) });
        let chamber = ShapeView::InnerCircle { center: v(0.0, 0.0), radius: 2.0 };
        assert_eq!(chamber.aabb(), Aabb { min: v(-2.0, -2.0), max: v(2.0, 2.0) });
        assert_eq!(ShapeView::Polygon(&SQUARE).aabb(), Aabb { min: v(0.0, 0.0), max: v(1.0, 1.0) });
    }
}
