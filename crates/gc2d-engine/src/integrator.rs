//! The 6-value Gear predictor-corrector for Newton's equations of a polygon: x, y and the angle φ (reference §3,
//! App. F).
//!
//! Each body carries a [`GearState`]: its position and angle and their first five time derivatives, stored as
//! *scaled* derivatives r_n = Δt^n/n! · dⁿr/dtⁿ (F.10). In that form the predictor is the Pascal-triangle matrix
//! (F.11), free of Δt, and the corrector adds one multiple c_n of a single mismatch to every r_n (F.13).
//!
//! The engine calls, once per step and in this order:
//! 1. [`Gear6::predict`] on all integrated bodies (Taylor step to t + Δt);
//! 2. its force computation at the predicted positions and velocities ([`GearState::position`],
//!    [`GearState::velocity`], [`GearState::angle`], [`GearState::angular_velocity`]);
//! 3. [`Gear6::correct`] with the accelerations F/m and M/I of the same bodies, in the same order.
//!
//! Fixed and kinematically driven bodies are not integrated: the engine passes only the slice of integrated bodies
//! (it keeps them contiguous), or calls the per-body [`Gear6::predict_body`] / [`Gear6::correct_body`] for any
//! other selection. Nothing here allocates.
//!
//! Rotation is a scalar angle, counter-clockwise positive, integrated by exactly the same scheme as x and y (§3.5).
//!
//! [`VelocityVerlet`] is a second-order baseline with the same predict/correct interface and the same state column;
//! [`Integrator`] chooses between the schemes in the World's configuration and [`BodyIntegrator`] runs the choice.

use glam::DVec2;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::ops::{Add, Mul, Sub};
use thiserror::Error;

mod verlet;

pub use verlet::VelocityVerlet;

/// Number of values per coordinate: the coordinate and its first five derivatives.
pub const GEAR_ORDER: usize = 6;

/// Why a time step cannot be used.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum IntegratorError {
    /// Δt must be a positive finite number whose powers up to Δt⁵/120 are normal floating-point numbers
    /// (roughly 1e-61 s < Δt < 1e61 s), so that scaling and unscaling derivatives never divides by zero.
    #[error("time step {0} s is not usable: it must be positive and finite, with Δt⁵/120 a normal f64")]
    InvalidTimeStep(f64),
}

/// A validated time step Δt with its Taylor scale factors Δt^n/n! (F.10) and their reciprocals, precomputed so that
/// converting between scaled and physical derivatives is a multiplication.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TimeStep {
    dt: f64,
    scale: [f64; GEAR_ORDER],
    inverse_scale: [f64; GEAR_ORDER],
}

impl TimeStep {
    /// Validates `dt` (seconds). See [`IntegratorError::InvalidTimeStep`] for the admissible range.
    pub fn new(dt: f64) -> Result<Self, IntegratorError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(IntegratorError::InvalidTimeStep(dt));
        }
        let mut scale = [1.0; GEAR_ORDER];
        for n in 1..GEAR_ORDER {
            scale[n] = scale[n - 1] * dt / n as f64;
        }
        if !scale.iter().all(|s| s.is_normal()) {
            return Err(IntegratorError::InvalidTimeStep(dt));
        }
        let inverse_scale = scale.map(|s| 1.0 / s);
        Ok(Self { dt, scale, inverse_scale })
    }

    /// Δt in seconds.
    #[inline]
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// The factors Δt^n/n! (n = 0..5) that turn the n-th physical derivative into the n-th scaled derivative (F.10).
    #[inline]
    pub fn scale_factors(&self) -> &[f64; GEAR_ORDER] {
        &self.scale
    }
}

/// Which c₀ the corrector uses. The other five coefficients are the p = 2 row of Table F.1 either way.
///
/// Table F.1 gives c₀ = 3/20 for r̈ = f(r). For r̈ = f(r, ṙ) Allen & Tildesley recommend c₀ = 3/16 instead (§3.4).
/// gc2d's forces depend on velocity (normal damping, and the tangential spring grows by v_∥Δt each step), so the
/// default is [`GearC0::VelocityDependent`]. The thesis does not say which gc2d used (decision D4). Measured on a
/// harmonic oscillator resolved with 32 steps per period, 3/20 slowly pumps energy in while 3/16 slowly drains it
/// (both drift linearly in time, 1–2·10⁻⁵ of the energy per period), so 3/16 keeps the property the thesis chose Gear
/// for: numerical error does not feed energy into the system. 3/20 is the more accurate for conservative forces
/// (order ≈ 7 versus 5 on the oscillator); with velocity-dependent forces both are fifth order. See `docs/model.md`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
pub enum GearC0 {
    /// c₀ = 3/20: Gear's coefficient for forces that depend on positions only.
    PositionDependent,
    /// c₀ = 3/16: the coefficient for velocity-dependent forces (the default).
    #[default]
    VelocityDependent,
}

impl GearC0 {
    /// The numerical value of c₀.
    pub fn value(self) -> f64 {
        match self {
            GearC0::PositionDependent => 3.0 / 20.0,
            GearC0::VelocityDependent => 3.0 / 16.0,
        }
    }

    /// All corrector coefficients c₀..c₅ for a second-order ODE (Table F.1, p = 2, with this c₀).
    pub fn coefficients(self) -> [f64; GEAR_ORDER] {
        [self.value(), 251.0 / 360.0, 1.0, 11.0 / 18.0, 1.0 / 6.0, 1.0 / 60.0]
    }
}

/// The six physical (unscaled) time derivatives d⁰..d⁵ of a body's position and angle, in SI units (m, m/s, …, m/s⁵;
/// rad, rad/s, …, rad/s⁵; angles counter-clockwise positive).
///
/// This is what a checkpoint stores: gc2d writes `Com`, velocity, acceleration and `PC_TRANS3..5` for translation and
/// `ANGLE`, `OMEGA`, `OMEGA_DOT` and `PC_ROT3..5` for rotation (§3.5), so a checkpoint does not depend on Δt.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct PhysicalDerivatives {
    /// Position of the centre of mass and its derivatives 1..5.
    pub linear: [DVec2; GEAR_ORDER],
    /// Angle and its derivatives 1..5.
    pub angular: [f64; GEAR_ORDER],
}

/// The Gear state of one body: scaled derivatives r_n = Δt^n/n! · dⁿr/dtⁿ (F.10) of its position and of its angle.
///
/// The scaled values belong to one Δt; converting to or from physical derivatives, or to another Δt
/// ([`GearState::rescale`]), needs that [`TimeStep`]. Plain data (144 bytes) so that the engine can keep a
/// `Vec<GearState>` as one column of its particle store.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct GearState {
    /// Scaled derivatives 0..5 of the centre-of-mass position (all in metres).
    pub linear: [DVec2; GEAR_ORDER],
    /// Scaled derivatives 0..5 of the angle (all in radians), counter-clockwise positive.
    pub angular: [f64; GEAR_ORDER],
}

impl GearState {
    /// A state with the given position, velocity and acceleration (and the same for the angle); the third to fifth
    /// derivatives are zero, as for a body that is just being created.
    pub fn from_physical(
        position: DVec2,
        velocity: DVec2,
        acceleration: DVec2,
        angle: f64,
        angular_velocity: f64,
        angular_acceleration: f64,
        time_step: &TimeStep,
    ) -> Self {
        let mut physical = PhysicalDerivatives::default();
        physical.linear[..3].copy_from_slice(&[position, velocity, acceleration]);
        physical.angular[..3].copy_from_slice(&[angle, angular_velocity, angular_acceleration]);
        Self::from_physical_derivatives(&physical, time_step)
    }

    /// The state with all six physical derivatives given, e.g. when a checkpoint is loaded.
    pub fn from_physical_derivatives(physical: &PhysicalDerivatives, time_step: &TimeStep) -> Self {
        Self {
            linear: std::array::from_fn(|n| physical.linear[n] * time_step.scale[n]),
            angular: std::array::from_fn(|n| physical.angular[n] * time_step.scale[n]),
        }
    }

    /// All six physical derivatives, e.g. for writing a checkpoint.
    pub fn physical_derivatives(&self, time_step: &TimeStep) -> PhysicalDerivatives {
        PhysicalDerivatives {
            linear: std::array::from_fn(|n| self.linear[n] * time_step.inverse_scale[n]),
            angular: std::array::from_fn(|n| self.angular[n] * time_step.inverse_scale[n]),
        }
    }

    /// Centre-of-mass position (m).
    #[inline]
    pub fn position(&self) -> DVec2 {
        self.linear[0]
    }

    /// Centre-of-mass velocity (m/s).
    #[inline]
    pub fn velocity(&self, time_step: &TimeStep) -> DVec2 {
        self.linear[1] * time_step.inverse_scale[1]
    }

    /// Centre-of-mass acceleration (m/s²).
    #[inline]
    pub fn acceleration(&self, time_step: &TimeStep) -> DVec2 {
        self.linear[2] * time_step.inverse_scale[2]
    }

    /// Angle (rad, counter-clockwise positive).
    #[inline]
    pub fn angle(&self) -> f64 {
        self.angular[0]
    }

    /// Angular velocity (rad/s, counter-clockwise positive).
    #[inline]
    pub fn angular_velocity(&self, time_step: &TimeStep) -> f64 {
        self.angular[1] * time_step.inverse_scale[1]
    }

    /// Angular acceleration (rad/s², counter-clockwise positive).
    #[inline]
    pub fn angular_acceleration(&self, time_step: &TimeStep) -> f64 {
        self.angular[2] * time_step.inverse_scale[2]
    }

    /// Re-expresses the scaled derivatives for a new time step: r_n ← (Δt_new/Δt_old)^n · r_n. The physical
    /// derivatives do not change (exactly so when the ratio is a power of two).
    pub fn rescale(&mut self, from: &TimeStep, to: &TimeStep) {
        let ratio = to.dt / from.dt;
        let mut factor = 1.0;
        for n in 1..GEAR_ORDER {
            factor *= ratio;
            self.linear[n] *= factor;
            self.angular[n] *= factor;
        }
    }

    /// Sets subnormal values (non-zero, below 2.2e-308 in magnitude) of derivatives 3 to 5 to zero. A particle in
    /// free flight has a constant acceleration, so these derivatives decay towards zero after its last contact and
    /// can end up alternating between ±5e-324 for ever; Intel CPUs compute with subnormal numbers through a slow
    /// microcode path, and such particles made the corrector of a settled pile of squares three times as slow per
    /// body as usual (docs/performance.md, "Subnormal numbers in the Gear state"). A subnormal derivative is far
    /// below the last bit of every physical quantity it is added to, so zero changes no position or velocity.
    /// Derivatives 0 to 2 (position, velocity, acceleration) were never seen subnormal and are left alone.
    #[inline]
    pub(crate) fn flush_subnormals(&mut self) {
        for derivative in &mut self.linear[3..] {
            derivative.x = zero_if_subnormal(derivative.x);
            derivative.y = zero_if_subnormal(derivative.y);
        }
        for derivative in &mut self.angular[3..] {
            *derivative = zero_if_subnormal(*derivative);
        }
    }
}

/// `x`, or zero where `x` is subnormal (or zero: a negative zero becomes a positive one). The comparison of the
/// magnitude compiles to fewer instructions than `f64::is_subnormal`.
#[inline(always)]
fn zero_if_subnormal(x: f64) -> f64 {
    if x.abs() < f64::MIN_POSITIVE { 0.0 } else { x }
}

/// The 6-value Gear predictor-corrector for second-order ODEs with one corrector pass per step (§3.3, §3.4).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Gear6 {
    time_step: TimeStep,
    c0: GearC0,
    coefficients: [f64; GEAR_ORDER],
}

impl Gear6 {
    /// An integrator with time step `time_step` and corrector coefficient `c0`.
    pub fn new(time_step: TimeStep, c0: GearC0) -> Self {
        Self { time_step, c0, coefficients: c0.coefficients() }
    }

    /// The time step the states are scaled with.
    #[inline]
    pub fn time_step(&self) -> &TimeStep {
        &self.time_step
    }

    /// The c₀ choice.
    #[inline]
    pub fn c0(&self) -> GearC0 {
        self.c0
    }

    /// Switches to a new time step and rescales `states` (all bodies, integrated or not) to it.
    pub fn set_time_step(&mut self, time_step: TimeStep, states: &mut [GearState]) {
        for state in states {
            state.rescale(&self.time_step, &time_step);
        }
        self.time_step = time_step;
    }

    /// Predictor for every state in `states` (F.11).
    pub fn predict(&self, states: &mut [GearState]) {
        for state in states {
            self.predict_body(state);
        }
    }

    /// Corrector for every state in `states` (F.13). `linear_acceleration[i]` (F/m, m/s²) and
    /// `angular_acceleration[i]` (M/I, rad/s²) must be evaluated at the predicted state of `states[i]`; the three
    /// slices must have the same length (a shorter slice limits the bodies corrected).
    pub fn correct(&self, states: &mut [GearState], linear_acceleration: &[DVec2], angular_acceleration: &[f64]) {
        debug_assert_eq!(states.len(), linear_acceleration.len());
        debug_assert_eq!(states.len(), angular_acceleration.len());
        for ((state, &a), &alpha) in states.iter_mut().zip(linear_acceleration).zip(angular_acceleration) {
            self.correct_body(state, a, alpha);
        }
    }

    /// Predictor for one body: the Taylor step r(t + Δt) ≈ Σ r_n, i.e. the Pascal-triangle matrix (F.11).
    #[inline(always)]
    pub fn predict_body(&self, state: &mut GearState) {
        predict_scaled(&mut state.linear);
        predict_scaled(&mut state.angular);
    }

    /// Corrector for one body: Δ = (Δt²/2)·a − r₂ᵖ and r_n += c_n·Δ (F.13), for translation and rotation.
    #[inline]
    pub fn correct_body(&self, state: &mut GearState, linear_acceleration: DVec2, angular_acceleration: f64) {
        let scale2 = self.time_step.scale[2];
        correct_scaled(&mut state.linear, linear_acceleration * scale2, &self.coefficients);
        correct_scaled(&mut state.angular, angular_acceleration * scale2, &self.coefficients);
        state.flush_subnormals();
    }
}

/// Pascal-triangle predictor (F.11) in place: each row uses only higher-order values, which are updated later.
#[inline(always)]
fn predict_scaled<T>(r: &mut [T; GEAR_ORDER])
where
    T: Copy + Add<Output = T> + Mul<f64, Output = T>,
{
    let [r0, r1, r2, r3, r4, r5] = *r;
    r[0] = r0 + r1 + r2 + r3 + r4 + r5;
    r[1] = r1 + r2 * 2.0 + r3 * 3.0 + r4 * 4.0 + r5 * 5.0;
    r[2] = r2 + r3 * 3.0 + r4 * 6.0 + r5 * 10.0;
    r[3] = r3 + r4 * 4.0 + r5 * 10.0;
    r[4] = r4 + r5 * 5.0;
}

/// Gear corrector (F.13) in place, given the scaled second derivative the ODE demands at the predicted state.
#[inline(always)]
fn correct_scaled<T>(r: &mut [T; GEAR_ORDER], corrected_r2: T, coefficients: &[f64; GEAR_ORDER])
where
    T: Copy + Add<Output = T> + Sub<Output = T> + Mul<f64, Output = T>,
{
    let mismatch = corrected_r2 - r[2];
    for (value, &c) in r.iter_mut().zip(coefficients) {
        *value = *value + mismatch * c;
    }
}

/// Which scheme integrates the particles: the 6-value Gear predictor-corrector of the thesis (§3) with its c₀, or
/// velocity Verlet, a second-order baseline for comparison (see `docs/validation.md`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Integrator {
    /// 6-value Gear predictor-corrector with the given c₀.
    Gear6(GearC0),
    /// Velocity Verlet (kick–drift–kick) with forces evaluated at the half-kicked velocity ([`VelocityVerlet`]).
    VelocityVerlet,
}

impl Default for Integrator {
    /// Gear with c₀ = 3/16, the thesis's integrator with the coefficient for velocity-dependent forces (D4).
    fn default() -> Self {
        Integrator::Gear6(GearC0::default())
    }
}

/// A configured [`Integrator`] with its time step: the per-body predict and correct calls the engine makes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum BodyIntegrator {
    /// The Gear predictor-corrector.
    Gear6(Gear6),
    /// Velocity Verlet.
    VelocityVerlet(VelocityVerlet),
}

impl BodyIntegrator {
    /// The scheme `integrator` with time step `time_step`.
    pub fn new(integrator: Integrator, time_step: TimeStep) -> Self {
        match integrator {
            Integrator::Gear6(c0) => BodyIntegrator::Gear6(Gear6::new(time_step, c0)),
            Integrator::VelocityVerlet => BodyIntegrator::VelocityVerlet(VelocityVerlet::new(time_step)),
        }
    }

    /// The time step the states are scaled with.
    #[inline]
    pub fn time_step(&self) -> &TimeStep {
        match self {
            BodyIntegrator::Gear6(gear) => gear.time_step(),
            BodyIntegrator::VelocityVerlet(verlet) => verlet.time_step(),
        }
    }

    /// Advances one body to t + Δt before the force evaluation (Gear predictor, or Verlet half kick and drift).
    /// Always inlined (with the Gear predictor): it runs in two row loops, the predictor's own pass and the vertex
    /// transform's, and the optimiser left it out of line for two callers (0.5–0.7 % more instructions a step).
    #[inline(always)]
    pub fn predict_body(&self, state: &mut GearState) {
        match self {
            BodyIntegrator::Gear6(gear) => gear.predict_body(state),
            BodyIntegrator::VelocityVerlet(verlet) => verlet.predict_body(state),
        }
    }

    /// Completes the step of one body with the accelerations evaluated after [`Self::predict_body`] (Gear corrector,
    /// or Verlet's second half kick).
    #[inline]
    pub fn correct_body(&self, state: &mut GearState, linear_acceleration: DVec2, angular_acceleration: f64) {
        match self {
            BodyIntegrator::Gear6(gear) => gear.correct_body(state, linear_acceleration, angular_acceleration),
            BodyIntegrator::VelocityVerlet(verlet) => {
                verlet.correct_body(state, linear_acceleration, angular_acceleration)
            }
        }
    }
}

/// The upper bound on Δt from eq. (2.9): (π/10)·sqrt(m/E), a tenth of a contact half-period of the lightest particle
/// (mass `mass_min` in kg per unit thickness, Young's modulus `e_modulus` in N/m), so that about ten steps resolve a
/// collision. `None` unless both arguments are positive and finite. It is an upper bound only; §3.6 asks for runs at
/// smaller Δt to confirm a result.
pub fn max_stable_time_step(mass_min: f64, e_modulus: f64) -> Option<f64> {
    let valid = |x: f64| x.is_finite() && x > 0.0;
    (valid(mass_min) && valid(e_modulus)).then(|| PI / 10.0 * (mass_min / e_modulus).sqrt())
}

/// The bound (2.9) for elongated particles (§3.6): the mass is that of the largest disk about the centre of mass that
/// fits inside the thinnest particle, m = π·r_min²·ρ (`inscribed_radius_min` in m, `area_density` ρ in kg/m²).
/// `None` unless all arguments are positive and finite.
pub fn max_stable_time_step_elongated(inscribed_radius_min: f64, area_density: f64, e_modulus: f64) -> Option<f64> {
    if !(inscribed_radius_min.is_finite() && inscribed_radius_min > 0.0) {
        return None;
    }
    max_stable_time_step(PI * inscribed_radius_min * inscribed_radius_min * area_density, e_modulus)
}

#[cfg(test)]
mod tests;
