//! Fluid velocity fields and drag laws for gc2d-rs (feedpipe.md §4, §7.1): the one-way coupled fluid of the feed
//! pipe, where the flow moves the particles and never feels them.
//!
//! A [`FluidField`] gives u(x, t) in m/s: [`FluidField::Uniform`], a [`Poiseuille`] channel, any field times a
//! [`TimeRamp`], a [`SampledField`] loaded from a legacy ASCII VTK export of OpenFOAM ([`vtk::VtkFile`]) and
//! interpolated bilinearly on a lattice or by Shepard's method on a point cloud (the two z-layers of a 2D mesh
//! merged), or a [`SnapshotSeries`] of loaded snapshots interpolated in time. Points off a loaded mesh get what the
//! scene's [`Outside`] says. Evaluation allocates nothing and is deterministic.
//!
//! The [`drag`] module holds the forces as pure functions: quadratic drag ½·ρ_f·c_w·A·|w|·w with a constant c_w or
//! Schiller–Naumann's c_w(Re), static buoyancy −ρ_f·V·g and the terminal speed. Decisions: docs/model.md, "Fluid".
//!
//! ```
//! use gc2d_fluid::{FluidField, Poiseuille, RampShape, TimeRamp};
//! use gc2d_geometry::DVec2;
//!
//! // A vertical channel 0.2 m wide, 3 m/s on its axis, switched on over the first half second.
//! let channel = Poiseuille::new(DVec2::new(0.1, 0.0), DVec2::Y, 0.1, 3.0).unwrap();
//! let ramp = TimeRamp { start_s: 0.0, end_s: 0.5, shape: RampShape::Linear };
//! let field = FluidField::Ramped { field: Box::new(FluidField::Poiseuille(channel)), ramp };
//! let u = field.velocity(DVec2::new(0.15, 1.0), 0.25).unwrap();
//! assert!((u.y - 0.5 * 3.0 * 0.75).abs() < 1e-12);
//! ```

pub mod drag;
pub mod field;
pub mod poiseuille;
pub mod ramp;
pub mod sampled;
pub mod series;
pub mod vtk;

pub use drag::{DragCoefficient, FluidProperties, ImmersedBody};
pub use field::{FluidField, Outside, OutsideField};
pub use poiseuille::{Poiseuille, PoiseuilleError};
pub use ramp::{RampShape, TimeRamp};
pub use sampled::{FieldSamples, Interpolation, SampledError, SampledField};
pub use series::{FieldSnapshot, SeriesError, SnapshotSeries, TimeInterpolation};
pub use vtk::{DataLocation, VtkError, VtkFile};
