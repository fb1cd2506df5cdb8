//! The gc2d-rs simulation engine: the World and its step pipeline (see ARCHITECTURE.md, "One step, as data flows").
//!
//! A [`World`] holds particles and walls ([`bodies`]), the persistent pair list of the sort-and-sweep
//! [`broadphase`] with each pair's contact history ([`narrowphase`]), the drivers that move walls and pull
//! particles ([`motion`], [`schedules`], [`sources`]), and the [`ledger`] that accounts for every joule. Particles
//! are integrated by the 6-value Gear predictor-corrector or, for comparison, velocity Verlet ([`integrator`]);
//! [`safety`] refuses unstable time steps and stops runs that blow up. A World saves and restores its complete state as a [`checkpoint`].
//!
//! The engine knows nothing about scene files, recordings or the command line; those crates build and observe a
//! World through the types exported here.

pub mod bodies;
pub mod body_forces;
mod body_sums;
pub mod broadphase;
pub mod checkpoint;
pub mod clearance;
pub mod events;
mod force_ranges;
mod heating;
mod home_threads;
pub mod inlets;
pub mod insertions;
pub mod integrator;
pub mod interactions;
pub mod ledger;
pub mod motion;
pub mod narrowphase;
pub mod outlets;
mod pair_sums;
mod parallel;
pub mod safety;
pub mod schedules;
pub mod shape;
pub mod sources;
pub mod stage_clock;
pub mod time_window;
pub mod transits;
pub mod world;

pub use bodies::{Bodies, BodyId, BodyKind};
pub use body_forces::{AttachedSpring, BodyForce, Fluid};
pub use checkpoint::CheckpointError;
pub use events::{ContactEvent, ContactEventKind, Episode};
pub use inlets::{Inlet, InletCounters, InletState};
pub use insertions::{Inserter, Insertion};
pub use integrator::{GearC0, Integrator};
pub use interactions::{ContactModel, InteractionError, InteractionTable, MaterialId, MaterialPair};
pub use ledger::EnergyLedger;
pub use motion::WallMotion;
pub use narrowphase::{ContactHistory, PairContact};
pub use outlets::{Outlet, OutletCounters, OutletState};
pub use safety::{SafetyError, SafetyLimits};
pub use shape::{BodyShape, BodyShapeError, DiskRecipe, MassModel, ParticleRecipe, ShapeKind, shape_view};
pub use sources::{DropHeight, DropSource};
pub use stage_clock::{Stage, StageTimes};
pub use time_window::TimeWindow;
pub use transits::{InletEntry, Transit};
pub use world::{
    ForceAlternation, MovingWall, RotorPower, RotorWork, StepStats, WallLoad, World, WorldConfig, WorldError,
};
