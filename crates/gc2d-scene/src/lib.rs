//! RON scene files for gc2d-rs: the schema a person writes, loading with located diagnostics, and building the
//! engine's World.
//!
//! A scene says everything gc2d's gsi format says (reference §9.2–§9.8) in a readable form: run settings, gravity
//! schedule and heating, named materials, walls (polygons, shape macros, motions, and the drum / funnel / silo /
//! box builders), particles (shapes, pose, velocity, drag spring), lattice blocks and drop sources. The format is
//! documented field by field in `docs/scene-format.md`.
//!
//! ```no_run
//! let scene = gc2d_scene::Scene::from_path("scenes/pile.ron")?;
//! println!("{}", scene.summary()?);
//! let mut world = scene.build()?;
//! world.run_until(0.01).expect("stable");
//! # Ok::<(), gc2d_scene::SceneError>(())
//! ```
//!
//! Errors are [`SceneError`]s: miette diagnostics naming the file, line, column and field path, with a suggestion
//! for misspelled names.

mod build;
mod checks;
pub mod error;
pub mod gsi;
mod load;
pub mod schema;
pub mod source;
pub mod spans;
pub mod summary;
mod validate;

pub use build::CheckpointComparison;
pub use build::blocks::MAX_INITIAL_PARTICLES;
pub use build::fluid::{DRAG_STEPS_PER_RELAXATION_TIME, DragScale, FluidSummary};
pub use build::safety::{AUTOMATIC_TIME_STEP_FRACTION, FALLBACK_TIME_STEP, SOURCE_SAMPLES};
pub use build::walls::MAX_DRUM_SEGMENTS;
pub use checks::{rounded_to_significant_digits, significant_digits};
pub use error::{ErrorKind, Location, SceneError};
pub use schema::*;
pub use source::SourceText;
pub use summary::SceneSummary;
