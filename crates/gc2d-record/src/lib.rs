//! Recordings of gc2d-rs runs: MCAP files that Foxglove replays, and PNG snapshots for everyone else.
//!
//! A [`Recorder`] observes a World after each step ([`Observer`]) and, at its [`Cadence`] (the frames per simulated
//! second it is given: `gc2d-rs run` gives the scene's `frames_per_second`), writes the particles, walls, force network and statistics as Foxglove messages. Each frame is
//! its own compressed chunk, flushed when written, so an interrupted run leaves a readable file. [`render_png`] draws
//! one state with the same colours. [`FrameBuilder`] builds a frame's messages for both the recorder and the
//! `LiveView` (feature `live`, on by default), which serves them over the Foxglove WebSocket protocol while a run goes
//! on. See docs/recording.md for opening the files in Foxglove.
//!
//! The engine does not depend on this crate; the program that runs the World drives the recorder.

pub mod cadence;
pub mod colour;
mod error;
pub mod fluid;
pub mod frame;
pub mod layout;
#[cfg(feature = "live")]
pub mod live;
mod mcap_file;
pub mod network;
pub mod png;
pub mod quantities;
pub mod recorder;
mod scene;
pub mod stats;

pub use cadence::Cadence;
pub use error::RecordError;
pub use frame::{Frame, FrameBuilder};
#[cfg(feature = "live")]
pub use live::LiveView;
pub use png::{MAX_PIXELS, PngOptions, body_bounds, render_png};
pub use quantities::{ColourBy, ColourRange};
pub use recorder::{Observer, RecordOptions, Recorder, RecordingSummary, RunInfo, SceneFile};
pub use scene::{FLUID_ENTITY, FRAME_ID, PARTICLE_BLOCK_SLOTS, particle_entity_id};
pub use stats::FrameStats;

/// Where the live view listens unless told otherwise: the Foxglove app's default for a local connection
/// (`ws://127.0.0.1:8765`).
pub const DEFAULT_LIVE_ADDRESS: &str = "127.0.0.1:8765";
