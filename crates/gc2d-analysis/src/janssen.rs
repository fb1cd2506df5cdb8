//! The Janssen fit (reference §7.1, eqs. 3.1–3.5): the wall friction coefficient μ_j from a measured wall pressure
//! σ_xx(z) with the measured stress ratio k, bulk density ρ and half-width r held fixed.
//!
//! σ_xx(z) = (ρ g r/μ_j)(1 − exp(−k μ_j z/r)) (3.4), z the depth below the fill surface. μ_j is the one free
//! parameter; it is found by least squares on a logarithmic scan followed by a golden-section refinement.
//!
//! [`fit_janssen_free_k`] also frees k: the asymptote ρ g r/μ_j then sets μ_j alone and the initial slope ρ g k sets
//! k. Where k varies with depth (narrow columns have a larger k near the surface), the thesis's one-parameter fit
//! with the column's k has to trade the plateau against the rise; the free-k fit reads μ_j off the plateau.

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

    /// The same parameters with `k` replaced.
    pub fn with_k(self, k: f64) -> Self {
        Self { k, ..self }
    }

    /// σ_zz = σ_xx / k at depth z (3.4), N/m.
    pub fn sigma_zz(&self, depth: f64, mu_j: f64) -> f64 {
        self.sigma_xx(depth, mu_j) / self.k
    }

    fn validate(&self) -> Result<(), AnalysisError> {
        positive("k", self.k)?;
        positive("rho", self.rho)?;
        positive("g", self.g)?;
        positive("half_width", self.half_width)
    }
}

/// `Ok` when the Janssen parameter `name` is positive and finite.
fn positive(name: &str, v: f64) -> Result<(), AnalysisError> {
    if v > 0.0 && v.is_finite() {
        Ok(())
    } else {
        Err(AnalysisError::InvalidParameter(format!("Janssen {name} = {v} must be positive and finite")))
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
    let points = fit_points(depth, sigma_xx, 2)?;
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

/// The fit of (3.4) with μ_j and k both free; ρ, g and r held fixed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct JanssenFreeKFit {
    /// Wall friction coefficient μ_j = ρ g r / asymptotic pressure.
    pub mu_j: f64,
    /// Effective k = asymptotic pressure / (ρ g · saturation depth), i.e. the initial slope over ρ g.
    pub k: f64,
    /// Root-mean-square of σ_xx − fit over the points, N/m.
    pub rms_residual: f64,
    /// `rms_residual` over the asymptotic pressure.
    pub relative_rms_residual: f64,
    /// Saturation depth r/(k μ_j), m.
    pub saturation_depth: f64,
    /// Asymptotic wall pressure ρ g r/μ_j, N/m.
    pub asymptotic_pressure: f64,
    /// Number of points fitted.
    pub points: usize,
}

/// Saturation depths the free-k fit considers, as multiples of the deepest point's depth. A best fit at the upper
/// end means the profile is straight: it does not saturate within the column and fixes neither μ_j nor k.
pub const FREE_K_DEPTH_RANGE: (f64, f64) = (1e-3, 1e2);

/// Least-squares μ_j and k for the profile (`depth`, `sigma_xx`) with bulk density `rho`, gravity `g` and
/// half-width `half_width` held fixed. Written as σ_xx = A (1 − exp(−z/L)), the model is linear in the asymptote A
/// for a given saturation depth L, so A is solved exactly and L found by a logarithmic scan and golden-section
/// refinement. Needs three usable points and a profile that bends within the column.
pub fn fit_janssen_free_k(
    depth: &[f64],
    sigma_xx: &[f64],
    rho: f64,
    g: f64,
    half_width: f64,
) -> Result<JanssenFreeKFit, AnalysisError> {
    positive("rho", rho)?;
    positive("g", g)?;
    positive("half_width", half_width)?;
    let points = fit_points(depth, sigma_xx, 3)?;
    let deepest = points.iter().map(|p| p.0).fold(0.0, f64::max);
    if deepest <= 0.0 {
        return Err(AnalysisError::NotEnoughData("free-k Janssen fit needs points below the surface".into()));
    }
    let shape = |z: f64, saturation: f64| -(-z / saturation).exp_m1();
    let asymptote = |saturation: f64| {
        let (sf, ff) = points.iter().fold((0.0, 0.0), |(sf, ff), &(z, s)| {
            let f = shape(z, saturation);
            (sf + s * f, ff + f * f)
        });
        sf / ff
    };
    let cost = |log_saturation: f64| {
        let saturation = log_saturation.exp();
        let a = asymptote(saturation);
        points.iter().map(|&(z, s)| (s - a * shape(z, saturation)).powi(2)).sum::<f64>()
    };
    const SCAN: usize = 400;
    let (lo, hi) = ((FREE_K_DEPTH_RANGE.0 * deepest).ln(), (FREE_K_DEPTH_RANGE.1 * deepest).ln());
    let step = (hi - lo) / SCAN as f64;
    let best = (0..=SCAN).map(|i| lo + i as f64 * step).min_by(|&a, &b| cost(a).total_cmp(&cost(b))).unwrap_or(lo);
    if best >= hi - 0.5 * step {
        return Err(AnalysisError::NotEnoughData(format!(
            "the wall pressure does not saturate within the column (deepest point {deepest:.3} m): the free-k \
             Janssen fit needs a profile that bends"
        )));
    }
    let log_saturation = golden_section(cost, (best - step).max(lo), (best + step).min(hi));
    let saturation_depth = log_saturation.exp();
    let asymptotic_pressure = asymptote(saturation_depth);
    if asymptotic_pressure.is_nan() || asymptotic_pressure <= 0.0 {
        return Err(AnalysisError::NotEnoughData(format!(
            "the free-k Janssen fit found a non-positive asymptotic wall pressure ({asymptotic_pressure:.3e} N/m)"
        )));
    }
    let rms_residual = (cost(log_saturation) / points.len() as f64).sqrt();
    Ok(JanssenFreeKFit {
        mu_j: rho * g * half_width / asymptotic_pressure,
        k: asymptotic_pressure / (rho * g * saturation_depth),
        rms_residual,
        relative_rms_residual: rms_residual / asymptotic_pressure,
        saturation_depth,
        asymptotic_pressure,
        points: points.len(),
    })
}

/// The (depth, σ_xx) pairs with finite values and non-negative depth; an error when fewer than `needed` remain.
fn fit_points(depth: &[f64], sigma_xx: &[f64], needed: usize) -> Result<Vec<(f64, f64)>, AnalysisError> {
    let points: Vec<(f64, f64)> = depth
        .iter()
        .zip(sigma_xx)
        .map(|(&z, &s)| (z, s))
        .filter(|&(z, s)| z.is_finite() && s.is_finite() && z >= 0.0)
        .collect();
    if points.len() < needed {
        return Err(AnalysisError::NotEnoughData(format!(
            "Janssen fit needs at least {needed} wall-pressure points, got {}",
            points.len()
        )));
    }
    Ok(points)
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
