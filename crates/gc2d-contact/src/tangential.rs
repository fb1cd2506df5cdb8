//! Tangential sub-model: Cundall–Strack spring with tangential damping and a Coulomb cap (2.23–2.27).

use crate::reciprocal_or_zero;
use serde::{Deserialize, Serialize};

/// Cundall–Strack friction: a spring attached at the contact point, dragged along when it exceeds the Coulomb limit.
///
/// Per step, with sliding velocity v∥ (of i relative to j, along the tangent) and k_t = (2/7)·E (2.23):
/// - trial spring S* = S_old − k_t·v∥·Δt (2.23; the minus makes the force on i oppose the sliding, decision D2);
/// - cap C = μ·F⊥ with the *elastic* F⊥ (2.24; decision D3);
/// - stored spring S = clamp(S*, ±C): the elastic part only, truncated while sliding (D3);
/// - damping D∥ = −sqrt(k_t·m∥)·v∥ (2.26);
/// - force on i along the tangent F∥ = clamp(S + D∥, ±C) (2.27 with the stored part kept elastic).
///
/// The stored scalar S is re-applied along the current tangent each step (it does not rotate with the contact line).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CundallStrack {
    /// Friction coefficient μ (gc2d's `MUE_STATISCH`).
    pub mu: f64,
}

/// Result of one tangential step: the force, the new spring, and the energy terms of the step (J).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TangentialStep {
    /// F∥: tangential force on body i along the tangent, N.
    pub force: f64,
    /// The spring S to store for the next step, N.
    pub spring: f64,
    /// (S² − S_old²)/(2k_t).
    pub spring_energy_change: f64,
    /// −(F∥ − S)·v∥·Δt ≥ 0: the damping part that survived the cap, times the tangential displacement.
    pub damping_dissipation: f64,
    /// −S·(S − S*)/k_t ≥ 0: the spring force (then at the cap) times the slip the clamp removed.
    pub sliding_dissipation: f64,
}

impl CundallStrack {
    /// Tangential stiffness over Young's modulus, 2/7, "adapted to Hertzian contact without rotation" (2.23).
    pub const STIFFNESS_FACTOR: f64 = 2.0 / 7.0;

    /// k_t = (2/7)·E in N/m.
    #[inline]
    pub fn stiffness(e_modulus: f64) -> f64 {
        Self::STIFFNESS_FACTOR * e_modulus
    }

    /// Energy S²/(2k_t) stored in a spring of force `spring`, J; zero if k_t is not positive.
    #[inline]
    pub fn spring_energy(e_modulus: f64, spring: f64) -> f64 {
        0.5 * spring * spring * reciprocal_or_zero(Self::stiffness(e_modulus))
    }

    /// One step of the spring: from `spring` (S_old) with sliding velocity `sliding_velocity` over `dt`, against
    /// the elastic normal force `elastic_normal_force` (the cap is μ times it).
    #[inline]
    pub fn step(
        &self,
        e_modulus: f64,
        tangential_mass: f64,
        spring: f64,
        sliding_velocity: f64,
        dt: f64,
        elastic_normal_force: f64,
    ) -> TangentialStep {
        let stiffness = Self::stiffness(e_modulus);
        let inv_stiffness = reciprocal_or_zero(stiffness);
        let cap = (self.mu * elastic_normal_force).max(0.0);
        let displacement = sliding_velocity * dt;
        let trial = spring - stiffness * displacement;
        let stored = clamp_magnitude(trial, cap);
        let damping = -(stiffness * tangential_mass).sqrt() * sliding_velocity;
        let force = clamp_magnitude(stored + damping, cap);
        TangentialStep {
            force,
            spring: stored,
            spring_energy_change: 0.5 * (stored * stored - spring * spring) * inv_stiffness,
            damping_dissipation: -(force - stored) * displacement,
            sliding_dissipation: -stored * (stored - trial) * inv_stiffness,
        }
    }
}

/// `x` limited to [−cap, cap] for cap ≥ 0 (unlike `f64::clamp`, never panics).
#[inline]
fn clamp_magnitude(x: f64, cap: f64) -> f64 {
    x.min(cap).max(-cap)
}

#[cfg(test)]
mod tests {
    use super::*;

    const E: f64 = 1e7;
    const MASS: f64 = 0.01;
    const DT: f64 = 1e-6;

    #[test]
    fn stick_builds_the_spring_linearly_and_opposes_sliding() {
        let friction = CundallStrack { mu: 0.5 };
        let k_t = CundallStrack::stiffness(E);
        let v = 1e-4;
        let mut spring = 0.0;
        for step in 1..=50 {
            let out = friction.step(E, MASS, spring, v, DT, 10.0);
            let expected_spring = -(step as f64) * k_t * v * DT;
            assert!((out.spring - expected_spring).abs() < 1e-12, "step {step}");
            let damping = -(k_t * MASS).sqrt() * v;
            assert!((out.force - (expected_spring + damping)).abs() < 1e-12);
            assert!(out.force < 0.0, "the force on i opposes its sliding along +t");
            assert_eq!(out.sliding_dissipation, 0.0);
            spring = out.spring;
        }
    }

    #[test]
    fn slip_caps_the_force_at_mu_f_and_truncates_the_spring() {
        let friction = CundallStrack { mu: 0.3 };
        let normal = 10.0;
        let out = friction.step(E, MASS, -2.9, 0.05, DT, normal);
        assert_eq!(out.force, -0.3 * normal);
        assert_eq!(out.spring, -0.3 * normal);
        assert!(out.sliding_dissipation > 0.0);
        // Steady sliding: the slip is the whole displacement and the dissipation is exactly C·|v|·Δt.
        let steady = friction.step(E, MASS, -3.0, 0.05, DT, normal);
        assert_eq!(steady.spring, -3.0);
        assert!((steady.sliding_dissipation - 3.0 * 0.05 * DT).abs() < 1e-18);
        assert_eq!(steady.damping_dissipation, 0.0);
        assert_eq!(steady.spring_energy_change, 0.0);
    }

    #[test]
    fn unloading_at_rest_truncates_the_spring_at_the_cap() {
        let friction = CundallStrack { mu: 0.5 };
        let k_t = CundallStrack::stiffness(E);
        // A spring of 4 N; the normal force drops so that the cap becomes 3 N; no sliding.
        let out = friction.step(E, MASS, 4.0, 0.0, DT, 6.0);
        assert_eq!(out.spring, 3.0);
        assert_eq!(out.force, 3.0);
        assert!((out.spring_energy_change + (16.0 - 9.0) / (2.0 * k_t)).abs() < 1e-18);
        // The slip (4 − 3)/k_t happens at the cap of 3 N.
        assert!((out.sliding_dissipation - 3.0 * (4.0 - 3.0) / k_t).abs() < 1e-18);
    }
}
