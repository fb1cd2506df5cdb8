//! The energy terms one contact reports for one step, for the engine's energy ledger.

use serde::{Deserialize, Serialize};

/// Energy stored and dissipated by one contact over the step that ends at this evaluation, in J (per unit
/// thickness). The definitions are in `docs/model.md` ("Contact law", energy).
///
/// The three `*_change` terms add up to the change of [`crate::ContactLaw::stored_energy`] from the previous to
/// the next [`crate::ContactState`] (for the penetration laws: of [`crate::PenetrationLaw::stored_energy`], with the
/// rolling spring's terms booked with the tangential ones). The work the contact force does on the relative motion of the bodies over the
/// step is `−`[`EnergyTerms::absorbed`]; the virtual surface velocity of a wall injects
/// [`EnergyTerms::surface_work`] on top.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct EnergyTerms {
    /// Change of the normal elastic energy U⊥ (trapezoid rule, may be negative).
    pub normal_elastic_change: f64,
    /// Change of the tangential spring energy S²/(2k_t).
    pub spring_change: f64,
    /// Change of the cohesive energy −k_coh·A.
    pub cohesion_change: f64,
    /// Dissipated by the normal damping, ≥ 0.
    pub normal_damping: f64,
    /// Dissipated by the tangential damping, ≥ 0.
    pub tangential_damping: f64,
    /// Dissipated by sliding (Coulomb cap times slip), ≥ 0.
    pub sliding: f64,
    /// Stored energy dropped when the contact opens, i.e. the bodies separate (both energies reset to zero); either sign.
    pub opening_residual: f64,
    /// Work done on the bodies by the virtual surface velocities of walls (reference §2.11).
    pub surface_work: f64,
}

impl EnergyTerms {
    /// Change of the energy stored in the contact over the step.
    pub fn stored_change(&self) -> f64 {
        self.normal_elastic_change + self.spring_change + self.cohesion_change
    }

    /// Energy dissipated by damping and sliding over the step (≥ 0).
    pub fn dissipation(&self) -> f64 {
        self.normal_damping + self.tangential_damping + self.sliding
    }

    /// Energy the contact took from the relative motion over the step: stored change + dissipation + residual.
    pub fn absorbed(&self) -> f64 {
        self.stored_change() + self.dissipation() + self.opening_residual
    }
}
