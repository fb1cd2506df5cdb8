//! Per-contact constants frozen at the first contact step (reference §2.5, §4.1; decision D1).

use crate::{BodyMotion, ContactGeometry, reciprocal_or_zero};
use serde::{Deserialize, Serialize};

/// The characteristic length and the two effective masses of a contact.
///
/// gc2d computes the reduced mass "only at the first occurrence of the collision" and caches it (§4.1), and assumes
/// "l constant during the collision" (after 2.21). All three are therefore computed from the geometry of the first
/// overlapping step and kept until the contact ends.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ContactConstants {
    /// l = |r_i||r_j|/(|r_i| + |r_j|) (2.15), m; against an anchored body (wall) l = |r_i|, the |r_j| → ∞ limit.
    pub length: f64,
    /// m⊥ = m_i m_j/(m_i + m_j) (2.16), kg; m_i against an anchored body.
    pub normal_mass: f64,
    /// m∥ = 1/(1/m_i + 1/m_j + r_i²/I_i + r_j²/I_j) (2.17, E1), kg; the j terms vanish for an anchored body.
    pub tangential_mass: f64,
}

impl ContactConstants {
    /// The constants for a contact whose first overlapping step has geometry `geometry`.
    ///
    /// Returns `None` when the characteristic length is not a positive finite number (a contact point at a centre
    /// of mass, or two anchored bodies touching at their reference points): such a contact cannot produce a
    /// meaningful E·A/l, and the law treats it as not touching.
    pub fn at_first_contact(geometry: &ContactGeometry, body_i: &BodyMotion, body_j: &BodyMotion) -> Option<Self> {
        let arm_i = geometry.arm_i.length();
        let arm_j = geometry.arm_j.length();
        let length = match (body_i.is_anchored(), body_j.is_anchored()) {
            (false, true) => arm_i,
            (true, false) => arm_j,
            _ => arm_i * arm_j / (arm_i + arm_j),
        };
        if !(length > 0.0 && length.is_finite()) {
            return None;
        }
        let inv_mass_sum = body_i.inv_mass + body_j.inv_mass;
        let rotational = |body: &BodyMotion, arm: f64| {
            if body.inv_inertia > 0.0 { arm * arm * body.inv_inertia } else { 0.0 }
        };
        let inv_tangential = inv_mass_sum + rotational(body_i, arm_i) + rotational(body_j, arm_j);
        Some(Self {
            length,
            normal_mass: reciprocal_or_zero(inv_mass_sum),
            tangential_mass: reciprocal_or_zero(inv_tangential),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gc2d_geometry::DVec2;

    fn geometry(arm_i: DVec2, arm_j: DVec2) -> ContactGeometry {
        ContactGeometry {
            area: 1e-8,
            normal: DVec2::Y,
            chord_length: 1e-3,
            arm_i,
            arm_j,
            centroid_offset: 0.0,
            rocking: true,
        }
    }

    #[test]
    fn particle_pair_uses_harmonic_length_and_e1_masses() {
        let (m_i, i_i, m_j, i_j) = (0.02, 3e-8, 0.05, 1e-7);
        let body_i = BodyMotion::free(m_i, i_i, DVec2::ZERO, 0.0);
        let body_j = BodyMotion::free(m_j, i_j, DVec2::ZERO, 0.0);
        let arm_i = DVec2::new(0.3e-3, -1.2e-3);
        let arm_j = DVec2::new(-0.5e-3, 2.0e-3);
        let c = ContactConstants::at_first_contact(&geometry(arm_i, arm_j), &body_i, &body_j).unwrap();
        let (ri, rj) = (arm_i.length(), arm_j.length());
        assert!((c.length - ri * rj / (ri + rj)).abs() < 1e-18);
        assert!((c.normal_mass - m_i * m_j / (m_i + m_j)).abs() < 1e-15);
        let expected = 1.0 / (1.0 / m_i + 1.0 / m_j + ri * ri / i_i + rj * rj / i_j);
        assert!((c.tangential_mass - expected).abs() < 1e-15 * expected.max(1.0));
        // Equal arms: l is half the arm.
        let equal = ContactConstants::at_first_contact(&geometry(arm_i, -arm_i), &body_i, &body_j).unwrap();
        assert!((equal.length - 0.5 * ri).abs() < 1e-18);
    }

    #[test]
    fn wall_contact_uses_particle_arm_and_particle_masses() {
        let (m, inertia) = (0.02, 3e-8);
        let particle = BodyMotion::free(m, inertia, DVec2::ZERO, 0.0);
        let wall = BodyMotion::wall(DVec2::ZERO);
        let arm_i = DVec2::new(0.4e-3, -1.0e-3);
        let far = DVec2::new(-5.0, 0.1);
        let c = ContactConstants::at_first_contact(&geometry(arm_i, far), &particle, &wall).unwrap();
        let r = arm_i.length();
        assert_eq!(c.length, r);
        assert_eq!(c.normal_mass, m);
        assert!((c.tangential_mass - 1.0 / (1.0 / m + r * r / inertia)).abs() < 1e-16);
        // The same with the roles swapped.
        let swapped = ContactConstants::at_first_contact(&geometry(far, arm_i), &wall, &particle).unwrap();
        assert_eq!(swapped.length, r);
        assert_eq!(swapped.normal_mass, m);
    }

    #[test]
    fn wall_limit_matches_a_very_heavy_partner() {
        let particle = BodyMotion::free(0.02, 3e-8, DVec2::ZERO, 0.0);
        let heavy = BodyMotion::free(1e12, 1e12, DVec2::ZERO, 0.0);
        let g = geometry(DVec2::new(0.0, -1e-3), DVec2::new(0.0, 1e-3));
        let wall = ContactConstants::at_first_contact(&g, &particle, &BodyMotion::wall(DVec2::ZERO)).unwrap();
        let limit = ContactConstants::at_first_contact(&g, &particle, &heavy).unwrap();
        assert!((wall.normal_mass - limit.normal_mass).abs() < 1e-12);
        assert!((wall.tangential_mass - limit.tangential_mass).abs() < 1e-12);
    }

    #[test]
    fn degenerate_arms_give_no_constants() {
        let particle = BodyMotion::free(0.02, 3e-8, DVec2::ZERO, 0.0);
        let g = geometry(DVec2::ZERO, DVec2::new(0.0, 1e-3));
        assert!(ContactConstants::at_first_contact(&g, &particle, &particle).is_none());
        let walls = geometry(DVec2::ZERO, DVec2::ZERO);
        let wall = BodyMotion::wall(DVec2::ZERO);
        assert!(ContactConstants::at_first_contact(&walls, &wall, &wall).is_none());
    }
}
