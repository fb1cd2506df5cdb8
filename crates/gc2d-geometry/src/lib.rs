//! Geometry of convex polygons, disks, capsules and chamber circles for the gc2d-rs discrete element engine.
//!
//! Everything here is f64 and counter-clockwise positive (see `docs/model.md`). A [`ConvexPolygon`] lives in its
//! body frame (centroid at the origin); a [`Pose`] places it in the world. The engine transforms body vertices into
//! world vertices once per step and hands the world slices to the contact routines of this crate, which neither
//! allocate nor panic.
//!
//! Disks, capsules and inner circles (a chamber's boundary) join the polygons through [`ShapeView`]: the
//! shape-generic pair queries [`area_contact`] (overlap area and chord, for the overlap-area law) and
//! [`penetration`] (depth, normal, contact point and surface curvature, for linear and Hertz laws) dispatch to the
//! per-family files of [`pair`].
//!
//! Particles and walls are made by the generators in [`shapes`] (regular and ellipse-inscribed polygons, plain, cut
//! and rounded rectangles) or drawn at random from a [`ShapeRecipe`], with the CONST / EQUAL / GAUSS rules of
//! [`randomize`] (reference §1.2, §1.8).

pub mod closest;
pub mod outline;
pub mod overlap;
pub mod pair;
pub mod polygon;
pub mod pose;
pub mod randomize;
pub mod recipe;
pub mod shape;
pub mod shapes;

pub use closest::{Feature, FeaturePair, Separation, closest_features};
pub use glam::DVec2;
pub use outline::{CIRCLE_SEGMENTS, TracedOutline};
pub use overlap::{
    ContactKind, OverlapGeometry, OverlapPolygon, contact_geometry, contact_geometry_from_exit,
    contact_geometry_with_centroid, overlap_polygon,
};
pub use pair::capsule::{disk_capsule_intersection_area, polygon_capsule_intersection_area};
pub use pair::circle_polygon::{circle_polygon_intersection_area, polygon_outside_circle_area};
pub use pair::circles::{disk_outside_circle_area, lens_area};
pub use pair::circular_segment_area;
pub use polygon::{ConvexPolygon, MAX_VERTICES, MassProperties, PolygonError};
pub use pose::{Aabb, Pose};
pub use randomize::{Randomization, UnknownOptionValue, truncated_gaussian};
pub use recipe::ShapeRecipe;
pub use shape::{AreaContact, Penetration, ShapeView, area_contact, area_contact_with_centroid, penetration};
pub use shapes::{
    AngleMode, ShapeError, cut_rectangle, ellipse_polygon, rectangle, regular_polygon, rounded_rectangle, square,
    square_cut, square_round,
};

/// The z component of the 2D cross product `a × b` (positive when `b` is counter-clockwise of `a`).
#[inline]
pub fn cross(a: DVec2, b: DVec2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// The index after `k` around a ring of `len` items (0 after the last).
#[inline]
pub(crate) fn cyclic_next(k: usize, len: usize) -> usize {
    if k + 1 == len { 0 } else { k + 1 }
}

/// The index before `k` around a ring of `len` items (the last before 0).
#[inline]
pub(crate) fn cyclic_previous(k: usize, len: usize) -> usize {
    if k == 0 { len - 1 } else { k - 1 }
}

/// The mean of a polygon's vertices (not its area centroid): the cheap centre that orients the pair queries.
pub(crate) fn vertex_mean(points: &[DVec2]) -> DVec2 {
    points.iter().copied().sum::<DVec2>() / points.len() as f64
}

/// The index of the point farthest along `direction` (the first one on ties; a NaN reach never wins) and its
/// reach `p · direction` (−∞ when none wins).
pub(crate) fn farthest_along(points: &[DVec2], direction: DVec2) -> (usize, f64) {
    let (mut best, mut reach) = (0, f64::NEG_INFINITY);
    for (k, p) in points.iter().enumerate() {
        let r = p.dot(direction);
        if r > reach {
            (best, reach) = (k, r);
        }
    }
    (best, reach)
}
