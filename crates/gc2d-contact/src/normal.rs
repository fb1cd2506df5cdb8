//! Normal sub-models: overlap-area elasticity (2.20) and clipped normal damping (2.21, E3, 2.22).

use serde::{Deserialize, Serialize};

/// Elastic normal force proportional to the overlap area: F⊥ = E·A/l (2.20), with h_eff = A/l (2.19).
///
/// E is the 2D Young's modulus in N/m, one value per scene in gc2d (walls share it).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct NormalElastic {
    /// Young's modulus E, N/m.
    pub e_modulus: f64,
}

impl NormalElastic {
    /// F⊥ = E·A/l (2.20) for overlap area `area` and characteristic length `length`, in N (repulsive, ≥ 0).
    #[inline]
    pub fn force(&self, area: f64, length: f64) -> f64 {
        self.e_modulus * area / length
    }
}

/// Normal damping after the damped oscillator, never attractive.
///
/// D*⊥ = γ·sqrt(E·m⊥)·(A − A_old)/(l·Δt) — (2.21) with the dimension fixed as in erratum E3 — and, by (2.22),
/// D⊥ = max(D*⊥, −F⊥) so that F⊥ + D⊥ ≥ 0: damping can cancel the elastic repulsion but never pull. While the
/// overlap grows D*⊥ > 0 > −F⊥ and the max changes nothing, so the one expression covers both branches of (2.22).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct NormalDamping {
    /// Damping constant γ (dimensionless); γ = 0 is the elastic case.
    pub gamma: f64,
}

impl NormalDamping {
    /// The clipped damping force D⊥ in N for an area change `area_change` = A − A_old over one step.
    ///
    /// `inv_dt` is 1/Δt (0 disables the term), `elastic_force` the F⊥ of this step.
    #[inline]
    pub fn force(
        &self,
        e_modulus: f64,
        normal_mass: f64,
        area_change: f64,
        length: f64,
        inv_dt: f64,
        elastic_force: f64,
    ) -> f64 {
        let unclipped = self.gamma * (e_modulus * normal_mass).sqrt() * area_change * inv_dt / length;
        unclipped.max(-elastic_force)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elastic_force_is_e_times_area_over_length() {
        let law = NormalElastic { e_modulus: 1e7 };
        assert_eq!(law.force(2e-9, 1e-3), 1e7 * 2e-9 / 1e-3);
        assert!((law.force(2e-9, 1e-3) - 20.0).abs() < 1e-12);
    }

    #[test]
    fn damping_is_exact_while_approaching_and_clipped_while_separating() {
        let damping = NormalDamping { gamma: 0.5 };
        let (e, m, l, dt): (f64, f64, f64, f64) = (1e7, 0.01, 1e-3, 1e-6);
        let coefficient = 0.5 * (e * m).sqrt();
        let approaching = damping.force(e, m, 1e-12, l, 1.0 / dt, 5.0);
        assert!((approaching - coefficient * 1e-12 / (l * dt)).abs() < 1e-12);
        // A fast separation would give −15.8 N; it is clipped at −F⊥.
        assert_eq!(damping.force(e, m, -1e-10, l, 1.0 / dt, 5.0), -5.0);
        // A slow one is not clipped.
        let slow = damping.force(e, m, -1e-15, l, 1.0 / dt, 5.0);
        assert!((slow + coefficient * 1e-15 / (l * dt)).abs() < 1e-12);
    }
}
