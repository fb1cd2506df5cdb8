//! Placing a body-frame polygon in the world (reference §1.4, eqs. 2.30/2.31 with CCW angles) and axis-aligned boxes.

use crate::DVec2;
use serde::{Deserialize, Serialize};

/// Where a body sits in the world: centroid position, counter-clockwise angle and uniform scale.
///
/// The scale `s` multiplies body coordinates before rotation (reference §1.6, global heating); `s = 1` is the
/// original size. gc2d's clockwise angles are converted at the file-format boundary only.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    /// Centroid in world coordinates, m.
    pub position: DVec2,
    /// Rotation, radians, counter-clockwise positive.
    pub angle: f64,
    /// Uniform size factor, dimensionless.
    pub scale: f64,
}

impl Pose {
    /// A pose at `position` turned by `angle` (CCW) at original size.
    pub fn new(position: DVec2, angle: f64) -> Self {
        Self { position, angle, scale: 1.0 }
    }

    /// The scaled rotation as a complex number (s·cos φ, s·sin φ): `rotate` multiplies by it.
    #[inline]
    pub fn scaled_rotation(&self) -> DVec2 {
        let (sin, cos) = self.angle.sin_cos();
        DVec2::new(cos, sin) * self.scale
    }

    /// Body point → world point.
    #[inline]
    pub fn apply(&self, body_point: DVec2) -> DVec2 {
        self.scaled_rotation().rotate(body_point) + self.position
    }

    /// Writes the world positions of `body` into `world` (equal lengths), computing the rotation once, and returns
    /// their tight box ([`Aabb::of_points`] of `world`), found in the same loop so that a caller who needs the box
    /// does not read the points again.
    pub fn transform_into(&self, body: &[DVec2], world: &mut [DVec2]) -> Aabb {
        debug_assert_eq!(body.len(), world.len());
        let rotation = self.scaled_rotation();
        let mut tight = Aabb::EMPTY;
        for (w, &b) in world.iter_mut().zip(body) {
            *w = rotation.rotate(b) + self.position;
            tight = tight.including(*w);
        }
        tight
    }
}

/// An axis-aligned bounding box. Boxes that touch count as overlapping (reference §4.2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Aabb {
    /// Lower-left corner.
    pub min: DVec2,
    /// Upper-right corner.
    pub max: DVec2,
}

impl Aabb {
    /// The inverted box that holds no point and overlaps nothing: where [`Self::including`] starts.
    pub const EMPTY: Self = Self { min: DVec2::splat(f64::INFINITY), max: DVec2::splat(f64::NEG_INFINITY) };

    /// The tight box around `points`; an empty slice gives [`Self::EMPTY`].
    pub fn of_points(points: &[DVec2]) -> Self {
        points.iter().fold(Self::EMPTY, |tight, &p| tight.including(p))
    }

    /// The smallest box that holds this one and `point`.
    #[inline]
    pub fn including(&self, point: DVec2) -> Self {
        Self { min: self.min.min(point), max: self.max.max(point) }
    }

    /// The box grown by `margin` on every side.
    pub fn expanded(&self, margin: f64) -> Self {
        Self { min: self.min - DVec2::splat(margin), max: self.max + DVec2::splat(margin) }
    }

    /// True when `point` lies in the box or on its edge; a point with a NaN coordinate is outside.
    #[inline]
    pub fn contains(&self, point: DVec2) -> bool {
        self.min.cmple(point).all() && point.cmple(self.max).all()
    }

    /// True when the boxes overlap or touch.
    #[inline]
    pub fn overlaps(&self, other: &Aabb) -> bool {
        self.min.x <= other.max.x && other.min.x <= self.max.x && self.min.y <= other.max.y && other.min.y <= self.max.y
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn a_box_contains_its_inside_and_edges_and_no_nan() {
        let square = Aabb { min: DVec2::ZERO, max: DVec2::ONE };
        assert!(square.contains(DVec2::splat(0.5)) && square.contains(DVec2::new(1.0, 0.0)));
        assert!(!square.contains(DVec2::new(1.5, 0.5)) && !square.contains(DVec2::new(0.5, -1e-300)));
        assert!(!square.contains(DVec2::new(f64::NAN, 0.5)));
    }

    #[test]
    fn quarter_turn_is_counter_clockwise() {
        let pose = Pose::new(DVec2::new(1.0, 2.0), FRAC_PI_2);
        assert_relative_eq!(pose.apply(DVec2::X), DVec2::new(1.0, 3.0), epsilon = 1e-15);
    }

    #[test]
    fn scale_multiplies_body_coordinates() {
        let pose = Pose { position: DVec2::ZERO, angle: 0.0, scale: 1.5 };
        let mut out = [DVec2::ZERO; 2];
        let tight = pose.transform_into(&[DVec2::new(1.0, 0.0), DVec2::new(0.0, -2.0)], &mut out);
        assert_eq!(out, [DVec2::new(1.5, 0.0), DVec2::new(0.0, -3.0)]);
        assert_eq!(tight, Aabb::of_points(&out));
        assert_eq!(tight, Aabb { min: DVec2::new(0.0, -3.0), max: DVec2::new(1.5, 0.0) });
    }

    #[test]
    fn touching_boxes_overlap() {
        let a = Aabb { min: DVec2::ZERO, max: DVec2::ONE };
        let b = Aabb { min: DVec2::new(1.0, 0.5), max: DVec2::new(2.0, 2.0) };
        let c = Aabb { min: DVec2::new(1.0 + 1e-12, 0.5), max: DVec2::new(2.0, 2.0) };
        assert!(a.overlaps(&b) && b.overlaps(&a));
        assert!(!a.overlaps(&c));
        assert!(!Aabb::of_points(&[]).overlaps(&a));
    }
}
