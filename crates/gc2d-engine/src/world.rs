//! The World: bodies, contacts and drivers, and the step that advances them by one Δt.
//!
//! One step, as data flows (ARCHITECTURE.md): predict → vertices and boxes → sort-and-sweep → narrowphase and contact
//! law per pair (parallel, each pair writes only its own record, each fixed chunk of pairs its own sums) →
//! accumulation in pair order → body forces → correct → walls, g(t), domain and outlet removals, sources and inlets,
//! s(t) → ledger and safety checks. Stages a scene does not use are skipped by a flag test, so a plain pile pays
//! nothing for drag springs, moving walls, heating, sources, inlets or outlets. On several threads, stages that need
//! nothing of other bodies in between share a pass over each range of bodies: predict with vertices and boxes where
//! no wall moves and nothing heats, accumulation with gravity and correct where gravity is the only body force and no
//! contact events are written. On any thread count, the ledger's kinetic and potential sums are taken in the
//! corrector's pass where no particle is removed or added after it.

use crate::bodies::{Bodies, BodyId, BodyKind, ForceColumns, IntegrationColumns, KinematicsColumns, travel_bound};
use crate::body_forces::{
    AttachedSpring, BodyForce, BodyForceStep, Fluid, OutletCrossings, WeighedBodies, add_weights,
};
use crate::body_sums::{BODIES_PER_CHUNK, BodySums, ClosingColumns, ClosingPass};
use crate::broadphase::{PairEntry, SortAndSweep};
use crate::clearance::Clearance;
use crate::events::{ContactEvent, ContactEventLog, Episode, PairStep};
use crate::force_ranges::{BodyRanges, add_contact_forces, add_pair_forces, mark_touching_pair};
use crate::heating::{ContactExpansion, keep_angular_momentum};
use crate::home_threads::for_each_on_home_thread;
use crate::inlets::{Inlet, InletState};
use crate::insertions::{Inserter, Insertion, InsertionLog};
use crate::integrator::{BodyIntegrator, GearState, Integrator, IntegratorError, TimeStep};
use crate::interactions::{InteractionError, InteractionTable, MaterialId};
use crate::ledger::EnergyLedger;
use crate::motion::WallMotion;
use crate::narrowphase::{ContactHistory, PairContact, PairContext};
use crate::outlets::{Outlet, OutletState};
use crate::pair_sums::{CHUNKS_PER_TASK, PAIRS_PER_CHUNK, PairSums};
use crate::parallel::steps_in_parallel;
use crate::safety::{self, SafetyError, SafetyLimits};
use crate::schedules::{DragSpring, GravitySchedule, HeatingSchedule};
use crate::shape::{BodyShape, MassModel, ShapeKind, shape_view};
use crate::sources::{DropHeight, DropSource, PLACEMENT_ATTEMPTS, SourceState};
use crate::stage_clock::{Stage, StageClock, StageTimes};
use crate::transits::{Transit, TransitLog};
use gc2d_geometry::{Aabb, DVec2, Pose, ShapeView, area_contact};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Everything global about a run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WorldConfig {
    /// Δt, s.
    pub time_step: f64,
    /// The integration scheme: Gear with c₀ = 3/16 by default (velocity-dependent forces), Gear with 3/20, or
    /// velocity Verlet as a second-order baseline.
    pub integrator: Integrator,
    /// The contact model of every pair of materials (gc2d scenes: one material, [`InteractionTable::uniform`]).
    pub interactions: InteractionTable,
    /// How particle masses follow from shape and density. Default per unit thickness (gc2d).
    #[serde(default)]
    pub mass_model: MassModel,
    /// g(t); gravity points along −y.
    pub gravity: GravitySchedule,
    /// Global size scaling s(t), if the scene heats.
    pub heating: Option<HeatingSchedule>,
    /// Blow-up limits and the time-step override.
    pub safety: SafetyLimits,
    /// Particles whose centroid leaves this box are removed (and counted); `None` keeps every particle.
    pub domain: Option<Aabb>,
    /// Seed of the World's random numbers (sources).
    pub seed: u64,
}

/// Why a World could not be built or advanced.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum WorldError {
    /// Δt is not a usable number.
    #[error(transparent)]
    TimeStep(#[from] IntegratorError),
    /// The interaction table is incomplete or a contact model's parameters are out of range.
    #[error(transparent)]
    Interactions(#[from] InteractionError),
    /// The run is unsafe or blew up.
    #[error(transparent)]
    Safety(#[from] SafetyError),
    /// A body could not be added.
    #[error("{0}")]
    InvalidBody(String),
    /// A loaded fluid field was sampled off its mesh where the scene asked for an error.
    #[error(transparent)]
    FluidOutside(#[from] gc2d_fluid::OutsideField),
}

impl WorldError {
    /// The bodies the error names, by id: a safety error's bodies, none otherwise.
    pub fn bodies(&self) -> Vec<u32> {
        match self {
            WorldError::Safety(error) => error.bodies(),
            _ => Vec::new(),
        }
    }
}

/// A wall that moves, with the pose it moves from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MovingWall {
    /// The wall's body.
    pub body: BodyId,
    /// Its pose at rest, which its motion law moves it from.
    pub rest: Pose,
    /// How it moves.
    pub motion: WallMotion,
}

/// Counters of the last step and of the run, for progress displays and statistics.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct StepStats {
    /// Pairs of touching boxes.
    pub box_pairs: usize,
    /// Pairs whose polygons overlap.
    pub contacts: usize,
    /// Largest overlap this step: the area as a fraction of the smaller particle's area (overlap-area law), the depth
    /// as a fraction of its diameter (penetration laws).
    pub max_overlap_fraction: f64,
    /// Closest-feature queries this step that needed more than one pass.
    pub multi_pass_queries: usize,
    /// Particles inserted by sources since the start.
    pub inserted: u64,
    /// Insertions skipped since the start because no free spot was found.
    pub insertions_skipped: u64,
    /// Particles removed for leaving the domain since the start.
    pub removed: u64,
    /// Particles fed by inlets since the start (per inlet: [`World::inlets`]).
    pub injected: u64,
    /// Due inlet particles that found no free spot and waited a step, since the start (per inlet: [`World::inlets`]).
    pub postponed: u64,
    /// Particles removed by outlets since the start (per outlet: [`World::outlets`]).
    pub removed_at_outlets: u64,
}

/// What the contacts did to one wall in the last step (a mill's rotor: its torque and the power it delivers).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WallLoad {
    /// Sum of the contact forces on the wall, N.
    pub force: DVec2,
    /// Sum of their torques on the wall about the chosen point, N·m; a drive holding the wall on its motion supplies
    /// the opposite.
    pub torque: f64,
    /// Power the wall's motion delivers to the particles through its contacts, Σ F_particle·v_wall at each contact
    /// point, W. For a wall turning at ω about the chosen point it equals −ω·`torque` (to round-off).
    pub power: f64,
    /// Contacts of the wall.
    pub contacts: usize,
}

/// The drive of the walls turning about pivots (a mill's rotor) in the last step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RotorPower {
    /// The torque the drive supplies to hold the turning walls on their motion, each about its own pivot, summed
    /// (the parts of one rotor share a pivot), N·m: minus the contacts' torque on them.
    pub torque: f64,
    /// ω·τ, from the torque, summed over the turning walls, W.
    pub power_from_torque: f64,
    /// Σ F·v over their contacts, the power they deliver to the particles, W. Equal to `power_from_torque` to
    /// round-off (the two ways the mill thesis measures the motor power, ballmill.md §7.6).
    pub power_from_work: f64,
}

/// The work of the walls turning about pivots (a mill's rotor) since t = 0, summed step by step from
/// [`RotorPower`]: the window means of the rotor's two powers are differences of these over the window's length, exact
/// where means of the instantaneous powers sampled at frames would miss most of the short blade hits.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct RotorWork {
    /// Σ ω·τ·Δt, J.
    pub from_torque: f64,
    /// Σ (Σ F·v)·Δt, J; the same to round-off, and the part of the ledger's wall work the turning walls did.
    pub from_work: f64,
}

/// The chatter diagnostic of one step, summed over the pairs of touching boxes with F the force on the pair:
/// `change` = Σ|F(n) − 2F(n−1) + F(n−2)| and `scale` = 2Σ(|F(n)| + |F(n−1)|), in N.
///
/// Their ratio is the relative step-to-step alternation: a force alternating M ± A gives A/M (a flat plate
/// chattering on a floor: 1), smooth motion about (ω Δt)², far below 0.01. A pair counts only on steps where it has
/// a force now and had one two steps ago, so the opening and closing of a contact (a whole force appearing or
/// vanishing, which is not an alternation) do not read as chatter; summing both parts over many steps before
/// dividing (as `gc2d-rs run` does) weighs the rest by force (docs/validation.md, "Chatter warning").
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ForceAlternation {
    /// Σ|F(n) − 2F(n−1) + F(n−2)|, N.
    pub change: f64,
    /// 2Σ(|F(n)| + |F(n−1)|), N.
    pub scale: f64,
}

impl ForceAlternation {
    /// Both parts NaN: the history is not known.
    pub fn not_measured() -> Self {
        Self { change: f64::NAN, scale: f64::NAN }
    }

    /// `change / scale`; 0 when no force acts, NaN when not measured.
    pub fn ratio(&self) -> f64 {
        if self.scale > 0.0 {
            self.change / self.scale
        } else if self.scale.is_nan() {
            f64::NAN
        } else {
            0.0
        }
    }
}

/// Which optional stages the step runs; fixed when the World is built, and set when drivers or particles are added.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
struct Stages {
    moving_walls: bool,
    /// A wall turns about a pivot: the step sums its [`RotorWork`].
    rotors: bool,
    heating: bool,
    variable_gravity: bool,
    sources: bool,
    domain: bool,
    inlets: bool,
    outlets: bool,
    /// A particle is a polygon: the predictor and corrector bound each particle's travel (`Bodies::travel`) for the
    /// clearance of polygon pairs; without one the travel stays infinite and costs nothing.
    polygon_particles: bool,
}

/// A simulation: bodies, the contacts between them, the drivers that move walls and pull particles, and time.
///
/// Serializable as a whole so that a checkpoint ([`crate::checkpoint`]) restores it bit for bit.
#[derive(Serialize, Deserialize)]
pub struct World {
    config: WorldConfig,
    integrator: BodyIntegrator,
    time: f64,
    steps: u64,
    bodies: Bodies,
    broadphase: SortAndSweep<PairContact>,
    moving_walls: Vec<MovingWall>,
    /// Gravity, drag springs and any other body force, applied in this order.
    body_forces: Vec<BodyForce>,
    sources: Vec<SourceState>,
    rng: ChaCha8Rng,
    inlets: Vec<InletState>,
    outlets: Vec<OutletState>,
    /// Inlet entries and outlet passages, in Worlds with inlets or outlets.
    transits: TransitLog,
    /// Which source or inlet inserted each particle added during the run.
    insertions: InsertionLog,
    /// Particle centres at the start of the step, for the outlets' crossing test; refilled every step, so not saved.
    #[serde(skip)]
    positions_before_step: Vec<DVec2>,
    ledger: EnergyLedger,
    /// The heating's work on the contacts, step by step (`heating.rs`).
    contact_expansion: ContactExpansion,
    /// ln(s_new/s_old) of the heating this step (0 where s stayed), set by the predictor for the step's booking.
    #[serde(skip)]
    scale_log_change: f64,
    rotor_work: RotorWork,
    stats: StepStats,
    stages: Stages,
    /// Contact episodes and events, while an observer records them ([`Self::record_contact_events`]).
    events: Option<ContactEventLog>,
    started: bool,
    /// How many of the forces F(n−1), F(n−2) the next step's [`Self::force_alternation`] will know: 2 in a new
    /// World, 1 after loading a checkpoint (which saves `force_on_a` but not the older history).
    #[serde(skip, default = "force_history_after_loading")]
    force_history_steps: u8,
    /// This step's [`Self::force_alternation`]; not saved in checkpoints (NaN after loading).
    #[serde(skip, default = "ForceAlternation::not_measured")]
    force_alternation: ForceAlternation,
    /// The narrowphase pass's sums, one per chunk of [`PAIRS_PER_CHUNK`] pairs; refilled every step, so not saved.
    #[serde(skip)]
    pair_sums: Vec<PairSums>,
    /// The closing pass's sums, one per chunk of [`BODIES_PER_CHUNK`] bodies; refilled every step, so not saved.
    #[serde(skip)]
    body_sums: Vec<BodySums>,
    /// The ranges of bodies the force accumulation adds up in parallel this step; set by the narrowphase pass, so not
    /// saved.
    #[serde(skip)]
    body_ranges: BodyRanges,
    /// Which touching pairs of each chunk of [`PAIRS_PER_CHUNK`] reach each range of `body_ranges`, one mask per
    /// range, chunk after chunk ([`mark_touching_pair`]); refilled every step that steps in parallel, so not saved.
    #[serde(skip)]
    range_masks: Vec<u64>,
    /// Time per stage of the step, while [`Self::start_stage_clock`] has turned it on; not saved.
    #[serde(skip)]
    stage_clock: Option<StageClock>,
}

impl World {
    /// An empty World at t = 0. Validates Δt and the contact law.
    pub fn new(config: WorldConfig) -> Result<Self, WorldError> {
        let time_step = TimeStep::new(config.time_step)?;
        config.interactions.validate()?;
        let stages = Stages {
            heating: config.heating.is_some(),
            variable_gravity: !config.gravity.is_constant(),
            domain: config.domain.is_some(),
            ..Stages::default()
        };
        Ok(Self {
            integrator: BodyIntegrator::new(config.integrator, time_step),
            rng: ChaCha8Rng::seed_from_u64(config.seed),
            config,
            time: 0.0,
            steps: 0,
            bodies: Bodies::default(),
            broadphase: SortAndSweep::new(),
            moving_walls: Vec::new(),
            body_forces: vec![BodyForce::Gravity],
            sources: Vec::new(),
            inlets: Vec::new(),
            outlets: Vec::new(),
            transits: TransitLog::default(),
            insertions: InsertionLog::default(),
            positions_before_step: Vec::new(),
            ledger: EnergyLedger::default(),
            contact_expansion: ContactExpansion::default(),
            scale_log_change: 0.0,
            rotor_work: RotorWork::default(),
            stats: StepStats::default(),
            stages,
            events: None,
            started: false,
            force_history_steps: FULL_FORCE_HISTORY,
            force_alternation: ForceAlternation::default(),
            pair_sums: Vec::new(),
            body_sums: Vec::new(),
            body_ranges: BodyRanges::default(),
            range_masks: Vec::new(),
            stage_clock: None,
        })
    }

    /// Adds a free particle of material 0 and density `density` (kg/m² or kg/m³ by the World's [`MassModel`]) at
    /// `pose`, moving with `velocity` and `angular_velocity` (CCW). Returns its id.
    pub fn add_particle(
        &mut self,
        shape: impl Into<BodyShape>,
        pose: Pose,
        density: f64,
        velocity: DVec2,
        angular_velocity: f64,
    ) -> Result<BodyId, WorldError> {
        if !(density > 0.0 && density.is_finite()) {
            return Err(WorldError::InvalidBody(format!("particle density must be positive, got {density}")));
        }
        if !(pose.position.is_finite()
            && pose.angle.is_finite()
            && velocity.is_finite()
            && angular_velocity.is_finite())
        {
            return Err(WorldError::InvalidBody("particle pose and velocity must be finite numbers".into()));
        }
        let shape = shape.into();
        shape.validate(true).map_err(|e| WorldError::InvalidBody(e.to_string()))?;
        let mass = self.config.mass_model.mass_properties(&shape, density);
        let id = self.bodies.push(BodyKind::Particle, &shape, pose, mass.mass, mass.inertia);
        self.stages.polygon_particles |= self.bodies.shape[id.index()] == ShapeKind::Polygon;
        let i = id.index();
        self.bodies.velocity[i] = velocity;
        self.bodies.angular_velocity[i] = angular_velocity;
        // Start from the acceleration of free flight: a new particle is almost always free (sources insert only into
        // free space), and a zero start would leave its velocity half a step behind for good.
        self.bodies.gear[i] = GearState::from_physical(
            pose.position,
            velocity,
            self.config.gravity.acceleration(self.time),
            pose.angle,
            angular_velocity,
            0.0,
            self.integrator.time_step(),
        );
        self.start_in_fluid(i)?;
        self.insert_into_broadphase(id, BodyKind::Particle);
        let g = self.config.gravity.magnitude(self.time);
        let translational = 0.5 * mass.mass * velocity.length_squared();
        let rotational = 0.5 * mass.inertia * pose.scale * pose.scale * angular_velocity * angular_velocity;
        let potential = mass.mass * g * pose.position.y;
        if self.started {
            // A particle added during the run brings its energy in from outside; before the start it is part of E_0.
            self.ledger.work_insertions += translational + rotational + potential;
        } else {
            // Before the first step the ledger shows the start's energies (the first step recomputes them all), so
            // that a time series row at t = 0 is not zero for particles that move, and its balance error is zero.
            self.ledger.kinetic_translational += translational;
            self.ledger.kinetic_rotational += rotational;
            self.ledger.potential += potential;
            self.ledger.initial_total += translational + rotational + potential;
        }
        Ok(id)
    }

    /// Adds a wall (infinite mass) at `pose`. `surface_velocity` is gc2d's virtual tangential surface velocity
    /// (drums, §2.11); `motion` moves the wall (vibration, rotation, piston).
    ///
    /// Panics on a shape that fails [`BodyShape::validate`] (a negative radius): walls are built from validated
    /// scenes.
    pub fn add_wall(
        &mut self,
        shape: impl Into<BodyShape>,
        pose: Pose,
        surface_velocity: DVec2,
        motion: WallMotion,
    ) -> BodyId {
        let shape = shape.into();
        assert!(shape.validate(false).is_ok(), "invalid wall shape {shape:?}");
        let id = self.bodies.push(BodyKind::Wall, &shape, pose, f64::INFINITY, f64::INFINITY);
        self.bodies.set_surface_velocity(id, surface_velocity);
        if !motion.is_static() {
            self.stages.rotors |= matches!(motion, WallMotion::Rotating(_));
            self.moving_walls.push(MovingWall { body: id, rest: pose, motion });
            self.stages.moving_walls = true;
        }
        self.insert_into_broadphase(id, BodyKind::Wall);
        id
    }

    /// Gives body `body` the material `material` (bodies start with material 0); the pair's contact model follows from
    /// the two bodies' materials.
    pub fn set_material(&mut self, body: BodyId, material: MaterialId) -> Result<(), WorldError> {
        if material.index() >= self.config.interactions.material_count() {
            return Err(WorldError::InvalidBody(format!(
                "material {} is not in the interaction table, which has {} materials",
                material.0,
                self.config.interactions.material_count()
            )));
        }
        let slot = self.bodies.material.get_mut(body.index());
        *slot.ok_or_else(|| WorldError::InvalidBody(format!("no body {}", body.0)))? = material;
        // A pair's contact model follows the materials, and only the polygon walk of the overlap-area law keeps the
        // clearance up to date: a pair that changes model forgets it, so none outlives steps it was not followed in.
        for pair in self.broadphase.pairs_mut().iter_mut().filter(|p| p.a() == body.0 || p.b() == body.0) {
            pair.payload.clearance = Clearance::NONE;
        }
        Ok(())
    }

    /// Attaches a drag spring (reference §2.12) to a particle.
    pub fn add_drag_spring(&mut self, particle: BodyId, spring: DragSpring) -> Result<(), WorldError> {
        if self.bodies.kind.get(particle.index()) != Some(&BodyKind::Particle) {
            return Err(WorldError::InvalidBody(format!("drag spring on body {} which is not a particle", particle.0)));
        }
        let attached = AttachedSpring { particle, spring };
        match self.body_forces.iter_mut().find_map(|f| match f {
            BodyForce::DragSprings(springs) => Some(springs),
            _ => None,
        }) {
            Some(springs) => springs.push(attached),
            None => self.body_forces.push(BodyForce::DragSprings(vec![attached])),
        }
        Ok(())
    }

    /// Puts the particles in `fluid` (drag and buoyancy on every particle, applied after gravity and drag springs),
    /// replacing any fluid set before. A World without one spends nothing on it.
    pub fn set_fluid(&mut self, fluid: Fluid) -> Result<(), WorldError> {
        fluid.validate().map_err(WorldError::InvalidBody)?;
        self.body_forces.retain(|f| !matches!(f, BodyForce::Fluid(_)));
        self.body_forces.push(BodyForce::Fluid(Box::new(fluid)));
        for i in 0..self.bodies.len() {
            if self.bodies.kind[i] == BodyKind::Particle && self.bodies.alive[i] {
                self.start_in_fluid(i)?;
            }
        }
        Ok(())
    }

    /// The unit normal of the touching pair {a, b} at the current poses, pointing from `b` into `a` (the direction of
    /// the normal force on `a`), by the query the pair's contact model uses; `None` when they do not overlap. For
    /// exports and diagnostics: it repeats a query the step made.
    pub fn contact_normal(&self, a: BodyId, b: BodyId) -> Option<DVec2> {
        let context = pair_context(&self.bodies, &self.config);
        let (low, high) = if a.0 < b.0 { (a.0, b.0) } else { (b.0, a.0) };
        context.contact_normal(low, high).map(|(i, _, n)| if i == a { n } else { -n })
    }

    /// The particles that outlets removed on the last step, with how they came in (empty without outlets).
    pub fn transits(&self) -> &[Transit] {
        self.transits.last_step()
    }

    /// Which source or inlet inserted particle `body` during the run, and after how many others of its own; `None`
    /// for a body of the start or one added by hand.
    pub fn insertion(&self, body: BodyId) -> Option<Insertion> {
        self.insertions.of(body)
    }

    /// The fluid the particles move in, if the World has one (for recordings and analyses that sample its field).
    pub fn fluid(&self) -> Option<&Fluid> {
        self.body_forces.iter().find_map(|force| match force {
            BodyForce::Fluid(fluid) => Some(fluid.as_ref()),
            _ => None,
        })
    }

    /// Gives particle `i` the start acceleration of free flight in the fluid, g + F_fluid/m (its Gear state otherwise
    /// starts from g alone, which would leave a particle at rest in a levitating stream moving); nothing without a
    /// fluid.
    fn start_in_fluid(&mut self, i: usize) -> Result<(), WorldError> {
        let Some(fluid) = self.body_forces.iter().find_map(|f| match f {
            BodyForce::Fluid(fluid) => Some(fluid),
            _ => None,
        }) else {
            return Ok(());
        };
        let b = &self.bodies;
        let gravity = self.config.gravity.acceleration(self.time);
        let force = fluid.force_on(b, i, gravity, self.time, self.config.mass_model)?;
        let (pose, angular_velocity) = (b.pose[i], b.angular_velocity[i]);
        let time_step = self.integrator.time_step();
        self.bodies.gear[i] = GearState::from_physical(
            pose.position,
            b.velocity[i],
            gravity + force * b.inverse_mass[i],
            pose.angle,
            angular_velocity,
            0.0,
            time_step,
        );
        Ok(())
    }

    /// Adds a particle source.
    pub fn add_source(&mut self, source: DropSource) -> Result<(), WorldError> {
        source.recipe.validate().map_err(|e| WorldError::InvalidBody(format!("drop source shape: {e}")))?;
        if source.material.index() >= self.config.interactions.material_count() {
            return Err(WorldError::InvalidBody(format!(
                "drop source material {} is not in the table",
                source.material.0
            )));
        }
        if !(source.interval > 0.0 && source.density > 0.0 && source.width >= 0.0) {
            return Err(WorldError::InvalidBody(
                "drop source needs a positive interval and density and a non-negative width".into(),
            ));
        }
        self.sources.push(SourceState::new(source));
        self.stages.sources = true;
        Ok(())
    }

    /// Adds a particle inlet (see [`crate::inlets`]); it draws from its own random stream, numbered by the order of
    /// the inlets. Refuses a zero-length or non-finite segment, a rate that is not positive and finite, a start
    /// velocity that does not point into the domain, an invalid recipe, a non-positive density and an unknown
    /// material.
    pub fn add_inlet(&mut self, inlet: Inlet) -> Result<(), WorldError> {
        let invalid = |what: String| Err(WorldError::InvalidBody(format!("inlet: {what}")));
        inlet.recipe.validate().map_err(|e| WorldError::InvalidBody(format!("inlet shape: {e}")))?;
        if !(inlet.from.is_finite() && inlet.to.is_finite() && inlet.from != inlet.to) {
            return invalid("the segment needs two distinct finite end points".into());
        }
        if !(inlet.rate > 0.0 && inlet.rate.is_finite()) {
            return invalid(format!("the rate must be a positive number of particles per second, got {}", inlet.rate));
        }
        if !(inlet.velocity.is_finite() && inlet.angular_velocity.is_finite() && inlet.normal_speed() > 0.0) {
            return invalid(format!(
                "the start velocity ({}, {}) m/s does not point into the domain (to the left of the segment)",
                inlet.velocity.x, inlet.velocity.y
            ));
        }
        let density_ok = inlet.density > 0.0 && inlet.density.is_finite();
        if !density_ok || inlet.start.is_nan() || inlet.stop.is_nan() {
            return invalid("the density must be positive and the times numbers".into());
        }
        if inlet.material.index() >= self.config.interactions.material_count() {
            return invalid(format!("material {} is not in the table", inlet.material.0));
        }
        let index = self.inlets.len();
        self.inlets.push(InletState::new(inlet, self.config.seed, index));
        self.stages.inlets = true;
        Ok(())
    }

    /// Adds a particle outlet (see [`crate::outlets`]). Refuses a zero-length or non-finite segment.
    pub fn add_outlet(&mut self, outlet: Outlet) -> Result<(), WorldError> {
        if !(outlet.from.is_finite() && outlet.to.is_finite() && outlet.from != outlet.to) {
            return Err(WorldError::InvalidBody("outlet: the segment needs two distinct finite end points".into()));
        }
        self.outlets.push(OutletState::new(outlet));
        self.stages.outlets = true;
        Ok(())
    }

    /// The inlets in the order they were added, with their counters.
    pub fn inlets(&self) -> &[InletState] {
        &self.inlets
    }

    /// The outlets in the order they were added, with their counters.
    pub fn outlets(&self) -> &[OutletState] {
        &self.outlets
    }

    /// The drop sources in the order they were added (for comparing a checkpoint with the scene it continues).
    pub fn sources(&self) -> impl Iterator<Item = &DropSource> {
        self.sources.iter().map(|state| &state.source)
    }

    /// The walls that move, in the order they were added, with the poses they move from.
    pub fn moving_walls(&self) -> &[MovingWall] {
        &self.moving_walls
    }

    /// Gravity, drag springs and any other body force, in the order they are applied.
    pub fn body_forces(&self) -> &[BodyForce] {
        &self.body_forces
    }

    fn insert_into_broadphase(&mut self, id: BodyId, kind: BodyKind) {
        // Ids are dense slots far below the broadphase limit of 2^31, and each slot is inserted once.
        let inserted = self.broadphase.insert(id.0, self.bodies.aabb(id.index()), kind);
        debug_assert!(inserted.is_ok());
    }

    /// Simulated time, s.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Δt, s.
    pub fn time_step(&self) -> f64 {
        self.config.time_step
    }

    /// The configuration the World was built with.
    pub fn config(&self) -> &WorldConfig {
        &self.config
    }

    /// The body store (read only).
    pub fn bodies(&self) -> &Bodies {
        &self.bodies
    }

    /// The energy ledger as of the last step.
    pub fn ledger(&self) -> &EnergyLedger {
        &self.ledger
    }

    /// Counters of the last step.
    pub fn stats(&self) -> &StepStats {
        &self.stats
    }

    /// How much the contact forces alternated from step to step on the last step: a detector of period-2 chatter
    /// (Δt too large for the contact damping, docs/model.md "Automatic Δt"). See [`ForceAlternation`]. NaN parts in
    /// a World loaded from a checkpoint until its second step (the older force history is not saved).
    pub fn force_alternation(&self) -> ForceAlternation {
        self.force_alternation
    }

    /// The load the contacts of the last step put on wall `wall`, torques about `about` (a rotor's pivot). The
    /// material velocity of the wall at a contact point is its velocity and angular velocity at the step's predicted
    /// state, as the contact laws saw it.
    pub fn wall_load(&self, wall: BodyId, about: DVec2) -> WallLoad {
        let b = &self.bodies;
        let (velocity, omega, position) =
            (b.velocity[wall.index()], b.angular_velocity[wall.index()], b.pose[wall.index()].position);
        let mut load = WallLoad::default();
        for (a, other, contact) in self.contacts() {
            let on_wall = if a == wall {
                contact.force_on_a
            } else if other == wall {
                -contact.force_on_a
            } else {
                continue;
            };
            let material_velocity = velocity + omega * (contact.point - position).perp();
            load.force += on_wall;
            load.torque += gc2d_geometry::cross(contact.point - about, on_wall);
            load.power -= on_wall.dot(material_velocity);
            load.contacts += 1;
        }
        load
    }

    /// The work of the walls turning about pivots since t = 0 (see [`RotorWork`]); zero when no wall does.
    pub fn rotor_work(&self) -> RotorWork {
        self.rotor_work
    }

    /// The drive of every wall that turns about a pivot (see [`RotorPower`]); zero when no wall does.
    pub fn rotor_power(&self) -> RotorPower {
        let mut drive = RotorPower::default();
        for wall in &self.moving_walls {
            if let WallMotion::Rotating(rotation) = &wall.motion {
                let load = self.wall_load(wall.body, rotation.pivot);
                let omega = self.bodies.angular_velocity[wall.body.index()];
                drive.torque -= load.torque;
                drive.power_from_torque -= omega * load.torque;
                drive.power_from_work += load.power;
            }
        }
        drive
    }

    /// Starts recording contact events from the next step on (see [`crate::events`]); recording costs nothing until
    /// it is asked for. A World restored from a checkpoint of a recording run records again and keeps its open
    /// episodes.
    pub fn record_contact_events(&mut self) {
        self.events.get_or_insert_with(ContactEventLog::default);
    }

    /// The contact events of the last step, in pair order; empty when not recording.
    pub fn contact_events(&self) -> &[ContactEvent] {
        self.events.as_ref().map_or(&[], |log| log.events())
    }

    /// The contact episodes still open (pairs touching now), with their totals so far; empty when not recording.
    pub fn open_contact_episodes(&self) -> impl Iterator<Item = (BodyId, BodyId, &Episode)> {
        self.events.iter().flat_map(|log| log.open()).map(|(&(a, b), episode)| (BodyId(a), BodyId(b), episode))
    }

    /// Current g (magnitude; gravity points along −y).
    pub fn gravity(&self) -> f64 {
        self.config.gravity.magnitude(self.time)
    }

    /// Gives back the spare room of the body columns, the broadphase's per-body buffers and its pair list, which
    /// grow by doubling (the pairs by a sixteenth) while bodies and pairs are added. Scene builds and checkpoint loads
    /// call it once the World is complete; a World that goes on growing grows them again as needed. Changes no
    /// value.
    pub fn shrink_to_fit(&mut self) {
        self.bodies.shrink_to_fit();
        self.broadphase.shrink_to_fit();
    }

    /// Heap memory held by the World, in bytes, counted from the capacities of its buffers: the body columns, the
    /// broadphase with its pair list and every pair's contact record, the chunk sums of the narrowphase and of the
    /// closing pass, and the drivers' lists. Divided by the number of particles it is the memory per particle
    /// including its share of the contacts.
    pub fn heap_bytes(&self) -> usize {
        self.bodies.heap_bytes()
            + self.broadphase.heap_bytes()
            + crate::bodies::vec_bytes(&self.moving_walls)
            + crate::bodies::vec_bytes(&self.body_forces)
            + self.body_forces.iter().map(BodyForce::heap_bytes).sum::<usize>()
            + crate::bodies::vec_bytes(&self.sources)
            + crate::bodies::vec_bytes(&self.inlets)
            + crate::bodies::vec_bytes(&self.outlets)
            + crate::bodies::vec_bytes(&self.positions_before_step)
            + crate::bodies::vec_bytes(&self.pair_sums)
            + crate::bodies::vec_bytes(&self.body_sums)
            + crate::bodies::vec_bytes(&self.range_masks)
            + self.transits.heap_bytes()
            + self.insertions.heap_bytes()
    }

    /// The number of bands the broadphase's y axis is split into: more than 1 in a scene much wider than high
    /// (decided at the first step, docs/model.md "Broadphase"), else 1.
    pub fn y_bands(&self) -> usize {
        self.broadphase.y_bands()
    }

    /// Every pair of bodies whose boxes touch, with its contact record (`a < b`).
    pub fn pairs(&self) -> impl Iterator<Item = (BodyId, BodyId, &PairContact)> {
        self.broadphase.pairs().iter().map(|p| (BodyId(p.a()), BodyId(p.b()), &p.payload))
    }

    /// The pairs whose polygons overlapped in the last step.
    pub fn contacts(&self) -> impl Iterator<Item = (BodyId, BodyId, &PairContact)> {
        self.pairs().filter(|(_, _, c)| c.touching)
    }

    /// How deep the pair {a, b} with record `contact` overlaps: for the overlap-area law the overlap area as a
    /// fraction of the smaller particle's area, for penetration laws the depth as a fraction of the smaller
    /// particle's diameter; 0 when it does not touch. Computed from the contact's history, as of the last step.
    pub fn overlap_fraction(&self, a: BodyId, b: BodyId, contact: &PairContact) -> f64 {
        let context = pair_context(&self.bodies, &self.config);
        context.overlap_fraction(a.0, b.0, contact)
    }

    /// The largest stable Δt of the particles now in the World, each against the stiffest contact model its material
    /// meets ([`safety::particle_time_step`]).
    pub fn stable_time_step(&self) -> Option<f64> {
        safety::stable_time_step(&self.bodies, &self.config.interactions, self.config.safety.max_impact_speed)
            .map(|bound| bound.dt)
    }

    /// Checks Δt against the stable bound (refused unless the safety limits allow it).
    pub fn check_time_step(&self) -> Result<(), SafetyError> {
        safety::check_time_step(&self.bodies, &self.config.interactions, self.config.time_step, &self.config.safety)
    }

    /// [`Self::check_time_step`] after inserting particle `id` into a World that passed it: only `id` can have
    /// lowered the bound, so only its bound is computed.
    fn check_added_time_step(&self, id: BodyId) -> Result<(), SafetyError> {
        safety::check_added_particle_time_step(
            &self.bodies,
            &self.config.interactions,
            id,
            self.config.time_step,
            &self.config.safety,
        )
    }

    /// Advances by one Δt. The first call checks the time step, refuses bodies that already overlap, and opens the
    /// energy ledger.
    pub fn step(&mut self) -> Result<(), WorldError> {
        if !self.started {
            self.check_time_step()?;
            if let Some((a, b, fraction)) =
                safety::deepest_initial_overlap(&self.bodies, self.config.safety.max_initial_overlap_fraction)
            {
                return Err(SafetyError::InitialOverlap { a: a.0, b: b.0, percent: 100.0 * fraction }.into());
            }
            // A scene much wider than high sorts its y axis in bands of x (broadphase::bands); decided once, here,
            // from the bodies the scene starts with, so a resumed run keeps the choice its checkpoint saved.
            self.broadphase.band_y_axis_if_wide();
            self.started = true;
            self.ledger.contact_stored = self.contact_stored_energy();
            self.refresh_stored_energies();
            self.ledger.initial_total = self.ledger.total();
        }
        let dt = self.config.time_step;
        let t_next = self.time + dt;
        if let Some(clock) = &mut self.stage_clock {
            clock.start_step();
        }
        if self.stages.outlets {
            self.transits.start_step();
            self.positions_before_step.clear();
            self.positions_before_step.extend(self.bodies.pose.iter().map(|pose| pose.position));
        }
        if self.predicts_in_transform_pass() {
            self.predict_and_transform();
        } else {
            self.predict(t_next);
            self.lap(Stage::Predict);
            self.bodies.update_world_vertices(self.broadphase.box_writer(self.bodies.len()));
        }
        self.lap(Stage::Vertices);
        if self.stages.sources || self.stages.inlets {
            self.broadphase.update_written_for_queries();
        } else {
            self.broadphase.update_written();
        }
        self.close_ended_pairs(t_next);
        self.lap(Stage::Broadphase);
        let forces_added = self.evaluate_pairs();
        self.lap(Stage::Narrowphase);
        let closing_with_corrector = self.closing_pass_with_corrector(t_next);
        // Gravity alone and no events: each range of bodies is corrected in the pass that adds its forces.
        let corrected_with_forces = forces_added == ForcesAdded::Later
            && self.events.is_none()
            && matches!(self.body_forces.as_slice(), [BodyForce::Gravity]);
        if corrected_with_forces {
            self.add_forces_and_correct(self.config.gravity.acceleration(t_next), closing_with_corrector.as_ref());
        } else if forces_added == ForcesAdded::Later {
            self.accumulate_contact_forces();
        }
        self.book_pair_sums();
        if self.stages.rotors {
            let drive = self.rotor_power();
            self.rotor_work.from_torque += drive.power_from_torque * dt;
            self.rotor_work.from_work += drive.power_from_work * dt;
        }
        if self.events.is_some() {
            self.log_contact_events(t_next);
        }
        self.lap(Stage::Accumulation);
        if !corrected_with_forces {
            self.apply_body_forces(t_next)?;
            self.lap(Stage::BodyForces);
            self.correct(closing_with_corrector.as_ref());
        }
        self.lap(Stage::Correct);
        if self.stages.moving_walls {
            self.advance_pistons();
        }
        let g_before = self.config.gravity.magnitude(self.time);
        self.time = t_next;
        self.steps += 1;
        if self.stages.variable_gravity {
            self.account_gravity_change(g_before);
        }
        if self.stages.outlets {
            self.remove_at_outlets();
        }
        if self.stages.domain {
            self.remove_escaped_particles();
        }
        if self.stages.sources {
            self.run_sources()?;
        }
        if self.stages.inlets {
            self.run_inlets()?;
        }
        self.lap(Stage::Boundaries);
        let closing =
            if closing_with_corrector.is_some() { self.book_stored_energies() } else { self.refresh_stored_energies() };
        let checked = self.check_blow_up(&closing);
        self.lap(Stage::LedgerAndChecks);
        if let Some(clock) = &mut self.stage_clock {
            clock.end_step();
        }
        checked
    }

    /// Books the time since the last lap to `stage` while the stage clock runs.
    fn lap(&mut self, stage: Stage) {
        if let Some(clock) = &mut self.stage_clock {
            clock.lap(stage);
        }
    }

    /// Times every stage of each step from now on, from zero if the clock already ran, until
    /// [`Self::stop_stage_clock`]. For finding what limits a run on many threads; costs a clock reading per stage.
    pub fn start_stage_clock(&mut self) {
        self.stage_clock = Some(StageClock::new());
    }

    /// Stops the stage clock and returns the wall-clock time per stage of the steps since
    /// [`Self::start_stage_clock`]; `None` where it was not running.
    pub fn stop_stage_clock(&mut self) -> Option<StageTimes> {
        self.stage_clock.take().map(StageClock::into_times)
    }

    /// Steps until the time reaches `t_end` (within half a step).
    ///
    /// The loop runs on a worker of the current rayon pool, so each step's parallel sections start inside the pool
    /// instead of being handed over from the calling thread, which then sleeps until they finish (that hand-over cost
    /// about 15 % of a 1,900-grain silo's step on one thread). A loop that calls [`step`](Self::step) itself gains the
    /// same by running inside `ThreadPool::install`.
    pub fn run_until(&mut self, t_end: f64) -> Result<(), WorldError> {
        rayon::scope(|_| {
            while self.time + 0.5 * self.config.time_step < t_end {
                self.step()?;
            }
            Ok(())
        })
    }

    /// Integrator's predict (Gear predictor or Verlet kick and drift) for particles, prescribed poses for moving
    /// walls, s(t) for everyone.
    fn predict(&mut self, t_next: f64) {
        let integrator = RowIntegrator::of(&self.integrator, self.stages.polygon_particles);
        let rows = self.bodies.split_for_integration().kinematics;
        for_each_kinematics_row(rows, |_, row| integrator.predict(row));
        let b = &mut self.bodies;
        if self.stages.moving_walls {
            for wall in &self.moving_walls {
                let kinematics = wall.motion.kinematics(t_next);
                let i = wall.body.index();
                let pose = kinematics.place(wall.rest);
                b.pose[i] = pose;
                b.velocity[i] = kinematics.point_velocity(pose.position);
                b.angular_velocity[i] = kinematics.angular_velocity;
            }
        }
        if self.stages.heating
            && let Some(heating) = self.config.heating
        {
            let scale = heating.scale(t_next);
            // Every particle has the same scale (an inserted one gets the current one), so one is enough to measure
            // the step's change.
            let mut changed_from = None;
            for i in 0..b.len() {
                if b.kind[i] != BodyKind::Particle {
                    continue;
                }
                let old_scale = b.pose[i].scale;
                if old_scale != scale {
                    // The travel bound is for poses of one scale: a grown body has moved by more than it says.
                    b.travel[i] = f32::INFINITY;
                    changed_from = Some(old_scale);
                    if b.alive[i] {
                        self.ledger.work_heating += keep_angular_momentum(b, i, old_scale, scale);
                    }
                }
                b.pose[i].scale = scale;
                b.inverse_inertia[i] = 1.0 / (b.inertia[i] * HeatingSchedule::inertia_factor(scale));
            }
            self.scale_log_change = changed_from.map_or(0.0, |old_scale| (scale / old_scale).ln());
        }
    }

    /// Whether the predictor runs in the vertex transform's pass ([`Self::predict_and_transform`]): where the World
    /// steps in parallel and has neither moving walls nor heating, whose poses and scales the predictor sets after the
    /// particles', sequentially.
    fn predicts_in_transform_pass(&self) -> bool {
        steps_in_parallel(self.bodies.len()) && !self.stages.moving_walls && !self.stages.heating
    }

    /// The predictor ([`Self::predict`]) and the vertex transform in one pass: each range of bodies is predicted and
    /// then transformed on its home thread, which spares a wait for every thread a step (docs/performance.md, "One
    /// pass for the forces and the corrector"). Each body's pose is predicted before its vertices are computed from
    /// it, as with two passes, so the bits are the same.
    fn predict_and_transform(&mut self) {
        let integrator = RowIntegrator::of(&self.integrator, self.stages.polygon_particles);
        let boxes = self.broadphase.box_writer(self.bodies.len());
        self.bodies.move_and_update_world_vertices(boxes, |first, rows| {
            for_each_row(first, rows, |_, row| integrator.predict(row));
        });
    }

    /// Contacts whose boxes separated in one step may still have held energy: book it as opening residual. Their
    /// open episodes end at `time`.
    fn close_ended_pairs(&mut self, time: f64) {
        if let Some(log) = &mut self.events {
            log.start_step();
        }
        for ended in self.broadphase.ended_pairs() {
            self.ledger.opening_residual += ended.payload.stored_energy;
            if let Some(log) = &mut self.events {
                let (a, b) = (BodyId(ended.a()), BodyId(ended.b()));
                let materials = [self.bodies.material[a.index()], self.bodies.material[b.index()]];
                log.end(a, b, materials, time, wall_pivot(&self.moving_walls, &self.bodies, a, b));
            }
        }
    }

    /// Writes the step's contact events and adds the step to the open episodes, in pair order (see
    /// [`crate::events`]). At first touch the impact speeds are those of the contact points along and across the
    /// contact normal, at the predicted state the contact law saw.
    fn log_contact_events(&mut self, time: f64) {
        let Some(log) = &mut self.events else { return };
        let context = pair_context(&self.bodies, &self.config);
        let b = &self.bodies;
        for pair in self.broadphase.pairs() {
            let c = &pair.payload;
            let (a, bb) = (BodyId(pair.a()), BodyId(pair.b()));
            let open = log.is_open(a, bb);
            if !c.touching && !open {
                continue;
            }
            let step = PairStep {
                a,
                b: bb,
                materials: [b.material[a.index()], b.material[bb.index()]],
                touching: c.touching,
                force_on_a: c.force_on_a,
                point: c.point,
                overlap_fraction: context.overlap_fraction(pair.a(), pair.b(), c),
                dissipated: c.dissipated,
            };
            if c.touching && !open {
                let (normal_speed, tangential_speed) = impact_speeds(&context, pair.a(), pair.b(), c.point);
                log.begin(&step, time, normal_speed, tangential_speed);
            }
            log.accumulate(&step, self.config.time_step);
            if !c.touching {
                log.end(a, bb, step.materials, time, wall_pivot(&self.moving_walls, b, a, bb));
            }
        }
    }

    /// Narrowphase and contact law for every pair, in parallel; each pair writes only its own record, and each
    /// fixed chunk of pairs its own [`PairSums`] (the ledger's terms, the chatter watch, the statistics) and its masks
    /// of the touching pairs that reach each range of bodies of the force accumulation (`force_ranges`).
    ///
    /// Where the pass runs on one thread (a small World, or a pool of one thread) it also adds each touching pair's
    /// forces to its bodies right after evaluating it, while the record is in cache, and returns
    /// [`ForcesAdded::InNarrowphase`]: the same additions in the same order as [`add_contact_forces`], so the same
    /// sums bit for bit, without reading the pair list a second time (docs/performance.md, "The forces added in the
    /// narrowphase on one thread").
    fn evaluate_pairs(&mut self) -> ForcesAdded {
        self.pair_sums.resize(self.broadphase.pairs().len().div_ceil(PAIRS_PER_CHUNK), PairSums::default());
        if !steps_in_parallel(self.bodies.len()) {
            self.evaluate_pairs_adding_forces();
            return ForcesAdded::InNarrowphase;
        }
        let context = pair_context(&self.bodies, &self.config);
        let pairs = self.broadphase.pairs_mut();
        let ranges = BodyRanges::of_pool(self.bodies.len());
        self.body_ranges = ranges;
        self.range_masks.resize(self.pair_sums.len() * ranges.count, 0);
        let heated = self.stages.heating;
        let evaluate_chunk = |((chunk, sums), masks): ((&mut [PairEntry<PairContact>], &mut PairSums), &mut [u64])| {
            masks.fill(0);
            let touching = |position, pair: &PairEntry<PairContact>| mark_touching_pair(masks, &ranges, position, pair);
            evaluate_chunk(&context, heated, chunk, sums, touching);
        };
        let chunks = pairs.par_chunks_mut(PAIRS_PER_CHUNK).zip(self.pair_sums.par_iter_mut());
        let chunks = chunks.zip(self.range_masks.par_chunks_mut(ranges.count));
        chunks.with_max_len(CHUNKS_PER_TASK).for_each(evaluate_chunk);
        ForcesAdded::Later
    }

    /// [`Self::evaluate_pairs`] on the calling thread (the chunks' sums already sized), adding each touching pair's
    /// forces to its bodies as it goes.
    fn evaluate_pairs_adding_forces(&mut self) {
        // The pair context reads the bodies while the forces are written: the two force columns are taken out of
        // the store for the pass (it reads neither) and put back after it.
        let mut forces = std::mem::take(&mut self.bodies.force);
        let mut torques = std::mem::take(&mut self.bodies.torque);
        forces.fill(DVec2::ZERO);
        torques.fill(0.0);
        let context = pair_context(&self.bodies, &self.config);
        let pairs = self.broadphase.pairs_mut();
        let heated = self.stages.heating;
        for (chunk, sums) in pairs.chunks_mut(PAIRS_PER_CHUNK).zip(self.pair_sums.iter_mut()) {
            let touching = |_, pair: &PairEntry<PairContact>| add_pair_forces(pair, 0, &mut forces, &mut torques);
            evaluate_chunk(&context, heated, chunk, sums, touching);
        }
        self.bodies.force = forces;
        self.bodies.torque = torques;
    }

    /// Adds the contact forces to the bodies, each body's in pair order (so independent of the thread count), in
    /// parallel over ranges of bodies, where the narrowphase pass did not add them ([`ForcesAdded::Later`]): one range
    /// per thread, each on its home thread (crate::home_threads), as the narrowphase marked them, so that a range reads
    /// only the touching pairs that reach it.
    fn accumulate_contact_forces(&mut self) {
        let pairs = self.broadphase.pairs();
        let (ranges, masks) = (&self.body_ranges, &self.range_masks);
        let per_range = ranges.per_range();
        let b = &mut self.bodies;
        let rows = b.force.chunks_mut(per_range).zip(b.torque.chunks_mut(per_range));
        for_each_on_home_thread(rows, |range, (forces, torques)| {
            add_contact_forces(pairs, masks, ranges, range, forces, torques);
        });
    }

    /// [`Self::accumulate_contact_forces`], gravity ([`BodyForce::Gravity`]) and [`Self::correct`] in one pass: each
    /// range of bodies adds its contact forces and weights and is corrected on its home thread before the pass ends
    /// (and, with `closing`, sums its chunks of the closing pass, as in [`Self::correct`]).
    /// For a World stepping in parallel whose only body force is gravity and that writes no contact events (which read
    /// the predicted velocities after the forces): it spares two passes over the bodies, each of which costs a wake-up
    /// of every thread and a wait for the slowest one (about 20 µs a step on 16 threads, docs/performance.md, "One pass
    /// for the forces and the corrector"). The same additions in the same order as the three passes, so the same
    /// results bit for bit.
    fn add_forces_and_correct(&mut self, gravity: DVec2, closing: Option<&ClosingPass>) {
        let pairs = self.broadphase.pairs();
        let (ranges, masks) = (&self.body_ranges, &self.range_masks);
        let per_range = ranges.per_range();
        let integrator = RowIntegrator::of(&self.integrator, self.stages.polygon_particles);
        let IntegrationColumns { kinematics: rows, forces, inscribed_radius } = self.bodies.split_for_integration();
        let ForceColumns { force, torque, mass, inverse_mass, inverse_inertia } = forces;
        let weighed = WeighedBodies { mass, kind: rows.kind, alive: rows.alive };
        let range_forces = force.chunks_mut(per_range).zip(torque.chunks_mut(per_range));
        let range_sums = self.body_sums.chunks_mut(per_range / BODIES_PER_CHUNK);
        let pieces = rows.ranges(per_range).zip(range_forces).zip(range_sums);
        for_each_on_home_thread(pieces, |range, ((mut rows, (forces, torques)), sums)| {
            add_contact_forces(pairs, masks, ranges, range, forces, torques);
            let first = range * per_range;
            add_weights(forces, first, &weighed, gravity);
            for_each_row(first, &mut rows, |i, row| {
                let k = i - first;
                integrator.correct(row, forces[k] * inverse_mass[i], torques[k] * inverse_inertia[i]);
            });
            if let Some(pass) = closing {
                let columns = ClosingColumns::of_rows(&rows, first, mass, inverse_inertia, inscribed_radius);
                pass.sum_chunks(&columns, first, sums);
            }
        });
    }

    /// Books the chunks' sums in chunk order: the contacts' energy terms, the energy they store (kept by the ledger
    /// until the next step: pairs of particles removed later in this step still hold it, and their ending books it as
    /// opening residual then), the chatter watch and the statistics.
    fn book_pair_sums(&mut self) {
        let mut sums = PairSums::default();
        self.pair_sums.iter().for_each(|chunk| sums.add(chunk));
        self.ledger.book_contacts(&sums.energy);
        self.ledger.contact_stored = sums.contact_stored;
        if self.stages.heating {
            self.ledger.work_heating += self.contact_expansion.step_work(self.scale_log_change, sums.expansion_virial);
        }
        self.stats = StepStats {
            box_pairs: self.broadphase.pairs().len(),
            contacts: sums.contacts,
            max_overlap_fraction: sums.max_overlap_fraction,
            multi_pass_queries: sums.multi_pass_queries,
            ..self.stats
        };
        self.force_alternation = if self.force_history_steps < FULL_FORCE_HISTORY {
            ForceAlternation::not_measured()
        } else {
            ForceAlternation { change: sums.alternation, scale: 2.0 * sums.force_scale }
        };
        self.force_history_steps = (self.force_history_steps + 1).min(FULL_FORCE_HISTORY);
    }

    /// The body forces, in list order, each booking its work in the ledger.
    fn apply_body_forces(&mut self, t_next: f64) -> Result<(), WorldError> {
        let step = BodyForceStep {
            gravity: self.config.gravity.acceleration(t_next),
            time: t_next,
            dt: self.config.time_step,
            mass_model: self.config.mass_model,
            time_step: *self.integrator.time_step(),
            crossings: OutletCrossings { outlets: &self.outlets, before: &self.positions_before_step },
        };
        for force in &self.body_forces {
            force.apply(&mut self.bodies, &step, &mut self.ledger)?;
        }
        Ok(())
    }

    /// Integrator's correct (Gear corrector or Verlet's second kick) for particles with a = F/m, α = τ/I; with
    /// `closing`, each range of bodies then sums its chunks of the closing pass ([`Self::closing_pass_with_corrector`]).
    fn correct(&mut self, closing: Option<&ClosingPass>) {
        let integrator = RowIntegrator::of(&self.integrator, self.stages.polygon_particles);
        let IntegrationColumns { kinematics: mut rows, forces, inscribed_radius } = self.bodies.split_for_integration();
        let ForceColumns { force, torque, mass, inverse_mass, inverse_inertia } = forces;
        let (force, torque) = (&*force, &*torque);
        let correct_range = |first: usize, rows: &mut KinematicsColumns, sums: &mut [BodySums]| {
            for_each_row(first, rows, |i, row| {
                integrator.correct(row, force[i] * inverse_mass[i], torque[i] * inverse_inertia[i]);
            });
            if let Some(pass) = closing {
                pass.sum_chunks(
                    &ClosingColumns::of_rows(rows, first, mass, inverse_inertia, inscribed_radius),
                    first,
                    sums,
                );
            }
        };
        let bodies = rows.len();
        if !steps_in_parallel(bodies) {
            correct_range(0, &mut rows, &mut self.body_sums);
            return;
        }
        let per_range = BodyRanges::of_pool(bodies).per_range();
        let pieces = rows.ranges(per_range).zip(self.body_sums.chunks_mut(per_range / BODIES_PER_CHUNK));
        for_each_on_home_thread(pieces, |range, (mut rows, sums)| correct_range(range * per_range, &mut rows, sums));
    }

    /// Force-controlled pistons react to the force the particles exerted on them this step.
    fn advance_pistons(&mut self) {
        let dt = self.config.time_step;
        for wall in &mut self.moving_walls {
            if let WallMotion::Piston(piston) = &mut wall.motion {
                let measured = piston.measured_force(self.bodies.force[wall.body.index()]);
                piston.advance(measured, dt);
            }
        }
    }

    /// A change of g at fixed positions changes the potential energy: that is work done from outside.
    fn account_gravity_change(&mut self, g_before: f64) {
        let dg = self.config.gravity.magnitude(self.time) - g_before;
        if dg != 0.0 {
            let b = &self.bodies;
            let mgy: f64 = b.particles().map(|id| b.mass[id.index()] * b.pose[id.index()].position.y).sum();
            self.ledger.work_gravity_change += dg * mgy;
        }
    }

    /// Removes particles whose centroid left the domain, booking their energy as removed.
    fn remove_escaped_particles(&mut self) {
        let Some(domain) = self.config.domain else { return };
        let g = self.config.gravity.magnitude(self.time);
        let escaped: Vec<BodyId> =
            self.bodies.particles().filter(|id| !domain.contains(self.bodies.pose[id.index()].position)).collect();
        for id in escaped {
            self.remove_particle(id, g);
            self.transits.forget(id);
            self.stats.removed += 1;
        }
    }

    /// Removes particles whose centre crossed an outlet outward during the step (tested in outlet order: a particle
    /// is counted by the first outlet it crossed), booking their energy as removed.
    fn remove_at_outlets(&mut self) {
        let g = self.config.gravity.magnitude(self.time);
        for i in 0..self.positions_before_step.len() {
            if !(self.bodies.alive[i] && self.bodies.kind[i] == BodyKind::Particle) {
                continue;
            }
            let (before, after) = (self.positions_before_step[i], self.bodies.pose[i].position);
            if let Some(index) = self.outlets.iter().position(|o| o.outlet().crossed_outward(before, after)) {
                self.outlets[index].removed();
                self.transits.left(BodyId(i as u32), index, self.time);
                self.remove_particle(BodyId(i as u32), g);
                self.stats.removed_at_outlets += 1;
            }
        }
    }

    /// Takes particle `id` out of the World, booking its kinetic and potential energy (at gravity `g`) as removed.
    fn remove_particle(&mut self, id: BodyId, g: f64) {
        let i = id.index();
        let b = &self.bodies;
        self.ledger.energy_removed += 0.5 * b.mass[i] * b.velocity[i].length_squared()
            + 0.5 * b.angular_velocity[i].powi(2) / b.inverse_inertia[i]
            + b.mass[i] * g * b.pose[i].position.y;
        self.bodies.alive[i] = false;
        self.broadphase.remove(id.0);
    }

    /// Inserts the particles the inlets owe at the end of this step, each inlet in order and its particles in due
    /// order; a due particle without a free spot waits for the next step, and so do those behind it.
    fn run_inlets(&mut self) -> Result<(), WorldError> {
        let (step, dt) = (self.steps, self.config.time_step);
        for i in 0..self.inlets.len() {
            while self.inlets[i].next_is_due(step, dt) {
                let Some(id) = self.insert_from_inlet(i) else {
                    self.inlets[i].postponed();
                    self.stats.postponed += 1;
                    break;
                };
                self.transits.entered(id, i, self.time);
                self.insertions.record(id, Inserter::Inlet(i as u32));
                self.inlets[i].inserted();
                self.stats.injected += 1;
                self.check_added_time_step(id)?;
            }
        }
        Ok(())
    }

    /// Draws the next particle of inlet `index` and up to [`PLACEMENT_ATTEMPTS`] points along its segment, and
    /// inserts the particle at the first free one; `None` when every point was taken.
    fn insert_from_inlet(&mut self, index: usize) -> Option<BodyId> {
        let (inlet, rng) = self.inlets[index].parts();
        let drawn = inlet.recipe.draw(rng);
        let fractions: [f64; PLACEMENT_ATTEMPTS] = std::array::from_fn(|_| rng.random::<f64>());
        let (shape, angle) = drawn.ok()?;
        let (from, to, velocity, angular_velocity) = (inlet.from, inlet.to, inlet.velocity, inlet.angular_velocity);
        let (density, material) = (inlet.density, inlet.material);
        let pose = fractions.iter().find_map(|&u| self.free_pose(&shape, angle, from + (to - from) * u))?;
        let id = self.add_particle(shape, pose, density, velocity, angular_velocity).ok()?;
        self.bodies.material[id.index()] = material;
        Some(id)
    }

    /// The pose of `shape` turned by `angle` with its centroid at `position` (at the current heating scale), if the
    /// particle would overlap no living body there.
    fn free_pose(&self, shape: &BodyShape, angle: f64, position: DVec2) -> Option<Pose> {
        let scale = self.config.heating.map_or(1.0, |h| h.scale(self.time));
        let points = shape.body_points();
        let mut world = [DVec2::ZERO; gc2d_geometry::MAX_VERTICES];
        let world = &mut world[..points.len()];
        let pose = Pose { position, angle, scale };
        pose.transform_into(&points, world);
        (!self.overlaps_any(shape_view(shape.kind(), world, shape.radius() * scale))).then_some(pose)
    }

    /// Inserts the particles the sources owe at the current time. A new particle smaller than any before may lower
    /// the stable time step, so the bound is checked again after each insertion.
    fn run_sources(&mut self) -> Result<(), WorldError> {
        let t = self.time;
        for s in 0..self.sources.len() {
            while self.sources[s].take_due(t) {
                let source = self.sources[s].source.clone();
                match self.insert_from_source(&source) {
                    Some(id) => {
                        self.insertions.record(id, Inserter::Source(s as u32));
                        self.stats.inserted += 1;
                        self.check_added_time_step(id)?;
                    }
                    None => self.stats.insertions_skipped += 1,
                }
            }
        }
        Ok(())
    }

    /// Draws a shape and finds a free spot for it on the source's line; `None` when every attempt overlapped.
    fn insert_from_source(&mut self, source: &DropSource) -> Option<BodyId> {
        let (shape, angle) = source.recipe.draw(&mut self.rng).ok()?;
        let half = 0.5 * source.width;
        let y = match source.height {
            DropHeight::Absolute => source.position.y,
            DropHeight::AboveHighest => {
                let highest = self.highest_particle_within(source.position.x, half);
                source.position.y + if highest.is_finite() { highest } else { 0.0 }
            }
        };
        for _ in 0..PLACEMENT_ATTEMPTS {
            let x = source.position.x + if half > 0.0 { self.rng.random_range(-half..=half) } else { 0.0 };
            if let Some(pose) = self.free_pose(&shape, angle, DVec2::new(x, y)) {
                let id = self.add_particle(shape.clone(), pose, source.density, DVec2::ZERO, 0.0).ok()?;
                self.bodies.material[id.index()] = source.material;
                return Some(id);
            }
        }
        None
    }

    /// The highest centroid (y) of a living particle whose centroid lies within `half_width` of `x`; −∞ if none.
    ///
    /// Walks the particles from the highest box top down (a broadphase query) and stops at the first box whose top
    /// is below the best centroid found: a centroid lies inside its box, which is that of the predicted pose, and
    /// the corrector moves a particle far less than its inscribed radius (the safety checks stop a run long before).
    /// Particles inserted since the last update are not in the broadphase's order and are looked at one by one.
    fn highest_particle_within(&self, x: f64, half_width: f64) -> f64 {
        let b = &self.bodies;
        let centroid_within = |body: u32| {
            let i = body as usize;
            let position = b.pose[i].position;
            (b.alive[i] && b.kind[i] == BodyKind::Particle && (position.x - x).abs() <= half_width)
                .then_some(position.y)
        };
        let mut highest = self
            .broadphase
            .pending()
            .iter()
            .filter_map(|&body| centroid_within(body))
            .fold(f64::NEG_INFINITY, f64::max);
        for (body, top) in self.broadphase.dynamic_bodies_from_top(x - half_width, x + half_width) {
            if top < highest {
                break;
            }
            if let Some(y) = centroid_within(body) {
                highest = highest.max(y);
            }
        }
        highest
    }

    /// True when the particle outline `shape` (world frame) overlaps any living body: a broadphase query for the
    /// bodies whose boxes meet its box (the broadphase tests the box, which is the one `Bodies::aabb` would compute
    /// from the same world vertices), then the exact overlap test on each.
    fn overlaps_any(&self, shape: ShapeView) -> bool {
        let b = &self.bodies;
        self.broadphase.any_box_meeting(&shape.aabb(), |body| {
            b.alive[body as usize] && area_contact(shape, b.shape_view(BodyId(body))).is_some()
        })
    }

    /// Recomputes the kinetic, potential and drag-spring energies of the ledger from the state, in one pass over the
    /// bodies (parallel over fixed chunks, [`crate::body_sums`]) that also checks that every living body passes
    /// [`state_is_finite`] and every particle the travel limit; returns what the checks found. The contact energy is
    /// summed where the pairs are visited anyway, in [`Self::evaluate_pairs`].
    fn refresh_stored_energies(&mut self) -> BodySums {
        let pass = self.closing_pass(self.time);
        let columns = ClosingColumns::of_bodies(&self.bodies);
        self.body_sums.resize(self.bodies.len().div_ceil(BODIES_PER_CHUNK), BodySums::default());
        let sum_chunk = |(k, sums): (usize, &mut BodySums)| *sums = pass.chunk(&columns, k * BODIES_PER_CHUNK, 0);
        if steps_in_parallel(self.bodies.len()) {
            self.body_sums.par_iter_mut().enumerate().for_each(sum_chunk);
        } else {
            self.body_sums.iter_mut().enumerate().for_each(sum_chunk);
        }
        self.book_stored_energies()
    }

    /// The closing pass of the step that ends at `time`.
    fn closing_pass(&self, time: f64) -> ClosingPass {
        ClosingPass {
            gravity: self.config.gravity.magnitude(time),
            dt: self.config.time_step,
            max_travel_fraction: self.config.safety.max_travel_fraction,
        }
    }

    /// The closing pass of the step that ends at `t_next`, to be summed by the corrector's pass as each range of bodies
    /// is corrected ([`Self::correct`], [`Self::add_forces_and_correct`]), where nothing after the corrector changes
    /// what it reads: no particle is removed (outlets, the domain) or added (sources, inlets). The same chunks of the
    /// same bodies in the same state, so the same sums bit for bit as the pass of its own, without another pass over
    /// the bodies (on many threads, another wake-up of every thread and wait for the slowest: docs/performance.md, "The
    /// closing sums in the corrector's pass"). Sizes the chunk sums for the bodies either way.
    fn closing_pass_with_corrector(&mut self, t_next: f64) -> Option<ClosingPass> {
        self.body_sums.resize(self.bodies.len().div_ceil(BODIES_PER_CHUNK), BodySums::default());
        let s = &self.stages;
        (!(s.outlets || s.domain || s.sources || s.inlets)).then(|| self.closing_pass(t_next))
    }

    /// Books the chunks' sums of the closing pass, in chunk order, as the ledger's kinetic and potential energies,
    /// with the drag springs' stored energy; returns the sums of all chunks.
    fn book_stored_energies(&mut self) -> BodySums {
        let b = &self.bodies;
        let mut all = BodySums::default();
        self.body_sums.iter().for_each(|chunk| all.add(chunk));
        let drag_stored: f64 = self.body_forces.iter().map(|f| f.stored_energy(b, self.time)).sum();
        let l = &mut self.ledger;
        l.kinetic_translational = all.translational;
        l.kinetic_rotational = all.rotational;
        l.peak_kinetic = l.peak_kinetic.max(l.kinetic());
        l.potential = all.potential;
        l.drag_stored = drag_stored;
        // A finite velocity can still overflow ½mv²: that poisons the ledger, so it counts as not finite.
        all.not_finite |= !(all.translational + all.rotational).is_finite();
        all
    }

    /// Energy stored in the contacts of the current pair list, J.
    fn contact_stored_energy(&self) -> f64 {
        self.broadphase.pairs().iter().map(|p| p.payload.stored_energy).sum()
    }

    /// How fast bodies `a` and `b` of the touching pair `contact` move relative to each other along its normal at its
    /// force point (m/s, closing or separating), and the overlap's depth (m): the area over the contact chord for the overlap-area
    /// law, the depth for penetration laws. For the advice of an excessive overlap.
    fn approach_and_depth(&self, a: BodyId, b: BodyId, contact: &PairContact) -> (f64, f64) {
        let bodies = &self.bodies;
        let point_velocity = |id: BodyId| {
            let i = id.index();
            let r = contact.point - bodies.pose[i].position;
            bodies.velocity[i] + bodies.angular_velocity[i] * r.perp()
        };
        let normal = self.contact_normal(a, b).unwrap_or(DVec2::ZERO);
        // Closing or already thrown apart: a force that reversed the motion within the step is as telling as the
        // approach before it.
        let approach = (point_velocity(a) - point_velocity(b)).dot(normal).abs();
        let (i, j) = (a.index(), b.index());
        let fraction = self.overlap_fraction(a, b, contact);
        let depth = match contact.state {
            ContactHistory::OverlapArea(state) if state.previous_chord > 0.0 => {
                let smaller = bodies.overlap_reference_area(i).min(bodies.overlap_reference_area(j));
                fraction * smaller / state.previous_chord
            }
            ContactHistory::Penetration(state) => state.previous_depth,
            ContactHistory::OverlapArea(_) => {
                let radius = |k: usize| match bodies.kind[k] {
                    BodyKind::Particle => bodies.contact_radius(k),
                    BodyKind::Wall => f64::INFINITY,
                };
                fraction * 2.0 * radius(i).min(radius(j))
            }
        };
        (approach, depth)
    }

    /// Stops the run on NaN (`closing.not_finite`: some living body's state may not be finite), on a tunnelling
    /// overlap, on a particle that travelled too far in the step (`closing.first_excessive_travel`), or on an energy
    /// gain the ledger cannot explain.
    fn check_blow_up(&self, closing: &BodySums) -> Result<(), WorldError> {
        let limits = &self.config.safety;
        let suggested = || safety::suggested_time_step(self.config.time_step, self.stable_time_step());
        let b = &self.bodies;
        if closing.not_finite
            && let Some(i) = (0..b.len()).find(|&i| b.alive[i] && !state_is_finite(b, i))
        {
            return Err(SafetyError::NotFinite {
                time: self.time,
                step: self.steps,
                body: i as u32,
                suggested_dt: suggested(),
            }
            .into());
        }
        if self.stats.max_overlap_fraction > limits.max_overlap_fraction
            && let Some((a, bb, c, overlap_fraction)) = self
                .contacts()
                .map(|(a, b, c)| (a, b, c, self.overlap_fraction(a, b, c)))
                .max_by(|x, y| x.3.total_cmp(&y.3))
        {
            let (approach_speed_m_s, depth) = self.approach_and_depth(a, bb, c);
            let measure = match c.state {
                ContactHistory::OverlapArea(_) => "area",
                ContactHistory::Penetration(_) => "diameter (the depth)",
            };
            return Err(SafetyError::ExcessiveOverlap {
                time: self.time,
                step: self.steps,
                a: a.0,
                b: bb.0,
                percent: 100.0 * overlap_fraction,
                measure,
                limit_percent: 100.0 * limits.max_overlap_fraction,
                approach_speed_m_s,
                approach_per_step: approach_speed_m_s * self.config.time_step / depth,
                suggested_dt: suggested(),
            }
            .into());
        }
        if let Some(i) = closing.first_excessive_travel {
            return Err(self.excessive_travel(i, suggested()).into());
        }
        let gain = self.ledger.balance_error();
        let scale = self.ledger.energy_scale();
        // A NaN gain fails every comparison, so it is caught explicitly: a NaN never passes silently.
        if !gain.is_finite() || gain > limits.max_energy_gain_fraction * scale {
            return Err(SafetyError::EnergyJump {
                time: self.time,
                step: self.steps,
                gain,
                energy_unit: match self.config.mass_model {
                    MassModel::PerUnitThickness => "J/m",
                    MassModel::SphereEquivalent => "J",
                },
                most_energetic: most_energetic_particle(b),
                percent: 100.0 * gain / scale,
                suggested_dt: suggested(),
            }
            .into());
        }
        Ok(())
    }

    /// The error for particle `i`, which moved further in the last step than the travel limit allows (reference §3.6
    /// failure mode 2: a particle that jumps right across a thin wall is never seen overlapping it).
    fn excessive_travel(&self, i: usize, suggested_dt: f64) -> SafetyError {
        let fraction = self.config.safety.max_travel_fraction;
        let dt = self.config.time_step;
        let b = &self.bodies;
        let inscribed_radius = b.inscribed_radius[i] * b.pose[i].scale;
        let travel = safety::step_travel(b, i, dt);
        // The step at which its travel would be half the limit. A scene that allows an unsafe Δt has opted out of the
        // stable bound (a free flight, a settling in a fluid): the travel alone then sets the suggestion, which the
        // stable bound of its contacts made 50,000 times smaller than needed for a 50 µm sphere settling in air.
        let travel_dt = 0.5 * dt * fraction * inscribed_radius / travel;
        SafetyError::ExcessiveTravel {
            time: self.time,
            step: self.steps,
            body: i as u32,
            travel,
            inscribed_radius,
            limit_percent: 100.0 * fraction,
            suggested_dt: if self.config.safety.allow_unsafe_time_step {
                travel_dt
            } else {
                suggested_dt.min(travel_dt)
            },
        }
    }
}

/// What a pair evaluation (or a query repeating one) reads: the bodies and the configuration's contact models and Δt.
/// Takes the two fields rather than the World, so the step can borrow the pair list mutably beside it.
fn pair_context<'a>(bodies: &'a Bodies, config: &'a WorldConfig) -> PairContext<'a> {
    PairContext { bodies, interactions: &config.interactions, dt: config.time_step }
}

/// Evaluates the pairs of `chunk` in list order (`heated`: whether the World is heated), writing their records and
/// the chunk's `sums`, and calls `touching` with each pair that touches and its position in the chunk, right after its
/// evaluation. Always inlined: left to the
/// compiler, the parallel narrowphase of the 12,800 squares ran about 1 % slower on two threads than with the loop
/// written in place (medians of 21 quiet rounds, 139.3 against 137.8 ns per particle-step).
#[inline(always)]
fn evaluate_chunk(
    context: &PairContext,
    heated: bool,
    chunk: &mut [PairEntry<PairContact>],
    sums: &mut PairSums,
    touching: impl FnMut(usize, &PairEntry<PairContact>),
) {
    if heated {
        evaluate_chunk_as::<true>(context, chunk, sums, touching);
    } else {
        evaluate_chunk_as::<false>(context, chunk, sums, touching);
    }
}

/// [`evaluate_chunk`] compiled for a heated World (`HEATED`, whose pairs compute their expansion virials) or not, so
/// that a World without heating runs none of that code ([`PairContext::evaluate`]).
#[inline(always)]
fn evaluate_chunk_as<const HEATED: bool>(
    context: &PairContext,
    chunk: &mut [PairEntry<PairContact>],
    sums: &mut PairSums,
    mut touching: impl FnMut(usize, &PairEntry<PairContact>),
) {
    *sums = PairSums::default();
    for (position, pair) in chunk.iter_mut().enumerate() {
        let evaluation = context.evaluate::<HEATED>(pair.a(), pair.b(), &mut pair.payload);
        // Only a touching pair has an overlap (and only a touching pair's counts in the sums). `overlap_fraction` tests
        // `touching` too, but it is a call: testing here first spares it for the pairs apart (d179a86; reading the
        // fraction inside `evaluate` instead cost 2-5 % more instructions, docs/performance.md, "Finiteness tests
        // without early exits").
        let overlap_fraction =
            if pair.payload.touching { context.overlap_fraction(pair.a(), pair.b(), &pair.payload) } else { 0.0 };
        sums.add_pair::<HEATED>(&pair.payload, &evaluation, overlap_fraction);
        if pair.payload.touching {
            touching(position, pair);
        }
    }
}

/// Where a step's contact forces are added to the bodies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ForcesAdded {
    /// Pair by pair in the narrowphase pass, which ran on one thread.
    InNarrowphase,
    /// By the force accumulation, in parallel over ranges of bodies.
    Later,
}

/// The normal approach speed and the tangential speed of the contact points of pair {a, b} at `point`, m/s, at the
/// state `context` sees; zeros when the pair's query finds no overlap.
fn impact_speeds(context: &PairContext, a: u32, b: u32, point: DVec2) -> (f64, f64) {
    let Some((i, j, normal)) = context.contact_normal(a, b) else { return (0.0, 0.0) };
    let bodies = context.bodies;
    let at = |id: BodyId| {
        let motion = context.motion(id);
        motion.velocity + motion.angular_velocity * (point - bodies.pose[id.index()].position).perp()
    };
    let relative = at(i) - at(j);
    (-relative.dot(normal), relative.dot(normal.perp()).abs())
}

/// Which body of pair {a, b} is a wall turning about a pivot, and the pivot: `(true, P)` for a, `(false, P)` for b.
fn wall_pivot(moving_walls: &[MovingWall], bodies: &Bodies, a: BodyId, b: BodyId) -> Option<(bool, DVec2)> {
    [(a, true), (b, false)].into_iter().find_map(|(id, is_a)| {
        if bodies.kind[id.index()] != BodyKind::Wall {
            return None;
        }
        moving_walls.iter().find(|w| w.body == id).and_then(|w| match &w.motion {
            WallMotion::Rotating(rotation) => Some((is_a, rotation.pivot)),
            _ => None,
        })
    })
}

/// Steps of contact-force history the force-alternation diagnostic needs (F(n−1) and F(n−2)).
const FULL_FORCE_HISTORY: u8 = 2;

/// A loaded World knows each pair's last force (saved) but not the one before.
fn force_history_after_loading() -> u8 {
    1
}

/// The living particle with the most kinetic energy and that energy (for the message of an energy blow-up).
fn most_energetic_particle(b: &Bodies) -> Option<(u32, f64)> {
    (0..b.len())
        .filter(|&i| b.alive[i] && b.kind[i] == BodyKind::Particle)
        .map(|i| (i as u32, kinetic_energy(b, i)))
        .max_by(|x, y| x.1.total_cmp(&y.1))
}

/// Kinetic energy of particle `i`, translational and rotational.
fn kinetic_energy(b: &Bodies, i: usize) -> f64 {
    0.5 * b.mass[i] * b.velocity[i].length_squared() + 0.5 * b.angular_velocity[i].powi(2) / b.inverse_inertia[i]
}

/// True when body `i`'s pose and velocities are finite and, for a particle, so is its kinetic energy (a finite
/// velocity can still overflow ½mv², which would poison the ledger).
fn state_is_finite(b: &Bodies, i: usize) -> bool {
    let kinematics_finite = b.pose[i].position.is_finite()
        && b.pose[i].angle.is_finite()
        && b.velocity[i].is_finite()
        && b.angular_velocity[i].is_finite();
    let energy_finite = b.kind[i] == BodyKind::Wall || kinetic_energy(b, i).is_finite();
    kinematics_finite && energy_finite
}

/// The kinematic columns of one body that the predictor and corrector update, and what they read.
struct KinematicsRow<'a> {
    state: &'a mut GearState,
    pose: &'a mut Pose,
    velocity: &'a mut DVec2,
    angular_velocity: &'a mut f64,
    travel: &'a mut f32,
    kind: BodyKind,
    alive: bool,
    reach: f64,
}

/// The predictor and corrector of one body, with what every body's prediction and correction read.
struct RowIntegrator<'a> {
    integrator: &'a BodyIntegrator,
    time_step: TimeStep,
    /// Whether to keep the travel bound (only once the World has a polygon particle).
    track_travel: bool,
}

impl<'a> RowIntegrator<'a> {
    fn of(integrator: &'a BodyIntegrator, track_travel: bool) -> Self {
        Self { integrator, time_step: *integrator.time_step(), track_travel }
    }

    /// Predicts `row`'s body, if it is a live particle (Gear predictor, or Verlet's kick and drift), copies its pose
    /// and velocities out of the state, and adds the move to its travel bound.
    #[inline(always)]
    fn predict(&self, row: KinematicsRow) {
        if row.kind == BodyKind::Particle && row.alive {
            let before = *row.pose;
            self.integrator.predict_body(row.state);
            sync_kinematics(row.state, &self.time_step, row.pose, row.velocity, row.angular_velocity);
            if self.track_travel {
                // The corrector left the move from the last predicted pose to the corrected one.
                *row.travel += travel_bound(&before, row.pose, row.reach * before.scale);
            }
        }
    }

    /// Corrects `row`'s body for acceleration a = F/m and angular acceleration α = τ/I, if it is a live particle
    /// (Gear corrector or Verlet's second kick), and copies its pose and velocities out of the state.
    #[inline(always)]
    fn correct(&self, row: KinematicsRow, acceleration: DVec2, angular_acceleration: f64) {
        if row.kind == BodyKind::Particle && row.alive {
            let predicted = *row.pose;
            self.integrator.correct_body(row.state, acceleration, angular_acceleration);
            sync_kinematics(row.state, &self.time_step, row.pose, row.velocity, row.angular_velocity);
            if self.track_travel {
                *row.travel = travel_bound(&predicted, row.pose, row.reach * predicted.scale);
            }
        }
    }
}

/// Calls `f(index, row)` for every body: where the World steps in parallel ([`steps_in_parallel`]) each range of
/// bodies on its home thread ([`for_each_on_home_thread`]), else on the calling thread.
fn for_each_kinematics_row(mut columns: KinematicsColumns, f: impl Fn(usize, KinematicsRow) + Sync + Send) {
    let bodies = columns.len();
    // `&f` on both paths: one copy of the row loop, into which the optimiser inlines `f` (with `f` on this path and
    // `&f` on the other, `f` was called out of line from two loops, about 75 instructions a particle-step more;
    // callgrind).
    if !steps_in_parallel(bodies) {
        for_each_row(0, &mut columns, &f);
        return;
    }
    let per_range = BodyRanges::of_pool(bodies).per_range();
    for_each_on_home_thread(columns.ranges(per_range), |range, mut rows| {
        for_each_row(range * per_range, &mut rows, &f)
    });
}

/// Calls `f(first + k, row)` for the k-th body of `columns`, in order, on the calling thread.
fn for_each_row(first: usize, columns: &mut KinematicsColumns, f: impl Fn(usize, KinematicsRow)) {
    let c = columns;
    let n = c.len();
    let (pose, velocity, angular_velocity, travel) =
        (&mut c.pose[..n], &mut c.velocity[..n], &mut c.angular_velocity[..n], &mut c.travel[..n]);
    let (kind, alive, reach) = (&c.kind[..n], &c.alive[..n], &c.reach[..n]);
    for (i, state) in c.gear.iter_mut().enumerate() {
        let row = KinematicsRow {
            state,
            pose: &mut pose[i],
            velocity: &mut velocity[i],
            angular_velocity: &mut angular_velocity[i],
            travel: &mut travel[i],
            kind: kind[i],
            alive: alive[i],
            reach: reach[i],
        };
        f(first + i, row);
    }
}

/// Copies position, angle and velocities out of a particle's Gear state.
#[inline]
fn sync_kinematics(
    state: &GearState,
    time_step: &TimeStep,
    pose: &mut Pose,
    velocity: &mut DVec2,
    angular_velocity: &mut f64,
) {
    pose.position = state.position();
    pose.angle = state.angle();
    *velocity = state.velocity(time_step);
    *angular_velocity = state.angular_velocity(time_step);
}
