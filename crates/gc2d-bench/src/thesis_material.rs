//! The particles and material of the thesis's dip-pile ensemble (reference §8.3): the dense 7-gon piles and layers of
//! the benchmarks, the engine's `pile` example and its `step_allocation` test.
//!
//! Material: Δt = 2·10⁻⁶ s, E = 10⁷ N/m, γ = 0.75, μ = 0.6, area density 5000 kg/m², g = 9.81 m/s². Particles:
//! 7-gons with corners at RAND1 positions on an ellipse whose semi-axes are drawn uniformly in 1.75 mm ± 25 %.

use crate::{benchmark_config, overlap_area_law};
use gc2d_engine::{MassModel, WorldConfig};
use gc2d_geometry::{AngleMode, DVec2, Randomization, ShapeRecipe};

/// Δt of the thesis's pile runs, s.
pub const TIME_STEP: f64 = 2e-6;
/// Area density of the particles, kg/m².
pub const DENSITY: f64 = 5000.0;
/// Nominal ellipse semi-axis ("radius"), m.
pub const SEMI_AXIS: f64 = 1.75e-3;
/// Relative spread of the semi-axes.
pub const SIZE_VARIATION: f64 = 0.25;

/// The World configuration of the thesis's pile runs.
pub fn thesis_config(seed: u64) -> WorldConfig {
    let interactions = overlap_area_law(1e7, 0.75, 0.6);
    benchmark_config(TIME_STEP, interactions, MassModel::PerUnitThickness, 9.81, seed)
}

/// RAND1 7-gons, semi-axes 1.75 mm ± 25 % (each axis drawn uniformly), uniformly random orientation.
pub fn thesis_recipe() -> ShapeRecipe {
    ShapeRecipe {
        semi_axes: DVec2::splat(SEMI_AXIS),
        size_variation: SIZE_VARIATION,
        size_randomization: Randomization::Equal,
        corners: 7,
        corner_variation: 0,
        corner_randomization: Randomization::Const,
        angle_mode: AngleMode::Rand1,
        rotation: std::f64::consts::PI,
        rotation_randomization: Randomization::Equal,
    }
}
