//! Validation studies of the gc2d-rs engine.
//!
//! [`convergence`] runs reference problems with known answers over a range of time steps for each integrator
//! (Gear c₀ = 3/20, Gear c₀ = 3/16, velocity Verlet) and reports errors, observed orders, instability thresholds
//! and wall-clock cost as CSV tables and SVG work-precision diagrams (`docs/validation.md`).

pub mod convergence;

pub use convergence::{ConvergenceError, ConvergenceOptions, ConvergenceReport, run_convergence};
