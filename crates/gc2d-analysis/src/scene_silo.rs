//! The analyses of a silo (Ch. 3, reference §7.1): wall pressure σ_xx against depth, the stress ratio k(z) and the
//! packing density ρ_rel(z) from rows of test areas, and the Janssen fit of μ_j.

use crate::density::{Grid, bulk_packing_fraction, density_grid};
use crate::error::AnalysisError;
use crate::figures::{self, Labels, Mark, Series};
use crate::geometry::Rect;
use crate::janssen::{JanssenFit, JanssenFreeKFit, JanssenParameters, fit_janssen, fit_janssen_free_k};
use crate::output::OutputDir;
use crate::pressure::{
    Facing, ProfileOptions, WallSelection, face_length, mean_pressure, pressure_profile, wall_forces,
};
use crate::repose::surface_envelope;
use crate::run::AnalyzeOptions;
use crate::scene_pile::{MOVING_AVERAGE_SAMPLES, auto_cell, auto_half_width, write_density, write_stress};
use crate::snapshot::Snapshot;
use crate::stress::{StressOptions, stress_grid};
use plotters::style::{BLACK, BLUE, GREEN, MAGENTA, RED};
use serde::Serialize;

/// The numbers of a silo analysis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SiloReport {
    /// Inner left boundary (leftmost particle vertex), m.
    pub left: f64,
    /// Inner right boundary (rightmost particle vertex), m.
    pub right: f64,
    /// Half-width r, m.
    pub half_width: f64,
    /// Floor level (lowest particle vertex), m.
    pub floor_level: f64,
    /// Fill surface: mean height of the surface envelope across the silo, m. Depth z is measured down from it.
    pub fill_surface: f64,
    /// Fill height (surface − floor), m.
    pub fill_height: f64,
    /// Window half-width b along the walls, m.
    pub window_half_width: f64,
    /// Contacts on the left wall's inner face.
    pub left_wall_forces: usize,
    /// Contacts on the right wall's inner face.
    pub right_wall_forces: usize,
    /// Mean floor pressure (2.36) over the floor faces, N/m.
    pub floor_mean_pressure: f64,
    /// Side of the square test areas used, m: the side asked for (or chosen) rounded so that a whole number of
    /// columns spans the region's width, or larger where [`Self::grid_capped`].
    pub grid_cell: f64,
    /// Columns and rows of the test areas, at most [`crate::density::MAX_GRID_CELLS_PER_AXIS`] each; the top row
    /// reaches past the region's top.
    pub grid_size: [usize; 2],
    /// True when the side asked for would have given more than [`crate::density::MAX_GRID_CELLS_PER_AXIS`] areas
    /// along an axis, so the areas are larger than asked.
    pub grid_capped: bool,
    /// k = Σσ_xx / Σσ_zz over the rows of test areas (used in the fit).
    pub k: f64,
    /// Mean of the row values k(z) = σ_xx/σ_zz (rows with σ_zz > 0).
    pub k_mean: f64,
    /// Standard deviation of the row values k(z).
    pub k_std: f64,
    /// Bulk packing fraction (2.45 on everything), used for ρ.
    pub packing_fraction: f64,
    /// Mean of the row packing fractions ρ_rel(z).
    pub packing_fraction_mean: f64,
    /// Standard deviation of the row packing fractions.
    pub packing_fraction_std: f64,
    /// ρ = ρ_rel · ρ_particle (3.5), kg/m².
    pub bulk_density: f64,
    /// The Janssen fit (3.4), when it could be done.
    pub janssen: Option<JanssenFit>,
    /// Why the fit was not done, otherwise.
    pub janssen_error: Option<String>,
    /// The Janssen fit with k free as well, when it could be done.
    pub janssen_free_k: Option<JanssenFreeKFit>,
    /// Why the free-k fit was not done, otherwise.
    pub janssen_free_k_error: Option<String>,
    /// Why the numbers may mean little: no side wall carrying a force, a fill too shallow for a wall-pressure
    /// profile, a Janssen fit not done (also printed by `gc2d-rs analyze` on stderr).
    pub warnings: Vec<String>,
}

/// Runs the silo analyses and writes their tables and figures.
pub fn analyze_silo(
    snapshot: &Snapshot,
    options: &AnalyzeOptions,
    out: &mut OutputDir,
) -> Result<SiloReport, AnalysisError> {
    let region = Rect::bounding(snapshot.particles.iter().flat_map(|p| p.vertices.iter().copied()))
        .ok_or_else(|| AnalysisError::NotEnoughData("particles have no finite vertices".into()))?;
    let mean_diameter = snapshot.mean_particle_diameter();
    let (left, right, floor_level) = (region.min.x, region.max.x, region.min.y);
    let half_width = 0.5 * (right - left);
    let fill_surface = mean_surface(snapshot, mean_diameter, left, right).unwrap_or(region.max.y);
    let fill_height = fill_surface - floor_level;

    let left_forces = wall_forces(snapshot, WallSelection::facing(Facing::Right));
    let right_forces = wall_forces(snapshot, WallSelection::facing(Facing::Left));
    let all: Vec<_> = left_forces.iter().chain(&right_forces).copied().collect();
    // The rule of thumb counts contacts per wall; `all` holds both walls' contacts, so double the window.
    let b = options.window_half_width.unwrap_or_else(|| 2.0 * auto_half_width(&all, mean_diameter));
    let profile_options = ProfileOptions { half_width: b, step: 0.5 * b, moving_average: MOVING_AVERAGE_SAMPLES };
    let range = Some((floor_level + b, fill_surface.max(floor_level + b)));
    let left_profile = pressure_profile(&left_forces, &profile_options, range);
    let right_profile = pressure_profile(&right_forces, &profile_options, range);
    let walls_with_forces = [&left_forces, &right_forces].iter().filter(|f| !f.is_empty()).count().max(1) as f64;
    let heights = if left_profile.positions.is_empty() { &right_profile.positions } else { &left_profile.positions };
    let pressure_at =
        |k: usize, profile: &crate::pressure::PressureProfile| profile.pressure.get(k).copied().unwrap_or(0.0);
    // A window centred above the fill surface (a fill shallower than b) is no point of the profile σ_xx(z).
    let wall_rows: Vec<(f64, f64, f64, f64, f64)> = heights
        .iter()
        .enumerate()
        .filter(|&(_, &y)| fill_surface - y >= 0.0)
        .map(|(k, &y)| {
            let (pl, pr) = (pressure_at(k, &left_profile), pressure_at(k, &right_profile));
            (fill_surface - y, y, pl, pr, (pl + pr) / walls_with_forces)
        })
        .collect();

    let packing_fraction = bulk_packing_fraction(snapshot);
    let bulk_density = packing_fraction * snapshot.particle_area_density();
    let cell = options.grid_cell.unwrap_or_else(|| auto_cell(snapshot, packing_fraction));
    let column = Rect::new(region.min, gc2d_geometry::DVec2::new(region.max.x, fill_surface.max(region.min.y + cell)));
    let grid = Grid::with_cell_size(column, cell);
    let densities = density_grid(snapshot, &grid);
    write_density(&densities, out)?;
    let stresses = stress_grid(snapshot, &grid, &StressOptions::default());
    write_stress(&stresses, out)?;

    let mut rows = Vec::new();
    for j in 0..grid.ny {
        let row_rect = grid.cell(0, j);
        let y = row_rect.center().y;
        let in_row = |r: &Rect| (r.center().y - y).abs() < 0.25 * row_rect.size().y;
        let cells: Vec<_> = stresses.iter().filter(|s| in_row(&s.rect)).collect();
        let density: Vec<f64> =
            densities.iter().filter(|d| in_row(&d.rect) && d.particles > 0).map(|d| d.corrected).collect();
        let mean = |v: &[f64]| if v.is_empty() { f64::NAN } else { v.iter().sum::<f64>() / v.len() as f64 };
        let sxx = mean(&cells.iter().map(|s| s.sigma.xx).collect::<Vec<_>>());
        let szz = mean(&cells.iter().map(|s| s.sigma.yy).collect::<Vec<_>>());
        rows.push(vec![fill_surface - y, y, sxx, szz, if szz > 0.0 { sxx / szz } else { f64::NAN }, mean(&density)]);
    }
    out.write_csv("silo_rows.csv", &["depth", "y", "sigma_xx", "sigma_zz", "k", "rho_rel"], &rows)?;
    let (sum_xx, sum_zz) =
        rows.iter().filter(|r| r[3] > 0.0 && r[2].is_finite()).fold((0.0, 0.0), |(a, b), r| (a + r[2], b + r[3]));
    let k = if sum_zz > 0.0 { sum_xx / sum_zz } else { f64::NAN };
    let (k_mean, k_std) = mean_std(rows.iter().map(|r| r[4]));
    let (packing_fraction_mean, packing_fraction_std) = mean_std(rows.iter().map(|r| r[5]));

    let parameters = JanssenParameters { k, rho: bulk_density, g: snapshot.gravity, half_width };
    let depth: Vec<f64> = wall_rows.iter().map(|r| r.0).collect();
    let sigma: Vec<f64> = wall_rows.iter().map(|r| r.4).collect();
    // Without a side wall carrying force there is no wall pressure to fit (a pile analysed as a silo gave a "fit" of
    // zeros with μ_J at its bound).
    let no_walls = all.is_empty().then(|| {
        "no side wall carries a force: the particles lean on no walls, so there is no wall pressure to fit (is it a \
         silo?)"
            .to_owned()
    });
    let (janssen, janssen_error) = match no_walls
        .clone()
        .map_or_else(|| fit_janssen(&depth, &sigma, parameters).map_err(|e| e.to_string()), Err)
    {
        Ok(fit) => (Some(fit), None),
        Err(error) => (None, Some(error)),
    };
    let free_k = no_walls.map_or_else(
        || fit_janssen_free_k(&depth, &sigma, bulk_density, snapshot.gravity, half_width).map_err(|e| e.to_string()),
        Err,
    );
    let (janssen_free_k, janssen_free_k_error) = match free_k {
        Ok(fit) => (Some(fit), None),
        Err(error) => (None, Some(error)),
    };
    let warnings = silo_warnings(
        all.is_empty(),
        wall_rows.len(),
        fill_height,
        b,
        janssen_error.as_deref(),
        janssen_free_k_error.as_deref(),
    );
    let fitted = |z: f64| janssen.map_or(f64::NAN, |f| parameters.sigma_xx(z, f.mu_j));
    let fitted_free_k = |z: f64| janssen_free_k.map_or(f64::NAN, |f| parameters.with_k(f.k).sigma_xx(z, f.mu_j));
    let table: Vec<Vec<f64>> =
        wall_rows.iter().map(|r| vec![r.0, r.1, r.2, r.3, r.4, fitted(r.0), fitted_free_k(r.0)]).collect();
    out.write_csv(
        "wall_pressure.csv",
        &["depth", "y", "pressure_left", "pressure_right", "sigma_xx", "janssen_sigma_xx", "janssen_free_k_sigma_xx"],
        &table,
    )?;
    let measured: Vec<(f64, f64)> = table.iter().map(|r| (r[0], r[4])).collect();
    let theory: Vec<(f64, f64)> = table.iter().map(|r| (r[0], r[5])).collect();
    let theory_free_k: Vec<(f64, f64)> = table.iter().map(|r| (r[0], r[6])).collect();
    let stress_xx: Vec<(f64, f64)> = rows.iter().map(|r| (r[0], r[2])).collect();
    let stress_zz: Vec<(f64, f64)> = rows.iter().map(|r| (r[0], r[3])).collect();
    figures::line_chart(
        &out.file("wall_pressure.svg"),
        Labels { title: "silo stresses against depth; Janssen fit (3.4)", x: "depth z / m", y: "σ / (N/m)" },
        &[
            Series { label: "σ_xx at the walls (2.40)", points: &measured, color: BLUE, mark: Mark::Line },
            Series { label: "Janssen fit, measured k", points: &theory, color: RED, mark: Mark::Line },
            Series { label: "Janssen fit, k free", points: &theory_free_k, color: MAGENTA, mark: Mark::Line },
            Series { label: "σ_xx (2.52), rows", points: &stress_xx, color: GREEN, mark: Mark::Dots },
            Series { label: "σ_zz (2.52), rows", points: &stress_zz, color: BLACK, mark: Mark::Dots },
        ],
    )?;
    let k_points: Vec<(f64, f64)> = rows.iter().map(|r| (r[0], r[4])).collect();
    figures::line_chart(
        &out.file("k_profile.svg"),
        Labels { title: "k(z) = σ_xx/σ_zz", x: "depth z / m", y: "k" },
        &[Series { label: "rows of test areas", points: &k_points, color: BLUE, mark: Mark::Line }],
    )?;
    let rho_points: Vec<(f64, f64)> = rows.iter().map(|r| (r[0], r[5])).collect();
    figures::line_chart(
        &out.file("density_profile.svg"),
        Labels { title: "packing density ρ_rel(z) (2.45)", x: "depth z / m", y: "ρ_rel" },
        &[Series { label: "rows of test areas", points: &rho_points, color: BLUE, mark: Mark::Line }],
    )?;

    let floor_selection = WallSelection::facing(Facing::Up);
    Ok(SiloReport {
        left,
        right,
        half_width,
        floor_level,
        fill_surface,
        fill_height,
        window_half_width: b,
        left_wall_forces: left_forces.len(),
        right_wall_forces: right_forces.len(),
        floor_mean_pressure: mean_pressure(
            &wall_forces(snapshot, floor_selection),
            face_length(snapshot, floor_selection),
        ),
        grid_cell: grid.side,
        grid_size: [grid.nx, grid.ny],
        grid_capped: grid.capped,
        k,
        k_mean,
        k_std,
        packing_fraction,
        packing_fraction_mean,
        packing_fraction_std,
        bulk_density,
        janssen,
        janssen_error,
        janssen_free_k,
        janssen_free_k_error,
        warnings,
    })
}

/// Wall-pressure points below the fill surface that the Janssen fits need at the least.
const FIT_POINTS: usize = 2;

/// The warnings of a silo analysis: without side-wall forces every silo number means nothing; with fewer than
/// [`FIT_POINTS`] wall-pressure points (`points`) the fill (`fill_height`, m) is too shallow for the pressure window
/// of half-width `b`; otherwise each Janssen fit not done, with its error.
fn silo_warnings(
    no_walls: bool,
    points: usize,
    fill_height: f64,
    b: f64,
    janssen_error: Option<&str>,
    free_k_error: Option<&str>,
) -> Vec<String> {
    if no_walls {
        return vec![
            "no side wall carries a force: the particles lean on no walls, so k, the wall pressure and the Janssen \
             fits mean nothing (is it a silo? --kind pile analyses a heap)"
                .to_owned(),
        ];
    }
    if points < FIT_POINTS {
        return vec![format!(
            "the fill is {fill_height:.3e} m deep, against a pressure window 2b = {:.3e} m along the walls: {points} \
             wall-pressure point(s) below the fill surface, too few for the Janssen fits (at least {FIT_POINTS}; a \
             deeper fill, or a smaller --window b)",
            2.0 * b
        )];
    }
    [("the measured k", janssen_error), ("k free", free_k_error)]
        .into_iter()
        .filter_map(|(which, error)| error.map(|e| format!("no Janssen fit with {which}: {e}")))
        .collect()
}

/// Mean height of the surface envelope between `left` and `right`, one particle diameter in from each wall.
fn mean_surface(snapshot: &Snapshot, mean_diameter: f64, left: f64, right: f64) -> Option<f64> {
    let envelope = surface_envelope(snapshot, 0.25 * mean_diameter);
    let inner: Vec<f64> =
        envelope.iter().filter(|p| p.x >= left + mean_diameter && p.x <= right - mean_diameter).map(|p| p.y).collect();
    let used = if inner.is_empty() { envelope.iter().map(|p| p.y).collect() } else { inner };
    (!used.is_empty()).then(|| used.iter().sum::<f64>() / used.len() as f64)
}

/// Mean and standard deviation of the finite values; NaN when there are none.
fn mean_std(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let finite: Vec<f64> = values.filter(|v| v.is_finite()).collect();
    if finite.is_empty() {
        return (f64::NAN, f64::NAN);
    }
    let n = finite.len() as f64;
    let mean = finite.iter().sum::<f64>() / n;
    (mean, (finite.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt())
}
