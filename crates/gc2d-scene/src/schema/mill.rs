//! The high-energy ball mill (Reichardt 2005; reference ballmill.md §1.10, §7.2): a chamber (circular, with ramps or
//! wavy), a kinematic rotor of a hub and capsule blades, steel balls and optionally ore grains. The section expands
//! into walls and particles when the scene is built.

use super::{Recipe, defaults};
use serde::{Deserialize, Serialize};

/// A ball mill's chamber, rotor and balls.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mill {
    /// Centre of the chamber and axis of the rotor, m. Default (0, 0).
    #[serde(default)]
    pub centre_m: [f64; 2],
    /// Radius of the circular chamber, m (for `Ramps` the circle the ramps sit on, for `Wavy` the mean radius).
    /// Default 0.073 (the Simoloyer's D = 146 mm).
    #[serde(default = "defaults::chamber_radius")]
    pub chamber_radius_m: f64,
    /// The chamber's outline. Default `Circle`.
    #[serde(default, skip_serializing_if = "Chamber::is_circle")]
    pub chamber: Chamber,
    /// The rotor.
    pub rotor: Rotor,
    /// The balls.
    pub balls: Balls,
    /// Ore grains among the balls. Default: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ore: Option<Ore>,
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

/// The outline of a mill's chamber, of radius `chamber_radius_m` R about the centre.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Chamber {
    /// The circle of radius R (an exact inner-circle wall).
    #[default]
    Circle,
    /// The circle with two flat ramps, at the top and at the bottom (ballmill.md §7.8 item 4, the geometric version
    /// of the thesis's tilted wall normals, §20.1.1): each ramp leaves the circle at `tilt_rad` to its tangent, rising
    /// into the chamber in the rotor's direction of turning to `height_m` inside the circle, and drops back to the
    /// circle along the radius there, so balls carried along the wall are thrown inwards.
    Ramps {
        /// Angle between a ramp and the circle's tangent at its foot, rad, in (0, π/2). Default π/6 (30°).
        #[serde(default = "ramp_tilt")]
        tilt_rad: f64,
        /// How far a ramp's crest reaches inside the circle, m. Default 0.005.
        #[serde(default = "ramp_height")]
        height_m: f64,
    },
    /// The wavy wall ρ(φ) = R + A·cos(n·φ) (ballmill.md §7.8 item 5, thesis (20-3)), φ from +x, traced by `segments`
    /// straight pieces.
    Wavy {
        /// The amplitude A, m.
        amplitude_m: f64,
        /// The number of waves n around the chamber. Default 6.
        #[serde(default = "wavy_lobes")]
        lobes: u32,
        /// Straight pieces tracing the outline, 256 to 10,000. Default 1024.
        #[serde(default = "wavy_segments")]
        segments: usize,
    },
}

impl Chamber {
    /// True for the plain circle (written out as nothing, the default).
    pub fn is_circle(&self) -> bool {
        *self == Chamber::Circle
    }
}

fn ramp_tilt() -> f64 {
    std::f64::consts::FRAC_PI_6
}

fn ramp_height() -> f64 {
    0.005
}

fn wavy_lobes() -> u32 {
    6
}

fn wavy_segments() -> usize {
    1024
}

/// The mill's balls: disks placed at random in the chamber without overlap, each moving at `speed_m_s` in a random
/// direction (the thesis's start, §13.1), or at rest in a bed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Balls {
    /// How many.
    pub count: usize,
    /// Radius, m. Default 0.0025 (5 mm balls).
    #[serde(default = "defaults::ball_radius")]
    pub radius_m: f64,
    /// Where they start. Default `Random`.
    #[serde(default, skip_serializing_if = "super::is_default")]
    pub placement: BallPlacement,
    /// Start speed, m/s, in a random direction; 0 starts them at rest. Default 1 for `Random`, 0 for `Bed` (the only
    /// speed a bed allows).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed_m_s: Option<f64>,
    /// Material. Default: the first material.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
}

impl Balls {
    /// The start speed, m/s: `speed_m_s`, or its default for the placement.
    pub fn start_speed(&self) -> f64 {
        self.speed_m_s.unwrap_or(match self.placement {
            BallPlacement::Random => 1.0,
            BallPlacement::Bed => 0.0,
        })
    }
}

/// Where the balls start.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum BallPlacement {
    /// Uniformly at random in the chamber (r = R·√u, φ = 2π·u'), none overlapping another ball, a wall or the rotor.
    #[default]
    Random,
    /// At rest in a loose triangular packing filled row by row from the chamber's bottom, each row from the middle
    /// outwards, leaving out the places that would overlap a wall or the rotor.
    Bed,
}

/// Ore grains: particles drawn from a recipe (random convex polygons, or disks) of their own material, placed at random
/// among the balls without overlap, moving like the balls at the start.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Ore {
    /// How many.
    pub count: usize,
    /// The recipe each grain is drawn from (see the scene format's recipes).
    pub shape: Recipe,
    /// Material. Default: the first material.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
}
