//! Body forces: the forces on particles that do not come from contacts, as one list the step walks in order
//! (gravity, then drag springs; fluid drag joins it later). Each force books its work in the energy ledger.

use crate::bodies::{Bodies, BodyId, BodyKind};
use crate::ledger::EnergyLedger;
use crate::schedules::DragSpring;
use gc2d_geometry::DVec2;
use serde::{Deserialize, Serialize};

/// A drag spring attached to a particle (reference §2.12).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AttachedSpring {
    /// The particle it pulls.
    pub particle: BodyId,
    /// The spring and its moving pulling point.
    pub spring: DragSpring,
}

/// One body force of a World.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum BodyForce {
    /// m·g(t) along −y on every particle. Its work is the change of the potential energy m·g·y, which the ledger
    /// keeps as the potential term (and as work of gravity changes when g(t) varies).
    Gravity,
    /// Drag springs, each pulling its particle towards a moving point. The springs' energy is the ledger's
    /// `drag_stored`; the work of the moving pulling points is `work_drag`.
    DragSprings(Vec<AttachedSpring>),
}

/// What the body forces of a step read besides the bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BodyForceStep {
    /// g at the end of the step, m/s² (a vector along −y).
    pub gravity: DVec2,
    /// Time at the end of the step, s.
    pub time: f64,
    /// Δt, s.
    pub dt: f64,
}

impl BodyForce {
    /// Adds this force's share to the bodies' force and torque columns for the step, and books its work.
    pub(crate) fn apply(&self, bodies: &mut Bodies, step: &BodyForceStep, ledger: &mut EnergyLedger) {
        match self {
            BodyForce::Gravity => {
                for i in 0..bodies.len() {
                    if bodies.kind[i] == BodyKind::Particle && bodies.alive[i] {
                        bodies.force[i] += bodies.mass[i] * step.gravity;
                    }
                }
            }
            BodyForce::DragSprings(springs) => {
                for AttachedSpring { particle, spring } in springs {
                    let i = particle.index();
                    if !bodies.alive[i] {
                        continue;
                    }
                    let (force, torque) = spring.force_and_torque(bodies.pose[i], step.time);
                    bodies.force[i] += force;
                    bodies.torque[i] += torque;
                    ledger.work_drag += spring.driving_power(bodies.pose[i], step.time) * step.dt;
                }
            }
        }
    }

    /// Energy this force stores at time `time` that is not part of the kinetic or potential energy, J: the drag
    /// springs' ½·K·d².
    pub(crate) fn stored_energy(&self, bodies: &Bodies, time: f64) -> f64 {
        match self {
            BodyForce::Gravity => 0.0,
            BodyForce::DragSprings(springs) => springs
                .iter()
                .filter(|s| bodies.alive[s.particle.index()])
                .map(|s| s.spring.stored_energy(bodies.pose[s.particle.index()], time))
                .sum(),
        }
    }

    /// Heap memory the force holds, bytes.
    pub(crate) fn heap_bytes(&self) -> usize {
        match self {
            BodyForce::Gravity => 0,
            BodyForce::DragSprings(springs) => crate::bodies::vec_bytes(springs),
        }
    }
}
