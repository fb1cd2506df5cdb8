//! CSV tables and the Markdown summary of the convergence study.

use super::problems::Against;
use super::sweep::{IntegratorSweep, OrderFit, RunRecord, integrator_name};
use super::{ConvergenceError, ProblemReport};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Δt/bound values at which the Markdown summary lists the primary error and the run time (present in both the
/// quick and the full sweep).
const SUMMARY_FRACTIONS: [f64; 5] = [0.04, 0.16, 0.64, 1.28, 2.56];

fn write(path: PathBuf, text: &str) -> Result<PathBuf, ConvergenceError> {
    std::fs::write(&path, text).map_err(|e| ConvergenceError::Output { path: path.clone(), message: e.to_string() })?;
    Ok(path)
}

/// A CSV field: quoted when it contains a comma, a quote or a line break.
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n']) { format!("\"{}\"", text.replace('"', "\"\"")) } else { text.to_owned() }
}

fn optional(value: Option<f64>) -> String {
    value.map_or(String::new(), |v| format!("{v:.6e}"))
}

/// `<dir>/<problem>.csv`: one line per run with Δt, Δt/bound, steps, wall-clock time, stability and every metric.
pub fn write_runs_csv(dir: &Path, report: &ProblemReport) -> Result<PathBuf, ConvergenceError> {
    let mut text = String::from("integrator,dt_s,dt_over_bound,steps,wall_s,stable,failure");
    for metric in &report.metrics {
        let _ = write!(text, ",error_{}", metric.id);
    }
    text.push('\n');
    for sweep in &report.sweeps {
        for run in &sweep.runs {
            let _ = write!(
                text,
                "{},{:.6e},{:.6e},{},{:.6e},{},{}",
                integrator_name(sweep.integrator),
                run.dt,
                run.fraction,
                run.steps,
                run.wall_seconds,
                run.is_stable(),
                csv_field(run.failure.as_deref().unwrap_or(""))
            );
            for m in 0..report.metrics.len() {
                let _ = write!(text, ",{}", optional(run.errors.as_ref().and_then(|e| e.get(m).copied())));
            }
            text.push('\n');
        }
    }
    write(dir.join(format!("{}.csv", report.id)), &text)
}

/// `<dir>/summary.csv`: per problem, integrator and metric the observed order with its fit range, and the
/// instability threshold.
pub fn write_summary_csv(dir: &Path, reports: &[ProblemReport]) -> Result<PathBuf, ConvergenceError> {
    let mut text = String::from(
        "problem,integrator,metric,against,order,fit_min_dt_over_bound,fit_max_dt_over_bound,fit_points,\
         fit_r_squared,last_stable_dt_over_bound,first_unstable_dt_over_bound\n",
    );
    for report in reports {
        for sweep in &report.sweeps {
            for (metric, fit) in report.metrics.iter().zip(&sweep.orders) {
                let _ = writeln!(
                    text,
                    "{},{},{},{},{},{},{},{},{},{},{}",
                    report.id,
                    integrator_name(sweep.integrator),
                    metric.id,
                    against(metric.against),
                    optional(fit.map(|f| f.order)),
                    optional(fit.map(|f| f.fraction_range.0)),
                    optional(fit.map(|f| f.fraction_range.1)),
                    fit.map_or(0, |f| f.points),
                    optional(fit.map(|f| f.r_squared)),
                    optional(sweep.instability.last_stable),
                    optional(sweep.instability.first_unstable),
                );
            }
        }
    }
    write(dir.join("summary.csv"), &text)
}

fn against(against: Against) -> &'static str {
    match against {
        Against::Analytic => "analytic",
        Against::Reference => "reference",
    }
}

/// R² of the log-log fit below which an order is marked as a slope through scattered errors, not a power law: the
/// errors of elastic collisions and Verlet's bounded energy swing depend on where the step falls in the contact or
/// the period (R² 0.74–0.87 in the study), the smooth problems' errors lie on a line (R² ≥ 0.91).
pub const SCATTERED_BELOW_R_SQUARED: f64 = 0.9;

/// Slope below which an error is marked as not falling with Δt (a model error, such as the incline's against the
/// analytic slide: 6.7e-3 at every Δt), rather than given an order.
pub const FLAT_BELOW_ORDER: f64 = 0.25;

/// The Markdown cell of an observed order: the slope, its fit range, points and R², or "–" where none was fitted.
fn order_cell(fit: &Option<OrderFit>) -> String {
    match fit {
        Some(f) => format!(
            "{:.2} ({:.2}–{:.2}, {} pts, R² {:.2}{})",
            f.order,
            f.fraction_range.0,
            f.fraction_range.1,
            f.points,
            f.r_squared,
            if f.order.abs() < FLAT_BELOW_ORDER {
                ": does not fall with Δt"
            } else if f.r_squared < SCATTERED_BELOW_R_SQUARED {
                ": scattered, no clean power law"
            } else {
                ""
            }
        ),
        None => "–".into(),
    }
}

fn threshold_cell(sweep: &IntegratorSweep) -> String {
    match (sweep.instability.last_stable, sweep.instability.first_unstable) {
        (Some(ok), Some(bad)) => format!("{ok:.2}–{bad:.2}"),
        (None, Some(bad)) => format!("< {bad:.2}"),
        (_, None) => format!("> {:.2}", sweep.runs.last().map_or(0.0, |r| r.fraction)),
    }
}

/// A short name for why the first unstable run of a sweep failed.
fn failure_kind(sweep: &IntegratorSweep) -> &'static str {
    let Some(message) = sweep.runs.iter().find_map(|r| r.failure.as_deref()) else { return "–" };
    if message.contains("overlap by") {
        "overlap limit"
    } else if message.contains("not a finite") {
        "non-finite state"
    } else if message.contains("energy rose") {
        "energy jump"
    } else if message.contains("in one step") {
        "travel limit"
    } else if message.contains("still touch") {
        "bodies did not separate"
    } else if message.contains(" above ") {
        "error above limit"
    } else {
        "engine error"
    }
}

fn run_at(sweep: &IntegratorSweep, fraction: f64) -> Option<&RunRecord> {
    sweep.runs.iter().find(|r| (r.fraction / fraction - 1.0).abs() < 1e-9)
}

/// The Markdown summary of one problem: bound and reference, observed orders and instability thresholds, and the
/// primary error with the run time at a few Δt.
pub fn problem_markdown(report: &ProblemReport) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "### `{}`: {}\n", report.id, report.title);
    let reference = &report.reference;
    let _ = writeln!(
        md,
        "Bound (π/10)·sqrt(m/E) = {:.3e} s. Reference: Gear c0=3/16 at Δt = {:.3e} s ({:.3} of the bound), \
         observation {:?}.\n",
        report.time_step_bound,
        reference.dt,
        reference.dt / report.time_step_bound,
        reference.observation.iter().map(|v| format!("{v:.9e}")).collect::<Vec<_>>(),
    );
    let names: Vec<&str> = report.sweeps.iter().map(|s| integrator_name(s.integrator)).collect();
    let _ = writeln!(md, "| observed order (fit range Δt/bound) | against | {} |", names.join(" | "));
    let _ = writeln!(md, "|---|---|{}", "---|".repeat(names.len()));
    for (m, metric) in report.metrics.iter().enumerate() {
        let cells: Vec<String> = report.sweeps.iter().map(|s| order_cell(&s.orders[m])).collect();
        let uncertainty = if metric.against == Against::Reference {
            format!(" (ref. ±{:.1e})", reference.uncertainty[m])
        } else {
            String::new()
        };
        let _ =
            writeln!(md, "| {}{} | {} | {} |", metric.label, uncertainty, against(metric.against), cells.join(" | "));
    }
    let cells: Vec<String> = report.sweeps.iter().map(threshold_cell).collect();
    let _ = writeln!(md, "| **unstable between Δt/bound** | | {} |", cells.join(" | "));
    let cells: Vec<&str> = report.sweeps.iter().map(failure_kind).collect();
    let _ = writeln!(md, "| what stopped the first unstable run | | {} |\n", cells.join(" | "));
    let _ = writeln!(
        md,
        "| {} at Δt/bound (wall-clock s) | {} |",
        report.metrics[0].label,
        SUMMARY_FRACTIONS.map(|f| format!("{f}")).join(" | ")
    );
    let _ = writeln!(md, "|---|{}", "---|".repeat(SUMMARY_FRACTIONS.len()));
    for sweep in &report.sweeps {
        let cells: Vec<String> = SUMMARY_FRACTIONS
            .iter()
            .map(|&f| match run_at(sweep, f) {
                Some(run) => match (&run.errors, run.is_stable()) {
                    (Some(e), true) => format!("{:.2e} ({:.3})", e[0], run.wall_seconds),
                    (Some(e), false) => format!("unstable: {:.1e}", e[0]),
                    (None, _) => "stopped".into(),
                },
                None => "–".into(),
            })
            .collect();
        let _ = writeln!(md, "| {} | {} |", integrator_name(sweep.integrator), cells.join(" | "));
    }
    md.push('\n');
    md
}

/// `<dir>/summary.md`: [`problem_markdown`] for every problem.
pub fn write_summary_markdown(dir: &Path, reports: &[ProblemReport]) -> Result<PathBuf, ConvergenceError> {
    let text: String = reports.iter().map(problem_markdown).collect();
    write(dir.join("summary.md"), &text)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::convergence::sweep::{Instability, RunRecord};

    /// Gear's first unstable head-on run stopped at the engine's travel limit and was labelled "engine error".
    #[test]
    fn the_travel_limit_is_named_as_such() {
        let travel = gc2d_engine::SafetyError::ExcessiveTravel {
            time: 1e-4,
            step: 12,
            body: 1,
            travel: 2e-3,
            inscribed_radius: 1e-3,
            limit_percent: 50.0,
            suggested_dt: 1e-6,
        };
        let run = RunRecord {
            dt: 1e-5,
            fraction: 1.28,
            steps: 12,
            wall_seconds: 0.0,
            errors: None,
            failure: Some(travel.to_string()),
        };
        let sweep = IntegratorSweep {
            integrator: gc2d_engine::Integrator::default(),
            runs: vec![run],
            orders: vec![],
            instability: Instability::default(),
        };
        assert_eq!(failure_kind(&sweep), "travel limit");
    }
}
