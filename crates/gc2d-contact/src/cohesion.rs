//! Cohesion: an attraction proportional to the contact-line length (2.28).

use serde::{Deserialize, Serialize};

/// Cohesive force F_coh = k_coh·|c1c2| (2.28), attractive (along −n on body i), acting at the contact point and only
/// while the bodies overlap (there is no contact line otherwise).
///
/// Because the approach of the bodies changes the overlap area by dA = |c1c2|·dh, this force is exactly the
/// gradient of the potential U_coh = −k_coh·A: cohesion stores −k_coh·A and dissipates nothing.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Cohesion {
    /// Cohesion strength k_coh, N/m.
    pub k_coh: f64,
}

impl Cohesion {
    /// Magnitude of the attraction, N, for a contact line of length `chord_length` (2.28).
    #[inline]
    pub fn force(&self, chord_length: f64) -> f64 {
        self.k_coh * chord_length
    }

    /// Cohesive energy −k_coh·A in J (per unit thickness) stored in a contact of overlap area `area`.
    #[inline]
    pub fn energy(&self, area: f64) -> f64 {
        -self.k_coh * area
    }
}
