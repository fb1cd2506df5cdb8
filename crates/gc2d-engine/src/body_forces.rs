//! Body forces: the forces on particles that do not come from contacts, as one list the step walks in order
//! (gravity, then drag springs, then a fluid's drag and buoyancy). Each force books its work in the energy ledger.

use crate::bodies::{Bodies, BodyId, BodyKind};
use crate::integrator::TimeStep;
use crate::ledger::EnergyLedger;
use crate::outlets::OutletState;
use crate::parallel::steps_in_parallel;
use crate::schedules::DragSpring;
use crate::shape::{MassModel, ShapeKind};
use gc2d_fluid::drag::{buoyancy_force, drag_force, equivalent_radius};
use gc2d_fluid::{DragCoefficient, FluidField, FluidProperties, ImmersedBody, OutsideField};
use gc2d_geometry::DVec2;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Fewest bodies one task of the parallel gravity pass takes.
const GRAVITY_BODIES_PER_TASK: usize = 4096;

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
    /// A fluid's drag ½·ρ_f·c_w·A·|w|·w (w = u(x, t) − v) and buoyancy −ρ_f·V·g on every particle. Its work, drag
    /// and buoyancy together, is the ledger's `work_fluid` (work in: negative where still fluid brakes a particle,
    /// positive where a stream drives it).
    Fluid(Box<Fluid>),
}

/// A fluid the particles move in, one-way coupled: it moves the particles and never feels them (docs/model.md,
/// "Fluid").
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Fluid {
    /// The fluid's velocity u(x, t), m/s.
    pub field: FluidField,
    /// Density ρ_f (kg/m³) and dynamic viscosity η (Pa·s; only Schiller–Naumann reads it).
    pub properties: FluidProperties,
    /// The drag coefficient c_w: constant or Schiller–Naumann.
    pub drag: DragCoefficient,
    /// Whether static buoyancy −ρ_f·V·g acts.
    pub buoyancy: bool,
}

impl Fluid {
    /// True when `self` and `other` are the same fluid but for the names of the files a loaded field came from
    /// ([`FluidField::same_flow`]).
    pub fn same_fluid(&self, other: &Fluid) -> bool {
        self.field.same_flow(&other.field)
            && self.properties == other.properties
            && self.drag == other.drag
            && self.buoyancy == other.buoyancy
    }

    /// Checks the numbers: ρ_f ≥ 0 and finite, a constant c_w ≥ 0 and finite, η > 0 and finite for
    /// Schiller–Naumann. The message names the field.
    pub fn validate(&self) -> Result<(), String> {
        let rho = self.properties.density_kg_m3;
        if !(rho >= 0.0 && rho.is_finite()) {
            return Err(format!("fluid density_kg_m3 must be >= 0 and finite, got {rho}"));
        }
        match self.drag {
            DragCoefficient::Constant(c) if !(c >= 0.0 && c.is_finite()) => {
                Err(format!("fluid drag coefficient must be >= 0 and finite, got {c}"))
            }
            DragCoefficient::SchillerNaumann
                if !(self.properties.dynamic_viscosity_pa_s > 0.0
                    && self.properties.dynamic_viscosity_pa_s.is_finite()) =>
            {
                Err(format!(
                    "fluid viscosity_pa_s must be > 0 and finite for Schiller-Naumann drag, got {}",
                    self.properties.dynamic_viscosity_pa_s
                ))
            }
            _ => Ok(()),
        }
    }

    /// Drag and (if on) buoyancy on particle `i` at its current position and velocity, at time `time` (s) under
    /// gravity `gravity` (m/s²), N (or N/m per unit thickness).
    pub(crate) fn force_on(
        &self,
        bodies: &Bodies,
        i: usize,
        gravity: DVec2,
        time: f64,
        mass_model: MassModel,
    ) -> Result<DVec2, OutsideField> {
        let body = immersed_body(bodies, i, mass_model);
        let u = self.field.velocity(bodies.pose[i].position, time)?;
        let mut force = drag_force(&self.properties, self.drag, &body, u - bodies.velocity[i]);
        if self.buoyancy {
            force += buoyancy_force(self.properties.density_kg_m3, &body, gravity);
        }
        Ok(force)
    }
}

/// The columns gravity reads to weigh the bodies, over all bodies.
pub(crate) struct WeighedBodies<'a> {
    pub mass: &'a [f64],
    pub kind: &'a [BodyKind],
    pub alive: &'a [bool],
}

/// Adds its weight m·g to the force of each live particle among bodies `first`, `first + 1`, … whose forces are
/// `forces`; walls and removed particles feel none. The one definition of gravity's pull, for the gravity pass and for
/// the force pass that corrects each range of bodies right after (`World::add_forces_and_correct`).
#[inline]
pub(crate) fn add_weights(forces: &mut [DVec2], first: usize, bodies: &WeighedBodies, gravity: DVec2) {
    for (i, force) in (first..).zip(forces) {
        if bodies.kind[i] == BodyKind::Particle && bodies.alive[i] {
            *force += bodies.mass[i] * gravity;
        }
    }
}

/// What the fluid sees of particle `i` under `mass_model`: a disk's radius, or a polygon's (or capsule's)
/// equal-area radius √(area/π).
fn immersed_body(bodies: &Bodies, i: usize, mass_model: MassModel) -> ImmersedBody {
    let area = bodies.area[i];
    let radius = if bodies.shape[i] == ShapeKind::Disk { bodies.radius[i] } else { equivalent_radius(area) };
    match mass_model {
        MassModel::PerUnitThickness => ImmersedBody::per_unit_thickness(radius, area),
        MassModel::SphereEquivalent => ImmersedBody::sphere_equivalent(radius),
    }
}

/// The outlets of a World and where its particles were at the start of the step, to tell a particle that is leaving
/// through an outlet in this step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct OutletCrossings<'a> {
    /// The outlets.
    pub outlets: &'a [OutletState],
    /// Each body's centre at the start of the step (empty in a World without outlets).
    pub before: &'a [DVec2],
}

impl OutletCrossings<'_> {
    /// True when particle `i`, now at `position`, has crossed an outlet outward since the step began.
    fn leaving(&self, i: usize, position: DVec2) -> bool {
        self.before
            .get(i)
            .is_some_and(|&before| self.outlets.iter().any(|o| o.outlet().crossed_outward(before, position)))
    }
}

/// What the body forces of a step read besides the bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BodyForceStep<'a> {
    /// g at the end of the step, m/s² (a vector along −y).
    pub gravity: DVec2,
    /// Time at the end of the step, s.
    pub time: f64,
    /// Δt, s.
    pub dt: f64,
    /// How masses (and so the fluid's areas and volumes) are counted.
    pub mass_model: MassModel,
    /// Δt with its scale factors, to read the predicted accelerations.
    pub time_step: TimeStep,
    /// The particles leaving through outlets in this step.
    pub crossings: OutletCrossings<'a>,
}

impl BodyForce {
    /// Adds this force's share to the bodies' force and torque columns for the step, and books its work. Fails only
    /// where a loaded fluid field is sampled off its mesh and the scene asked for an error there.
    pub(crate) fn apply(
        &self,
        bodies: &mut Bodies,
        step: &BodyForceStep,
        ledger: &mut EnergyLedger,
    ) -> Result<(), OutsideField> {
        match self {
            BodyForce::Gravity => {
                let Bodies { force, mass, kind, alive, .. } = bodies;
                let weighed = WeighedBodies { mass, kind, alive };
                let pull = |(piece, forces): (usize, &mut [DVec2])| {
                    add_weights(forces, piece * GRAVITY_BODIES_PER_TASK, &weighed, step.gravity);
                };
                // One addition per body: the same bits in any order, so parallel where the World is, in pieces large
                // enough that handing them out costs less than the additions (rayon's finest split made this stage
                // three to five times slower on 16 threads, docs/performance.md).
                if steps_in_parallel(force.len()) {
                    force.par_chunks_mut(GRAVITY_BODIES_PER_TASK).enumerate().for_each(pull);
                } else {
                    force.chunks_mut(GRAVITY_BODIES_PER_TASK).enumerate().for_each(pull);
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
            BodyForce::Fluid(fluid) => {
                // The work over the step is F·v at the step's midpoint, v_pred − ½·a_pred·Δt (second order, like
                // the trapezoid of the start and end velocities), with F evaluated at the predicted velocity.
                let mut power = 0.0;
                for i in 0..bodies.len() {
                    if bodies.kind[i] != BodyKind::Particle || !bodies.alive[i] {
                        continue;
                    }
                    let force = match fluid.force_on(bodies, i, step.gravity, step.time, step.mass_model) {
                        Ok(force) => force,
                        // A particle crossing an outlet in this step is sampled just beyond it, where a loaded mesh
                        // may end (an outlet on its edge): it feels no fluid on its way out, and the outlet removes it
                        // at the step's end (docs/model.md, "Fluid").
                        Err(_) if step.crossings.leaving(i, bodies.pose[i].position) => DVec2::ZERO,
                        Err(outside) => return Err(outside),
                    };
                    bodies.force[i] += force;
                    let midpoint = bodies.velocity[i] - 0.5 * step.dt * bodies.gear[i].acceleration(&step.time_step);
                    power += force.dot(midpoint);
                }
                ledger.work_fluid += power * step.dt;
            }
        }
        Ok(())
    }

    /// Energy this force stores at time `time` that is not part of the kinetic or potential energy, J: the drag
    /// springs' ½·K·d².
    pub(crate) fn stored_energy(&self, bodies: &Bodies, time: f64) -> f64 {
        match self {
            BodyForce::Gravity | BodyForce::Fluid(_) => 0.0,
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
            BodyForce::Fluid(_) => std::mem::size_of::<Fluid>(),
        }
    }
}
