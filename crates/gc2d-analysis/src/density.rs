//! Local packing density in a test rectangle (reference §5.6, eqs. 2.43–2.45), and the grid of square test areas
//! that the density and stress maps share.
//!
//! α_i a_i is the exact area of particle i inside the rectangle (convex clipping). The simple density (2.44) divides
//! Σ α_i a_i by the rectangle area; the corrected one (2.45) divides by the area A_k of the convex hull of the
//! clipped particle pieces, so that a test area reaching over a free surface is not diluted by the empty part.

use crate::geometry::{Rect, clip_to_rect, hull_area};
use crate::snapshot::Snapshot;
use gc2d_geometry::{DVec2, OverlapPolygon};
use serde::Serialize;

/// A regular grid of square test areas covering a region.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Grid {
    /// The area the cells cover: the region asked for, its width exactly, its height rounded up to a whole number of
    /// cells (the top row reaches past the region's top by less than one cell).
    pub region: Rect,
    /// Columns.
    pub nx: usize,
    /// Rows.
    pub ny: usize,
    /// Side of the square cells, m.
    pub side: f64,
    /// True when the side asked for would have given more than [`MAX_GRID_CELLS_PER_AXIS`] cells along an axis: the
    /// cells are then larger than asked.
    pub capped: bool,
}

/// No grid has more cells than this along one axis.
pub const MAX_GRID_CELLS_PER_AXIS: usize = 1000;

impl Grid {
    /// The grid of square cells whose side is `cell_size` rounded so that a whole number of columns spans the
    /// region's width. The rows, of the same side, start at the region's bottom; the top one reaches past its top.
    /// At most [`MAX_GRID_CELLS_PER_AXIS`] cells along each axis: a smaller side asked for gets larger squares
    /// ([`Grid::capped`]). Squares cannot tile a region of any aspect ratio, hence the overhang at the top.
    pub fn with_cell_size(region: Rect, cell_size: f64) -> Self {
        let size = region.size();
        let (width, height) = (size.x.max(0.0), size.y.max(0.0));
        let most = MAX_GRID_CELLS_PER_AXIS as f64;
        let smallest = width.max(height) / most;
        let asked = if cell_size > 0.0 && cell_size.is_finite() { cell_size } else { width.max(height) };
        let capped = asked < smallest;
        let wanted = if asked.max(smallest) > 0.0 { asked.max(smallest) } else { 1.0 };
        // Rows needed for `side`, with a tolerance so that an exact fit does not get an extra row from rounding.
        let rows = |side: f64| (height / side * (1.0 - 1e-9)).ceil().max(1.0);
        let (nx, side) = if width > 0.0 {
            let mut nx = (width / wanted).round().clamp(1.0, most);
            if rows(width / nx) > most {
                nx = (width / wanted).floor().max(1.0);
            }
            (nx as usize, width / nx)
        } else {
            (1, wanted)
        };
        let ny = rows(side).min(most) as usize;
        let min = DVec2::new(region.min.x - 0.5 * (nx as f64 * side - width), region.min.y);
        let covered = Rect::new(min, min + side * DVec2::new(nx as f64, ny as f64));
        Self { region: covered, nx, ny, side, capped }
    }

    /// The cell in column `i`, row `j` (row 0 at the bottom).
    pub fn cell(&self, i: usize, j: usize) -> Rect {
        let min = self.region.min + self.side * DVec2::new(i as f64, j as f64);
        Rect::new(min, min + DVec2::splat(self.side))
    }

    /// All cells, row by row from the bottom, each with its (column, row).
    pub fn cells(&self) -> impl Iterator<Item = (usize, usize, Rect)> + '_ {
        (0..self.ny).flat_map(move |j| (0..self.nx).map(move |i| (i, j, self.cell(i, j))))
    }
}

/// Packing density in one test rectangle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LocalDensity {
    /// The test rectangle.
    pub rect: Rect,
    /// Σ α_i a_i, the particle area inside the rectangle, m².
    pub particle_area: f64,
    /// Area A_k of the convex hull of the particle pieces inside the rectangle, m².
    pub hull_area: f64,
    /// ρ'_rel = Σ α_i a_i / A (2.44).
    pub simple: f64,
    /// ρ_rel = Σ α_i a_i / A_k (2.45); 0 when no particle reaches into the rectangle.
    pub corrected: f64,
    /// Particles with α_i > 0.
    pub particles: usize,
}

/// Density (2.44) and (2.45) in `rect`. The hull is taken over the vertices of every particle's piece inside the
/// rectangle: its vertices inside (E1), the crossings of its outline with the rectangle's boundary (E2), and the
/// rectangle corners it covers.
pub fn local_density(snapshot: &Snapshot, rect: Rect) -> LocalDensity {
    let mut clipped = OverlapPolygon::new();
    let mut hull_points: Vec<DVec2> = Vec::new();
    let mut particle_area = 0.0;
    let mut particles = 0;
    for particle in &snapshot.particles {
        if !overlaps_box(&particle.vertices, &rect) {
            continue;
        }
        clip_to_rect(&particle.vertices, &rect, &mut clipped);
        if clipped.area() > 0.0 {
            particle_area += clipped.area();
            particles += 1;
            hull_points.extend_from_slice(clipped.vertices());
        }
    }
    let hull_area = hull_area(&hull_points);
    let area = rect.area();
    LocalDensity {
        rect,
        particle_area,
        hull_area,
        simple: if area > 0.0 { particle_area / area } else { 0.0 },
        corrected: if hull_area > 0.0 { particle_area / hull_area } else { 0.0 },
        particles,
    }
}

/// Density in every cell of `grid`, row by row from the bottom.
pub fn density_grid(snapshot: &Snapshot, grid: &Grid) -> Vec<LocalDensity> {
    grid.cells().map(|(_, _, rect)| local_density(snapshot, rect)).collect()
}

/// Packing fraction of the whole granulate: total particle area over the convex hull of all particle vertices, i.e.
/// (2.45) with a test area enclosing everything. Used for the bulk density ρ = ρ_rel · ρ_particle (3.5). A disk's
/// traced polygon is inscribed in its circle, so its vertices are pushed out to the circumscribed polygon: the hull
/// then encloses every disk (a single disk gave 1.0029 against its exact area).
pub fn bulk_packing_fraction(snapshot: &Snapshot) -> f64 {
    let points: Vec<DVec2> = snapshot
        .particles
        .iter()
        .flat_map(|p| {
            let outward = if p.is_disk { 1.0 / (std::f64::consts::PI / p.vertices.len() as f64).cos() } else { 1.0 };
            p.vertices.iter().map(move |&v| p.centroid + (v - p.centroid) * outward)
        })
        .collect();
    let hull = hull_area(&points);
    if hull > 0.0 { snapshot.total_particle_area() / hull } else { 0.0 }
}

/// True when the bounding box of `vertices` meets `rect`.
fn overlaps_box(vertices: &[DVec2], rect: &Rect) -> bool {
    Rect::bounding(vertices.iter().copied()).is_some_and(|b| {
        b.min.x <= rect.max.x && b.max.x >= rect.min.x && b.min.y <= rect.max.y && b.max.y >= rect.min.y
    })
}
