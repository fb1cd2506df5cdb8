//! The couples of the [`Winkler`](crate::AreaFormulation::Winkler) formulation: the overlap seen as a bed of springs
//! and dashpots along the contact line (a Winkler foundation; docs/model.md, "Rocking of flat contacts").

use crate::{AreaFormulation, ContactConstants, ContactGeometry, ContactLaw};

/// Couples a contact adds to the forces at the chord midpoint, and their energy over the step. Zero for the
/// formulations that apply the force at the chord midpoint, and for contacts that cannot rock (a disk in the pair).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct RockingMoments {
    /// Torque on body i, N·m; body j receives the opposite (both are couples: no net force).
    pub(crate) torque_on_i: f64,
    /// Work done against the elastic couple this step, J: added to the stored normal energy.
    pub(crate) elastic_work: f64,
    /// Energy the dashpot couple dissipated this step, J (≥ 0): added to the normal damping.
    pub(crate) damping_dissipation: f64,
}

impl RockingMoments {
    /// The couples of `law` for a contact with this step's `geometry`, elastic force `elastic` (N), relative angular
    /// velocity `relative_spin` = ω_i − ω_j (rad/s) and step `dt` (0 for no rate terms).
    ///
    /// Moving the elastic force from the chord midpoint to the centroid's projection, s̄ along the tangent t, adds
    /// the torque s̄·t × F⊥·n = −s̄·F⊥ on i: for a flat contact tilted by θ (local depth δ0 + θ·s) this is the
    /// restoring moment (E/l)·∫δ·s ds = E·c³·θ/(12 l) of the potential (E/2l)·∫δ² ds. The dashpots, of the density
    /// γ·√(E·m⊥)/l per unit length that gives the normal damping force for a uniform approach, add the couple
    /// −γ·√(E·m⊥)/l · c³/12 · (ω_i − ω_j) on i, which a uniform approach does not excite.
    #[inline]
    pub(crate) fn of(
        law: &ContactLaw,
        constants: &ContactConstants,
        geometry: &ContactGeometry,
        elastic: f64,
        relative_spin: f64,
        dt: f64,
    ) -> Self {
        if law.elastic.formulation != AreaFormulation::Winkler || !geometry.rocking {
            return Self::default();
        }
        let elastic_torque = -geometry.centroid_offset * elastic;
        let c = geometry.chord_length;
        let dashpot_coefficient = law.damping.map_or(0.0, |d| {
            d.gamma * (law.elastic.e_modulus * constants.normal_mass).sqrt() / constants.length * c * c * c / 12.0
        });
        let damping_torque = -dashpot_coefficient * relative_spin;
        Self {
            torque_on_i: elastic_torque + damping_torque,
            elastic_work: -elastic_torque * relative_spin * dt,
            damping_dissipation: -damping_torque * relative_spin * dt,
        }
    }
}
