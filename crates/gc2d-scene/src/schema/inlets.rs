//! Inlets and outlets: segments of the boundary that feed particles into the domain and take them out
//! (feedpipe.md §2.12; docs/scene-format.md "inlets and outlets").

use super::shapes::Recipe;
use super::{Window, defaults};
use serde::{Deserialize, Serialize};

/// A particle inlet: the segment from `from_m` to `to_m` feeds `rate_per_s` particles per second, each at its own
/// random point of the segment, starting with `velocity_m_s`. Walking from `from_m` to `to_m`, the domain lies on
/// the left; the start velocity must point to that side. A particle whose spot is taken waits for the next step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Inlet {
    /// The name of its columns in `timeseries.csv` and its entry in `summary.json` (letters, digits, `_` and `-`).
    /// Default: its index in `inlets`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// First end of the segment, m.
    pub from_m: [f64; 2],
    /// Second end of the segment, m.
    pub to_m: [f64; 2],
    /// Particles per second (the thesis's pps), s⁻¹; the k-th is due at t1 + k/rate.
    pub rate_per_s: f64,
    /// Start velocity of every particle, m/s; must point into the domain (to the left of the segment).
    pub velocity_m_s: [f64; 2],
    /// Start angular velocity, rad/s CCW. Default 0.
    #[serde(default)]
    pub angular_velocity_rad_s: f64,
    /// (t1, t2): particles are due from t1 on and none at or after t2, s. Default (0, inf).
    #[serde(default = "defaults::open_window")]
    pub window_s: Window,
    /// How each particle is drawn (the recipes of sources and blocks: disks or polygons, size spread).
    pub shape: Recipe,
    /// The material's name. Default: the first material.
    #[serde(default)]
    pub material: Option<String>,
}

/// A particle outlet: the segment from `from_m` to `to_m` removes every particle whose centre crosses it from the
/// domain's side (the left, walking from `from_m` to `to_m`) to the other. Not a wall: particles feel nothing there.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Outlet {
    /// The name of its column in `timeseries.csv` and its entry in `summary.json` (letters, digits, `_` and `-`).
    /// Default: its index in `outlets`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// First end of the segment, m.
    pub from_m: [f64; 2],
    /// Second end of the segment, m.
    pub to_m: [f64; 2],
}
