//! Geometry of convex polygons for the gc2d-rs discrete element engine.
//!
//! Everything here is f64 and counter-clockwise positive (see `docs/model.md`). A [`ConvexPolygon`] lives in its
//! body frame (centroid at the origin); a [`Pose`] places it in the world. The engine transforms body vertices into
//! world vertices once per step and hands the world slices to the contact routines of this crate, which neither
//! allocate nor panic.

pub mod closest;
pub mod polygon;
pub mod pose;

pub use closest::{Feature, FeaturePair, Separation, closest_features};
pub use glam::DVec2;
pub use polygon::{ConvexPolygon, MAX_VERTICES, MassProperties, PolygonError};
pub use pose::{Aabb, Pose};

/// The z component of the 2D cross product `a × b` (positive when `b` is counter-clockwise of `a`).
#[inline]
pub fn cross(a: DVec2, b: DVec2) -> f64 {
    a.x * b.y - a.y * b.x
}
