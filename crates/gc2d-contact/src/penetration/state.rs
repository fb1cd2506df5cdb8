//! Per-pair history of a penetration contact, carried from step to step.

use serde::{Deserialize, Serialize};

/// What a penetration contact remembers between steps: five numbers, 40 bytes, `Copy`; the default value is "not
/// touching".
///
/// The contact is active exactly when `previous_depth > 0`; a contact episode runs from the first touching step to
/// the first step that does not touch, and everything resets then. The stored energies are not kept: they follow
/// from the depth and the springs ([`super::PenetrationLaw::stored_energy`]), the normal one exactly.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct PenetrationState {
    /// Normal approach speed of the contact points at the first touching step of the episode, m/s (≥ 0).
    pub impact_speed: f64,
    /// The episode's damping ratio D, fixed at the first touching step (from e(impact_speed) where e is given).
    pub damping_ratio: f64,
    /// Penetration depth of the last step, m; 0 while not touching.
    pub previous_depth: f64,
    /// Stored tangential spring force S along the tangent, N (elastic part only, |S| ≤ μ·F_n).
    pub spring: f64,
    /// Stored rolling spring moment M on body i, N·m (|M| ≤ μ_r·R*·F_n).
    pub rolling: f64,
}

impl PenetrationState {
    /// True while the bodies touch (the contact is active).
    #[inline]
    pub fn is_touching(&self) -> bool {
        self.previous_depth > 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn state_is_small_and_starts_not_touching() {
        assert_eq!(std::mem::size_of::<PenetrationState>(), 40, "the state lives in every broadphase pair");
        assert!(!PenetrationState::default().is_touching());
    }
}
