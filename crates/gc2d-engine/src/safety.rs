//! Safety before speed: the time-step bound checked at load, and blow-up detection during the run (reference §3.6,
//! §10.4). Every error names the time, the bodies involved and a time step to try.

use crate::bodies::{Bodies, BodyId};
use crate::integrator::max_stable_time_step_elongated;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Limits of the run-time blow-up checks.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SafetyLimits {
    /// Largest overlap area allowed, as a fraction of the smaller particle's area. Settled piles at the thesis's
    /// parameters stay below 1e-3; an overlap of 5 % means a particle has tunnelled into another.
    pub max_overlap_fraction: f64,
    /// Largest unexplained energy gain allowed, as a fraction of the energy scale of the run (see
    /// [`crate::ledger::EnergyLedger::energy_scale`]). The ledger books damping at the end-of-step force, so its error
    /// is first order in Δt and can reach a quarter of the energy in play during the very first contact steps of a
    /// sound damped run; a blow-up creates energy many times the energy in play. The default, 1.0, stops a run only
    /// when it has gained more energy than everything the run has moved around.
    pub max_energy_gain_fraction: f64,
    /// Run with a Δt above the stable bound anyway (for experiments on instability).
    pub allow_unsafe_time_step: bool,
}

impl Default for SafetyLimits {
    fn default() -> Self {
        Self { max_overlap_fraction: 0.05, max_energy_gain_fraction: 1.0, allow_unsafe_time_step: false }
    }
}

/// A run that cannot start or cannot go on.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SafetyError {
    /// Δt above the bound (π/10)·sqrt(m/E) of eq. (2.9).
    #[error(
        "time step {dt:.3e} s is above the stable bound {safe_dt:.3e} s = (π/10)·sqrt(m/E) for particle {particle} \
         (m = π·r²·ρ with its inscribed radius r = {inscribed_radius:.3e} m, E = {e_modulus:.3e} N/m); \
         use a time step of at most {safe_dt:.3e} s, or allow unsafe time steps explicitly"
    )]
    UnsafeTimeStep {
        /// The requested Δt, s.
        dt: f64,
        /// The bound, s.
        safe_dt: f64,
        /// The particle that sets the bound.
        particle: u32,
        /// Its inscribed radius, m.
        inscribed_radius: f64,
        /// Young's modulus, N/m.
        e_modulus: f64,
    },
    /// A position, velocity or kinetic energy became NaN or infinite.
    #[error(
        "the simulation blew up at t = {time:.6} s (step {step}): particle {body} has a position, velocity or kinetic energy \
         that is not a finite number; reduce the time step (try {suggested_dt:.3e} s)"
    )]
    NotFinite {
        /// Simulated time, s.
        time: f64,
        /// Step number.
        step: u64,
        /// The first offending body.
        body: u32,
        /// A time step to try, s.
        suggested_dt: f64,
    },
    /// Two bodies overlap far more than elastic contacts ever do: one has tunnelled into the other.
    #[error(
        "the simulation blew up at t = {time:.6} s (step {step}): bodies {a} and {b} overlap by {percent:.1} % of the \
         smaller particle's area (limit {limit_percent:.1} %); a particle moved too far in one step — reduce the \
         time step (try {suggested_dt:.3e} s)"
    )]
    ExcessiveOverlap {
        /// Simulated time, s.
        time: f64,
        /// Step number.
        step: u64,
        /// First body.
        a: u32,
        /// Second body.
        b: u32,
        /// Overlap in percent of the smaller area.
        percent: f64,
        /// The limit in percent.
        limit_percent: f64,
        /// A time step to try, s.
        suggested_dt: f64,
    },
    /// The total energy rose by more than the work put in can explain.
    #[error(
        "the simulation blew up at t = {time:.6} s (step {step}): the energy rose by {gain:.3e} J more than the work \
         done on the system explains ({percent:.0} % of the run's energy scale); reduce the time step \
         (try {suggested_dt:.3e} s)"
    )]
    EnergyJump {
        /// Simulated time, s.
        time: f64,
        /// Step number.
        step: u64,
        /// Unexplained gain, J (per unit thickness).
        gain: f64,
        /// The gain in percent of the energy scale.
        percent: f64,
        /// A time step to try, s.
        suggested_dt: f64,
    },
}

/// The stable time step of the particles in `bodies` for Young's modulus `e_modulus`, and the particle that sets
/// it; `None` when there are no particles.
///
/// gc2d-rs always uses the inscribed-circle mass m = π·r_in²·ρ (reference §3.6). For round particles it is within a
/// few percent of the mass itself, and for elongated ones it is the bound the thesis asks for, so one rule serves all.
pub fn stable_time_step(bodies: &Bodies, e_modulus: f64) -> Option<(f64, BodyId)> {
    bodies
        .particles()
        .filter_map(|id| {
            let i = id.index();
            let density = bodies.mass[i] / bodies.area[i];
            let radius = bodies.inscribed_radius[i] * bodies.pose[i].scale;
            max_stable_time_step_elongated(radius, density, e_modulus).map(|dt| (dt, id))
        })
        .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)))
}

/// Refuses `dt` above the stable bound unless `limits` allow it.
pub fn check_time_step(bodies: &Bodies, e_modulus: f64, dt: f64, limits: &SafetyLimits) -> Result<(), SafetyError> {
    let Some((safe_dt, particle)) = stable_time_step(bodies, e_modulus) else { return Ok(()) };
    if dt <= safe_dt || limits.allow_unsafe_time_step {
        return Ok(());
    }
    let i = particle.index();
    Err(SafetyError::UnsafeTimeStep {
        dt,
        safe_dt,
        particle: particle.0,
        inscribed_radius: bodies.inscribed_radius[i] * bodies.pose[i].scale,
        e_modulus,
    })
}

/// The time step to suggest after a blow-up: a quarter of the current one, and never above the stable bound.
pub fn suggested_time_step(dt: f64, stable_dt: Option<f64>) -> f64 {
    let quarter = dt / 4.0;
    stable_dt.map_or(quarter, |safe| quarter.min(safe / 2.0))
}
