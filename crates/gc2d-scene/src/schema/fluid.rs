//! The fluid the particles move in (feedpipe.md §2.10, §4, §7; docs/scene-format.md "fluid"): its density and
//! viscosity, the drag law, buoyancy, and the velocity field u(x, t): analytic or loaded from CFD exports.

use gc2d_fluid::{DataLocation, Interpolation, Outside, RampShape, TimeInterpolation};
use serde::{Deserialize, Serialize};

/// A fluid, one-way coupled: drag ½·ρ_f·c_w·A·|w|·w (w = u − v) and buoyancy −ρ_f·V·g act on every particle; the
/// fluid never feels the particles.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Fluid {
    /// ρ_f, kg/m³ (air at 20 °C: 1.2).
    pub density_kg_m3: f64,
    /// Dynamic viscosity η, Pa·s; only `SchillerNaumann` drag reads it. Default 1.8e-5 (air at 20 °C).
    #[serde(default = "defaults::air_viscosity")]
    pub viscosity_pa_s: f64,
    /// The drag coefficient c_w. Default `Constant(0.47)` (a sphere, the thesis's value).
    #[serde(default)]
    pub drag: Drag,
    /// Whether static buoyancy −ρ_f·V·g acts. Default true.
    #[serde(default = "defaults::yes")]
    pub buoyancy: bool,
    /// The fluid's velocity u(x, t).
    pub field: Field,
    /// Switches the field on over a time window (the field times a factor rising from 0 to 1). Default: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ramp: Option<Ramp>,
}

/// The drag coefficient c_w.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Drag {
    /// A constant c_w, independent of the Reynolds number.
    Constant(f64),
    /// Schiller–Naumann's sphere correlation from the particle Reynolds number (needs `viscosity_pa_s`).
    SchillerNaumann,
}

impl Default for Drag {
    fn default() -> Self {
        Drag::Constant(gc2d_fluid::drag::SPHERE_DRAG_COEFFICIENT)
    }
}

/// The fluid's velocity field.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Field {
    /// The same velocity everywhere (plug flow), m/s: `Uniform((0, 5))`.
    Uniform([f64; 2]),
    /// Laminar flow in a straight channel: u = U_c·(1 − (d/h)²)·direction at distance d from the axis, zero at and
    /// beyond the walls d = h.
    Poiseuille {
        /// A point on the channel's axis, m.
        axis_point_m: [f64; 2],
        /// The flow direction (any length but zero).
        direction: [f64; 2],
        /// Half the channel's width h, m.
        half_width_m: f64,
        /// The speed on the axis U_c, m/s.
        centre_speed_m_s: f64,
    },
    /// A field loaded from legacy VTK files as OpenFOAM's `foamToVTK` writes them: one file (a steady field) or a
    /// series of snapshots at their times.
    Vtk {
        /// A steady field's file, relative to the scene file's folder. Give this or `snapshots`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        file: Option<String>,
        /// Snapshots at their times, in time order. Give this or `file`.
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        snapshots: Vec<VtkSnapshot>,
        /// How a series goes from one snapshot to the next. Default `Linear`.
        #[serde(default)]
        time_interpolation: TimeInterpolation,
        /// The velocity array's name. Default `U` (OpenFOAM's).
        #[serde(default = "defaults::velocity_array")]
        array: String,
        /// Whether the array is read at the mesh's points (`Points`, as foamToVTK interpolates them) or cells
        /// (`Cells`, OpenFOAM's own values at the cell centres). Default `Points`.
        #[serde(default = "defaults::points")]
        location: DataLocation,
        /// `Bilinear` (the nodes must form a lattice) or `Shepard(power: 2, neighbours: 4)`. Default: Shepard with the
        /// thesis's 4 neighbours and power 2.
        #[serde(default = "defaults::shepard")]
        interpolation: Interpolation,
        /// What the field gives off its mesh: `Zero`, `Nearest` or `Error` (stops the run). Default `Error`.
        #[serde(default = "defaults::outside")]
        outside: Outside,
    },
}

/// One snapshot of a loaded series.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VtkSnapshot {
    /// When it holds, s.
    pub time_s: f64,
    /// Its file, relative to the scene file's folder.
    pub file: String,
}

/// A time ramp: the field times a factor 0 before `window_s.0`, 1 after `window_s.1`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Ramp {
    /// (t0, t1) in s: the factor rises from 0 at t0 to 1 at t1 (t0 ≤ t1; equal makes a step).
    pub window_s: [f64; 2],
    /// `Linear` or `Smooth` (smoothstep: no kink at either end). Default `Linear`.
    #[serde(default)]
    pub shape: RampShape,
}

mod defaults {
    use gc2d_fluid::{DataLocation, Interpolation, Outside};

    pub fn air_viscosity() -> f64 {
        1.8e-5
    }
    pub fn yes() -> bool {
        true
    }
    pub fn velocity_array() -> String {
        "U".to_owned()
    }
    pub fn points() -> DataLocation {
        DataLocation::Points
    }
    pub fn shepard() -> Interpolation {
        Interpolation::SHEPARD_THESIS
    }
    pub fn outside() -> Outside {
        Outside::Error
    }
}
