//! The energy ledger: where every joule of a run is, so that E_now − E_0 = W_in − D is checkable at any time.
//!
//! Stored energies (kinetic, potential, contact, drag springs) are recomputed from the state; inputs and dissipation
//! are summed step by step from what the contact law and the drivers report. `balance_error` is what the two sides
//! disagree by: time-integration error in a sound run, a blow-up when it jumps.

use crate::narrowphase::LedgerTerms;
use serde::{Deserialize, Serialize};

/// Energies of a World, J per unit thickness.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct EnergyLedger {
    /// Σ ½ m v² over particles.
    pub kinetic_translational: f64,
    /// Σ ½ I ω² over particles.
    pub kinetic_rotational: f64,
    /// Σ m g y over particles, with the current g.
    pub potential: f64,
    /// Energy stored in the contacts: normal elastic, tangential springs and cohesion.
    pub contact_stored: f64,
    /// Energy stored in the drag springs, ½ K d².
    pub drag_stored: f64,
    /// Dissipated by normal damping since the start.
    pub dissipated_normal_damping: f64,
    /// Dissipated by tangential damping since the start.
    pub dissipated_tangential_damping: f64,
    /// Dissipated by sliding (Coulomb friction) since the start.
    pub dissipated_sliding: f64,
    /// Stored contact energy left when contacts opened (the area force is not exactly conservative), since the start.
    pub opening_residual: f64,
    /// Work done on the particles by moving walls and wall surface velocities since the start.
    pub work_walls: f64,
    /// Work done by the moving pulling points of drag springs since the start.
    pub work_drag: f64,
    /// Work done on the particles by a fluid's drag and buoyancy since the start (negative where still fluid brakes
    /// them, positive where a stream drives them).
    pub work_fluid: f64,
    /// Work done by changes of g at fixed positions since the start (variable gravity).
    pub work_gravity_change: f64,
    /// Work done by heating (the particles' size change, s(t)) since the start: on the contacts the expansion presses
    /// deeper, and on the spin of the particles, whose angular momentum I·ω it keeps while I grows with s²
    /// (docs/model.md, "Spin under heating" and "Heating's work on the contacts").
    pub work_heating: f64,
    /// Energy of inserted particles (sources) at their insertion, since the start.
    pub work_insertions: f64,
    /// Energy of removed particles at their removal, since the start.
    pub energy_removed: f64,
    /// Total energy at the start of the run.
    pub initial_total: f64,
    /// The largest kinetic energy (translational and rotational) at the end of any step since the start, J: part of
    /// [`Self::energy_scale`], so that a run judges its balance against the energy it has set in motion, not only
    /// against what moves now (an elastic ball at the top of its bounce has almost none).
    pub peak_kinetic: f64,
}

impl EnergyLedger {
    /// Books a step's contact terms (summed over the pairs): the three dissipations, the opening residual and the
    /// walls' work.
    pub(crate) fn book_contacts(&mut self, terms: &LedgerTerms) {
        self.dissipated_normal_damping += terms.normal_damping;
        self.dissipated_tangential_damping += terms.tangential_damping;
        self.dissipated_sliding += terms.sliding;
        self.opening_residual += terms.opening_residual;
        self.work_walls += terms.work_walls;
    }

    /// Kinetic energy, translational and rotational.
    pub fn kinetic(&self) -> f64 {
        self.kinetic_translational + self.kinetic_rotational
    }

    /// Everything stored now: kinetic, potential, contacts and drag springs.
    pub fn total(&self) -> f64 {
        self.kinetic() + self.potential + self.contact_stored + self.drag_stored
    }

    /// Everything dissipated since the start (≥ 0).
    pub fn dissipated(&self) -> f64 {
        self.dissipated_normal_damping + self.dissipated_tangential_damping + self.dissipated_sliding
    }

    /// Net energy brought in from outside since the start (walls, drag springs, the fluid, g changes, heating,
    /// insertions − removals).
    pub fn work_in(&self) -> f64 {
        self.work_walls
            + self.work_drag
            + self.work_fluid
            + self.work_gravity_change
            + self.work_heating
            + self.work_insertions
            - self.energy_removed
    }

    /// (E_now − E_0) − (W_in − D − residual): zero for exact bookkeeping; its drift is the integration error.
    pub fn balance_error(&self) -> f64 {
        (self.total() - self.initial_total) - (self.work_in() - self.dissipated() - self.opening_residual)
    }

    /// A scale against which the balance error is judged: the largest of the energies moved around in the run (the
    /// kinetic energy now and at its peak, the contacts' stored energy, the dissipated energy, the work from outside and
    /// the change of the total), and never below a millionth of the initial total energy (so a World at rest does not
    /// judge round-off against 0).
    pub fn energy_scale(&self) -> f64 {
        [
            self.kinetic(),
            self.peak_kinetic,
            self.contact_stored.abs(),
            self.dissipated(),
            self.work_in().abs(),
            (self.total() - self.initial_total).abs(),
        ]
        .into_iter()
        .fold(f64::MIN_POSITIVE.max(1e-6 * self.initial_total.abs()), f64::max)
    }
}
