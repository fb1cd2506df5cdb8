//! The analyses of a pile (Ch. 4, reference §8.3): floor pressure profile in the scaled form, angle of repose of
//! both flanks, height and width, density and stress maps.

use crate::density::{Grid, LocalDensity, bulk_packing_fraction, density_grid};
use crate::error::AnalysisError;
use crate::figures::{self, ColourQuantity, Labels, Mark, SERIES_COLOURS, Series};
use crate::geometry::Rect;
use crate::output::OutputDir;
use crate::pressure::{Facing, ProfileOptions, WallForce, WallSelection, pressure_profile, wall_forces};
use crate::repose::{FlankFit, FlankOptions, angle_of_repose};
use crate::run::{AnalyzeOptions, CONTACTS_PER_WINDOW, PARTICLES_PER_TEST_AREA};
use crate::snapshot::Snapshot;
use crate::stress::{LocalStress, StressOptions, stress_grid};
use gc2d_geometry::DVec2;
use plotters::style::{BLACK, BLUE, RED, RGBColor};
use serde::Serialize;
use std::path::Path;

/// Samples of the moving average drawn beside the raw pressure profile.
pub const MOVING_AVERAGE_SAMPLES: usize = 5;

/// The floor pressure under a pile.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FloorPressureReport {
    /// Window half-width b, m.
    pub half_width: f64,
    /// Floor contacts.
    pub forces: usize,
    /// Σ n·F on the floor, N.
    pub total_normal_force: f64,
    /// Weight of the pile Σ m g, N (equals the total at rest).
    pub weight: f64,
    /// The scale ρ g h of the pressures, N/m.
    pub rho_g_h: f64,
    /// Largest smoothed pressure / ρgh.
    pub peak_scaled: f64,
    /// Smoothed pressure under the apex / ρgh.
    pub apex_scaled: f64,
    /// Smoothed pressure under the apex over the largest one: below 1 when there is a dip.
    pub apex_to_peak: f64,
}

/// The numbers of a pile analysis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PileReport {
    /// Particles in the pile (the largest contact-connected group).
    pub particles: usize,
    /// Particles left out (in flight or bounced away).
    pub left_out: usize,
    /// Floor level (lowest particle vertex), m.
    pub floor_level: f64,
    /// Pile height above the floor level, m.
    pub height: f64,
    /// Pile width at the floor, m.
    pub width: f64,
    /// x of the apex, m.
    pub apex_x: f64,
    /// x-bin width of the fit method, m.
    pub bin_width: f64,
    /// Fit method, left flank, degrees.
    pub left_degrees: Option<f64>,
    /// Fit method, right flank, degrees.
    pub right_degrees: Option<f64>,
    /// Mean of both flanks, degrees.
    pub mean_degrees: Option<f64>,
    /// RMS distance of the left surface points from the fitted line, m.
    pub left_rms_residual: Option<f64>,
    /// RMS distance of the right surface points from the fitted line, m.
    pub right_rms_residual: Option<f64>,
    /// Area method (2.42), left flank, degrees.
    pub area_left_degrees: Option<f64>,
    /// Area method (2.42), right flank, degrees.
    pub area_right_degrees: Option<f64>,
    /// Area method, whole pile (tan φ = 4a/b²), degrees.
    pub area_whole_degrees: Option<f64>,
    /// Floor pressure, when the pile stands on a floor.
    pub floor: Option<FloorPressureReport>,
    /// Side of the square test areas used, m: the side asked for (or chosen) rounded so that a whole number of
    /// columns spans the region's width, or larger where [`Self::grid_capped`].
    pub grid_cell: f64,
    /// Columns and rows of the test areas, at most [`crate::density::MAX_GRID_CELLS_PER_AXIS`] each; the top row
    /// reaches past the region's top.
    pub grid_size: [usize; 2],
    /// True when the side asked for would have given more than [`crate::density::MAX_GRID_CELLS_PER_AXIS`] areas
    /// along an axis, so the areas are larger than asked.
    pub grid_capped: bool,
    /// Test areas with particles (density map).
    pub density_cells: usize,
    /// Test areas with a stress (stress map).
    pub stress_cells: usize,
}

/// Runs the pile analyses on `pile` (the largest contact-connected group of a snapshot of `all_particles`
/// particles, see [`Snapshot::largest_cluster`]) and writes their tables and figures.
pub fn analyze_pile(
    pile: &Snapshot,
    all_particles: usize,
    options: &AnalyzeOptions,
    out: &mut OutputDir,
) -> Result<PileReport, AnalysisError> {
    let repose = angle_of_repose(pile, &FlankOptions::default())
        .ok_or_else(|| AnalysisError::NotEnoughData("the pile has no particle with a usable size".into()))?;
    let shape = repose.shape;
    let mean_diameter = pile.mean_particle_diameter();
    let packing = bulk_packing_fraction(pile);
    let rho_g_h = packing * pile.particle_area_density() * pile.gravity * shape.height;

    let surface: Vec<(f64, f64)> = repose.surface.iter().map(|p| (p.x, p.y)).collect();
    out.write_csv("surface.csv", &["x", "y_top"], &surface.iter().map(|&(x, y)| vec![x, y]).collect::<Vec<_>>())?;
    let mut flank_rows = Vec::new();
    for (side, fit) in [(0.0, &repose.left), (1.0, &repose.right)] {
        if let Some(fit) = fit {
            flank_rows.extend(fit.points.iter().map(|p| vec![side, p.x, p.y, fit.intercept + fit.slope * p.x]));
        }
    }
    out.write_csv("flank_points.csv", &["flank_right", "x", "y_centroid", "y_fit"], &flank_rows)?;
    let flank_points: Vec<(f64, f64)> = flank_rows.iter().map(|r| (r[1], r[2])).collect();
    let surface_figure = SurfaceFigure { surface: &surface, flank_points: &flank_points };
    surface_figure.draw(&out.file("surface.svg"), repose.left.as_ref(), repose.right.as_ref())?;

    let floor_forces = wall_forces(pile, WallSelection::facing(Facing::Up));
    let floor = floor_pressure(&floor_forces, options, mean_diameter, pile, shape, rho_g_h, out)?;

    let cell = options.grid_cell.unwrap_or_else(|| auto_cell(pile, packing));
    let region = Rect::bounding(pile.particles.iter().flat_map(|p| p.vertices.iter().copied()))
        .ok_or_else(|| AnalysisError::NotEnoughData("pile particles have no finite vertices".into()))?;
    let grid = Grid::with_cell_size(region, cell);
    let densities = density_grid(pile, &grid);
    write_density(&densities, out)?;
    let stresses = stress_grid(pile, &grid, &StressOptions::default());
    write_stress(&stresses, out)?;

    Ok(PileReport {
        particles: pile.particles.len(),
        left_out: all_particles.saturating_sub(pile.particles.len()),
        floor_level: shape.floor,
        height: shape.height,
        width: shape.width,
        apex_x: shape.apex_x,
        bin_width: repose.bin_width,
        left_degrees: repose.left.as_ref().map(|f| f.angle_degrees),
        right_degrees: repose.right.as_ref().map(|f| f.angle_degrees),
        mean_degrees: repose.mean_degrees,
        left_rms_residual: repose.left.as_ref().map(|f| f.rms_residual),
        right_rms_residual: repose.right.as_ref().map(|f| f.rms_residual),
        area_left_degrees: repose.area_left_degrees,
        area_right_degrees: repose.area_right_degrees,
        area_whole_degrees: repose.area_whole_degrees,
        floor,
        grid_cell: grid.side,
        grid_size: [grid.nx, grid.ny],
        grid_capped: grid.capped,
        density_cells: densities.iter().filter(|d| d.particles > 0).count(),
        stress_cells: stresses.len(),
    })
}

/// b from the §5.2 rule of thumb: [`CONTACTS_PER_WINDOW`] forces per window of width 2b over the span of the
/// forces, and at least half a mean particle diameter.
pub fn auto_half_width(forces: &[WallForce], mean_diameter: f64) -> f64 {
    let lo = forces.iter().map(|f| f.along).fold(f64::INFINITY, f64::min);
    let hi = forces.iter().map(|f| f.along).fold(f64::NEG_INFINITY, f64::max);
    let minimum = 0.5 * mean_diameter;
    if forces.len() < 2 || hi.is_nan() || lo.is_nan() || hi <= lo {
        return mean_diameter.max(f64::MIN_POSITIVE);
    }
    (0.5 * CONTACTS_PER_WINDOW * (hi - lo) / forces.len() as f64).max(minimum)
}

/// Side of a square test area holding about [`PARTICLES_PER_TEST_AREA`] particles at packing fraction `packing`.
pub fn auto_cell(snapshot: &Snapshot, packing: f64) -> f64 {
    let count = snapshot.particles.len().max(1) as f64;
    let mean_area = snapshot.total_particle_area() / count;
    let side = (PARTICLES_PER_TEST_AREA * mean_area / packing.max(0.1)).sqrt();
    if side > 0.0 && side.is_finite() { side } else { 1.0 }
}

/// Colours of the left and the right flank fit in `surface.svg`: distinct from each other, from the envelope (black)
/// and from the fitted points ([`SERIES_COLOURS`]`[0]`).
pub const FLANK_FIT_COLOURS: [RGBColor; 2] = [SERIES_COLOURS[1], SERIES_COLOURS[4]];

/// The data of `surface.svg`: the surface envelope and the points the flanks were fitted to, m.
#[derive(Debug, Clone, Copy)]
pub struct SurfaceFigure<'a> {
    /// Highest point per x bin of the pile (drawn as a black line).
    pub surface: &'a [(f64, f64)],
    /// Highest centroid per bin of both flanks (drawn as dots).
    pub flank_points: &'a [(f64, f64)],
}

impl SurfaceFigure<'_> {
    /// Draws the figure to `path` with the fitted lines of both flanks in [`FLANK_FIT_COLOURS`], with equal scales on
    /// both axes so that the flanks appear at their fitted angles.
    pub fn draw(&self, path: &Path, left: Option<&FlankFit>, right: Option<&FlankFit>) -> Result<(), AnalysisError> {
        let fits: Vec<FitLine> = [("left", left), ("right", right)]
            .into_iter()
            .zip(FLANK_FIT_COLOURS)
            .filter_map(|((name, fit), colour)| {
                let label = format!("{name} flank fit, {:.1}°", fit?.angle_degrees);
                Some(FitLine { label, points: fit_line_points(fit?), colour })
            })
            .collect();
        let mut series = vec![
            Series { label: "surface envelope", points: self.surface, color: BLACK, mark: Mark::Line },
            Series {
                label: "highest centroid per bin (fitted)",
                points: self.flank_points,
                color: SERIES_COLOURS[0],
                mark: Mark::Dots,
            },
        ];
        series.extend(fits.iter().map(|f| Series {
            label: &f.label,
            points: &f.points,
            color: f.colour,
            mark: Mark::Line,
        }));
        let labels =
            Labels { title: "pile surface and flank fits (x and y to the same scale)", x: "x / m", y: "y / m" };
        figures::line_chart_equal_aspect(path, labels, &series)
    }
}

/// The fitted line of one flank as drawn in `surface.svg`.
struct FitLine {
    /// Legend text: the flank and its angle.
    label: String,
    /// Ends of the line over the fitted points' x range, m.
    points: Vec<(f64, f64)>,
    /// One of [`FLANK_FIT_COLOURS`].
    colour: RGBColor,
}

fn fit_line_points(fit: &FlankFit) -> Vec<(f64, f64)> {
    let (lo, hi) = fit.points.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| (l.min(p.x), h.max(p.x)));
    [lo, hi].iter().map(|&x| (x, fit.intercept + fit.slope * x)).collect()
}

fn floor_pressure(
    forces: &[WallForce],
    options: &AnalyzeOptions,
    mean_diameter: f64,
    pile: &Snapshot,
    shape: crate::repose::PileShape,
    rho_g_h: f64,
    out: &mut OutputDir,
) -> Result<Option<FloorPressureReport>, AnalysisError> {
    if forces.is_empty() {
        return Ok(None);
    }
    let half_width = options.window_half_width.unwrap_or_else(|| auto_half_width(forces, mean_diameter));
    let profile_options =
        ProfileOptions { half_width, step: 0.25 * half_width, moving_average: MOVING_AVERAGE_SAMPLES };
    let profile = pressure_profile(forces, &profile_options, None);
    let scaled = profile.scaled(shape.left, shape.width, rho_g_h);
    let rows: Vec<Vec<f64>> = (0..profile.positions.len())
        .map(|k| {
            let (xs, ps, ms) = scaled.get(k).copied().unwrap_or((f64::NAN, f64::NAN, f64::NAN));
            vec![profile.positions[k], profile.pressure[k], profile.smoothed[k], xs, ps, ms]
        })
        .collect();
    out.write_csv(
        "floor_pressure.csv",
        &["x", "pressure", "pressure_smoothed", "x_scaled", "pressure_scaled", "pressure_smoothed_scaled"],
        &rows,
    )?;
    type Curve = Vec<(f64, f64)>;
    let (raw, smooth, labels): (Curve, Curve, Labels) = if scaled.is_empty() {
        (
            rows.iter().map(|r| (r[0], r[1])).collect(),
            rows.iter().map(|r| (r[0], r[2])).collect(),
            Labels { title: "floor pressure (2.39)", x: "x / m", y: "p / (N/m)" },
        )
    } else {
        (
            scaled.iter().map(|s| (s.0, s.1)).collect(),
            scaled.iter().map(|s| (s.0, s.2)).collect(),
            Labels { title: "floor pressure (2.39), scaled", x: "(x − x_left) / width", y: "p / (ρ g h)" },
        )
    };
    figures::line_chart(
        &out.file("floor_pressure.svg"),
        labels,
        &[
            Series { label: "window 2b", points: &raw, color: BLUE, mark: Mark::Line },
            Series { label: "moving average", points: &smooth, color: RED, mark: Mark::Line },
        ],
    )?;
    let peak = profile.smoothed.iter().copied().fold(0.0, f64::max);
    let apex = profile
        .positions
        .iter()
        .zip(&profile.smoothed)
        .min_by(|a, b| (a.0 - shape.apex_x).abs().total_cmp(&(b.0 - shape.apex_x).abs()))
        .map_or(0.0, |(_, &p)| p);
    let scale = |p: f64| if rho_g_h > 0.0 { p / rho_g_h } else { f64::NAN };
    Ok(Some(FloorPressureReport {
        half_width: profile.half_width,
        forces: forces.len(),
        total_normal_force: profile.total_normal_force,
        weight: pile.total_mass() * pile.gravity,
        rho_g_h,
        peak_scaled: scale(peak),
        apex_scaled: scale(apex),
        apex_to_peak: if peak > 0.0 { apex / peak } else { f64::NAN },
    }))
}

/// Writes `density_grid.csv` and `density_map.svg`.
pub fn write_density(cells: &[LocalDensity], out: &mut OutputDir) -> Result<(), AnalysisError> {
    let rows: Vec<Vec<f64>> = cells
        .iter()
        .map(|c| {
            let (center, size) = (c.rect.center(), c.rect.size());
            vec![center.x, center.y, size.x, size.y, c.simple, c.corrected, c.particles as f64]
        })
        .collect();
    out.write_csv("density_grid.csv", &["x", "y", "width", "height", "rho_simple", "rho_rel", "particles"], &rows)?;
    let filled: Vec<(Rect, f64)> = cells.iter().filter(|c| c.particles > 0).map(|c| (c.rect, c.corrected)).collect();
    let quantity = ColourQuantity { label: "ρ_rel", unit: "" };
    figures::cell_map(&out.file("density_map.svg"), "packing density ρ_rel (2.45)", quantity, &filled, &[])
}

/// Writes `stress_grid.csv` and `stress_map.svg` (colour σ_zz, red segments along the major principal axis).
pub fn write_stress(cells: &[LocalStress], out: &mut OutputDir) -> Result<(), AnalysisError> {
    let rows: Vec<Vec<f64>> = cells
        .iter()
        .map(|c| {
            let center = c.rect.center();
            let (s, p) = (c.sigma, c.principal);
            vec![
                center.x,
                center.y,
                s.xx,
                s.xy,
                s.yy,
                p.major,
                p.minor,
                p.psi_degrees,
                c.particles as f64,
                c.forces as f64,
                c.volume,
            ]
        })
        .collect();
    out.write_csv(
        "stress_grid.csv",
        &["x", "y", "sigma_xx", "sigma_xy", "sigma_zz", "major", "minor", "psi_deg", "particles", "forces", "volume"],
        &rows,
    )?;
    let filled: Vec<(Rect, f64)> = cells.iter().map(|c| (c.rect, c.sigma.yy)).collect();
    let segments: Vec<(DVec2, DVec2)> = cells
        .iter()
        .map(|c| {
            let psi = c.principal.psi_degrees.to_radians();
            let half = 0.4 * c.rect.size().min_element() * DVec2::new(-psi.sin(), psi.cos());
            (c.rect.center() - half, c.rect.center() + half)
        })
        .collect();
    let quantity = ColourQuantity { label: "σ_zz / (N/m)", unit: "N/m" };
    figures::cell_map(&out.file("stress_map.svg"), "σ_zz (2.52) and major axis Ψ", quantity, &filled, &segments)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flank fit of `degrees` (positive: rising to the right) through (x0, 0), with points from x0 to x1.
    fn flank(degrees: f64, x0: f64, x1: f64) -> FlankFit {
        let slope = degrees.to_radians().tan();
        let points = (0..8).map(|k| x0 + (x1 - x0) * k as f64 / 7.0).map(|x| DVec2::new(x, slope * (x - x0))).collect();
        FlankFit { angle_degrees: degrees.abs(), slope, intercept: -slope * x0, rms_residual: 0.0, points }
    }

    /// The points of the first polyline stroked in `colour`: the series (its legend line comes after it).
    fn first_polyline(svg: &str, colour: RGBColor) -> Vec<(f64, f64)> {
        let stroke = format!("stroke=\"#{:02X}{:02X}{:02X}\"", colour.0, colour.1, colour.2);
        let line = svg.split("<polyline").find(|p| p.contains(&stroke)).expect("no polyline in the colour");
        let points = line.split("points=\"").nth(1).unwrap().split('"').next().unwrap();
        points
            .split_whitespace()
            .map(|xy| xy.split_once(',').map(|(x, y)| (x.parse().unwrap(), y.parse().unwrap())).unwrap())
            .collect()
    }

    #[test]
    fn the_surface_figure_draws_both_flank_fits_at_their_angles_in_distinct_colours() {
        // The QA case: a flat pile 0.15 m wide and 0.022 m high, flanks of 10.1° and 13.6°.
        let (left, right) = (flank(10.1, -0.075, -0.005), flank(-13.6, 0.005, 0.075));
        let surface: Vec<(f64, f64)> = [(-0.075, 0.0), (0.0, 0.022), (0.075, 0.0)].to_vec();
        let flank_points: Vec<(f64, f64)> = left.points.iter().chain(&right.points).map(|p| (p.x, p.y)).collect();
        let path = std::env::temp_dir().join(format!("gc2d-surface-test-{}.svg", std::process::id()));
        let figure = SurfaceFigure { surface: &surface, flank_points: &flank_points };
        figure.draw(&path, Some(&left), Some(&right)).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_ne!(FLANK_FIT_COLOURS[0], FLANK_FIT_COLOURS[1]);
        assert!(!FLANK_FIT_COLOURS.contains(&SERIES_COLOURS[0]) && !FLANK_FIT_COLOURS.contains(&BLACK));
        for (colour, degrees) in FLANK_FIT_COLOURS.into_iter().zip([10.1, 13.6]) {
            let line = first_polyline(&svg, colour);
            let (a, b) = (line[0], line[line.len() - 1]);
            let drawn = ((b.1 - a.1) / (b.0 - a.0)).atan().to_degrees().abs();
            assert!((drawn - degrees).abs() < 0.3, "the {degrees}° fit is drawn at {drawn:.2}°");
        }
        assert!(svg.contains("left flank fit, 10.1°") && svg.contains("right flank fit, 13.6°"));
    }
}
