//! SVG figures of the convergence study: for a problem's metric, its error against Δt/bound (the convergence
//! plot) and against wall-clock time (the work-precision diagram), both log-log, one curve per integrator.

use super::sweep::{IntegratorSweep, integrator_name};
use super::{ConvergenceError, ProblemReport};
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// Figure size in pixels: two panels side by side.
const SIZE: (u32, u32) = (1200, 500);
/// Metrics that are conserved to round-off by construction and therefore not plotted.
const UNPLOTTED_METRICS: [&str; 1] = ["momentum"];
/// Curve colours, one per integrator in study order.
const COLOURS: [RGBColor; 3] = [RGBColor(31, 119, 180), RGBColor(214, 39, 40), RGBColor(44, 160, 44)];

/// One plotted point: (Δt/bound, wall-clock s, error).
type Point = (f64, f64, f64);
/// A legend name with its points.
type Series = (String, Vec<Point>);

/// Writes `<dir>/<problem>_<metric>.svg` for every plotted metric of `report`; returns the paths.
pub fn write_figures(dir: &Path, report: &ProblemReport) -> Result<Vec<PathBuf>, ConvergenceError> {
    let mut paths = Vec::new();
    for (m, metric) in report.metrics.iter().enumerate() {
        if UNPLOTTED_METRICS.contains(&metric.id) {
            continue;
        }
        let path = dir.join(format!("{}_{}.svg", report.id, metric.id));
        draw(&path, report, m).map_err(|e| ConvergenceError::Output { path: path.clone(), message: e })?;
        paths.push(path);
    }
    Ok(paths)
}

/// The plotted points of a sweep for metric `m`: (Δt/bound, wall-clock s, error) of the stable runs with a positive
/// error (a log axis has no zero).
fn points(sweep: &IntegratorSweep, m: usize) -> Vec<Point> {
    sweep
        .runs
        .iter()
        .filter(|r| r.is_stable())
        .filter_map(|r| {
            let e = *r.errors.as_ref()?.get(m)?;
            (e > 0.0 && e.is_finite()).then_some((r.fraction, r.wall_seconds.max(1e-7), e))
        })
        .collect()
}

/// A log axis range enclosing `values` with a little margin, rounded out to decades.
fn decade_range(values: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if !(lo.is_finite() && hi.is_finite()) {
        return 1e-16..1.0;
    }
    10f64.powf(lo.log10().floor())..10f64.powf(hi.log10().ceil().max(lo.log10().floor() + 1.0))
}

fn draw(path: &Path, report: &ProblemReport, m: usize) -> Result<(), String> {
    let root = SVGBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let root = root
        .titled(&format!("{}: {}", report.id, report.metrics[m].label), ("sans-serif", 20))
        .map_err(|e| e.to_string())?;
    let (left, right) = root.split_horizontally(SIZE.0 / 2);
    let series: Vec<Series> =
        report.sweeps.iter().map(|s| (integrator_name(s.integrator).to_owned(), points(s, m))).collect();
    let errors = decade_range(series.iter().flat_map(|(_, p)| p.iter().map(|q| q.2)));
    let fractions = decade_range(series.iter().flat_map(|(_, p)| p.iter().map(|q| q.0)));
    let times = decade_range(series.iter().flat_map(|(_, p)| p.iter().map(|q| q.1)));
    // Errors grow with Δt and fall with run time, so the emptiest corners are lower right and upper right.
    let by_dt = ("error against Δt / bound", "Δt / (π/10)·sqrt(m/E)", SeriesLabelPosition::LowerRight);
    let by_time =
        ("work-precision: error against run time", "wall-clock time per run (s)", SeriesLabelPosition::UpperRight);
    panel(&left, by_dt, fractions, errors.clone(), &series, |q| q.0)?;
    panel(&right, by_time, times, errors, &series, |q| q.1)?;
    root.present().map_err(|e| e.to_string())
}

/// One log-log panel; `labels` is (caption, x-axis description, legend position).
fn panel(
    area: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    (caption, x_label, legend): (&str, &str, SeriesLabelPosition),
    x_range: std::ops::Range<f64>,
    y_range: std::ops::Range<f64>,
    series: &[Series],
    x_of: fn(&Point) -> f64,
) -> Result<(), String> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 16))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(x_range.log_scale(), y_range.log_scale())
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc("error")
        .x_label_formatter(&|x| format!("{x:.0e}"))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .draw()
        .map_err(|e| e.to_string())?;
    for ((name, points), colour) in series.iter().zip(COLOURS) {
        let xy: Vec<(f64, f64)> = points.iter().map(|q| (x_of(q), q.2)).collect();
        chart
            .draw_series(LineSeries::new(xy.clone(), colour.stroke_width(2)))
            .map_err(|e| e.to_string())?
            .label(name.as_str())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2)));
        chart.draw_series(xy.into_iter().map(|p| Circle::new(p, 3, colour.filled()))).map_err(|e| e.to_string())?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .position(legend)
        .draw()
        .map_err(|e| e.to_string())
}
