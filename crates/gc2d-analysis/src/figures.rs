//! SVG figures (plotters, SVG backend only): line charts, bar charts, a polar plot, cell maps with principal-axis
//! segments, and the force network drawn as in §5.5 (one line from each centre of mass to the force point, width and
//! colour growing with |F|: black, red, yellow).

use crate::error::AnalysisError;
use crate::geometry::Rect;
use crate::snapshot::{BodyRef, Snapshot};
use gc2d_geometry::DVec2;
use plotters::prelude::*;
use std::error::Error;
use std::path::Path;

type DrawResult = Result<(), Box<dyn Error>>;

/// Colours of a figure's series, in order (matplotlib's "tab10" without olive and cyan), shared by the analyses' and
/// the sweeps' figures so that the same series looks the same in both.
pub const SERIES_COLOURS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
];

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mark {
    /// A polyline.
    Line,
    /// Small filled circles.
    Dots,
}

/// One data series of a line chart.
#[derive(Debug, Clone, Copy)]
pub struct Series<'a> {
    /// Legend text.
    pub label: &'a str,
    /// (x, y) points; non-finite points are skipped.
    pub points: &'a [(f64, f64)],
    /// Colour.
    pub color: RGBColor,
    /// Line or dots.
    pub mark: Mark,
}

/// Axis titles and the chart title.
#[derive(Debug, Clone, Copy)]
pub struct Labels<'a> {
    /// Caption above the chart.
    pub title: &'a str,
    /// x-axis title.
    pub x: &'a str,
    /// y-axis title.
    pub y: &'a str,
}

fn figure_error(path: &Path, error: Box<dyn Error>) -> AnalysisError {
    AnalysisError::Figure { file: path.display().to_string(), message: error.to_string() }
}

/// A range covering the finite `values` with 5 % padding; (0, 1) when there are none, ±0.5 around a single value.
pub fn padded_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) =
        values.filter(|v| v.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
    if lo > hi {
        return (0.0, 1.0);
    }
    if hi - lo <= 1e-12 * (lo.abs() + hi.abs()).max(f64::MIN_POSITIVE) {
        let half = 0.5 * lo.abs().max(1e-12);
        return (lo - half, hi + half);
    }
    let pad = 0.05 * (hi - lo);
    (lo - pad, hi + pad)
}

/// Line chart of several series with a legend.
pub fn line_chart(path: &Path, labels: Labels, series: &[Series]) -> Result<(), AnalysisError> {
    draw_line_chart(path, labels, series).map_err(|e| figure_error(path, e))
}

fn draw_line_chart(path: &Path, labels: Labels, series: &[Series]) -> DrawResult {
    let all = || series.iter().flat_map(|s| s.points.iter().copied()).filter(|(x, y)| x.is_finite() && y.is_finite());
    let (x0, x1) = padded_range(all().map(|p| p.0));
    let (y0, y1) = padded_range(all().map(|p| p.1));
    let root = SVGBackend::new(path, (800, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(labels.title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart.configure_mesh().x_desc(labels.x).y_desc(labels.y).draw()?;
    for s in series {
        let points: Vec<(f64, f64)> =
            s.points.iter().copied().filter(|(x, y)| x.is_finite() && y.is_finite()).collect();
        let color = s.color;
        let legend = move |(x, y): (i32, i32)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2));
        match s.mark {
            Mark::Line => {
                chart.draw_series(LineSeries::new(points, color.stroke_width(2)))?.label(s.label).legend(legend);
            }
            Mark::Dots => {
                chart
                    .draw_series(points.into_iter().map(|p| Circle::new(p, 2, color.filled())))?
                    .label(s.label)
                    .legend(legend);
            }
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

/// Bar chart: each bar is (left edge, right edge, height).
pub fn bar_chart(path: &Path, labels: Labels, bars: &[(f64, f64, f64)]) -> Result<(), AnalysisError> {
    draw_bar_chart(path, labels, bars).map_err(|e| figure_error(path, e))
}

fn draw_bar_chart(path: &Path, labels: Labels, bars: &[(f64, f64, f64)]) -> DrawResult {
    let (x0, x1) = padded_range(bars.iter().flat_map(|b| [b.0, b.1]));
    let (_, y1) = padded_range(bars.iter().map(|b| b.2).chain([0.0]));
    let root = SVGBackend::new(path, (800, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(labels.title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(x0..x1, 0.0..y1)?;
    chart.configure_mesh().x_desc(labels.x).y_desc(labels.y).draw()?;
    chart.draw_series(
        bars.iter()
            .filter(|b| b.0.is_finite() && b.1.is_finite() && b.2.is_finite())
            .map(|&(l, r, h)| Rectangle::new([(l, 0.0), (r, h)], BLUE.mix(0.6).filled())),
    )?;
    root.present()?;
    Ok(())
}

/// Polar plot of a distribution over directions (P(α), §5.3): radius = value at each angle, closed curve.
pub fn polar_chart(path: &Path, title: &str, angles_degrees: &[f64], values: &[f64]) -> Result<(), AnalysisError> {
    draw_polar_chart(path, title, angles_degrees, values).map_err(|e| figure_error(path, e))
}

fn draw_polar_chart(path: &Path, title: &str, angles_degrees: &[f64], values: &[f64]) -> DrawResult {
    let radius = values.iter().copied().filter(|v| v.is_finite()).fold(0.0f64, f64::max).max(1e-12) * 1.1;
    let root = SVGBackend::new(path, (640, 640)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(-radius..radius, -radius..radius)?;
    chart.configure_mesh().disable_mesh().x_desc("P cos α").y_desc("P sin α").draw()?;
    for fraction in [0.25, 0.5, 0.75, 1.0] {
        let r = fraction * radius / 1.1;
        let ring = (0..=72).map(|k| {
            let a = (k as f64 * 5.0).to_radians();
            (r * a.cos(), r * a.sin())
        });
        chart.draw_series(LineSeries::new(ring, BLACK.mix(0.2)))?;
    }
    let mut curve: Vec<(f64, f64)> = angles_degrees
        .iter()
        .zip(values)
        .filter(|(a, v)| a.is_finite() && v.is_finite())
        .map(|(a, v)| (v * a.to_radians().cos(), v * a.to_radians().sin()))
        .collect();
    if let Some(&first) = curve.first() {
        curve.push(first);
    }
    chart.draw_series(LineSeries::new(curve, RED.stroke_width(2)))?;
    root.present()?;
    Ok(())
}

/// Colour of `t` in [0, 1] on a dark-blue → green → yellow scale.
fn color_scale(t: f64) -> RGBColor {
    const STOPS: [(f64, (u8, u8, u8)); 4] =
        [(0.0, (48, 18, 59)), (0.35, (33, 145, 140)), (0.7, (122, 209, 81)), (1.0, (253, 231, 37))];
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
    for pair in STOPS.windows(2) {
        let ((t0, c0), (t1, c1)) = (pair[0], pair[1]);
        if t <= t1 {
            let s = (t - t0) / (t1 - t0);
            let mix = |a: u8, b: u8| (a as f64 + s * (b as f64 - a as f64)).round() as u8;
            return RGBColor(mix(c0.0, c1.0), mix(c0.1, c1.1), mix(c0.2, c1.2));
        }
    }
    RGBColor(253, 231, 37)
}

/// Aspect ratios (height/width) of map figures are kept in this range by widening the shorter side of the region.
const MAP_ASPECT: (f64, f64) = (0.2, 2.0);

/// The region widened about its centre so that its aspect ratio is within [`MAP_ASPECT`] (a degenerate region
/// becomes a unit square), and the pixel size that shows it with equal scales on both axes (up to the label areas).
fn map_frame(region: Rect) -> (Rect, (u32, u32)) {
    let size = region.size();
    if !(size.x > 0.0 && size.y > 0.0 && size.is_finite()) {
        return (Rect::centered(region.center(), DVec2::ONE), (800, 820));
    }
    let aspect = size.y / size.x;
    let target = aspect.clamp(MAP_ASPECT.0, MAP_ASPECT.1);
    let framed = if aspect < target {
        DVec2::new(size.x, size.x * target)
    } else if aspect > target {
        DVec2::new(size.y / target, size.y)
    } else {
        size
    };
    (Rect::centered(region.center(), framed), (800, (120.0 + 700.0 * target).round() as u32))
}

/// A map of cells coloured by value over `range` (caption states the range), with optional line segments on top
/// (e.g. major principal axes).
pub fn cell_map(
    path: &Path,
    title: &str,
    cells: &[(Rect, f64)],
    range: (f64, f64),
    segments: &[(DVec2, DVec2)],
) -> Result<(), AnalysisError> {
    draw_cell_map(path, title, cells, range, segments).map_err(|e| figure_error(path, e))
}

fn draw_cell_map(
    path: &Path,
    title: &str,
    cells: &[(Rect, f64)],
    range: (f64, f64),
    segments: &[(DVec2, DVec2)],
) -> DrawResult {
    let bounds =
        Rect::bounding(cells.iter().flat_map(|(r, _)| [r.min, r.max])).unwrap_or(Rect::new(DVec2::ZERO, DVec2::ONE));
    let (region, pixels) = map_frame(bounds);
    let root = SVGBackend::new(path, pixels).into_drawing_area();
    root.fill(&WHITE)?;
    let caption = format!("{title} (colour {:.3e} … {:.3e})", range.0, range.1);
    let mut chart = ChartBuilder::on(&root)
        .caption(caption, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(region.min.x..region.max.x, region.min.y..region.max.y)?;
    chart.configure_mesh().disable_mesh().x_desc("x / m").y_desc("y / m").draw()?;
    let span = range.1 - range.0;
    chart.draw_series(cells.iter().filter(|(_, v)| v.is_finite()).map(|(r, v)| {
        let t = if span > 0.0 { (v - range.0) / span } else { 0.5 };
        Rectangle::new([(r.min.x, r.min.y), (r.max.x, r.max.y)], color_scale(t).filled())
    }))?;
    chart.draw_series(
        segments
            .iter()
            .filter(|(a, b)| a.is_finite() && b.is_finite())
            .map(|(a, b)| PathElement::new(vec![(a.x, a.y), (b.x, b.y)], RED.stroke_width(2))),
    )?;
    root.present()?;
    Ok(())
}

/// The particles (grey outlines) and the force network of §5.5.
pub fn force_network(path: &Path, snapshot: &Snapshot) -> Result<(), AnalysisError> {
    draw_force_network(path, snapshot).map_err(|e| figure_error(path, e))
}

fn draw_force_network(path: &Path, snapshot: &Snapshot) -> DrawResult {
    let bounds = Rect::bounding(snapshot.particles.iter().flat_map(|p| p.vertices.iter().copied()))
        .unwrap_or(Rect::new(DVec2::ZERO, DVec2::ONE));
    let (region, pixels) = map_frame(bounds);
    let root = SVGBackend::new(path, pixels).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption("force network (width and colour ∝ |F|)", ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(region.min.x..region.max.x, region.min.y..region.max.y)?;
    chart.configure_mesh().disable_mesh().x_desc("x / m").y_desc("y / m").draw()?;
    chart.draw_series(snapshot.particles.iter().map(|p| {
        let mut outline: Vec<(f64, f64)> = p.vertices.iter().map(|v| (v.x, v.y)).collect();
        if let Some(&first) = outline.first() {
            outline.push(first);
        }
        PathElement::new(outline, BLACK.mix(0.25))
    }))?;
    let largest = snapshot.contacts.iter().map(|c| c.force_on_a.length()).filter(|f| f.is_finite()).fold(0.0, f64::max);
    if largest > 0.0 {
        let mut lines = Vec::new();
        for contact in &snapshot.contacts {
            let relative = contact.force_on_a.length() / largest;
            if !relative.is_finite() || !contact.point.is_finite() {
                continue;
            }
            let color = if relative > 0.66 {
                RGBColor(230, 200, 0)
            } else if relative > 0.33 {
                RED
            } else {
                BLACK
            };
            let width = (1.0 + 4.0 * relative).round() as u32;
            for side in [contact.a, contact.b] {
                if let BodyRef::Particle(i) = side
                    && let Some(p) = snapshot.particles.get(i)
                {
                    lines.push(PathElement::new(
                        vec![(p.centroid.x, p.centroid.y), (contact.point.x, contact.point.y)],
                        color.stroke_width(width),
                    ));
                }
            }
        }
        chart.draw_series(lines)?;
    }
    root.present()?;
    Ok(())
}

/// One annular cell of a [`polar_cell_map`]: inner and outer radius (m), first and last angle (rad CCW from +x) and
/// its value.
pub type PolarCell = ([f64; 2], [f64; 2], f64);

/// A map of annular cells about `centre` coloured by value over the finite values' range (caption states it; cells
/// without a value stay white), inside a circle of `radius` (a mill's sector maps).
pub fn polar_cell_map(
    path: &Path,
    title: &str,
    centre: DVec2,
    radius: f64,
    cells: &[PolarCell],
) -> Result<(), AnalysisError> {
    draw_polar_cell_map(path, title, centre, radius, cells).map_err(|e| figure_error(path, e))
}

fn draw_polar_cell_map(path: &Path, title: &str, centre: DVec2, radius: f64, cells: &[PolarCell]) -> DrawResult {
    let (lo, hi) = cells
        .iter()
        .map(|c| c.2)
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
    let root = SVGBackend::new(path, (720, 760)).into_drawing_area();
    root.fill(&WHITE)?;
    let caption = if lo <= hi { format!("{title} ({lo:.3e} … {hi:.3e})") } else { format!("{title} (no data)") };
    let r = 1.05 * radius;
    let mut chart = ChartBuilder::on(&root)
        .caption(caption, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(centre.x - r..centre.x + r, centre.y - r..centre.y + r)?;
    chart.configure_mesh().disable_mesh().x_desc("x / m").y_desc("y / m").draw()?;
    let point = |r: f64, a: f64| (centre.x + r * a.cos(), centre.y + r * a.sin());
    let arc = |r: f64, [a0, a1]: [f64; 2]| (0..=8).map(move |k| point(r, a0 + (a1 - a0) * k as f64 / 8.0));
    chart.draw_series(cells.iter().filter(|c| c.2.is_finite()).map(|&(radii, angles, value)| {
        let t = if hi > lo { (value - lo) / (hi - lo) } else { 0.5 };
        let outline: Vec<(f64, f64)> = arc(radii[1], angles).chain(arc(radii[0], [angles[1], angles[0]])).collect();
        Polygon::new(outline, color_scale(t).filled())
    }))?;
    let rim = (0..=144).map(|k| point(radius, std::f64::consts::TAU * k as f64 / 144.0));
    chart.draw_series(LineSeries::new(rim, BLACK))?;
    root.present()?;
    Ok(())
}
