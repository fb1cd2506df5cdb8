//! Per-contact history carried from step to step (reference §2.7, §2.8, App. B.2 `Old_Area`, `Summ_Friction`).

use crate::ContactConstants;
use serde::{Deserialize, Serialize};

/// What a contact remembers between steps. Small and `Copy`: it lives in the broadphase pair list, and the default
/// value is "not touching".
///
/// The contact is active (touching) exactly when `constants` is `Some`; all other fields are zero when it is not.
/// When the overlap area returns to zero the whole state resets, including the spring (decision D11).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct ContactState {
    /// l, m⊥, m∥ frozen at the first overlapping step; `None` while the bodies do not touch.
    pub constants: Option<ContactConstants>,
    /// Overlap area of the last step, m² (gc2d's `Old_Area`).
    pub previous_area: f64,
    /// Contact-line length of the last step, m (for the energy bookkeeping).
    pub previous_chord: f64,
    /// Stored tangential spring force S along the tangent, N (gc2d's `Summ_Friction`, elastic part only, decision D3).
    pub spring: f64,
    /// Normal elastic energy U⊥ accumulated by the trapezoid rule, J.
    pub normal_energy: f64,
}

impl ContactState {
    /// True while the bodies overlap (the contact is active).
    #[inline]
    pub fn is_touching(&self) -> bool {
        self.constants.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn state_is_small_and_starts_not_touching() {
        assert!(std::mem::size_of::<ContactState>() <= 64, "the state lives in every broadphase pair");
        let state = ContactState::default();
        assert!(!state.is_touching());
        assert_eq!((state.previous_area, state.spring, state.normal_energy), (0.0, 0.0, 0.0));
    }
}
