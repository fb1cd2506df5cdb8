//! Normal elastic sub-models of the penetration laws: a linear spring and the Hertz sphere law (feedpipe.md §2.2).

use serde::{Deserialize, Serialize};

/// The elastic normal force F(δ) ≥ 0 as a function of the penetration depth δ, and its potential U(δ).
///
/// Both are sphere (3D) laws: F in N, for disks that carry the sphere-equivalent mass model (ARCHITECTURE.md,
/// "2D units"; feedpipe.md §7.1 item 10). Because U is known in closed form, the normal elastic energy of a step
/// is the exact U(δ) − U(δ_old), with no quadrature error.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum NormalSpring {
    /// F = k·δ, U = ½·k·δ² with the stiffness k in N/m.
    Linear {
        /// Normal stiffness k, N/m.
        stiffness_n_m: f64,
    },
    /// Hertz: F = (4/3)·E*·√R*·δ^{3/2}, U = (8/15)·E*·√R*·δ^{5/2} (feedpipe.md (3.29), (3.31), (3.34)), with E* from
    /// [`crate::penetration::effective_modulus`] and R* the pair's effective radius.
    Hertz {
        /// Effective modulus E* in Pa (feedpipe.md (3.32)).
        effective_modulus_pa: f64,
    },
}

impl NormalSpring {
    /// Elastic normal force F(δ) in N for depth `depth` (m) and effective radius `radius` R* (m); 0 for δ ≤ 0.
    #[inline]
    pub fn force(&self, depth: f64, radius: f64) -> f64 {
        self.secant_stiffness(depth, radius) * depth.max(0.0)
    }

    /// Elastic energy U(δ) in J stored at depth `depth`: ½kδ² or (8/15)·E*·√R*·δ^{5/2}; 0 for δ ≤ 0.
    #[inline]
    pub fn energy(&self, depth: f64, radius: f64) -> f64 {
        let depth = depth.max(0.0);
        match *self {
            Self::Linear { stiffness_n_m } => 0.5 * stiffness_n_m * depth * depth,
            Self::Hertz { effective_modulus_pa } => {
                8.0 / 15.0 * effective_modulus_pa * (radius * depth).sqrt() * depth * depth
            }
        }
    }

    /// R*·∂U/∂R* at depth `depth`, J: how much the stored energy grows with the effective radius at a fixed depth,
    /// per unit of ln R*: 0 for the linear spring, U/2 for Hertz (U ∝ √R*). Heating grows the radii, and this is
    /// part of its work on a contact (docs/model.md, "Heating's work on the contacts").
    #[inline]
    pub fn energy_radius_sensitivity(&self, depth: f64, radius: f64) -> f64 {
        match *self {
            Self::Linear { .. } => 0.0,
            Self::Hertz { .. } => 0.5 * self.energy(depth, radius),
        }
    }

    /// Secant stiffness k_n(δ) = F(δ)/δ in N/m: k, or k_Hz·√δ = (4/3)·E*·√(R*·δ) (feedpipe.md (3.42)). This is the
    /// stiffness the thesis puts into the damping coefficient (3.44) and the one the Cundall–Strack stiffness ratio
    /// multiplies.
    #[inline]
    pub fn secant_stiffness(&self, depth: f64, radius: f64) -> f64 {
        match *self {
            Self::Linear { stiffness_n_m } => stiffness_n_m,
            Self::Hertz { effective_modulus_pa } => 4.0 / 3.0 * effective_modulus_pa * (radius * depth.max(0.0)).sqrt(),
        }
    }

    /// Tangent stiffness dF/dδ in N/m: k, or 2·E*·√(R*·δ). It sets the frequency of small oscillations about δ, hence
    /// the stable time step.
    #[inline]
    pub fn tangent_stiffness(&self, depth: f64, radius: f64) -> f64 {
        match *self {
            Self::Linear { stiffness_n_m } => stiffness_n_m,
            Self::Hertz { effective_modulus_pa } => 2.0 * effective_modulus_pa * (radius * depth.max(0.0)).sqrt(),
        }
    }

    /// The largest depth of an undamped head-on impact at normal speed `speed` (m/s) of a pair with effective mass
    /// `mass` m* (kg) and radius `radius` R* (m), in m: v·√(m*/k), or (15·m*·v²/(16·E*·√R*))^{2/5} for Hertz
    /// (ballmill.md §7.4, feedpipe.md §7.2). Damping only makes it smaller.
    pub fn max_depth(&self, speed: f64, mass: f64, radius: f64) -> f64 {
        match *self {
            Self::Linear { stiffness_n_m } => speed.abs() * (mass / stiffness_n_m).sqrt(),
            Self::Hertz { effective_modulus_pa } => hertz_max_depth(mass, radius, effective_modulus_pa, speed),
        }
    }
}

/// Largest overlap of an undamped Hertz impact, δ_max = (15·m*·v²/(16·E*·√R*))^{2/5} in m (ballmill.md §7.4), for
/// effective mass `mass` (kg), radius `radius` (m), modulus `modulus` E* (Pa) and impact speed `speed` (m/s). It
/// follows from ½·m*·v² = U(δ_max).
pub fn hertz_max_depth(mass: f64, radius: f64, modulus: f64, speed: f64) -> f64 {
    (15.0 * mass * speed * speed / (16.0 * modulus * radius.sqrt())).powf(0.4)
}

/// The Hertz contact-time constant: t_c = [`HERTZ_CONTACT_TIME_FACTOR`]·(m*²/(R*·E*²·v))^{1/5}. It is
/// 2·√π·Γ(7/5)/Γ(9/10)·(15/16)^{2/5} = 2.868 (ballmill.md §7.4, feedpipe.md §7.4 item 11): the time of an undamped
/// impact, 2·δ_max/v·∫₀¹ dx/√(1 − x^{5/2}).
pub const HERTZ_CONTACT_TIME_FACTOR: f64 = 2.868_265_699_195_333;

/// Analytic duration of an undamped Hertz impact in s, t_c = 2.868·(m*²/(R*·E*²·v))^{1/5}, for effective mass
/// `mass` (kg), radius `radius` (m), modulus `modulus` E* (Pa) and impact normal speed `speed` (m/s)
/// (ballmill.md §7.4; feedpipe.md §7.4 item 11).
pub fn hertz_contact_time(mass: f64, radius: f64, modulus: f64, speed: f64) -> f64 {
    HERTZ_CONTACT_TIME_FACTOR * (mass * mass / (radius * modulus * modulus * speed)).powf(0.2)
}

/// Duration of a linear spring–dashpot impact in s, t_c = π/(ω₀·√(1 − D²)) with ω₀ = √(k/m*) (feedpipe.md §2.4),
/// for stiffness `stiffness` (N/m), effective mass `mass` (kg) and damping ratio `damping_ratio` D < 1; infinite for
/// D ≥ 1 (no clamp: the overdamped contact only ends asymptotically).
pub fn linear_contact_time(stiffness: f64, mass: f64, damping_ratio: f64) -> f64 {
    if damping_ratio >= 1.0 {
        return f64::INFINITY;
    }
    std::f64::consts::PI / ((stiffness / mass).sqrt() * (1.0 - damping_ratio * damping_ratio).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn force_is_the_derivative_of_the_energy() {
        for spring in [NormalSpring::Linear { stiffness_n_m: 3e6 }, NormalSpring::Hertz { effective_modulus_pa: 1e11 }]
        {
            let (radius, depth, h) = (0.0125, 2e-6, 1e-10);
            let numeric = (spring.energy(depth + h, radius) - spring.energy(depth - h, radius)) / (2.0 * h);
            let force = spring.force(depth, radius);
            assert!((numeric - force).abs() < 1e-7 * force, "{spring:?}");
            let numeric_k = (spring.force(depth + h, radius) - spring.force(depth - h, radius)) / (2.0 * h);
            assert!((numeric_k - spring.tangent_stiffness(depth, radius)).abs() < 1e-6 * numeric_k);
            assert_eq!(spring.force(-1e-6, radius), 0.0);
            assert_eq!(spring.energy(-1e-6, radius), 0.0);
        }
    }

    #[test]
    fn the_radius_sensitivity_is_r_times_the_energy_s_radius_derivative() {
        for spring in [NormalSpring::Linear { stiffness_n_m: 3e6 }, NormalSpring::Hertz { effective_modulus_pa: 1e11 }]
        {
            let (radius, depth, h) = (0.0125, 2e-6, 1e-6);
            let numeric = radius
                * (spring.energy(depth, radius * (1.0 + h)) - spring.energy(depth, radius * (1.0 - h)))
                / (2.0 * h * radius);
            let sensitivity = spring.energy_radius_sensitivity(depth, radius);
            assert!((numeric - sensitivity).abs() <= 1e-9 * spring.energy(depth, radius), "{spring:?}: {numeric}");
        }
    }

    #[test]
    fn contact_time_factor_is_the_hertz_integral() {
        // ∫₀¹ dx/√(1 − x^{5/2}) by the substitution x = 1 − s², which removes the end singularity.
        let n = 200_000;
        let integrand = |s: f64| {
            let x = 1.0 - s * s;
            2.0 * s / (1.0 - x.powf(2.5)).sqrt()
        };
        let h = 1.0 / n as f64;
        // Midpoint rule (the integrand is finite at s → 0: 2s/√(2.5·s²) → 2/√2.5).
        let integral: f64 = (0..n).map(|k| integrand((k as f64 + 0.5) * h) * h).sum();
        let factor = 2.0 * integral * (15.0f64 / 16.0).powf(0.4);
        assert!((factor - HERTZ_CONTACT_TIME_FACTOR).abs() < 1e-8, "{factor}");
    }
}
