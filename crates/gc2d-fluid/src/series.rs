//! Snapshots of a loaded field at their own times, interpolated linearly in time (feedpipe.md §7.1 item 8) or held
//! piecewise constant as the thesis did (§4.2, Eq. 4.2, with the times a scene gives).

use crate::field::OutsideField;
use crate::sampled::SampledField;
use gc2d_geometry::DVec2;
use serde::{Deserialize, Serialize};

/// One snapshot of a series.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FieldSnapshot {
    /// The time the snapshot shows, s.
    pub time_s: f64,
    /// Its field.
    pub field: SampledField,
}

/// How a series goes from one snapshot to the next.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum TimeInterpolation {
    /// Linear between the two snapshots around t.
    #[default]
    Linear,
    /// The latest snapshot at or before t, held until the next (the thesis's behaviour, feedpipe.md §4.2).
    Hold,
}

/// Why snapshots make no series.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SeriesError {
    /// No snapshots.
    #[error("a series needs at least one snapshot")]
    Empty,
    /// Times not finite or not strictly increasing.
    #[error("snapshot times must be finite and increase strictly: {file} at {time_s} s follows {previous_s} s")]
    Times {
        /// The snapshot out of order.
        file: String,
        /// Its time, s.
        time_s: f64,
        /// The time before it, s.
        previous_s: f64,
    },
}

/// Snapshots at increasing times. Before the first the first holds, after the last the last.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SnapshotSeries {
    snapshots: Vec<FieldSnapshot>,
    interpolation: TimeInterpolation,
}

impl SnapshotSeries {
    /// Clears the snapshots' file names ([`FluidField::same_flow`]).
    pub(crate) fn forget_sources(&mut self) {
        self.snapshots.iter_mut().for_each(|snapshot| snapshot.field.forget_source());
    }

    /// A series of `snapshots` (times finite and strictly increasing).
    pub fn new(snapshots: Vec<FieldSnapshot>, interpolation: TimeInterpolation) -> Result<Self, SeriesError> {
        let Some(first) = snapshots.first() else { return Err(SeriesError::Empty) };
        if !first.time_s.is_finite() {
            return Err(SeriesError::Times {
                file: first.field.source().to_string(),
                time_s: first.time_s,
                previous_s: f64::NEG_INFINITY,
            });
        }
        for pair in snapshots.windows(2) {
            if !(pair[1].time_s > pair[0].time_s && pair[1].time_s.is_finite()) {
                return Err(SeriesError::Times {
                    file: pair[1].field.source().to_string(),
                    time_s: pair[1].time_s,
                    previous_s: pair[0].time_s,
                });
            }
        }
        Ok(SnapshotSeries { snapshots, interpolation })
    }

    /// The snapshots, in time order.
    pub fn snapshots(&self) -> &[FieldSnapshot] {
        &self.snapshots
    }

    /// The velocity at `x` and time `t`, m/s.
    pub fn velocity(&self, x: DVec2, t: f64) -> Result<DVec2, OutsideField> {
        // The first snapshot after t; t lies between snapshots `after - 1` and `after`.
        let after = self.snapshots.partition_point(|s| s.time_s <= t);
        if after == 0 {
            return self.snapshots[0].field.velocity(x);
        }
        let before = &self.snapshots[after - 1];
        match (self.interpolation, self.snapshots.get(after)) {
            (TimeInterpolation::Linear, Some(next)) => {
                let s = (t - before.time_s) / (next.time_s - before.time_s);
                Ok((1.0 - s) * before.field.velocity(x)? + s * next.field.velocity(x)?)
            }
            _ => before.field.velocity(x),
        }
    }
}
