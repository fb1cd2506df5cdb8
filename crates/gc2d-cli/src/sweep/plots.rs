//! SVG figures of outputs against a parameter (plotters, in the analysis figures' style): one series per
//! combination of the other parameters' values, each point the mean over the completed seeds with an error bar of
//! ± one (sample) standard deviation; the legend says so.

use super::collect::Table;
use super::file::Plot;
use crate::failure::CommandFailure;
use gc2d_analysis::figures::{SERIES_COLOURS, padded_range};
use plotters::prelude::*;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// One series: its legend and its (x, mean, standard deviation, seeds) points in x order.
#[derive(Debug, Clone, PartialEq)]
pub struct SeriesStats {
    /// Legend text.
    pub label: String,
    /// (x, mean, sample standard deviation (0 for one seed), number of seeds).
    pub points: Vec<(f64, f64, f64, usize)>,
}

/// The figures of a sweep: the files drawn, and why the others were not.
#[derive(Debug, Default)]
pub struct DrawnPlots {
    /// The SVG files written.
    pub files: Vec<PathBuf>,
    /// One line per figure left out: its y is not a column of this table (an analysis that found nothing to report,
    /// or a misspelt name), which the sweep file cannot be checked for before the runs.
    pub skipped: Vec<String>,
}

/// Draws every figure the sweep file asks for into `folder` (`<y>_vs_<x>.svg`); a figure whose y is not a column is
/// skipped, with a line saying why, so that the other figures of a long sweep are still drawn.
pub fn draw_plots(table: &Table, plots: &[Plot], folder: &Path) -> Result<DrawnPlots, CommandFailure> {
    let mut drawn = DrawnPlots::default();
    if plots.is_empty() {
        return Ok(drawn);
    }
    std::fs::create_dir_all(folder)
        .map_err(|e| CommandFailure::failed(format!("cannot create {}: {e}", folder.display())))?;
    for plot in plots {
        for y in &plot.y {
            if table.column(y).is_none() {
                let names: Vec<&str> = table.numbers.iter().map(String::as_str).collect();
                let hint =
                    gc2d_scene::error::suggest(y, &names).map_or(String::new(), |s| format!(" (did you mean `{s}`?)"));
                drawn.skipped.push(format!(
                    "the figure of `{y}` against `{}` is not drawn: `{y}` is not a column of the collected table{hint}; \
                     its columns are listed in sweep.csv",
                    plot.x
                ));
                continue;
            }
            let series = series(table, &plot.x, y)?;
            let path = folder.join(format!("{}_vs_{}.svg", file_part(y), file_part(&plot.x)));
            draw(&path, &plot.x, y, &series)
                .map_err(|e| CommandFailure::failed(format!("cannot draw {}: {e}", path.display())))?;
            drawn.files.push(path);
        }
    }
    Ok(drawn)
}

/// The series of column `y` against parameter `x`: rows grouped by the other parameters' values, then by x; the mean
/// and sample standard deviation over the group's seeds (points that did not complete, and rows where y is missing or
/// not finite, are left out).
pub fn series(table: &Table, x: &str, y: &str) -> Result<Vec<SeriesStats>, CommandFailure> {
    let Some(x_index) = table.parameters.iter().position(|p| p == x) else {
        return Err(CommandFailure::input(format!("a plot's x, `{x}`, is not a parameter")));
    };
    let Some(column) = table.column(y) else {
        let names: Vec<&str> = table.numbers.iter().map(String::as_str).collect();
        let hint = gc2d_scene::error::suggest(y, &names).map_or(String::new(), |s| format!(" (did you mean `{s}`?)"));
        return Err(CommandFailure::input(format!(
            "a plot's y, `{y}`, is not a column of the collected table{hint}; its columns are listed in sweep.csv"
        )));
    };
    // Series in the order their first row appears; within each, x values in increasing order.
    let mut order: Vec<String> = Vec::new();
    let mut groups: BTreeMap<String, BTreeMap<OrderedX, Vec<f64>>> = BTreeMap::new();
    for (row, value) in table.rows.iter().zip(column) {
        if row.outcome.as_deref() != Some("completed") {
            continue;
        }
        let Ok(xv) = row.parameters[x_index].parse::<f64>() else {
            return Err(CommandFailure::input(format!(
                "a plot's x, `{x}`, has the value `{}`, which is not a number",
                row.parameters[x_index]
            )));
        };
        let label: Vec<String> = table
            .parameters
            .iter()
            .zip(&row.parameters)
            .enumerate()
            .filter(|(k, _)| *k != x_index)
            .map(|(_, (name, v))| format!("{name}={}", v.trim_matches('"')))
            .collect();
        let label = label.join(", ");
        if !order.contains(&label) {
            order.push(label.clone());
        }
        let values = groups.entry(label).or_default().entry(OrderedX(xv)).or_default();
        if let Some(v) = value.filter(|v| v.is_finite()) {
            values.push(v);
        }
    }
    Ok(order
        .into_iter()
        .map(|label| {
            let points = groups[&label]
                .iter()
                .filter(|(_, v)| !v.is_empty())
                .map(|(x, v)| {
                    let (mean, sd) = mean_and_sd(v);
                    (x.0, mean, sd, v.len())
                })
                .collect();
            SeriesStats { label, points }
        })
        .collect())
}

/// An x value ordered by `total_cmp`, to key a map.
#[derive(Debug, Clone, Copy)]
struct OrderedX(f64);

impl PartialEq for OrderedX {
    fn eq(&self, other: &Self) -> bool {
        self.0.total_cmp(&other.0).is_eq()
    }
}

impl Eq for OrderedX {}

impl PartialOrd for OrderedX {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for OrderedX {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// Mean and sample standard deviation (n − 1; 0 for a single value).
pub fn mean_and_sd(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    if values.len() < 2 {
        return (mean, 0.0);
    }
    let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, variance.sqrt())
}

/// A column name as part of a file name.
fn file_part(name: &str) -> String {
    name.chars().map(|c| if c.is_ascii_alphanumeric() || matches!(c, '_' | '-') { c } else { '_' }).collect()
}

fn draw(path: &Path, x: &str, y: &str, series: &[SeriesStats]) -> Result<(), Box<dyn std::error::Error>> {
    let all = || series.iter().flat_map(|s| s.points.iter());
    let (x0, x1) = padded_range(all().map(|p| p.0));
    let (y0, y1) = padded_range(all().flat_map(|p| [p.1 - p.2, p.1 + p.2]));
    let seeds = all().map(|p| p.3).max().unwrap_or(0);
    let root = SVGBackend::new(path, (800, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(format!("{y} against {x}"), ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart.configure_mesh().x_desc(x).y_desc(y).draw()?;
    let cap = 0.01 * (x1 - x0);
    for (k, s) in series.iter().enumerate() {
        let colour = SERIES_COLOURS[k % SERIES_COLOURS.len()];
        let style = colour.stroke_width(2);
        let label = match (s.label.is_empty(), seeds > 1) {
            (true, true) => format!("mean ± s.d. over {seeds} seeds"),
            (false, true) => format!("{}: mean ± s.d. over {seeds} seeds", s.label),
            (true, false) => y.to_owned(),
            (false, false) => s.label.clone(),
        };
        chart
            .draw_series(LineSeries::new(s.points.iter().map(|p| (p.0, p.1)), style))?
            .label(label)
            .legend(move |(lx, ly)| PathElement::new(vec![(lx, ly), (lx + 20, ly)], style));
        chart.draw_series(s.points.iter().map(|p| Circle::new((p.0, p.1), 3, colour.filled())))?;
        for &(px, mean, sd, _) in s.points.iter().filter(|p| p.2 > 0.0) {
            let (lo, hi) = (mean - sd, mean + sd);
            chart.draw_series([
                PathElement::new(vec![(px, lo), (px, hi)], colour.stroke_width(1)),
                PathElement::new(vec![(px - cap, lo), (px + cap, lo)], colour.stroke_width(1)),
                PathElement::new(vec![(px - cap, hi), (px + cap, hi)], colour.stroke_width(1)),
            ])?;
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mean_and_sample_deviation() {
        assert_eq!(mean_and_sd(&[2.0]), (2.0, 0.0));
        let (mean, sd) = mean_and_sd(&[1.0, 2.0, 3.0]);
        assert_eq!(mean, 2.0);
        assert_eq!(sd, 1.0);
    }
}
