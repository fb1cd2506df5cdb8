//! Velocity Verlet (kick–drift–kick), the second-order baseline the Gear predictor-corrector is compared with.
//!
//! The state lives in the same [`GearState`] column as Gear's, with the same scaling (F.10): r₀ = x, r₁ = Δt·v,
//! r₂ = (Δt²/2)·a, where a is the acceleration of the *last* force evaluation. r₃..r₅ are not used and stay as they
//! were seeded (zero for every new body). One step, in scaled form:
//!
//! 1. [`VelocityVerlet::predict_body`]: half kick v_{n+½} = v_n + (Δt/2)·a_n, i.e. r₁ += r₂, then drift
//!    x_{n+1} = x_n + Δt·v_{n+½}, i.e. r₀ += r₁. The body's velocity now reads v_{n+½}.
//! 2. The engine evaluates the forces at x_{n+1} **with the half-kicked velocity v_{n+½}**.
//! 3. [`VelocityVerlet::correct_body`]: r₂ = (Δt²/2)·a_{n+1}, then the second half kick r₁ += r₂.
//!
//! Why v_{n+½} in step 2: it is the velocity that actually carried the body from x_n to x_{n+1}, so the tangential
//! spring's increment v_∥·Δt (2.23) is exactly the displacement of the step, and the viscous terms see the same
//! interval [t_n, t_{n+1}] as the normal damping, which the contact law computes from positions as (A − A_old)/Δt
//! (2.21) anyway. The scheme stays explicit with one force evaluation per step. The price: for velocity-dependent
//! forces the force uses a velocity half a step old, so the damping terms are only first-order accurate. For
//! forces that depend on positions only, the scheme is the symplectic, time-reversible Störmer–Verlet method of
//! order 2. `docs/model.md` ("Velocity Verlet") records the measured consequences.

use super::{GearState, TimeStep};
use glam::DVec2;
use serde::{Deserialize, Serialize};

/// The velocity Verlet integrator for translation and rotation, with one force evaluation per step.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct VelocityVerlet {
    time_step: TimeStep,
}

impl VelocityVerlet {
    /// An integrator with time step `time_step`.
    pub fn new(time_step: TimeStep) -> Self {
        Self { time_step }
    }

    /// The time step the states are scaled with.
    #[inline]
    pub fn time_step(&self) -> &TimeStep {
        &self.time_step
    }

    /// First half kick and drift: v ← v + (Δt/2)·a, x ← x + Δt·v (in scaled form r₁ += r₂, r₀ += r₁).
    #[inline]
    pub fn predict_body(&self, state: &mut GearState) {
        state.linear[1] += state.linear[2];
        state.linear[0] += state.linear[1];
        state.angular[1] += state.angular[2];
        state.angular[0] += state.angular[1];
    }

    /// Stores the new accelerations (F/m, M/I evaluated after [`Self::predict_body`]) and applies the second half
    /// kick v ← v + (Δt/2)·a.
    #[inline]
    pub fn correct_body(&self, state: &mut GearState, linear_acceleration: DVec2, angular_acceleration: f64) {
        let scale2 = self.time_step.scale[2];
        state.linear[2] = linear_acceleration * scale2;
        state.linear[1] += state.linear[2];
        state.angular[2] = angular_acceleration * scale2;
        state.angular[1] += state.angular[2];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// Runs x'' = −ω²x (ω = 1, x(0) = 1, v(0) = 0) for `periods` periods with `steps_per_period` steps; returns the
    /// final velocity and the largest |E − E₀|/E₀ over the first and over the last ten periods.
    fn oscillator(steps_per_period: usize, periods: usize) -> (f64, f64, f64) {
        let ts = TimeStep::new(2.0 * PI / steps_per_period as f64).unwrap();
        let verlet = VelocityVerlet::new(ts);
        let mut state = GearState::from_physical(DVec2::X, DVec2::ZERO, -DVec2::X, 0.0, 0.0, 0.0, &ts);
        let energy = |s: &GearState| 0.5 * (s.velocity(&ts).length_squared() + s.position().length_squared());
        let total = steps_per_period * periods;
        let window = 10 * steps_per_period;
        let (mut first, mut last) = (0.0_f64, 0.0_f64);
        for step in 1..=total {
            verlet.predict_body(&mut state);
            let a = -state.position();
            verlet.correct_body(&mut state, a, 0.0);
            let error = (energy(&state) - 0.5).abs() / 0.5;
            if step <= window {
                first = first.max(error);
            }
            if step + window > total {
                last = last.max(error);
            }
        }
        (state.velocity(&ts).x, first, last)
    }

    #[test]
    fn free_fall_is_exact_to_round_off() {
        // Constant acceleration: kick–drift–kick reproduces x0 + v0·t + a·t²/2 exactly in exact arithmetic; in f64
        // the 10⁴ steps leave only accumulated round-off (observed ≤ 1e-13 of the values).
        let ts = TimeStep::new(1e-4).unwrap();
        let verlet = VelocityVerlet::new(ts);
        let (x0, v0, a) = (DVec2::new(0.2, 1.0), DVec2::new(0.3, 2.0), DVec2::new(0.0, -9.81));
        let (w0, alpha) = (5.0, -40.0);
        let mut state = GearState::from_physical(x0, v0, a, 0.1, w0, alpha, &ts);
        for n in 1..=10_000 {
            verlet.predict_body(&mut state);
            verlet.correct_body(&mut state, a, alpha);
            let t = n as f64 * ts.dt();
            let expected = x0 + v0 * t + 0.5 * a * t * t;
            let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * (1.0 + y.abs());
            let p = state.position();
            assert!(close(p.x, expected.x) && close(p.y, expected.y), "step {n}: {:?}", p - expected);
            let v = state.velocity(&ts);
            assert!(close(v.x, v0.x + a.x * t) && close(v.y, v0.y + a.y * t), "step {n}: {v:?}");
            assert!(close(state.angle(), 0.1 + w0 * t + 0.5 * alpha * t * t), "step {n}");
            assert!(close(state.angular_velocity(&ts), w0 + alpha * t), "step {n}");
        }
    }

    #[test]
    fn harmonic_oscillator_energy_error_is_bounded() {
        // Symplectic: the discrete flow conserves ½v² + ½ω²x²(1 − ω²Δt²/4) exactly, so the energy error oscillates
        // with an amplitude of about (ωΔt)²/4 and does not grow. At 32 steps per period over 1000 periods, observed
        // 9.638e-3 in the first ten periods and 9.633e-3 in the last ten (bound (ωΔt)²/4 = 9.638e-3).
        let (_, first, last) = oscillator(32, 1000);
        let bound = (2.0 * PI / 32.0_f64).powi(2) / 4.0;
        assert!(
            first <= bound * (1.0 + 1e-9) && last <= bound * (1.0 + 1e-9),
            "energy error {first:e} then {last:e}, bound {bound:e}"
        );
        assert!((last / first - 1.0).abs() < 1e-2, "energy error grows: {first:e} → {last:e}");
    }

    #[test]
    fn position_error_is_second_order() {
        // After one period v = 0; the phase error ∝ Δt² shows in the velocity (the position at the turning point
        // is only hit to second order in the phase). Observed log₂ ratios 2.00, 2.00.
        let errors: Vec<f64> = [32, 64, 128].iter().map(|&n| oscillator(n, 1).0.abs()).collect();
        for w in errors.windows(2) {
            let order = (w[0] / w[1]).log2();
            assert!((order - 2.0).abs() < 0.05, "observed order {order}: {errors:?}");
        }
    }
}
