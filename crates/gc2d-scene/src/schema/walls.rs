//! Walls: single polygons with a surface velocity and a motion (gsi `WALL`, §9.6), and the wall-builder macros that
//! make many walls at once (drum, D.7; funnel, §8.3; silo, §7.1; closed box).

use super::defaults;
use super::shapes::Shape;
use serde::{Deserialize, Serialize};

/// One entry of the scene's `walls` list: a single wall, or a wall-builder macro that expands into several.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum WallItem {
    /// An immovable polygon (gsi `WALL`). It interacts with particles through the scene's contact law.
    Wall {
        /// The outline.
        shape: Shape,
        /// Where the centroid goes, m. Default: a `Polygon` stays where its corners are written; other shapes sit
        /// at the origin.
        #[serde(default)]
        position_m: Option<[f64; 2]>,
        /// Rotation about the centroid, radians CCW. Default 0.
        #[serde(default)]
        angle_rad: f64,
        /// Virtual surface velocity, m/s: the wall stays put but its surface drags particles like a conveyor belt;
        /// only the tangential part acts (gsi `VELOCITY`, §2.11). Default (0, 0).
        #[serde(default)]
        surface_velocity_m_s: [f64; 2],
        /// How the wall moves. Default `Static`.
        #[serde(default)]
        motion: Motion,
        /// The walls' material (its name). Default: the first material.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        material: Option<String>,
    },
    /// A rotating drum after gc2d's `gc2d_drum` (D.7): `segments` trapezoidal walls between radius r and r + d
    /// around the centre. The walls do not move; each carries the tangential surface velocity `surface_speed_m_s`
    /// along its inner face, counter-clockwise for positive speeds, like a fixed drum lined with a conveyor belt.
    Drum {
        /// Centre, m.
        centre_m: [f64; 2],
        /// Inner radius r (the corners of the inner faces lie on it), m.
        inner_radius_m: f64,
        /// Wall thickness d, m.
        thickness_m: f64,
        /// Tangential surface speed v on the inside, m/s, CCW positive.
        surface_speed_m_s: f64,
        /// Number of wall segments N, 3 to 10 000.
        segments: usize,
        /// The walls' material (its name). Default: the first material.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        material: Option<String>,
    },
    /// A funnel: two straight slabs that rise symmetrically from the edges of an opening (the point source of the
    /// poured piles, §8.3).
    Funnel {
        /// Centre of the opening, m (the lower inner corners of the slabs are at x ± opening/2 on this height).
        outlet_m: [f64; 2],
        /// Width of the opening, m.
        opening_m: f64,
        /// Slope of each slab against the horizontal, radians, in (0, π/2].
        slope_rad: f64,
        /// Length of each slab along its slope, m.
        length_m: f64,
        /// Thickness of each slab, m (added outside the funnel).
        thickness_m: f64,
        /// The walls' material (its name). Default: the first material.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        material: Option<String>,
    },
    /// A silo outline (§7.1): a floor and two side walls around the inner rectangle, open at the top.
    Silo {
        /// Inner x range (x_min, x_max), m.
        x_range_m: [f64; 2],
        /// Inner y range (floor top, wall top), m.
        y_range_m: [f64; 2],
        /// Wall thickness, m (added outside the inner rectangle).
        thickness_m: f64,
        /// The walls' material (its name). Default: the first material.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        material: Option<String>,
    },
    /// A closed box, written `Box(…)`: a floor, two side walls and a lid around the inner rectangle.
    #[serde(rename = "Box")]
    Enclosure {
        /// Inner x range (x_min, x_max), m.
        x_range_m: [f64; 2],
        /// Inner y range (floor top, lid bottom), m.
        y_range_m: [f64; 2],
        /// Wall thickness, m (added outside the inner rectangle).
        thickness_m: f64,
        /// The walls' material (its name). Default: the first material.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        material: Option<String>,
    },
}

/// How a wall moves (§2.11). One motion per wall: gc2d forbids a vibrating piston.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Motion {
    /// Never moves.
    #[default]
    Static,
    /// Periodic displacement along a direction (gsi `VIB_*`).
    Vibration {
        /// Width W of the displacement, m (`VIB_WIDTH`).
        amplitude_m: f64,
        /// f, Hz (`VIB_FREQUENCE`).
        frequency_hz: f64,
        /// Direction of the displacement, radians CCW from +x (`VIB_ANGLE`). Default π/2 (vertical).
        #[serde(default = "defaults::half_pi")]
        direction_rad: f64,
        /// The waveform (`VIB_TYPE`). Default `Cosine`.
        #[serde(default)]
        waveform: Waveform,
        /// (t1, t2) during which the wall moves, s (`VIB_TIME`). Default (0, inf).
        #[serde(default = "defaults::open_window")]
        window_s: [f64; 2],
    },
    /// Rotation about a fixed pivot (mill rotors; not in gc2d): from rest to ω over `spin_up_s`, then at ω.
    Rotation {
        /// The pivot, m.
        pivot_m: [f64; 2],
        /// ω, rad/s, CCW positive.
        angular_velocity_rad_s: f64,
        /// (t1, t2) during which the wall turns, s. Default (0, inf).
        #[serde(default = "defaults::open_window")]
        window_s: [f64; 2],
        /// Time of a linear ramp from rest to ω at the start of the window, s. Default 0 (at ω from the start).
        #[serde(default, skip_serializing_if = "is_zero")]
        spin_up_s: f64,
    },
    /// A force-controlled stamp (gsi `PISTON_*`).
    Piston {
        /// Direction in which it pushes, radians CCW from +x (`PISTON_ANGLE`). Default 0.
        #[serde(default)]
        direction_rad: f64,
        /// Force to exert, N per unit thickness (`PISTON_FORCE`).
        force_n: f64,
        /// Speed limit, m/s (`PISTON_V_MAX`). Default 1.
        #[serde(default = "defaults::one")]
        max_speed_m_s: f64,
    },
}

/// The periodic shape of a vibration (gsi `VIB_TYPE`, §2.11).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Waveform {
    /// `COSINUS`: W·½(1 − cos 2πft).
    #[default]
    Cosine,
    /// `SAWTOOTH`: W·(t mod 1/f)·f.
    Sawtooth,
    /// `TAPPING`: W·sin(2πft)^30, two taps per period.
    Tapping,
    /// `TRIANGLE`: up to W at half period and back.
    Triangle,
}

impl WallItem {
    /// The material the entry names, if any (its walls then have it; else the scene's first material).
    pub fn material(&self) -> Option<&str> {
        match self {
            WallItem::Wall { material, .. }
            | WallItem::Drum { material, .. }
            | WallItem::Funnel { material, .. }
            | WallItem::Silo { material, .. }
            | WallItem::Enclosure { material, .. } => material.as_deref(),
        }
    }
}

/// True for a zero, which the scene as written out leaves away.
fn is_zero(value: &f64) -> bool {
    *value == 0.0
}
