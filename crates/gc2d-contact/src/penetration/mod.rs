//! Penetration-depth contact laws for disks (spheres moving in a plane): linear and Hertz springs, damping from a
//! damping ratio, a restitution coefficient or a speed-dependent e(v), Cundall–Strack or Mindlin friction, and
//! rolling resistance (feedpipe.md §2, §7.1; ballmill.md §3.2, §7.3–§7.5).
//!
//! Every sub-model reads the same per-pair context: the [`PenetrationGeometry`] of the step (depth, normal, arms),
//! the [`PairProperties`] fixed for the pair (R*, m*, m_t, J*), the two [`crate::BodyMotion`]s and the
//! [`PenetrationState`] (the LAMMPS GRANULAR `granular_model` idea). [`PenetrationLaw::evaluate`] composes them; it
//! is pure and never allocates. The area law ([`crate::ContactLaw`]) is untouched; both laws report the same
//! [`crate::EnergyTerms`].

mod context;
mod damping;
mod elastic;
mod law;
mod rolling;
mod spring;
mod state;
mod tangential;

pub use context::{PairProperties, PenetrationGeometry, effective_modulus, effective_shear_modulus, shear_modulus};
pub use damping::{
    HERTZ_DAMPING_FACTOR, ImpactLaw, MIN_CLAMPED_RESTITUTION, PenetrationDamping, RestitutionTable,
    hertz_clamped_damping_ratio, hertz_clamped_restitution, hertz_damping_ratio, hertz_restitution,
    linear_clamped_damping_ratio, linear_clamped_restitution, linear_damping_ratio, linear_restitution,
};
pub use elastic::{HERTZ_CONTACT_TIME_FACTOR, NormalSpring, hertz_contact_time, hertz_max_depth, linear_contact_time};
pub use law::{PenetrationLaw, PenetrationLawError, PenetrationResponse};
pub use rolling::RollingResistance;
pub use state::PenetrationState;
pub use tangential::{TangentialSpring, TangentialStiffness};
