//! gc2d-rs analysis: the thesis's Matlab post-processing layer (reference §5, §7.1, §10.1 item 20) as library
//! functions.
//!
//! Every quantity is computed from a [`Snapshot`] (particles, walls, contact forces, g) so that it can be tested on
//! hand-made configurations. [`analyze_run`] loads a run's `final.ckpt`, computes what applies to a pile or a silo,
//! and writes CSV tables, SVG figures and `analysis.json` into `<run_dir>/analysis/`. See `docs/analysis.md`.

pub mod density;
pub mod error;
pub mod figures;
pub mod geometry;
pub mod janssen;
pub mod mill_space;
pub mod mill_speeds;
pub mod output;
pub mod particle_state;
pub mod pressure;
pub mod repose;
pub mod run;
pub mod scene_feedpipe;
pub mod scene_mill;
pub mod scene_pile;
pub mod scene_silo;
pub mod snapshot;
pub mod statistics;
pub mod stress;
mod table;

pub use density::{Grid, LocalDensity, bulk_packing_fraction, density_grid, local_density};
pub use error::AnalysisError;
pub use geometry::{Rect, convex_hull, hull_area, polygon_area};
pub use janssen::{JanssenFit, JanssenFreeKFit, JanssenParameters, fit_janssen, fit_janssen_free_k};
pub use particle_state::{ParticleShape, ParticleState, particle_states};
pub use pressure::{
    Facing, PressureProfile, ProfileOptions, WallForce, WallSelection, face_length, mean_pressure, pressure_profile,
    wall_forces,
};
pub use repose::{FlankFit, FlankOptions, PileShape, Repose, angle_of_repose, surface_envelope};
pub use run::{AnalyzeOptions, Report, SceneKind, analyze_run, analyze_snapshot, detect_scene};
pub use scene_feedpipe::{FeedpipeOptions, FeedpipeReport, analyze_feedpipe, feedpipe_report};
pub use scene_mill::{
    BallIds, BallSpeeds, CollisionClass, MillOptions, MillPower, MillReport, StressEnergySpectrum, WarmUp,
    analyze_mill, mill_report,
};
pub use scene_pile::{FloorPressureReport, PileReport};
pub use scene_silo::SiloReport;
pub use snapshot::{BodyRef, Contact, ParticleOutline, Snapshot, Wall};
pub use statistics::{
    Coordination, DirectionHistogram, MagnitudeHistogram, coordination, force_direction_histogram,
    force_magnitude_histogram,
};
pub use stress::{LocalStress, PrincipalStress, StressOptions, StressTensor, StressVolume, local_stress, stress_grid};
