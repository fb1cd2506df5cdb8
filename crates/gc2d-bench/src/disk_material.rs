//! The disks and contact law of the dense disk pile of the benchmarks (docs/performance.md): radius 1 mm ± 20 %
//! (uniform), glass density 2500 kg/m³ with sphere-equivalent masses, a linear spring of 2000 N/m with restitution 0.5
//! and Cundall–Strack friction μ = 0.5. The stiffness is far below glass's, as is usual in DEM, to afford a Δt that
//! settles the pile in minutes: in the settled 10,000-disk pile the deepest overlap is about 0.8 % of the smaller
//! diameter. Δt is half the engine's stable bound for the smallest disk (5.75 µs).

use gc2d_contact::{
    CundallStrack, NormalSpring, PenetrationDamping, PenetrationLaw, TangentialSpring, TangentialStiffness,
};
use gc2d_engine::ContactModel;
use gc2d_engine::SafetyLimits;
use gc2d_engine::safety::{ParticleInertia, particle_time_step};
use std::f64::consts::PI;

/// Mean disk radius, m.
pub const RADIUS: f64 = 1e-3;
/// Relative spread of the radii: uniform in `RADIUS`·(1 ± `SIZE_VARIATION`).
pub const SIZE_VARIATION: f64 = 0.2;
/// Density of glass, kg/m³.
pub const DENSITY: f64 = 2500.0;
/// Normal stiffness of the linear spring, N/m.
pub const STIFFNESS: f64 = 2000.0;
/// Coefficient of restitution of every impact.
pub const RESTITUTION: f64 = 0.5;
/// Coulomb friction coefficient.
pub const FRICTION: f64 = 0.5;
/// Δt as a fraction of the engine's stable bound for the smallest disk.
const TIME_STEP_FRACTION: f64 = 0.5;
/// Gap between neighbours on the start lattice beyond the largest diameter, m.
pub const LATTICE_GAP: f64 = 0.1e-3;
/// Packing fraction assumed when sizing the box for the settled pile.
pub const ASSUMED_PACKING: f64 = 0.82;

/// The contact law of every pair: linear spring `STIFFNESS`, restitution `RESTITUTION`, friction `FRICTION`.
pub fn contact_model() -> ContactModel {
    ContactModel::Penetration(PenetrationLaw {
        damping: Some(PenetrationDamping::Restitution(RESTITUTION)),
        tangential: Some(TangentialSpring {
            mu: FRICTION,
            stiffness: TangentialStiffness::CundallStrack { stiffness_ratio: CundallStrack::STIFFNESS_FACTOR },
            damping_ratio: 0.0,
        }),
        ..PenetrationLaw::elastic(NormalSpring::Linear { stiffness_n_m: STIFFNESS })
    })
}

/// `TIME_STEP_FRACTION` of the engine's stable Δt for the smallest disk, s.
pub fn time_step(model: &ContactModel) -> f64 {
    let radius = RADIUS * (1.0 - SIZE_VARIATION);
    let mass = DENSITY * 4.0 / 3.0 * PI * radius.powi(3);
    let inertia = ParticleInertia {
        inscribed_radius: radius,
        area_density: mass / (PI * radius * radius),
        mass,
        inertia: 0.4 * mass * radius * radius,
        contact_radius: radius,
        reach: radius,
        flat_contact_ratio: 0.0,
    };
    let bound = particle_time_step([model], &inertia, SafetyLimits::default().max_impact_speed);
    TIME_STEP_FRACTION * bound.expect("the linear spring bounds the time step")
}
