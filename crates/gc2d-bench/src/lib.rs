//! The standard benchmark piles of gc2d-rs and the timing of `World::step` on them: what `gc2d-rs bench` and the
//! engine's throughput examples (`bench_pile`, `bench_disk_pile`) measure, so that anyone can reproduce the figures
//! of docs/performance.md on their own machine.
//!
//! - [`piles`]: the four standard piles ([`StandardPile`]) built and settled;
//! - [`deposition`]: sequential deposition, the dense start without overlaps that the polygon piles share;
//! - [`thesis_material`], [`square_material`], [`disk_material`]: their particles and contact laws;
//! - [`timing`]: one timed measurement on a rayon pool of a given size.

pub mod deposition;
pub mod disk_material;
pub mod piles;
pub mod square_material;
pub mod thesis_material;
pub mod timing;

pub use piles::StandardPile;
pub use timing::{Measurement, measure};
