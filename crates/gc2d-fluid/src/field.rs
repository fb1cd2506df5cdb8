//! The fluid velocity field u(x, t) a scene prescribes: analytic, loaded, ramped in time, or a series of snapshots.

use crate::poiseuille::Poiseuille;
use crate::ramp::TimeRamp;
use crate::sampled::SampledField;
use crate::series::SnapshotSeries;
use gc2d_geometry::DVec2;
use serde::{Deserialize, Serialize};

/// What a loaded field gives at points off its mesh (feedpipe.md §4.4 pitfall d).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Outside {
    /// Fluid at rest.
    Zero,
    /// The value at the nearest point of the mesh: the nearest node's velocity (Shepard), or the interpolant at
    /// the nearest point of the lattice's rectangle (bilinear).
    Nearest,
    /// An [`OutsideField`] error, which stops a run.
    Error,
}

/// A loaded field was sampled off its mesh where the scene asked for [`Outside::Error`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("the fluid field of {file} was sampled at ({x}, {y}) m, outside its mesh", x = position.x, y = position.y)]
pub struct OutsideField {
    /// The field's source file.
    pub file: String,
    /// Where it was sampled, m.
    pub position: DVec2,
}

/// A fluid velocity field u(x, t) in the plane, m/s. Evaluating it does not allocate (except to report an
/// [`OutsideField`]) and depends only on its arguments.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum FluidField {
    /// The same velocity everywhere (plug flow), m/s.
    Uniform(DVec2),
    /// Laminar flow across a channel.
    Poiseuille(Poiseuille),
    /// A field times a time ramp.
    Ramped {
        /// The field ramped.
        field: Box<FluidField>,
        /// The ramp.
        ramp: TimeRamp,
    },
    /// A loaded snapshot, the same at every time.
    Sampled(Box<SampledField>),
    /// Loaded snapshots at their times.
    Series(SnapshotSeries),
}

impl FluidField {
    /// The velocity at `x` (m) and time `t` (s), m/s.
    pub fn velocity(&self, x: DVec2, t: f64) -> Result<DVec2, OutsideField> {
        match self {
            FluidField::Uniform(u) => Ok(*u),
            FluidField::Poiseuille(p) => Ok(p.velocity(x)),
            FluidField::Ramped { field, ramp } => Ok(ramp.factor(t) * field.velocity(x, t)?),
            FluidField::Sampled(field) => field.velocity(x),
            FluidField::Series(series) => series.velocity(x, t),
        }
    }
}
