//! The Janssen fit (reference §7.1, eqs. 3.1–3.5): the wall friction coefficient μ_j from a measured wall pressure
//! σ_xx(z) with the measured stress ratio k, bulk density ρ and half-width r held fixed.
//!
//! σ_xx(z) = (ρ g r/μ_j)(1 − exp(−k μ_j z/r)) (3.4), z the depth below the fill surface. μ_j is the one free
//! parameter; it is found by least squares on a logarithmic scan followed by a golden-section refinement.

use crate::error::AnalysisError;
use serde::Serialize;

/// The quantities held fixed in the fit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct JanssenParameters {
    /// k = σ_xx/σ_zz (3.2).
    pub k: f64,
    /// Bulk density ρ = ρ_rel · ρ_particle (3.5), kg/m².
    pub rho: f64,
    /// g, m/s².
    pub g: f64,
    /// Half-width r of the silo, m.
    pub half_width: f64,
}

impl JanssenParameters {
    /// σ_xx at depth z for wall friction μ_j (3.4), N/m.
    pub fn sigma_xx(&self, depth: f64, mu_j: f64) -> f64 {
        self.rho * self.g * self.half_width / mu_j * -(-self.k * mu_j * depth / self.half_width).exp_m1()
    }

    /// σ_zz = σ_xx / k at depth z (3.4), N/m.
    pub fn sigma_zz(&self, depth: f64, mu_j: f64) -> f64 {
        self.sigma_xx(depth, mu_j) / self.k
    }

    fn validate(&self) -> Result<(), AnalysisError> {
        let positive = |name: &str, v: f64| {
            if v > 0.0 && v.is_finite() {
                Ok(())
            } else {
                Err(AnalysisError::InvalidParameter(format!("Janssen {name} = {v} must be positive and finite")))
            }
        };
        positive("k", self.k)?;
        positive("rho", self.rho)?;
        positive("g", self.g)?;
        positive("half_width", self.half_width)
    }
}

/// The fitted μ_j and what follows from it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct JanssenFit {
    /// The parameters held fixed.
    pub parameters: JanssenParameters,
    /// Wall friction coefficient μ_j.
    pub mu_j: f64,
    /// Root-mean-square of σ_xx − fit over the points, N/m.
    pub rms_residual: f64,
    /// `rms_residual` over the asymptotic pressure.
    pub relative_rms_residual: f64,
    /// Saturation depth r/(k μ_j): the pressure reaches 1 − 1/e ≈ 63 % of its asymptote there (and 95 % at three
    /// times this depth), m.
    pub saturation_depth: f64,
    /// Asymptotic wall pressure ρ g r/μ_j, N/m.
    pub asymptotic_pressure: f64,
    /// Number of points fitted.
    pub points: usize,
}

/// Smallest and largest μ_j the fit considers.
pub const MU_J_RANGE: (f64, f64) = (1e-4, 1e2);

/// Least-squares μ_j for the profile (`depth`, `sigma_xx`). Points with a non-finite value or negative depth are
/// ignored; at least two must remain.
pub fn fit_janssen(
    depth: &[f64],
    sigma_xx: &[f64],
    parameters: JanssenParameters,
) -> Result<JanssenFit, AnalysisError> {
    parameters.validate()?;
    let points: Vec<(f64, f64)> = depth
        .iter()
        .zip(sigma_xx)
        .map(|(&z, &s)| (z, s))
        .filter(|&(z, s)| z.is_finite() && s.is_finite() && z >= 0.0)
        .collect();
    if points.len() < 2 {
        return Err(AnalysisError::NotEnoughData(format!(
            "Janssen fit needs at least two wall-pressure points, got {}",
            points.len()
        )));
    }
    let cost = |log_mu: f64| {
        let mu = log_mu.exp();
        points.iter().map(|&(z, s)| (s - parameters.sigma_xx(z, mu)).powi(2)).sum::<f64>()
    };
    const SCAN: usize = 400;
    let (lo, hi) = (MU_J_RANGE.0.ln(), MU_J_RANGE.1.ln());
    let step = (hi - lo) / SCAN as f64;
    let best = (0..=SCAN).map(|i| lo + i as f64 * step).min_by(|&a, &b| cost(a).total_cmp(&cost(b))).unwrap_or(lo);
    let log_mu = golden_section(cost, (best - step).max(lo), (best + step).min(hi));
    let mu_j = log_mu.exp();
    let rms_residual = (cost(log_mu) / points.len() as f64).sqrt();
    let asymptotic_pressure = parameters.rho * parameters.g * parameters.half_width / mu_j;
    Ok(JanssenFit {
        parameters,
        mu_j,
        rms_residual,
        relative_rms_residual: rms_residual / asymptotic_pressure,
        saturation_depth: parameters.half_width / (parameters.k * mu_j),
        asymptotic_pressure,
        points: points.len(),
    })
}

/// Minimum of `f` on [a, b] by golden-section search to a relative width of 1e-12.
fn golden_section(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let mut c = b - ratio * (b - a);
    let mut d = a + ratio * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..200 {
        if (b - a).abs() <= 1e-12 * (a.abs() + b.abs()).max(1.0) {
            break;
        }
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - ratio * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + ratio * (b - a);
            fd = f(d);
        }
    }
    0.5 * (a + b)
}
