//! The squares and contact law of the benchmark against LAMMPS's BODY package (../shared/bench/lammps, README
//! "What is compared"): squares of side 4.5 mm at 5000 kg/m², the overlap-area law with E = 2.5·10⁶ N/m, γ = 0.05,
//! μ = 0.3, g = 10 m/s², Δt = 3·10⁻⁶ s.

use crate::{benchmark_config, overlap_area_law};
use gc2d_engine::{MassModel, WorldConfig};

/// Side of the squares, m (LAMMPS: core side 4 plus a rounding of 0.25 on each side, with L0 = 1 mm).
pub const SIDE: f64 = 4.5e-3;
/// Area density, kg/m² (the mass of one square is LAMMPS's mass unit, 0.10125 kg).
pub const DENSITY: f64 = 5000.0;
/// Time step, s (3·10⁻⁴ τ with τ = 0.01 s).
pub const TIME_STEP: f64 = 3e-6;

/// The World configuration of the squares benchmark.
pub fn square_config(seed: u64) -> WorldConfig {
    let interactions = overlap_area_law(2.5e6, 0.05, 0.3);
    benchmark_config(TIME_STEP, interactions, MassModel::PerUnitThickness, 10.0, seed)
}

/// Width of the box for `count` squares, m: the LAMMPS example's replicated box, 12·sqrt(N/2) mm.
pub fn box_width(count: usize) -> f64 {
    12e-3 * (count as f64 / 2.0).sqrt()
}
