//! SVG figures (plotters, SVG backend only): line charts, bar charts, a polar plot, cell maps with principal-axis
//! segments, and the force network drawn as in §5.5 (one line from each centre of mass to the force point, width and
//! colour growing with |F|: black, red, yellow).

use crate::error::AnalysisError;
use crate::geometry::Rect;
use crate::snapshot::{BodyRef, Snapshot};
use gc2d_geometry::DVec2;
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::data::float::FloatPrettyPrinter;
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

/// Pixels of the margin around every figure.
const MARGIN: u32 = 12;
/// Height of the x-axis label area and width of the y-axis label area of line and bar charts, pixels.
const CHART_LABEL_AREAS: (u32, u32) = (45, 75);
/// Height of the x-axis label area and width of the y-axis label area of maps and polar plots, pixels.
const MAP_LABEL_AREAS: (u32, u32) = (40, 60);
/// Width of a line chart, pixels.
const CHART_WIDTH: u32 = 800;
/// Pixels taken above the plotting area by a 22-pixel caption (an estimate: the scales of an equal-scale chart are
/// made equal from the plotting area's actual size, this only sizes the canvas).
const CAPTION_HEIGHT: u32 = 32;
/// Height/width of the plotting area of an equal-scale line chart is kept in this range by widening the shorter
/// data range, so that a flat pile still gets a readable figure drawn to scale.
const EQUAL_SCALE_ASPECT: (f64, f64) = (0.45, 1.2);

/// How the axes of a line chart are scaled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Scales {
    /// Each axis spans its data.
    Free,
    /// One unit is as long on both axes (slopes are drawn at their true angle).
    Equal,
}

/// The chart type of every figure here: f64 on both axes, drawn to SVG.
type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// A tick label as plotters writes it, but scientific where the plain form would read 0, and never "-0": a value
/// within 10⁻⁹ of the axis `span` of zero (rounding in the tick positions) is written as 0.
fn tick_label(value: f64, span: f64) -> String {
    let value = if value.abs() <= 1e-9 * span.abs() { 0.0 } else { value + 0.0 };
    let text = FloatPrettyPrinter { allow_scientific: true, min_decimal: 1, max_decimal: 5 }.print(value);
    match text.strip_prefix('-') {
        Some(rest) if rest.chars().filter(char::is_ascii_digit).all(|c| c == '0') => rest.to_string(),
        _ => text,
    }
}

/// Draws the axes of `chart`, titled `x` and `y`, with [`tick_label`]s, and the grid when `grid`.
fn draw_axes(chart: &mut Chart, x: &str, y: &str, grid: bool) -> DrawResult {
    let (x_range, y_range) = (chart.x_range(), chart.y_range());
    let x_label = move |v: &f64| tick_label(*v, x_range.end - x_range.start);
    let y_label = move |v: &f64| tick_label(*v, y_range.end - y_range.start);
    let mut mesh = chart.configure_mesh();
    mesh.x_desc(x).y_desc(y).x_label_formatter(&x_label).y_label_formatter(&y_label);
    if !grid {
        mesh.disable_mesh();
    }
    mesh.draw()?;
    Ok(())
}

/// The area of `root` inside the margin and below the caption `title` (which it draws).
fn titled_area<'b>(
    root: &DrawingArea<SVGBackend<'b>, Shift>,
    title: &str,
    font_size: u32,
) -> Result<DrawingArea<SVGBackend<'b>, Shift>, Box<dyn Error>> {
    Ok(root.margin(MARGIN, MARGIN, MARGIN, MARGIN).titled(title, ("sans-serif", font_size))?)
}

/// The pixel size of the plotting area that a chart on `area` with label areas (x-label height, y-label width) gets.
fn plotting_pixels(area: &DrawingArea<SVGBackend, Shift>, (x_labels, y_labels): (u32, u32)) -> (u32, u32) {
    let (w, h) = area.dim_in_pixel();
    (w.saturating_sub(y_labels), h.saturating_sub(x_labels))
}

/// `x` and `y` widened about their centres so that one unit is as many pixels on both axes of a plotting area of
/// `pixels` (width, height); plotters maps a range onto the pixels less one.
fn equal_scale(x: (f64, f64), y: (f64, f64), pixels: (u32, u32)) -> ((f64, f64), (f64, f64)) {
    let (w, h) = (pixels.0.max(2) as f64 - 1.0, pixels.1.max(2) as f64 - 1.0);
    let per_pixel = ((x.1 - x.0) / w).max((y.1 - y.0) / h);
    let widen = |(lo, hi): (f64, f64), n: f64| {
        let centre = 0.5 * (lo + hi);
        (centre - 0.5 * per_pixel * n, centre + 0.5 * per_pixel * n)
    };
    (widen(x, w), widen(y, h))
}

/// Canvas size of a line chart: fixed for free scales; for equal scales as tall as the data's aspect ratio
/// (clamped to [`EQUAL_SCALE_ASPECT`]) asks.
fn line_chart_size(scales: Scales, x: (f64, f64), y: (f64, f64)) -> (u32, u32) {
    if scales == Scales::Free {
        return (CHART_WIDTH, 560);
    }
    let aspect = ((y.1 - y.0) / (x.1 - x.0)).clamp(EQUAL_SCALE_ASPECT.0, EQUAL_SCALE_ASPECT.1);
    let aspect = if aspect.is_finite() { aspect } else { 1.0 };
    let plot_width = (CHART_WIDTH - 2 * MARGIN - CHART_LABEL_AREAS.1) as f64;
    let height = (plot_width * aspect).round() as u32 + CAPTION_HEIGHT + 2 * MARGIN + CHART_LABEL_AREAS.0;
    (CHART_WIDTH, height)
}

/// Line chart of several series with a legend, each axis spanning its data.
pub fn line_chart(path: &Path, labels: Labels, series: &[Series]) -> Result<(), AnalysisError> {
    draw_line_chart(path, labels, series, Scales::Free).map_err(|e| figure_error(path, e))
}

/// Line chart of several series with a legend, drawn with equal scales on both axes so that slopes appear at their
/// true angle (a pile's surface); the shorter data range is widened to fill the plotting area.
pub fn line_chart_equal_aspect(path: &Path, labels: Labels, series: &[Series]) -> Result<(), AnalysisError> {
    draw_line_chart(path, labels, series, Scales::Equal).map_err(|e| figure_error(path, e))
}

fn draw_line_chart(path: &Path, labels: Labels, series: &[Series], scales: Scales) -> DrawResult {
    let all = || series.iter().flat_map(|s| s.points.iter().copied()).filter(|(x, y)| x.is_finite() && y.is_finite());
    let (mut x, mut y) = (padded_range(all().map(|p| p.0)), padded_range(all().map(|p| p.1)));
    let root = SVGBackend::new(path, line_chart_size(scales, x, y)).into_drawing_area();
    root.fill(&WHITE)?;
    let area = titled_area(&root, labels.title, 22)?;
    if scales == Scales::Equal {
        (x, y) = equal_scale(x, y, plotting_pixels(&area, CHART_LABEL_AREAS));
    }
    let mut chart = ChartBuilder::on(&area)
        .x_label_area_size(CHART_LABEL_AREAS.0)
        .y_label_area_size(CHART_LABEL_AREAS.1)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)?;
    draw_axes(&mut chart, labels.x, labels.y, true)?;
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
    let bars: Vec<_> = bars.iter().filter(|b| b.0.is_finite() && b.1.is_finite() && b.2.is_finite()).collect();
    let (x0, x1) = padded_range(bars.iter().flat_map(|b| [b.0, b.1]));
    let tallest = bars.iter().map(|b| b.2).fold(0.0, f64::max);
    let y1 = if tallest > 0.0 { 1.05 * tallest } else { 1.0 };
    let root = SVGBackend::new(path, (CHART_WIDTH, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    let area = titled_area(&root, labels.title, 22)?;
    let mut chart = ChartBuilder::on(&area)
        .x_label_area_size(CHART_LABEL_AREAS.0)
        .y_label_area_size(CHART_LABEL_AREAS.1)
        .build_cartesian_2d(x0..x1, 0.0..y1)?;
    draw_axes(&mut chart, labels.x, labels.y, true)?;
    chart.draw_series(bars.iter().map(|&&(l, r, h)| Rectangle::new([(l, 0.0), (r, h)], BLUE.mix(0.6).filled())))?;
    root.present()?;
    Ok(())
}

/// Polar plot of a distribution over directions (P(α), §5.3): radius = value at each angle, closed curve.
pub fn polar_chart(path: &Path, title: &str, angles_degrees: &[f64], values: &[f64]) -> Result<(), AnalysisError> {
    draw_polar_chart(path, title, angles_degrees, values).map_err(|e| figure_error(path, e))
}

fn draw_polar_chart(path: &Path, title: &str, angles_degrees: &[f64], values: &[f64]) -> DrawResult {
    let largest = values.iter().copied().filter(|v| v.is_finite()).fold(0.0f64, f64::max);
    let radius = if largest > 0.0 { 1.1 * largest } else { 1.1 };
    let root = SVGBackend::new(path, (640, 640)).into_drawing_area();
    root.fill(&WHITE)?;
    let area = titled_area(&root, title, 22)?;
    let (x, y) = equal_scale((-radius, radius), (-radius, radius), plotting_pixels(&area, MAP_LABEL_AREAS));
    let mut chart = ChartBuilder::on(&area)
        .x_label_area_size(MAP_LABEL_AREAS.0)
        .y_label_area_size(MAP_LABEL_AREAS.1)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)?;
    draw_axes(&mut chart, "P cos α", "P sin α", false)?;
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
/// becomes a unit square), and a pixel size whose plotting area has about that aspect ratio ([`equal_scale`] then
/// widens the region to make the scales exactly equal).
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

/// Width of the colour bar beside a map (strip, ticks and label), pixels.
const COLOUR_BAR_WIDTH: u32 = 130;
/// Width of the colour bar's strip, pixels.
const COLOUR_STRIP_WIDTH: u32 = 20;
/// Font size of the colour bar's text (that of the maps' tick labels; plotters' default would scale with the
/// narrow bar).
const COLOUR_BAR_FONT: u32 = 12;
/// Bands the colour bar's strip is drawn with.
const COLOUR_BAR_BANDS: usize = 64;

/// What a map's colours show: the colour bar's title and the unit written after values ("" when dimensionless).
#[derive(Debug, Clone, Copy)]
pub struct ColourQuantity<'a> {
    /// Title of the colour bar, with the unit, e.g. "σ_zz / (N/m)"; "" for none.
    pub label: &'a str,
    /// Unit of the values, e.g. "N/m"; "" when dimensionless.
    pub unit: &'a str,
}

/// The finite values of a map, as its colours show them.
#[derive(Debug, Clone, Copy, PartialEq)]
enum ValueRange {
    /// No finite value.
    Empty,
    /// All values equal: one colour.
    Uniform(f64),
    /// Lowest and highest value, lowest < highest: the whole colour scale.
    Span(f64, f64),
}

impl ValueRange {
    /// The range of the finite `values`.
    fn of(values: impl Iterator<Item = f64>) -> Self {
        let (lo, hi) =
            values.filter(|v| v.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)));
        if lo > hi {
            ValueRange::Empty
        } else if lo == hi {
            ValueRange::Uniform(lo)
        } else {
            ValueRange::Span(lo, hi)
        }
    }

    /// The colour of `value`: its place on the scale, the middle colour when uniform.
    fn colour(self, value: f64) -> RGBColor {
        match self {
            ValueRange::Span(lo, hi) => color_scale((value - lo) / (hi - lo)),
            _ => color_scale(0.5),
        }
    }

    /// The caption of a map titled `title`: the range with its unit, how large the spread is against the values
    /// when they have one sign, "uniform" for a single value.
    fn caption(self, title: &str, unit: &str) -> String {
        let with_unit = |v: f64| if unit.is_empty() { value_text(v) } else { format!("{} {unit}", value_text(v)) };
        match self {
            ValueRange::Empty => format!("{title} (no data)"),
            ValueRange::Uniform(v) => format!("{title}: uniform {}", with_unit(v)),
            ValueRange::Span(lo, hi) if lo > 0.0 || hi < 0.0 => {
                let spread = 100.0 * (hi - lo) / lo.abs().max(hi.abs());
                format!("{title}: {} … {} (spread {spread:.1} %)", value_text(lo), with_unit(hi))
            }
            ValueRange::Span(lo, hi) => format!("{title}: {} … {}", value_text(lo), with_unit(hi)),
        }
    }
}

/// `value` with 4 significant digits, plainly between 0.01 and 10⁴, else in scientific notation; never "-0".
fn value_text(value: f64) -> String {
    let value = value + 0.0;
    let magnitude = value.abs();
    if value == 0.0 {
        "0".to_string()
    } else if (1e-2..1e4).contains(&magnitude) {
        let decimals = (3 - magnitude.log10().floor() as i32).max(0) as usize;
        format!("{value:.decimals$}")
    } else {
        format!("{value:.3e}")
    }
}

/// Draws the colour bar of `range` on `area`: a vertical strip with ticks in the values' unit and `quantity`'s
/// label, or one swatch saying "uniform" and the value; nothing without data. `bottom` pixels are left free below
/// it (the map's x-axis labels).
fn draw_colour_bar(
    area: &DrawingArea<SVGBackend, Shift>,
    range: ValueRange,
    quantity: ColourQuantity,
    bottom: u32,
) -> DrawResult {
    match range {
        ValueRange::Empty => Ok(()),
        ValueRange::Uniform(value) => draw_uniform_swatch(area, value, quantity, bottom),
        ValueRange::Span(lo, hi) => draw_colour_strip(area, (lo, hi), quantity, bottom),
    }
}

fn draw_colour_strip(
    area: &DrawingArea<SVGBackend, Shift>,
    (lo, hi): (f64, f64),
    quantity: ColourQuantity,
    bottom: u32,
) -> DrawResult {
    let (width, _) = area.dim_in_pixel();
    let mut chart = ChartBuilder::on(area)
        .margin_left(MARGIN)
        .x_label_area_size(bottom)
        .right_y_label_area_size(width.saturating_sub(MARGIN + COLOUR_STRIP_WIDTH))
        .build_cartesian_2d(0.0..1.0, lo..hi)?;
    let y_label = move |v: &f64| tick_label(*v, hi - lo);
    chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .x_labels(0)
        .set_all_tick_mark_size(5)
        .label_style(("sans-serif", COLOUR_BAR_FONT))
        .axis_desc_style(("sans-serif", COLOUR_BAR_FONT))
        .y_desc(quantity.label)
        .y_label_formatter(&y_label)
        .draw()?;
    let band = (hi - lo) / COLOUR_BAR_BANDS as f64;
    chart.draw_series((0..COLOUR_BAR_BANDS).map(|k| {
        let y0 = lo + k as f64 * band;
        let colour = color_scale((k as f64 + 0.5) / COLOUR_BAR_BANDS as f64);
        Rectangle::new([(0.0, y0), (1.0, y0 + band)], colour.filled())
    }))?;
    Ok(())
}

fn draw_uniform_swatch(
    area: &DrawingArea<SVGBackend, Shift>,
    value: f64,
    quantity: ColourQuantity,
    bottom: u32,
) -> DrawResult {
    let (_, height) = area.dim_in_pixel();
    let (left, top, low) = (MARGIN as i32, 0, height.saturating_sub(bottom) as i32);
    let right = left + COLOUR_STRIP_WIDTH as i32;
    area.draw(&Rectangle::new([(left, top), (right, low)], color_scale(0.5).filled()))?;
    let font = ("sans-serif", COLOUR_BAR_FONT).into_font();
    let middle = (top + low) / 2;
    area.draw(&Text::new("uniform", (right + 6, middle - 18), font.clone()))?;
    area.draw(&Text::new(value_text(value), (right + 6, middle), font.clone()))?;
    area.draw(&Text::new(quantity.unit.to_string(), (right + 6, middle + 18), font))?;
    Ok(())
}

/// A map of cells coloured by value over the finite values' range, with a colour bar at the right in the unit of
/// `quantity` (the caption states the range and, for values of one sign, the spread in %; one value is "uniform"),
/// drawn with equal scales on both axes, and optional line segments on top (e.g. major principal axes).
pub fn cell_map(
    path: &Path,
    title: &str,
    quantity: ColourQuantity,
    cells: &[(Rect, f64)],
    segments: &[(DVec2, DVec2)],
) -> Result<(), AnalysisError> {
    draw_cell_map(path, title, quantity, cells, segments).map_err(|e| figure_error(path, e))
}

fn draw_cell_map(
    path: &Path,
    title: &str,
    quantity: ColourQuantity,
    cells: &[(Rect, f64)],
    segments: &[(DVec2, DVec2)],
) -> DrawResult {
    let cells: Vec<&(Rect, f64)> = cells.iter().filter(|(r, v)| v.is_finite() && r.min.is_finite()).collect();
    let range = ValueRange::of(cells.iter().map(|c| c.1));
    let bounds =
        Rect::bounding(cells.iter().flat_map(|(r, _)| [r.min, r.max])).unwrap_or(Rect::new(DVec2::ZERO, DVec2::ONE));
    let (region, (width, height)) = map_frame(bounds);
    let root = SVGBackend::new(path, (width + COLOUR_BAR_WIDTH, height)).into_drawing_area();
    root.fill(&WHITE)?;
    let area = titled_area(&root, &range.caption(title, quantity.unit), 20)?;
    let (map, bar) = area.split_horizontally(area.dim_in_pixel().0.saturating_sub(COLOUR_BAR_WIDTH));
    let mut chart = equal_scale_map(&map, region)?;
    draw_axes(&mut chart, "x / m", "y / m", false)?;
    chart.draw_series(
        cells.iter().map(|(r, v)| Rectangle::new([(r.min.x, r.min.y), (r.max.x, r.max.y)], range.colour(*v).filled())),
    )?;
    chart.draw_series(
        segments
            .iter()
            .filter(|(a, b)| a.is_finite() && b.is_finite())
            .map(|(a, b)| PathElement::new(vec![(a.x, a.y), (b.x, b.y)], RED.stroke_width(2))),
    )?;
    draw_colour_bar(&bar, range, quantity, MAP_LABEL_AREAS.0)?;
    root.present()?;
    Ok(())
}

/// A chart on `area` showing at least `region`, with equal scales on both axes.
fn equal_scale_map<'a, 'b>(
    area: &'a DrawingArea<SVGBackend<'b>, Shift>,
    region: Rect,
) -> Result<Chart<'a, 'b>, Box<dyn Error>> {
    let (x, y) =
        equal_scale((region.min.x, region.max.x), (region.min.y, region.max.y), plotting_pixels(area, MAP_LABEL_AREAS));
    Ok(ChartBuilder::on(area)
        .x_label_area_size(MAP_LABEL_AREAS.0)
        .y_label_area_size(MAP_LABEL_AREAS.1)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)?)
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
    let area = titled_area(&root, "force network (width and colour ∝ |F|)", 20)?;
    let mut chart = equal_scale_map(&area, region)?;
    draw_axes(&mut chart, "x / m", "y / m", false)?;
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

/// A map of annular cells about `centre` coloured by value over the finite values' range (caption states it, a
/// unit-less colour bar at the right shows it, as the title names the quantity; cells without a value stay white),
/// inside a circle of `radius` (a mill's sector maps), with equal scales on both axes.
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
    let range = ValueRange::of(cells.iter().map(|c| c.2));
    let root = SVGBackend::new(path, (720 + COLOUR_BAR_WIDTH, 760)).into_drawing_area();
    root.fill(&WHITE)?;
    let area = titled_area(&root, &range.caption(title, ""), 20)?;
    let (map, bar) = area.split_horizontally(area.dim_in_pixel().0.saturating_sub(COLOUR_BAR_WIDTH));
    let r = if radius > 0.0 && radius.is_finite() { 1.05 * radius } else { 1.0 };
    let region = Rect::centered(centre, DVec2::splat(2.0 * r));
    let mut chart = equal_scale_map(&map, region)?;
    draw_axes(&mut chart, "x / m", "y / m", false)?;
    let point = |r: f64, a: f64| (centre.x + r * a.cos(), centre.y + r * a.sin());
    let arc = |r: f64, [a0, a1]: [f64; 2]| (0..=8).map(move |k| point(r, a0 + (a1 - a0) * k as f64 / 8.0));
    chart.draw_series(cells.iter().filter(|c| c.2.is_finite()).map(|&(radii, angles, value)| {
        let outline: Vec<(f64, f64)> = arc(radii[1], angles).chain(arc(radii[0], [angles[1], angles[0]])).collect();
        Polygon::new(outline, range.colour(value).filled())
    }))?;
    let rim = (0..=144).map(|k| point(radius, std::f64::consts::TAU * k as f64 / 144.0));
    chart.draw_series(LineSeries::new(rim, BLACK))?;
    draw_colour_bar(&bar, range, ColourQuantity { label: "", unit: "" }, MAP_LABEL_AREAS.0)?;
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_never_read_negative_zero() {
        assert_eq!(tick_label(-0.0, 1.0), "0");
        // plotters puts the zero tick of -0.045 … 0.0023 at -6.9e-18, which its own formatter writes "-0.0".
        assert_eq!(tick_label(-6.938893903907228e-18, 0.047), "0");
        assert_eq!(tick_label(-0.01, 0.047), "-0.01");
        assert_eq!(tick_label(0.25, 1.0), "0.25");
    }

    #[test]
    fn tick_labels_of_tiny_values_are_scientific_rather_than_zero() {
        assert_eq!(tick_label(2e-7, 1e-6), "2.0e-7");
    }

    #[test]
    fn values_are_written_with_four_significant_digits() {
        assert_eq!(value_text(479.5), "479.5");
        assert_eq!(value_text(1680.0), "1680");
        assert_eq!(value_text(0.81234), "0.8123");
        assert_eq!(value_text(12345.0), "1.234e4");
        assert_eq!(value_text(-0.0), "0");
    }

    #[test]
    fn equal_scale_widens_the_shorter_range_to_the_plotting_area() {
        // 100 × 50 pixel steps: 0.01 per pixel on both axes, so y spans 0.5 about its centre 0.05.
        let (x, y) = equal_scale((0.0, 1.0), (0.0, 0.1), (101, 51));
        assert_eq!(x, (0.0, 1.0));
        assert!((y.0 + 0.2).abs() < 1e-12 && (y.1 - 0.3).abs() < 1e-12, "{y:?}");
    }

    #[test]
    fn a_caption_states_the_range_with_its_unit_and_the_spread() {
        assert_eq!(ValueRange::Span(479.5, 494.2).caption("σ", "N/m"), "σ: 479.5 … 494.2 N/m (spread 3.0 %)");
        assert_eq!(ValueRange::Span(-1.0, 3.0).caption("σ", "N/m"), "σ: -1.000 … 3.000 N/m");
        assert_eq!(ValueRange::Uniform(0.5).caption("ρ", ""), "ρ: uniform 0.5000");
        assert_eq!(ValueRange::Empty.caption("ρ", ""), "ρ (no data)");
    }
}
