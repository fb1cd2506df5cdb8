//! Particle sources (gc2d's DROPSOURCE, reference §9.8): insert one particle per interval inside a time window.

use crate::interactions::MaterialId;
use crate::shape::ParticleRecipe;
use crate::time_window::TimeWindow;
use gc2d_geometry::DVec2;
use serde::{Deserialize, Serialize};

/// Where a source puts the new particle's centroid vertically.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum DropHeight {
    /// gc2d `ABS`: at the source's y.
    Absolute,
    /// gc2d `REL`: at the source's y above the highest particle centroid within the source's width (0 if none), so
    /// the drop height stays constant above a growing pile.
    AboveHighest,
}

/// A particle source. Each insertion draws a shape from `recipe` (a polygon or a disk), places it at a uniformly
/// random x within `width` around `position.x`, and starts it at rest.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DropSource {
    /// Centre of the insertion line, m.
    pub position: DVec2,
    /// Width of the insertion line, m.
    pub width: f64,
    /// How the insertion height is found.
    pub height: DropHeight,
    /// When the source inserts.
    pub window: TimeWindow,
    /// Time between two insertions, s.
    pub interval: f64,
    /// Shape of the inserted particles.
    pub recipe: ParticleRecipe,
    /// Density of the inserted particles (kg/m² or kg/m³ by the World's mass model).
    pub density: f64,
    /// Material of the inserted particles.
    pub material: MaterialId,
}

/// Attempts at a free spot per insertion before the insertion is skipped (and counted).
pub const PLACEMENT_ATTEMPTS: usize = 10;

/// A source and the time of its next insertion.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(crate) struct SourceState {
    pub source: DropSource,
    pub next_insertion: f64,
}

impl SourceState {
    /// A source whose first insertion is at the start of its window.
    pub fn new(source: DropSource) -> Self {
        let next_insertion = source.window.start.max(0.0);
        Self { source, next_insertion }
    }

    /// True when an insertion is due at time `t`, and moves the schedule on by one interval.
    pub fn take_due(&mut self, t: f64) -> bool {
        let due = self.next_insertion <= t && self.source.window.is_active(self.next_insertion);
        if due {
            self.next_insertion += self.source.interval;
        }
        due
    }
}
