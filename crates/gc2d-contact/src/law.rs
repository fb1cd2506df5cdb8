//! The composed contact law and its single entry point, [`ContactLaw::evaluate`] (reference §2.15).

use crate::{
    AreaFormulation, BodyMotion, Cohesion, ContactConstants, ContactGeometry, ContactState, CundallStrack, EnergyTerms,
    NormalDamping, NormalElastic, TangentialStep, reciprocal_or_zero, rocking::RockingMoments,
};
use gc2d_geometry::{DVec2, cross};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// The contact law of a scene, assembled from sub-models. A `None` sub-model is switched off and costs one branch.
///
/// gc2d has one E, γ, μ and k_coh per scene, shared by walls, so one law per scene reproduces it; a law per material
/// pair fits the same type later.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ContactLaw {
    /// Overlap-area elasticity, F⊥ = E·A/l (2.20) or its energy-conserving variant; always present.
    pub elastic: NormalElastic,
    /// Normal damping (2.21, 2.22).
    pub damping: Option<NormalDamping>,
    /// Cundall–Strack friction with Coulomb cap (2.23–2.27).
    pub friction: Option<CundallStrack>,
    /// Cohesion k_coh·|c1c2| (2.28).
    pub cohesion: Option<Cohesion>,
}

/// A law parameter outside its physical range.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum ContactLawError {
    /// Young's modulus must be positive and finite.
    #[error("Young's modulus E must be a positive finite number (N/m), got {0}")]
    YoungsModulus(f64),
    /// A coefficient must be a non-negative finite number.
    #[error("{name} must be a non-negative finite number, got {value}")]
    NegativeCoefficient {
        /// The parameter's name as in the reference (gamma, mu, k_coh).
        name: &'static str,
        /// The rejected value.
        value: f64,
    },
}

/// Everything one evaluation of a contact produces.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactResponse {
    /// Total contact force on body i, N; body j receives the opposite force. Both act at the contact point.
    pub force_on_i: DVec2,
    /// Torque on body i about its centre of mass, r_i × F (2.29), N·m, counter-clockwise positive.
    pub torque_on_i: f64,
    /// Torque on body j about its centre of mass, r_j × (−F), N·m.
    pub torque_on_j: f64,
    /// Net normal force on i along the normal, F⊥ + D⊥ − F_coh, N (positive = repulsive).
    pub normal_force: f64,
    /// Tangential force F∥ on i along the tangent, N.
    pub tangential_force: f64,
    /// Energy terms of the step.
    pub energy: EnergyTerms,
    /// The history to pass to the next evaluation of this pair.
    pub state: ContactState,
}

impl ContactLaw {
    /// The purely elastic law with Young's modulus `e_modulus` (N/m): no damping, friction or cohesion.
    pub fn elastic(e_modulus: f64) -> Self {
        Self { elastic: NormalElastic::thesis(e_modulus), damping: None, friction: None, cohesion: None }
    }

    /// Checks that every parameter lies in its physical range, naming the first one that does not.
    pub fn validate(&self) -> Result<(), ContactLawError> {
        let e = self.elastic.e_modulus;
        if !(e > 0.0 && e.is_finite()) {
            return Err(ContactLawError::YoungsModulus(e));
        }
        let coefficients = [
            ("gamma", self.damping.map(|d| d.gamma)),
            ("mu", self.friction.map(|f| f.mu)),
            ("k_coh", self.cohesion.map(|c| c.k_coh)),
        ];
        for (name, value) in coefficients {
            match value {
                Some(value) if !(value >= 0.0 && value.is_finite()) => {
                    return Err(ContactLawError::NegativeCoefficient { name, value });
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// Energy stored in a contact with history `state`: U⊥ + S²/(2k_t) − k_coh·A, J. Summed over all contacts it is
    /// the contact term of the engine's energy ledger.
    pub fn stored_energy(&self, state: &ContactState) -> f64 {
        let cohesion = self.cohesion.map_or(0.0, |c| c.energy(state.previous_area));
        state.normal_energy + CundallStrack::spring_energy(self.elastic.e_modulus, state.spring) + cohesion
    }

    /// Evaluates one contact for one time step `dt` (reference §2.15).
    ///
    /// `previous` is the state returned by the last evaluation of this pair (the default state for a new pair).
    /// A non-overlapping `geometry` ends an active contact (it opens), reporting its left-over stored energy, and resets the state.
    /// Degenerate input (NaN, zero characteristic length, non-positive `dt`) yields finite output: no force for
    /// unusable geometry, and no rate-dependent terms for a non-positive `dt`.
    ///
    /// Always inlined: the engine's pair evaluation is compiled twice (with and without heating), and left to itself
    /// the compiler then called this law out of line, 6.5 % more instructions a particle-step of a dense pile
    /// (docs/performance.md, "Heating's work: what the others pay").
    #[inline(always)]
    pub fn evaluate(
        &self,
        geometry: &ContactGeometry,
        body_i: &BodyMotion,
        body_j: &BodyMotion,
        previous: &ContactState,
        dt: f64,
    ) -> ContactResponse {
        if !geometry.is_overlapping() {
            return self.separate(previous);
        }
        let constants = match previous.constants {
            Some(constants) => constants,
            None => match ContactConstants::at_first_contact(geometry, body_i, body_j) {
                Some(constants) => constants,
                None => return self.separate(previous),
            },
        };
        let dt = if (dt > 0.0) & dt.is_finite() { dt } else { 0.0 };
        let inv_dt = if dt > 0.0 { 1.0 / dt } else { 0.0 };
        let e = self.elastic.e_modulus;
        let area = geometry.area;
        let area_change = area - previous.previous_area;
        // Normal approach over the step, Δh = ΔA/c̄ (∂A/∂h = chord length).
        let approach = area_change * reciprocal_or_zero(mean_chord(previous.previous_chord, geometry.chord_length));

        let elastic = self.elastic.force(area, geometry.chord_length, constants.length);
        let damping = self
            .damping
            .map_or(0.0, |d| d.force(e, constants.normal_mass, area_change, constants.length, inv_dt, elastic));
        let cohesion = self.cohesion.map_or(0.0, |c| c.force(geometry.chord_length));

        let tangent = geometry.tangent();
        let (tangential, surface_work) = match self.friction {
            Some(friction) => {
                let sliding_velocity = (body_i.contact_point_velocity(geometry.arm_i)
                    - body_j.contact_point_velocity(geometry.arm_j))
                .dot(tangent);
                let step = friction.step(e, constants.tangential_mass, previous.spring, sliding_velocity, dt, elastic);
                let surface_slip = (body_j.surface_velocity - body_i.surface_velocity).dot(tangent);
                (step, step.force * surface_slip * dt)
            }
            None => (TangentialStep::default(), 0.0),
        };

        let normal_force = elastic + damping - cohesion;
        let force = normal_force * geometry.normal + tangential.force * tangent;
        let rocking = RockingMoments::of(
            self,
            &constants,
            geometry,
            elastic,
            body_i.angular_velocity - body_j.angular_velocity,
            dt,
        );
        // The thesis and Winkler laws book their work by the trapezoid rule (Winkler's with the work against its
        // couple); the conservative one stores its potential W(A).
        let (normal_elastic_change, normal_energy) = match self.elastic.formulation {
            AreaFormulation::Thesis | AreaFormulation::Winkler => {
                let previous_elastic =
                    self.elastic.force(previous.previous_area, previous.previous_chord, constants.length);
                let change = 0.5 * (previous_elastic + elastic) * approach + rocking.elastic_work;
                (change, previous.normal_energy + change)
            }
            AreaFormulation::Conservative => {
                let energy = self.elastic.potential(area, constants.length);
                (energy - previous.normal_energy, energy)
            }
        };
        ContactResponse {
            force_on_i: force,
            torque_on_i: cross(geometry.arm_i, force) + rocking.torque_on_i,
            torque_on_j: -cross(geometry.arm_j, force) - rocking.torque_on_i,
            normal_force,
            tangential_force: tangential.force,
            energy: EnergyTerms {
                normal_elastic_change,
                spring_change: tangential.spring_energy_change,
                cohesion_change: self.cohesion.map_or(0.0, |c| c.energy(area_change)),
                normal_damping: damping * approach + rocking.damping_dissipation,
                tangential_damping: tangential.damping_dissipation,
                sliding: tangential.sliding_dissipation,
                opening_residual: 0.0,
                surface_work,
            },
            state: ContactState {
                constants: Some(constants),
                previous_area: area,
                previous_chord: geometry.chord_length,
                spring: tangential.spring,
                normal_energy,
            },
        }
    }

    /// The response of a pair that does not (or no longer) overlap: no force, a reset state and, if a contact was
    /// active, the energy terms of its last step (the elastic force falls to zero by the trapezoid rule over the
    /// previous chord; whatever the contact still stores is the opening residual). Under the conservative
    /// formulation the normal energy W(A) returns to W(0) = 0 exactly and only the tangential spring can be left.
    fn separate(&self, previous: &ContactState) -> ContactResponse {
        let Some(constants) = previous.constants else {
            return ContactResponse::default();
        };
        let normal_left = match self.elastic.formulation {
            AreaFormulation::Thesis | AreaFormulation::Winkler => {
                let previous_elastic =
                    self.elastic.force(previous.previous_area, previous.previous_chord, constants.length);
                let last_approach = -previous.previous_area * reciprocal_or_zero(previous.previous_chord);
                previous.normal_energy + 0.5 * previous_elastic * last_approach
            }
            AreaFormulation::Conservative => 0.0,
        };
        let spring_energy = CundallStrack::spring_energy(self.elastic.e_modulus, previous.spring);
        ContactResponse {
            energy: EnergyTerms {
                normal_elastic_change: -previous.normal_energy,
                spring_change: -spring_energy,
                cohesion_change: self.cohesion.map_or(0.0, |c| -c.energy(previous.previous_area)),
                opening_residual: normal_left + spring_energy,
                ..EnergyTerms::default()
            },
            ..ContactResponse::default()
        }
    }
}

/// Mean contact-line length over a step; the one that exists on the first step of a contact (old chord 0).
#[inline]
fn mean_chord(old: f64, new: f64) -> f64 {
    if old > 0.0 { 0.5 * (old + new) } else { new }
}

#[cfg(test)]
mod tests;
