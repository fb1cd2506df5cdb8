//! What the contact law needs to know about each of the two bodies (reference §2.5, §2.11).

use gc2d_geometry::DVec2;

/// Motion and inertia of one body of a contact pair.
///
/// Walls and fixed bodies have `inv_mass = 0` and `inv_inertia = 0`; such a body counts as *anchored*, which decides
/// the characteristic length (see [`crate::ContactConstants`]). Angular velocity is counter-clockwise positive.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BodyMotion {
    /// Velocity of the centre of mass, m/s.
    pub velocity: DVec2,
    /// Angular velocity, rad/s, counter-clockwise positive.
    pub angular_velocity: f64,
    /// 1/m in 1/kg; 0 for walls and fixed bodies.
    pub inv_mass: f64,
    /// 1/I about the centre of mass in 1/(kg·m²); 0 for walls and fixed bodies.
    pub inv_inertia: f64,
    /// Virtual surface velocity of a wall (gsi `VELOCITY`, reference §2.11), m/s; zero for particles.
    /// Only its component along the contact tangent acts: the surface slides, the body does not move.
    pub surface_velocity: DVec2,
}

impl BodyMotion {
    /// A free body with mass `mass` > 0 and moment of inertia `inertia` > 0, moving with `velocity` and
    /// `angular_velocity`.
    pub fn free(mass: f64, inertia: f64, velocity: DVec2, angular_velocity: f64) -> Self {
        Self {
            velocity,
            angular_velocity,
            inv_mass: 1.0 / mass,
            inv_inertia: 1.0 / inertia,
            surface_velocity: DVec2::ZERO,
        }
    }

    /// A wall at rest whose surface slides with `surface_velocity` (use `DVec2::ZERO` for a plain wall).
    pub fn wall(surface_velocity: DVec2) -> Self {
        Self { surface_velocity, ..Self::default() }
    }

    /// True for walls and fixed bodies (zero inverse mass): they take part in l only through the other body's arm.
    #[inline]
    pub fn is_anchored(&self) -> bool {
        self.inv_mass <= 0.0
    }

    /// Velocity of the material point at `arm` from the centre of mass: v + ω×r with ω×r = ω·(−r_y, r_x), plus the
    /// surface velocity (reference (2.18) as corrected in E2). Callers project it on the tangent, so the surface
    /// velocity enters only tangentially, as gc2d prescribes.
    #[inline]
    pub fn contact_point_velocity(&self, arm: DVec2) -> DVec2 {
        self.velocity + self.angular_velocity * arm.perp() + self.surface_velocity
    }
}
