//! The run loop's frame sinks: an MCAP recording for Foxglove, PNG pictures and restartable checkpoints.

use crate::numbered_files::{FolderCadence, NumberedFolder};
use crate::runner::{FrameSink, first_tick};
use gc2d_engine::{CheckpointError, World};
use gc2d_geometry::Aabb;
use gc2d_record::{PngOptions, Recorder, body_bounds, render_png};
use gc2d_scene::Scene;
use std::path::{Path, PathBuf};

/// Feeds an MCAP [`Recorder`] one frame per tick.
pub struct Recording {
    /// The recorder; `None` once finished.
    pub recorder: Option<Recorder>,
    /// Simulated time between frames, s.
    pub interval: f64,
}

impl FrameSink for Recording {
    fn interval(&self) -> f64 {
        self.interval
    }

    fn take(&mut self, world: &World) -> Result<(), String> {
        match self.recorder.as_mut() {
            Some(recorder) => recorder.record_frame(world).map(|_| ()).map_err(|e| format!("recording: {e}")),
            None => Ok(()),
        }
    }
}

/// The folder of a run's pictures, under its output directory.
pub const FRAMES_DIR: &str = "frames";

/// Writes `<dir>/frame-<k>.png` on its cadence, k the picture's place on it (taken at k·interval), so that a
/// resumed run numbers its pictures on from where the earlier part stopped instead of overwriting them from 0. Every
/// picture shows one region, so that the frames have one size and scale (a movie needs both): the options' view, or
/// where they have none the region the run's first picture fitted (recorded in the folder's cadence, so that a
/// resumed part keeps it).
pub struct PngFrames {
    /// Output directory.
    pub dir: PathBuf,
    /// Simulated time between pictures, s.
    pub interval: f64,
    /// How the pictures look.
    pub options: PngOptions,
}

impl PngFrames {
    /// The pictures' folder as a [`NumberedFolder`].
    pub fn folder(&self) -> NumberedFolder<'_> {
        Self::folder_at(&self.dir)
    }

    /// The pictures' folder `dir` (a run's `<out>/frames/`) as a [`NumberedFolder`], for a part that draws none.
    pub fn folder_at(dir: &Path) -> NumberedFolder<'_> {
        NumberedFolder { dir, prefix: "frame-", flag: "--png-every", format_flag: "--png-every" }
    }

    /// The interval the pictures are taken on, and the region they show once it is known.
    pub fn cadence(&self) -> FolderCadence {
        FolderCadence { interval: self.interval, formats: "png".to_owned(), region: self.options.view }
    }

    /// Makes `frames/` ready for a part of the run that starts at `world`'s time, as [`crate::dumps::StateDumps::prepare`]
    /// does `dumps/`; a resumed part without a view of its own shows the region the earlier part's pictures show,
    /// in this folder or, for a checkpoint continued in a new directory, in `origin` (its run's `frames/`).
    pub fn prepare(&mut self, world: &World, resumed: bool, origin: Option<&Path>) -> Result<(), String> {
        let folder = self.folder();
        if resumed {
            let origin_region = || {
                let recorded = Self::folder_at(origin?).recorded().ok().flatten();
                recorded.and_then(|cadence| cadence.region)
            };
            let earlier = folder.recorded()?.and_then(|cadence| cadence.region).or_else(origin_region);
            folder.remove_from(first_tick(self.interval, world.time(), 0.5 * world.time_step()))?;
            self.options.view = self.options.view.or(earlier);
        }
        self.folder().record(&self.cadence())
    }
}

impl FrameSink for PngFrames {
    fn interval(&self) -> f64 {
        self.interval
    }

    fn take(&mut self, world: &World) -> Result<(), String> {
        std::fs::create_dir_all(&self.dir).map_err(|e| format!("cannot create {}: {e}", self.dir.display()))?;
        let index = crate::runner::cadence_index(world, self.interval);
        let path = self.dir.join(format!("frame-{index:05}.png"));
        if self.options.view.is_none() {
            self.options.view = body_bounds(world);
            self.folder().record(&self.cadence())?;
        }
        render_png(world, &path, &self.options).map_err(|e| format!("picture {}: {e}", path.display()))
    }
}

/// The region every picture of a run of `scene` shows: its `view`, else its `run.domain`; `None` where it has neither
/// (the first picture then fits the bodies, [`PngFrames`]).
pub fn picture_region(scene: &Scene) -> Option<Aabb> {
    scene.view.or(scene.run.domain).map(|area| area.aabb())
}

/// Writes `<dir>/checkpoint-<step>.ckpt` on its cadence.
pub struct Checkpoints {
    /// Output directory.
    pub dir: PathBuf,
    /// Simulated time between checkpoints, s.
    pub interval: f64,
}

impl FrameSink for Checkpoints {
    fn interval(&self) -> f64 {
        self.interval
    }

    fn is_checkpoint(&self) -> bool {
        true
    }

    fn take(&mut self, world: &World) -> Result<(), String> {
        std::fs::create_dir_all(&self.dir).map_err(|e| format!("cannot create {}: {e}", self.dir.display()))?;
        let path = self.dir.join(format!("checkpoint-{:010}.ckpt", world.steps()));
        save_checkpoint(world, &path).map_err(|e| format!("cannot write {}: {e}", path.display()))
    }
}

/// Writes `world` to the checkpoint `path` ([`World::save_checkpoint_file`]: into `<path>.tmp`, then renamed); a write
/// that fails (a full disk) removes its temporary file instead of leaving it beside the run's outputs.
pub fn save_checkpoint(world: &World, path: &Path) -> Result<(), CheckpointError> {
    let saved = world.save_checkpoint_file(path);
    if saved.is_err() {
        let _ = std::fs::remove_file(crate::resume::temporary_path(path));
    }
    saved
}
