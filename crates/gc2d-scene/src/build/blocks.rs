//! GENERATE_BLOCK (reference §9.7, App. B.1.6): lattice points in a rectangle, their scatter, and one random particle
//! per point.

use crate::checks::{finite_pair, ordered_range, positive};
use crate::error::SceneError;
use crate::schema::{Block, GridType};
use crate::spans::field_path;
use gc2d_geometry::{DVec2, truncated_gaussian};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Most particles a scene may create at its start (explicit particles and blocks together).
pub const MAX_INITIAL_PARTICLES: usize = 1_000_000;

/// A point counts as inside the range when it overshoots the end by at most this fraction of the spacing, so that
/// a range that is a whole number of spacings includes its end point despite rounding.
const END_POINT_TOLERANCE: f64 = 1e-9;

/// The lattice of a block: rows at y_min + j·Δy, points at x_min + shift_j + i·Δx, where `Fcc` grids shift every odd
/// row by Δx/2 (two square lattices offset by (Δx/2, Δy); for Δy = Δx·√3/2 this is the triangular lattice).
pub(crate) struct Lattice {
    x_range: [f64; 2],
    spacing: DVec2,
    rows: usize,
    y_min: f64,
    offset_rows: bool,
}

impl Lattice {
    /// Checks the block's ranges and spacing at `path`; the lattice may not exceed [`MAX_INITIAL_PARTICLES`] points.
    pub fn of(block: &Block, path: &str) -> Result<Self, SceneError> {
        let x_range = ordered_range(&field_path(path, "x_range_m"), block.x_range_m, false)?;
        let y_range = ordered_range(&field_path(path, "y_range_m"), block.y_range_m, false)?;
        let spacing_path = field_path(path, "grid_spacing_m");
        finite_pair(&spacing_path, block.grid_spacing_m)?;
        positive(&spacing_path, block.grid_spacing_m[0])?;
        positive(&spacing_path, block.grid_spacing_m[1])?;
        let spacing = DVec2::from_array(block.grid_spacing_m);
        let columns = (x_range[1] - x_range[0]) / spacing.x + 1.0;
        let rows = (y_range[1] - y_range[0]) / spacing.y + 1.0;
        if columns * rows > MAX_INITIAL_PARTICLES as f64 {
            return Err(SceneError::value(
                spacing_path,
                format!(
                    "the block would hold about {:.0} particles, more than the {MAX_INITIAL_PARTICLES} a scene may start with",
                    columns * rows
                ),
            )
            .with_help("check the units: ranges and spacing are in metres"));
        }
        let offset_rows = block.grid.is_fcc();
        Ok(Self {
            x_range,
            spacing,
            rows: count_points(y_range[1] - y_range[0], spacing.y),
            y_min: y_range[0],
            offset_rows,
        })
    }

    /// The number of lattice points.
    pub fn len(&self) -> usize {
        (0..self.rows).map(|row| self.columns(row)).sum()
    }

    fn row_shift(&self, row: usize) -> f64 {
        if self.offset_rows && row % 2 == 1 { 0.5 * self.spacing.x } else { 0.0 }
    }

    fn columns(&self, row: usize) -> usize {
        count_points(self.x_range[1] - self.x_range[0] - self.row_shift(row), self.spacing.x)
    }

    /// The lattice points, row by row from the bottom, left to right.
    pub fn points(&self) -> impl Iterator<Item = DVec2> + '_ {
        (0..self.rows).flat_map(move |row| {
            let y = self.y_min + row as f64 * self.spacing.y;
            let x0 = self.x_range[0] + self.row_shift(row);
            (0..self.columns(row)).map(move |column| DVec2::new(x0 + column as f64 * self.spacing.x, y))
        })
    }
}

/// Points at 0, s, 2s, … up to `length` (with the end-point tolerance); 0 for a negative length.
fn count_points(length: f64, spacing: f64) -> usize {
    let steps = length / spacing + END_POINT_TOLERANCE;
    if steps >= 0.0 { steps.floor() as usize + 1 } else { 0 }
}

/// One particle of a block, before it is added to the World.
pub(crate) struct BlockParticle {
    pub position: DVec2,
    pub shape: gc2d_engine::BodyShape,
    pub angle: f64,
    pub velocity: DVec2,
}

/// Draws the block's particles. Per point, in this order: the scatter (x, then y; none for `Rect` and `Fcc`), the
/// shape (see `ShapeRecipe::draw`), the speed, the direction (each only if its range has a width).
pub(crate) fn generate(
    block: &Block,
    lattice: &Lattice,
    recipe: &gc2d_engine::ParticleRecipe,
    rng: &mut ChaCha8Rng,
    path: &str,
) -> Result<Vec<BlockParticle>, SceneError> {
    let speed = ordered_range(&field_path(path, "speed_range_m_s"), block.speed_range_m_s, false)?;
    let direction = ordered_range(&field_path(path, "direction_range_rad"), block.direction_range_rad, false)?;
    let half = 0.5 * lattice.spacing;
    let mut particles = Vec::with_capacity(lattice.len());
    for point in lattice.points() {
        let scatter = match block.grid {
            GridType::Rect | GridType::Fcc => DVec2::ZERO,
            GridType::RectGauss | GridType::FccGauss => {
                let fx = truncated_gaussian(rng);
                let fy = truncated_gaussian(rng);
                DVec2::new(2.0 * fx - 1.0, 2.0 * fy - 1.0) * half
            }
            GridType::RectEqual | GridType::FccEqual => {
                let fx: f64 = rng.random();
                let fy: f64 = rng.random();
                DVec2::new(2.0 * fx - 1.0, 2.0 * fy - 1.0) * half
            }
        };
        let (shape, angle) =
            recipe.draw(rng).map_err(|e| SceneError::value(field_path(path, "shape"), e.to_string()))?;
        let magnitude = uniform_in(speed, rng);
        let heading = uniform_in(direction, rng);
        particles.push(BlockParticle {
            position: point + scatter,
            shape,
            angle,
            velocity: magnitude * DVec2::from_angle(heading),
        });
    }
    Ok(particles)
}

/// Uniform in [min, max]; draws nothing for an empty range.
fn uniform_in(range: [f64; 2], rng: &mut ChaCha8Rng) -> f64 {
    if range[1] > range[0] { range[0] + (range[1] - range[0]) * rng.random::<f64>() } else { range[0] }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schema::Recipe;

    fn block(grid: GridType) -> Block {
        Block {
            x_range_m: [-0.247, 0.098],
            y_range_m: [0.012, 0.098],
            grid_spacing_m: [0.005, 0.005],
            grid,
            shape: Recipe {
                semi_axes_m: [0.003, 0.003],
                size_spread: Default::default(),
                corners: 8,
                corner_spread: Default::default(),
                corner_positions: Default::default(),
                orientation: Default::default(),
                disk: false,
            },
            material: None,
            speed_range_m_s: [0.0, 0.0],
            direction_range_rad: [0.0, std::f64::consts::TAU],
        }
    }

    #[test]
    fn the_b18_piston_block_has_70_columns_and_18_rows() {
        let rect = Lattice::of(&block(GridType::Rect), "blocks[0]").unwrap();
        assert_eq!(rect.len(), 70 * 18);
        let fcc = Lattice::of(&block(GridType::Fcc), "blocks[0]").unwrap();
        // Odd rows are shifted by Δx/2 and lose their last point: 9 rows of 70 and 9 of 69.
        assert_eq!(fcc.len(), 9 * 70 + 9 * 69);
        let points: Vec<DVec2> = fcc.points().collect();
        assert!((points[70].x - (-0.247 + 0.0025)).abs() < 1e-15);
        assert!((points[70].y - 0.017).abs() < 1e-15);
    }

    #[test]
    fn ranges_that_are_whole_multiples_include_their_end_points() {
        let mut exact = block(GridType::Rect);
        exact.x_range_m = [0.0, 0.3];
        exact.y_range_m = [0.0, 0.0];
        exact.grid_spacing_m = [0.1, 0.1];
        assert_eq!(Lattice::of(&exact, "b").unwrap().len(), 4);
    }

    #[test]
    fn oversized_blocks_are_refused_before_allocating() {
        let mut huge = block(GridType::Rect);
        huge.grid_spacing_m = [1e-9, 1e-9];
        let error = Lattice::of(&huge, "blocks[0]").err().unwrap();
        assert_eq!(error.path(), "blocks[0].grid_spacing_m");
    }
}
