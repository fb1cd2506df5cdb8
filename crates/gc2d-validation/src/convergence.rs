//! The convergence study (issue "error-against-run-time report", item 3): every reference problem of
//! [`problems`] is run with Gear c₀ = 3/20, Gear c₀ = 3/16 and velocity Verlet over a geometric range of Δt from
//! about a hundredth of the §3.6 bound (π/10)·sqrt(m/E) to beyond it, until each integrator becomes unstable. Each
//! run is timed (the only place in gc2d-rs where wall-clock time is measured) and scored against the problem's
//! known answer. The study writes CSV tables, a Markdown summary and SVG work-precision diagrams.
//!
//! Entry point: [`run_convergence`] with [`ConvergenceOptions`].

pub mod plot;
pub mod problems;
pub mod sweep;
pub mod tables;

use problems::{Metric, Problem};
use std::path::{Path, PathBuf};
use sweep::{IntegratorSweep, Reference};
use thiserror::Error;

/// What to run and where to write it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ConvergenceOptions {
    /// Directory for the CSV tables, the Markdown summary and the SVG figures (created if missing).
    pub out_dir: PathBuf,
    /// A coarse sweep (factor 2 between time steps, reference at five times the problem's reference Δt) that runs
    /// in seconds, instead of the full one (factor √2) that takes a minute or two.
    pub quick: bool,
}

/// Why the study could not be completed.
#[derive(Debug, Error)]
pub enum ConvergenceError {
    /// A reference run failed: the study has nothing to compare with.
    #[error("reference run failed: {0}")]
    Reference(String),
    /// Writing a table or figure failed.
    #[error("cannot write {path}: {message}")]
    Output {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        message: String,
    },
}

/// The results of one problem.
#[derive(Debug, Clone, PartialEq)]
pub struct ProblemReport {
    /// The problem's short name.
    pub id: &'static str,
    /// Its description.
    pub title: &'static str,
    /// Its error metrics; the first is the primary one.
    pub metrics: Vec<Metric>,
    /// The §3.6 bound of its particles, s.
    pub time_step_bound: f64,
    /// The reference run.
    pub reference: Reference,
    /// One sweep per integrator.
    pub sweeps: Vec<IntegratorSweep>,
}

/// Everything the study measured, and the files it wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvergenceReport {
    /// One entry per problem, in study order.
    pub problems: Vec<ProblemReport>,
    /// The files written, in writing order.
    pub files: Vec<PathBuf>,
}

/// The Δt values of a sweep as fractions of the bound: 0.01 · √2^k up to 10.24 (full), or 0.02 · 2^k up to 10.24
/// (quick).
pub fn sweep_fractions(quick: bool) -> Vec<f64> {
    if quick {
        (0..=9).map(|k| 0.02 * 2f64.powi(k)).collect()
    } else {
        (0..=20).map(|k| 0.01 * 2f64.sqrt().powi(k)).collect()
    }
}

/// The reference run's Δt of `problem` as a fraction of the bound.
pub fn reference_fraction(problem: &Problem, quick: bool) -> f64 {
    if quick { 5.0 * problem.reference_fraction } else { problem.reference_fraction }
}

/// Runs one problem: its reference, then every integrator over `fractions`.
pub fn run_problem(
    problem: &Problem,
    fractions: &[f64],
    reference_fraction: f64,
) -> Result<ProblemReport, ConvergenceError> {
    let reference = sweep::reference(problem, reference_fraction).map_err(ConvergenceError::Reference)?;
    let sweeps =
        sweep::INTEGRATORS.iter().map(|&integrator| sweep::sweep(problem, integrator, fractions, &reference)).collect();
    Ok(ProblemReport {
        id: problem.id,
        title: problem.title,
        metrics: problem.metrics.to_vec(),
        time_step_bound: problem.time_step_bound,
        reference,
        sweeps,
    })
}

/// Runs the whole study and writes, into `options.out_dir`: `<problem>.csv` (every run), `summary.csv` (orders and
/// instability thresholds), `summary.md` (the same as Markdown tables) and `<problem>_<metric>.svg` (error against
/// Δt/bound and against wall-clock time, log-log, one curve per integrator).
pub fn run_convergence(options: &ConvergenceOptions) -> Result<ConvergenceReport, ConvergenceError> {
    create_dir(&options.out_dir)?;
    let fractions = sweep_fractions(options.quick);
    let mut report = ConvergenceReport { problems: Vec::new(), files: Vec::new() };
    for problem in problems::all_problems() {
        let result = run_problem(&problem, &fractions, reference_fraction(&problem, options.quick))?;
        report.files.push(tables::write_runs_csv(&options.out_dir, &result)?);
        report.files.extend(plot::write_figures(&options.out_dir, &result)?);
        report.problems.push(result);
    }
    report.files.push(tables::write_summary_csv(&options.out_dir, &report.problems)?);
    report.files.push(tables::write_summary_markdown(&options.out_dir, &report.problems)?);
    Ok(report)
}

fn create_dir(dir: &Path) -> Result<(), ConvergenceError> {
    std::fs::create_dir_all(dir)
        .map_err(|e| ConvergenceError::Output { path: dir.to_path_buf(), message: e.to_string() })
}
