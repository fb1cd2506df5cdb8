//! Normal sub-models: overlap-area elasticity (2.20, or its energy-conserving variant) and clipped normal damping
//! (2.21, E3, 2.22).

use serde::{Deserialize, Serialize};

/// Elastic normal force of the overlap-area law, by one of two formulations (docs/model.md, "Contact law",
/// "Energy of the area law").
///
/// E is the 2D Young's modulus in N/m, l the characteristic length frozen at the first contact step.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct NormalElastic {
    /// Young's modulus E, N/m.
    pub e_modulus: f64,
    /// Which force law: gc2d's E·A/l or the exact gradient of the potential E·A²/(2l²). Default: the thesis's.
    #[serde(default)]
    pub formulation: AreaFormulation,
}

/// How the overlap-area law turns the overlap area A, the chord length c and the frozen length l into a force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum AreaFormulation {
    /// gc2d's thesis law F⊥ = E·A/l (2.20), with h_eff = A/l (2.19). Not the gradient of a potential when the chord
    /// length changes along a path, so elastic collisions of angular bodies gain or lose energy (booked as opening
    /// residual). Reproduces the thesis.
    #[default]
    Thesis,
    /// The exact gradient of the potential W(A) = E·A²/(2l²) of the overlap area (Feng's energy-conserving contact
    /// theory): F⊥ = W′(A)·c = (E·A/l)·(c/l), since ∂A/∂h = c. With the force at the chord midpoint the torques are
    /// exact too, so an elastic contact returns all the energy it stored.
    Conservative,
    /// The overlap as a bed of springs and dashpots along the chord (a Winkler foundation; docs/model.md, "Rocking
    /// of flat contacts"): gc2d's F⊥ = E·A/l, applied at the overlap centroid projected on the chord instead of the
    /// chord midpoint, plus a dashpot couple. Against a flat face this is the exact gradient of the potential
    /// (E/2l)·∫δ² ds of the local overlap depth δ along the chord, so a tilted face meets the restoring moment
    /// E·c³·θ/(12 l) and elastic impacts on walls keep their energy; the dashpots make rocking decay, so blocks rest
    /// on slopes below the friction angle. The centroid is computed for polygons against polygons, disks, capsules
    /// and chamber circles; two round outlines need none (it lies on the chord's bisector).
    Winkler,
}

impl NormalElastic {
    /// gc2d's thesis law with Young's modulus `e_modulus`, N/m.
    pub fn thesis(e_modulus: f64) -> Self {
        Self { e_modulus, formulation: AreaFormulation::Thesis }
    }

    /// The energy-conserving law with Young's modulus `e_modulus`, N/m.
    pub fn conservative(e_modulus: f64) -> Self {
        Self { e_modulus, formulation: AreaFormulation::Conservative }
    }

    /// The elastic normal force in N (repulsive, ≥ 0) for overlap area `area`, chord length `chord` and
    /// characteristic length `length`: E·A/l (thesis, Winkler) or E·A·c/l² (conservative).
    #[inline]
    pub fn force(&self, area: f64, chord: f64, length: f64) -> f64 {
        match self.formulation {
            AreaFormulation::Thesis | AreaFormulation::Winkler => self.e_modulus * area / length,
            AreaFormulation::Conservative => self.e_modulus * area * chord / (length * length),
        }
    }

    /// The conservative formulation's potential W(A) = E·A²/(2l²), J (per unit thickness).
    #[inline]
    pub fn potential(&self, area: f64, length: f64) -> f64 {
        0.5 * self.e_modulus * area * area / (length * length)
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
        let law = NormalElastic::thesis(1e7);
        assert_eq!(law.force(2e-9, 5e-3, 1e-3), 1e7 * 2e-9 / 1e-3);
        assert!((law.force(2e-9, 5e-3, 1e-3) - 20.0).abs() < 1e-12);
    }

    #[test]
    fn conservative_force_is_the_derivative_of_the_potential_times_the_chord() {
        let law = NormalElastic::conservative(1e7);
        let (area, chord, length) = (2e-9, 5e-3, 1e-3);
        let derivative =
            (law.potential(area * (1.0 + 1e-6), length) - law.potential(area * (1.0 - 1e-6), length)) / (2e-6 * area);
        assert!((law.force(area, chord, length) - derivative * chord).abs() < 1e-9 * law.force(area, chord, length));
        // The thesis force times c/l.
        assert!((law.force(area, chord, length) - 20.0 * chord / length).abs() < 1e-12);
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
