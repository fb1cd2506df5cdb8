//! The per-pair kinematics context every penetration sub-model reads (in the spirit of LAMMPS GRANULAR's shared
//! `granular_model` context: overlap, normal, effective radius and mass), and the material mixing rules.

use crate::{BodyMotion, reciprocal_or_zero};
use gc2d_geometry::DVec2;
use serde::{Deserialize, Serialize};

/// One contact's geometry at this step, as the narrowphase gives it for two disks (or a disk and a wall).
///
/// Conventions as for the area law ([`crate::ContactGeometry`]): `normal` points from j to i, so the repulsive force
/// on i is along `+normal`; the tangent is `normal` turned counter-clockwise by 90°. The overlap is positive while
/// touching (feedpipe.md §7.1 item 1 turns the thesis' negative δ of (3.28) into this positive one).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PenetrationGeometry {
    /// Penetration depth δ in m: R_i + R_j − |x_i − x_j| for two disks; the disks touch when δ > 0.
    pub depth: f64,
    /// Unit normal from j to i.
    pub normal: DVec2,
    /// r_i = s − x_i: from i's centre of mass to the contact point s, m.
    pub arm_i: DVec2,
    /// r_j = s − x_j: from j's centre of mass (for a wall: its reference point) to the contact point, m.
    pub arm_j: DVec2,
}

impl PenetrationGeometry {
    /// A pair that does not touch. Evaluating it ends a contact that was active.
    pub const SEPARATED: Self = Self { depth: 0.0, normal: DVec2::Y, arm_i: DVec2::ZERO, arm_j: DVec2::ZERO };

    /// The geometry of two disks with centres `centre_i`, `centre_j` and radii `radius_i`, `radius_j` (m). The
    /// contact point lies on the line of centres in the middle of the overlap, x_j + (R_j − δ/2)·n. Coincident
    /// centres give [`Self::SEPARATED`] (no usable normal).
    pub fn between_disks(centre_i: DVec2, radius_i: f64, centre_j: DVec2, radius_j: f64) -> Self {
        let offset = centre_i - centre_j;
        let distance = offset.length();
        if !(distance > 0.0 && distance.is_finite()) {
            return Self::SEPARATED;
        }
        let normal = offset / distance;
        let depth = radius_i + radius_j - distance;
        let point = centre_j + (radius_j - 0.5 * depth) * normal;
        Self { depth, normal, arm_i: point - centre_i, arm_j: point - centre_j }
    }

    /// Unit tangent: the normal turned counter-clockwise by 90°, (−n_y, n_x).
    #[inline]
    pub fn tangent(&self) -> DVec2 {
        self.normal.perp()
    }

    /// True when the bodies touch (δ > 0) with a usable, finite geometry. NaN or infinite input counts as not
    /// touching, so bad geometry produces no force rather than a NaN. The finiteness tests are combined without early
    /// exits, as in [`ContactGeometry::is_overlapping`](crate::ContactGeometry::is_overlapping).
    #[inline]
    pub fn is_touching(&self) -> bool {
        self.depth > 0.0
            && (self.depth.is_finite() & self.normal.is_finite() & self.arm_i.is_finite() & self.arm_j.is_finite())
    }
}

/// The inertia and size of a pair, fixed by the engine for the pair (for disks they do not change during a contact).
///
/// All four are effective ("starred") values of the pair. A wall counts as a body of infinite radius and mass
/// (feedpipe.md (3.61), (3.62)): R* = R_i, m* = m_i. [`PairProperties::disks`] computes them from the two bodies.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PairProperties {
    /// R* = (1/R_i + 1/R_j)⁻¹ (feedpipe.md (3.33)), m.
    pub effective_radius: f64,
    /// m* = (1/m_i + 1/m_j)⁻¹ (feedpipe.md (3.41)), kg: the mass of the normal oscillator.
    pub effective_mass: f64,
    /// m_t = (1/m_i + 1/m_j + R_i²/I_i + R_j²/I_j)⁻¹, kg: the mass of the tangential oscillator (a contact point
    /// pushed along the tangent moves the centres and turns the bodies), as the area law's m∥ (2.17, E1).
    pub tangential_mass: f64,
    /// J* = (1/I_i + 1/I_j)⁻¹, kg·m²: the inertia of the relative rotation the rolling spring resists.
    pub rolling_inertia: f64,
}

impl PairProperties {
    /// The properties of disks i and j with radii `radius_i`, `radius_j` (m; `f64::INFINITY` for a wall) and the
    /// inverse masses and inertias of `body_i`, `body_j` (0 for a wall or a fixed body). The lever arms of the
    /// tangential mass are the radii (the overlap is small against them).
    pub fn disks(radius_i: f64, body_i: &BodyMotion, radius_j: f64, body_j: &BodyMotion) -> Self {
        let rotational = |radius: f64, body: &BodyMotion| {
            if body.inv_inertia > 0.0 { radius * radius * body.inv_inertia } else { 0.0 }
        };
        let inv_mass = body_i.inv_mass + body_j.inv_mass;
        Self {
            effective_radius: reciprocal_or_zero(reciprocal_or_zero(radius_i) + reciprocal_or_zero(radius_j)),
            effective_mass: reciprocal_or_zero(inv_mass),
            tangential_mass: reciprocal_or_zero(inv_mass + rotational(radius_i, body_i) + rotational(radius_j, body_j)),
            rolling_inertia: reciprocal_or_zero(body_i.inv_inertia + body_j.inv_inertia),
        }
    }
}

/// Hertz effective modulus E* = ((1 − ν_i²)/E_i + (1 − ν_j²)/E_j)⁻¹ in Pa (feedpipe.md (3.32)) from the Young's
/// moduli `e_i`, `e_j` (Pa) and Poisson ratios `nu_i`, `nu_j`. A wall's material enters like any other (feedpipe.md
/// §7.4 item 11); an infinitely stiff partner (E = ∞) contributes nothing.
pub fn effective_modulus(e_i: f64, nu_i: f64, e_j: f64, nu_j: f64) -> f64 {
    reciprocal_or_zero((1.0 - nu_i * nu_i) * reciprocal_or_zero(e_i) + (1.0 - nu_j * nu_j) * reciprocal_or_zero(e_j))
}

/// Shear modulus G = E/(2(1 + ν)) in Pa (feedpipe.md (3.49)).
pub fn shear_modulus(e: f64, nu: f64) -> f64 {
    e / (2.0 * (1.0 + nu))
}

/// Mindlin effective shear modulus G* = ((2 − ν_i)/G_i + (2 − ν_j)/G_j)⁻¹ in Pa with G = E/(2(1 + ν)), from the
/// Young's moduli `e_i`, `e_j` (Pa) and Poisson ratios `nu_i`, `nu_j`. This is the standard rule that feedpipe.md
/// §2.5 (b) recommends instead of the thesis' ν_eff (3.51).
pub fn effective_shear_modulus(e_i: f64, nu_i: f64, e_j: f64, nu_j: f64) -> f64 {
    let compliance = |e: f64, nu: f64| (2.0 - nu) * reciprocal_or_zero(shear_modulus(e, nu));
    reciprocal_or_zero(compliance(e_i, nu_i) + compliance(e_j, nu_j))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mixing_rules_for_equal_steels() {
        let (e, nu) = (196.2e9, 0.3);
        assert!((effective_modulus(e, nu, e, nu) - e / (2.0 * (1.0 - nu * nu))).abs() < 1e-3);
        let g = e / (2.0 * 1.3);
        assert!((effective_shear_modulus(e, nu, e, nu) - g / (2.0 * (2.0 - nu))).abs() < 1e-3);
        // A rigid wall counts nothing.
        assert!((effective_modulus(e, nu, f64::INFINITY, 0.3) - e / (1.0 - nu * nu)).abs() < 1e-3);
    }

    #[test]
    fn disk_pair_and_wall_properties() {
        let (m, r) = (0.5, 0.025);
        let inertia = 0.4 * m * r * r;
        let ball = BodyMotion::free(m, inertia, DVec2::ZERO, 0.0);
        let pair = PairProperties::disks(r, &ball, r, &ball);
        assert!((pair.effective_radius - r / 2.0).abs() < 1e-15);
        assert!((pair.effective_mass - m / 2.0).abs() < 1e-15);
        assert!((pair.tangential_mass - m / 7.0).abs() < 1e-15, "1/(2/m + 2·2.5/m) = m/7");
        assert!((pair.rolling_inertia - inertia / 2.0).abs() < 1e-18);
        let wall = PairProperties::disks(r, &ball, f64::INFINITY, &BodyMotion::wall(DVec2::ZERO));
        assert_eq!(wall.effective_radius, r);
        assert_eq!(wall.effective_mass, m);
        assert!((wall.tangential_mass - m / 3.5).abs() < 1e-15);
        assert_eq!(wall.rolling_inertia, inertia);
    }

    #[test]
    fn disk_geometry_puts_the_contact_point_mid_overlap() {
        let g = PenetrationGeometry::between_disks(DVec2::new(0.0, 0.019), 0.01, DVec2::ZERO, 0.01);
        assert!((g.depth - 1e-3).abs() < 1e-15);
        assert_eq!(g.normal, DVec2::Y);
        assert!((g.arm_i - DVec2::new(0.0, -0.0095)).length() < 1e-15);
        assert!((g.arm_j - DVec2::new(0.0, 0.0095)).length() < 1e-15);
        assert!(!PenetrationGeometry::between_disks(DVec2::ZERO, 1.0, DVec2::ZERO, 1.0).is_touching());
    }
}
