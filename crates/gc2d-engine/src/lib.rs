//! The gc2d-rs simulation engine: the World and its step pipeline (see ARCHITECTURE.md, "One step, as data flows").
//!
//! The engine knows nothing about scene files, recordings or the command line; those crates build and observe a
//! World through the types exported here.

pub mod integrator;
pub mod motion;
pub mod schedules;
pub mod time_window;
pub mod broadphase;
