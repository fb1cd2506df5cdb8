//! The high-energy ball mill (Reichardt 2005; reference ballmill.md §1.10, §7.2): a circular chamber, a kinematic
//! rotor of a hub and capsule blades, and steel balls. The section expands into walls and particles when the scene is
//! built.

use super::defaults;
use serde::{Deserialize, Serialize};

/// A ball mill's chamber, rotor and balls.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mill {
    /// Centre of the chamber and axis of the rotor, m. Default (0, 0).
    #[serde(default)]
    pub centre_m: [f64; 2],
    /// Radius of the circular chamber, m. Default 0.073 (the Simoloyer's D = 146 mm).
    #[serde(default = "defaults::chamber_radius")]
    pub chamber_radius_m: f64,
    /// The rotor.
    pub rotor: Rotor,
    /// The balls.
    pub balls: Balls,
    /// Material of the chamber wall. Default: the first material.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub chamber_material: Option<String>,
    /// Material of the hub and the blades. Default: the first material.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotor_material: Option<String>,
}

/// A kinematic rotor: a hub disk and radial capsule blades turning about the chamber's centre; infinitely heavy, never
/// pushed back.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rotor {
    /// Rotor speed, revolutions per minute, counter-clockwise positive.
    pub rpm: f64,
    /// Time of a linear ramp from rest to `rpm` at the start, s. Default 0 (at speed from the start).
    #[serde(default)]
    pub spin_up_s: f64,
    /// Radius of the hub, m. Default 0.008.
    #[serde(default = "defaults::hub_radius")]
    pub hub_radius_m: f64,
    /// Radius the blade tips reach, m. Default 0.058.
    #[serde(default = "defaults::tip_radius")]
    pub tip_radius_m: f64,
    /// Width of a blade (twice its capsule radius), m. Default 0.008.
    #[serde(default = "defaults::blade_width")]
    pub blade_width_m: f64,
    /// Directions of the blades at t = 0, radians CCW from +x. Default (0, π): one bar through the hub, the thesis's
    /// single axial slice.
    #[serde(default = "defaults::one_bar")]
    pub arms_rad: Vec<f64>,
}

/// The mill's balls: disks placed at random in the chamber without overlap, each moving at `speed_m_s` in a random
/// direction (the thesis's start, §13.1) or at rest.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Balls {
    /// How many.
    pub count: usize,
    /// Radius, m. Default 0.0025 (5 mm balls).
    #[serde(default = "defaults::ball_radius")]
    pub radius_m: f64,
    /// Start speed, m/s, in a random direction; 0 starts them at rest. Default 1.
    #[serde(default = "defaults::one")]
    pub speed_m_s: f64,
    /// Material. Default: the first material.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
}
