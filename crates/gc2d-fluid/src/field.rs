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
#[error(
    "the fluid field of {file} was sampled at ({x}, {y}) m, outside its mesh; to go on there, give the scene's \
     `fluid.field: Vtk(…)` `outside: Nearest` (the value at the mesh's nearest point) or `outside: Zero` (fluid at \
     rest) (docs/scene-format.md)",
    x = short(position.x),
    y = short(position.y)
)]
pub struct OutsideField {
    /// The field's source file.
    pub file: String,
    /// Where it was sampled, m.
    pub position: DVec2,
}

/// `value` to 9 significant digits, as short as they allow (`1.00000003`, `2.15688129e-10`, `0.3`): a position to a
/// nanometre on a metre's scale, not the 17 digits, written out in full, that f64's own formatting gives.
fn short(value: f64) -> String {
    let rounded: f64 = format!("{value:.8e}").parse().unwrap_or(value);
    if rounded == 0.0 || !rounded.is_finite() || (1e-4..1e9).contains(&rounded.abs()) {
        format!("{rounded}")
    } else {
        format!("{rounded:e}")
    }
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

    /// True when `self` and `other` are the same field but for the names of the files a loaded one came from: the same
    /// file reached by two paths (`fields/air.vtk`, `scenes/../fields/air.vtk`) gives the same flow.
    pub fn same_flow(&self, other: &FluidField) -> bool {
        self.without_file_names() == other.without_file_names()
    }

    /// A copy whose loaded snapshots have no file names.
    fn without_file_names(&self) -> FluidField {
        let mut copy = self.clone();
        copy.forget_file_names();
        copy
    }

    fn forget_file_names(&mut self) {
        match self {
            FluidField::Uniform(_) | FluidField::Poiseuille(_) => {}
            FluidField::Ramped { field, .. } => field.forget_file_names(),
            FluidField::Sampled(field) => field.forget_source(),
            FluidField::Series(series) => series.forget_sources(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ramp::RampShape;
    use crate::sampled::{FieldSamples, Interpolation};
    use crate::vtk::Cells;

    /// A field of four samples at the corners of the unit square, named `source`, u = (x + `shift`, y).
    fn square(source: &str, shift: f64) -> FluidField {
        let positions = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let samples = FieldSamples {
            source: source.into(),
            velocities: positions.iter().map(|p| DVec2::new(p[0] + shift, p[1])).collect(),
            mesh_points: positions.clone(),
            positions,
            cells: Cells { offsets: vec![0, 4], indices: vec![0, 1, 2, 3] },
        };
        FluidField::Sampled(Box::new(SampledField::new(&samples, Interpolation::Bilinear, Outside::Zero).unwrap()))
    }

    #[test]
    fn the_same_samples_under_two_file_names_are_the_same_flow() {
        let ramp = |field| {
            let ramp = TimeRamp { start_s: 0.0, end_s: 1.0, shape: RampShape::default() };
            FluidField::Ramped { field: Box::new(field), ramp }
        };
        assert!(square("fields/air.vtk", 0.0) != square("scenes/../fields/air.vtk", 0.0));
        assert!(square("fields/air.vtk", 0.0).same_flow(&square("scenes/../fields/air.vtk", 0.0)));
        assert!(ramp(square("a.vtk", 0.0)).same_flow(&ramp(square("b.vtk", 0.0))));
        assert!(!square("fields/air.vtk", 0.0).same_flow(&square("fields/air.vtk", 0.5)));
    }

    /// A position off the mesh is written to 9 significant digits, not in f64's 26-digit positional notation, and
    /// the message names the scene option that goes on there (QA docs 17 d).
    #[test]
    fn a_point_off_the_mesh_is_written_short_with_the_option_that_avoids_the_stop() {
        let error =
            OutsideField { file: "riser.vtk".into(), position: DVec2::new(2.1568812943736007e-10, 1.0000000277142587) };
        assert!(
            error.to_string().starts_with(
                "the fluid field of riser.vtk was sampled at (2.15688129e-10, 1.00000003) m, outside its mesh; to go \
                 on there, give the scene's `fluid.field: Vtk(…)` `outside: Nearest`"
            ),
            "{error}"
        );
        assert!(error.to_string().contains("or `outside: Zero` (fluid at rest)"), "{error}");
        for (value, written) in [(0.3, "0.3"), (-0.05, "-0.05"), (0.0, "0"), (12345.678, "12345.678"), (3e12, "3e12")] {
            assert_eq!(short(value), written);
        }
    }
}
