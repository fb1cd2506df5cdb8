//! The Δt sweep of one problem for one integrator: timed runs, the observed order in the asymptotic range, and the
//! time step beyond which the integrator becomes unstable.

use super::problems::{Against, Observation, Problem};
use gc2d_engine::{GearC0, Integrator};
use std::time::Instant;

/// The integrators of the study, in report order.
pub const INTEGRATORS: [Integrator; 3] = [
    Integrator::Gear6(GearC0::PositionDependent),
    Integrator::Gear6(GearC0::VelocityDependent),
    Integrator::VelocityVerlet,
];

/// A short human name of an integrator for tables and legends.
pub fn integrator_name(integrator: Integrator) -> &'static str {
    match integrator {
        Integrator::Gear6(GearC0::PositionDependent) => "Gear c0=3/20",
        Integrator::Gear6(GearC0::VelocityDependent) => "Gear c0=3/16",
        Integrator::VelocityVerlet => "Verlet",
    }
}

/// One timed run of a problem.
#[derive(Debug, Clone, PartialEq)]
pub struct RunRecord {
    /// Δt, s.
    pub dt: f64,
    /// Δt as a fraction of the problem's §3.6 bound.
    pub fraction: f64,
    /// Steps the run needed (or would have needed) to reach its end time.
    pub steps: u64,
    /// Wall-clock time of the run, s (World construction and all steps, one thread).
    pub wall_seconds: f64,
    /// Errors per metric; `None` when the engine stopped the run.
    pub errors: Option<Vec<f64>>,
    /// Why the run counts as unstable: the engine's message, or the error that exceeded the problem's limit.
    pub failure: Option<String>,
}

impl RunRecord {
    /// True when the run finished with an acceptable primary error.
    pub fn is_stable(&self) -> bool {
        self.failure.is_none()
    }
}

/// A least-squares fit of log(error) against log(Δt).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrderFit {
    /// The slope: the observed order of convergence.
    pub order: f64,
    /// Smallest and largest Δt/bound of the points used.
    pub fraction_range: (f64, f64),
    /// Number of points used.
    pub points: usize,
    /// The coefficient of determination R² of the log-log fit: near 1 where the error falls as a power of Δt.
    pub r_squared: f64,
}

/// Where an integrator stopped being stable, as fractions of the bound; `None` when the sweep did not find it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Instability {
    /// The largest stable Δt/bound below the first unstable one.
    pub last_stable: Option<f64>,
    /// The smallest Δt/bound whose run was unstable.
    pub first_unstable: Option<f64>,
}

/// The sweep of one integrator over one problem.
#[derive(Debug, Clone, PartialEq)]
pub struct IntegratorSweep {
    /// The integrator.
    pub integrator: Integrator,
    /// The runs, by increasing Δt.
    pub runs: Vec<RunRecord>,
    /// The observed order per metric, where enough points lie in the asymptotic range.
    pub orders: Vec<Option<OrderFit>>,
    /// The instability threshold.
    pub instability: Instability,
}

/// The reference answer of a problem and how far it can be trusted.
#[derive(Debug, Clone, PartialEq)]
pub struct Reference {
    /// Δt of the reference run, s.
    pub dt: f64,
    /// What the reference run observed.
    pub observation: Observation,
    /// Per metric: the difference between the reference run and a run at twice its Δt, an upper estimate of the
    /// reference's own error for metrics against the reference; zero for analytic metrics.
    pub uncertainty: Vec<f64>,
}

/// Errors below this are round-off, not truncation error, and are left out of order fits.
const ROUND_OFF_FLOOR: f64 = 1e-13;
/// Points whose error exceeds this are outside the asymptotic range.
const ASYMPTOTIC_CEILING: f64 = 1e-1;
/// Points above this Δt/bound are left out of order fits (beyond the bound the error is rarely asymptotic).
const FIT_MAX_FRACTION: f64 = 1.0;
/// A point must exceed the reference's uncertainty by this factor to enter a fit.
const REFERENCE_MARGIN: f64 = 10.0;
/// The sweep of an integrator stops after this many consecutive unstable runs.
const UNSTABLE_RUNS_TO_STOP: usize = 2;

/// Runs the reference of `problem`: Gear c₀ = 3/16 at `fraction` of the bound, and at twice that for the
/// uncertainty estimate.
pub fn reference(problem: &Problem, fraction: f64) -> Result<Reference, String> {
    let dt = fraction * problem.time_step_bound;
    let integrator = Integrator::Gear6(GearC0::VelocityDependent);
    let observation = problem.simulate(integrator, dt).map_err(|e| format!("{}: reference run: {e}", problem.id))?;
    let coarse = problem.simulate(integrator, 2.0 * dt).map_err(|e| format!("{}: reference check: {e}", problem.id))?;
    let differences = problem.errors(&coarse, &observation);
    let uncertainty = problem
        .metrics
        .iter()
        .zip(differences)
        .map(|(metric, d)| if metric.against == Against::Reference { d } else { 0.0 })
        .collect();
    Ok(Reference { dt, observation, uncertainty })
}

/// One timed run at `fraction` of the bound, scored against `reference`.
pub fn timed_run(problem: &Problem, integrator: Integrator, fraction: f64, reference: &Reference) -> RunRecord {
    let dt = fraction * problem.time_step_bound;
    let start = Instant::now();
    let result = problem.simulate(integrator, dt);
    let wall_seconds = start.elapsed().as_secs_f64();
    let (errors, failure) = match result {
        Ok(observation) => {
            let errors = problem.errors(&observation, &reference.observation);
            let (metric, limit) = problem.instability;
            let error = errors.get(metric).copied().unwrap_or(f64::NAN);
            // A NaN error counts as unstable too.
            let within = error <= limit;
            let failure =
                (!within).then(|| format!("error {} = {error:.3e} above {limit:.1e}", problem.metrics[metric].id));
            (Some(errors), failure)
        }
        Err(message) => (None, Some(message)),
    };
    RunRecord { dt, fraction, steps: steps_for(problem, dt), wall_seconds, errors, failure }
}

/// The number of steps a run of `problem` takes at `dt` (its end time over Δt), for the tables.
fn steps_for(problem: &Problem, dt: f64) -> u64 {
    (problem.run_time / dt).round() as u64
}

/// Sweeps `integrator` over `fractions` (increasing) of the bound, stopping after repeated instability.
pub fn sweep(problem: &Problem, integrator: Integrator, fractions: &[f64], reference: &Reference) -> IntegratorSweep {
    let mut runs = Vec::with_capacity(fractions.len());
    let mut unstable_in_a_row = 0;
    for &fraction in fractions {
        let run = timed_run(problem, integrator, fraction, reference);
        unstable_in_a_row = if run.is_stable() { 0 } else { unstable_in_a_row + 1 };
        runs.push(run);
        if unstable_in_a_row >= UNSTABLE_RUNS_TO_STOP {
            break;
        }
    }
    let orders = (0..problem.metrics.len()).map(|m| fit_order(&runs, m, reference.uncertainty[m])).collect();
    let instability = instability(&runs);
    IntegratorSweep { integrator, runs, orders, instability }
}

/// The first unstable run and the stable run before it.
fn instability(runs: &[RunRecord]) -> Instability {
    match runs.iter().position(|r| !r.is_stable()) {
        Some(i) => Instability {
            last_stable: i.checked_sub(1).map(|j| runs[j].fraction),
            first_unstable: Some(runs[i].fraction),
        },
        None => Instability::default(),
    }
}

/// The observed order of metric `metric`: the least-squares slope of log error against log Δt over the stable runs
/// below the bound whose error lies between the noise floor (round-off, or 10 × the reference's uncertainty) and
/// 0.1, and only up to the first unstable run. `None` with fewer than three such points.
pub fn fit_order(runs: &[RunRecord], metric: usize, reference_uncertainty: f64) -> Option<OrderFit> {
    let floor = ROUND_OFF_FLOOR.max(REFERENCE_MARGIN * reference_uncertainty);
    let points: Vec<(f64, f64, f64)> = runs
        .iter()
        .take_while(|r| r.is_stable())
        .filter(|r| r.fraction <= FIT_MAX_FRACTION)
        .filter_map(|r| {
            let error = *r.errors.as_ref()?.get(metric)?;
            (error > floor && error < ASYMPTOTIC_CEILING).then_some((r.dt.ln(), error.ln(), r.fraction))
        })
        .collect();
    if points.len() < 3 {
        return None;
    }
    let xs: Vec<f64> = points.iter().map(|p| p.0).collect();
    let ys: Vec<f64> = points.iter().map(|p| p.1).collect();
    let fractions = points.iter().map(|p| p.2);
    let range = fractions.clone().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), f| (lo.min(f), hi.max(f)));
    let order = least_squares_slope(&xs, &ys);
    let r_squared = coefficient_of_determination(&xs, &ys, order);
    Some(OrderFit { order, fraction_range: range, points: points.len(), r_squared })
}

/// R² of the least-squares line of slope `slope` through the means of `xs` and `ys`: 1 − residual/total sum of
/// squares; 1 where `ys` is constant (nothing to explain).
fn coefficient_of_determination(xs: &[f64], ys: &[f64], slope: f64) -> f64 {
    let n = xs.len() as f64;
    let (mean_x, mean_y) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let total: f64 = ys.iter().map(|y| (y - mean_y).powi(2)).sum();
    let residual: f64 = xs.iter().zip(ys).map(|(x, y)| (y - mean_y - slope * (x - mean_x)).powi(2)).sum();
    if total > 0.0 { 1.0 - residual / total } else { 1.0 }
}

/// The least-squares slope of `ys` against `xs` (same length, at least two distinct xs).
pub fn least_squares_slope(xs: &[f64], ys: &[f64]) -> f64 {
    let n = xs.len() as f64;
    let (mean_x, mean_y) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let covariance: f64 = xs.iter().zip(ys).map(|(x, y)| (x - mean_x) * (y - mean_y)).sum();
    let variance: f64 = xs.iter().map(|x| (x - mean_x).powi(2)).sum();
    covariance / variance
}
