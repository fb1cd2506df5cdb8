//! The standard benchmark piles of gc2d-rs and the timing of `World::step` on them: what `gc2d-rs bench` and the
//! engine's throughput examples (`bench_pile`, `bench_disk_pile`) measure, so that anyone can reproduce the figures
//! of docs/performance.md on their own machine.
//!
//! - [`piles`]: the four standard piles ([`StandardPile`]) built and settled;
//! - [`deposition`]: sequential deposition, the dense start without overlaps that the polygon piles share;
//! - [`thesis_material`], [`square_material`], [`disk_material`]: their particles and contact laws;
//! - [`timing`]: one timed measurement on a rayon pool of a given size;
//! - [`line_trip`]: a cache line's round trip between two threads, which bounds what more threads gain.

pub mod deposition;
pub mod disk_material;
pub mod line_trip;
pub mod piles;
pub mod square_material;
pub mod thesis_material;
pub mod timing;

pub use piles::StandardPile;
pub use timing::{Measurement, measure};

use gc2d_contact::{ContactLaw, CundallStrack, NormalDamping, NormalElastic};
use gc2d_engine::schedules::GravitySchedule;
use gc2d_engine::{InteractionTable, MassModel, SafetyLimits, WorldConfig};

/// The World configuration every benchmark pile shares: `interactions` for its contacts, Gear integration at
/// `time_step`, constant gravity `gravity` (m/s²), the default safety limits, no heating and no domain.
fn benchmark_config(
    time_step: f64,
    interactions: InteractionTable,
    mass_model: MassModel,
    gravity: f64,
    seed: u64,
) -> WorldConfig {
    WorldConfig {
        time_step,
        integrator: Default::default(),
        interactions,
        mass_model,
        gravity: GravitySchedule::constant(gravity),
        heating: None,
        safety: SafetyLimits::default(),
        domain: None,
        seed,
    }
}

/// gc2d's overlap-area law for every pair: the thesis's elastic term with Young's modulus `e` (N/m), damping `gamma`
/// and Cundall–Strack friction `mu`, no cohesion.
fn overlap_area_law(e: f64, gamma: f64, mu: f64) -> InteractionTable {
    InteractionTable::uniform(ContactLaw {
        elastic: NormalElastic::thesis(e),
        damping: Some(NormalDamping { gamma }),
        friction: Some(CundallStrack { mu }),
        cohesion: None,
    })
}
