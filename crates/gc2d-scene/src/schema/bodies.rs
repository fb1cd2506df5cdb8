//! Particles: placed one by one (gsi `PARTICLE`, §9.5), on a lattice (`GENERATE_BLOCK`, §9.7) or inserted during the
//! run by a source (`DROPSOURCE`, §9.8).

use super::defaults;
use super::shapes::{Recipe, Shape};
use serde::{Deserialize, Serialize};

/// One free particle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Particle {
    /// The outline.
    pub shape: Shape,
    /// Where the centroid goes, m (gsi `COM`). Default: a `Polygon` stays where its corners are written (gsi
    /// `POSITION_ABSOLUT`); other shapes sit at the origin.
    #[serde(default)]
    pub position_m: Option<[f64; 2]>,
    /// Rotation about the centroid, radians CCW (gsi `ANGLE` is clockwise). For a `Random` shape it is added to the
    /// drawn orientation. Default 0.
    #[serde(default)]
    pub angle_rad: f64,
    /// Initial velocity of the centroid, m/s. Default (0, 0).
    #[serde(default)]
    pub velocity_m_s: [f64; 2],
    /// Initial angular velocity, rad/s CCW (gsi `OMEGA` is clockwise). Default 0.
    #[serde(default)]
    pub angular_velocity_rad_s: f64,
    /// The material's name. Default: the first material.
    #[serde(default)]
    pub material: Option<String>,
    /// A spring pulling the particle towards a moving point (gsi `DRAG_*`, §2.12). Default: none.
    #[serde(default)]
    pub drag_spring: Option<DragSpring>,
}

impl Particle {
    /// A particle of the given shape with every other field at its default (at rest, first material, no spring).
    pub fn new(shape: Shape) -> Self {
        Self {
            shape,
            position_m: None,
            angle_rad: 0.0,
            velocity_m_s: [0.0, 0.0],
            angular_velocity_rad_s: 0.0,
            material: None,
            drag_spring: None,
        }
    }
}

/// A spring of rest length 0 from a point of a particle to a pulling point that moves along a straight line
/// ("Teilchen mit Feder", §2.12).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DragSpring {
    /// Spring constant K, N/m (`DRAG_K`). Default 100.
    #[serde(default = "defaults::drag_stiffness")]
    pub stiffness_n_m: f64,
    /// Attachment point relative to the centroid in the particle's frame, m; turns with the particle
    /// (`DRAG_FIXING_POINT`). Default (0, 0).
    #[serde(default)]
    pub fixing_point_m: [f64; 2],
    /// Start of the pulling point, world coordinates, m (`DRAG_PULLING_POINT`). Default (0, 0).
    #[serde(default)]
    pub pulling_start_m: [f64; 2],
    /// Direction of the pulling point's travel, radians CCW from +x (`DRAG_ANGLE`). Default 0.
    #[serde(default)]
    pub direction_rad: f64,
    /// Speed of the pulling point, m/s (`DRAG_VELOCITY`). Default 0.1.
    #[serde(default = "defaults::drag_speed")]
    pub speed_m_s: f64,
    /// (t1, t2) during which the pulling point moves, s (`DRAG_TIME`). Default (0, 1).
    #[serde(default = "defaults::unit_window")]
    pub window_s: [f64; 2],
}

impl Default for DragSpring {
    /// gc2d's defaults: K = 100 N/m, both points at the origin, direction 0, 0.1 m/s during (0, 1) s.
    fn default() -> Self {
        Self {
            stiffness_n_m: defaults::drag_stiffness(),
            fixing_point_m: [0.0, 0.0],
            pulling_start_m: [0.0, 0.0],
            direction_rad: 0.0,
            speed_m_s: defaults::drag_speed(),
            window_s: defaults::unit_window(),
        }
    }
}

/// Particles on a lattice inside a rectangle (gsi `GENERATE_BLOCK`). Rows sit at y_min + j·Δy up to y_max,
/// columns at x_min + i·Δx up to x_max (every other row shifted by Δx/2 for the `Fcc` grids); the count follows
/// from the ranges and the spacing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Block {
    /// (x_min, x_max) of the lattice points, m.
    pub x_range_m: [f64; 2],
    /// (y_min, y_max) of the lattice points, m.
    pub y_range_m: [f64; 2],
    /// (Δx, Δy), m: point spacing along x and row spacing.
    pub grid_spacing_m: [f64; 2],
    /// The lattice and its scatter (`GRID_TYPE`). Default `Rect`.
    #[serde(default)]
    pub grid: GridType,
    /// How each particle is drawn.
    pub shape: Recipe,
    /// The material's name. Default: the first material.
    #[serde(default)]
    pub material: Option<String>,
    /// Initial speed range (min, max), m/s, drawn uniformly (`VELOCITY_RANGE`). Default (0, 0).
    #[serde(default)]
    pub speed_range_m_s: [f64; 2],
    /// Initial direction range (min, max), radians CCW from +x, drawn uniformly (`ANGLE_RANGE`). Default (0, 2π).
    #[serde(default = "defaults::full_turn")]
    pub direction_range_rad: [f64; 2],
}

impl Block {
    /// A block with the given ranges, spacing and recipe, and every other field at its default (`Rect`, at rest,
    /// first material).
    pub fn new(x_range_m: [f64; 2], y_range_m: [f64; 2], grid_spacing_m: [f64; 2], shape: Recipe) -> Self {
        Self {
            x_range_m,
            y_range_m,
            grid_spacing_m,
            grid: GridType::Rect,
            shape,
            material: None,
            speed_range_m_s: [0.0, 0.0],
            direction_range_rad: defaults::full_turn(),
        }
    }
}

/// A lattice type of GENERATE_BLOCK (Abb. B.6). The scatter is an offset in [−Δx/2, Δx/2] × [−Δy/2, Δy/2].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum GridType {
    /// Rectangular lattice, centroids on the points.
    #[default]
    Rect,
    /// Rectangular lattice, centroids scattered with gc2d's truncated Gaussian.
    RectGauss,
    /// Rectangular lattice, centroids scattered uniformly.
    RectEqual,
    /// Two square lattices offset by (Δx/2, Δy), centroids on the points.
    Fcc,
    /// Offset lattices, truncated-Gaussian scatter.
    FccGauss,
    /// Offset lattices, uniform scatter.
    FccEqual,
}

impl GridType {
    /// Whether every other row is shifted by half a spacing.
    pub fn is_fcc(self) -> bool {
        matches!(self, GridType::Fcc | GridType::FccGauss | GridType::FccEqual)
    }
}

/// A particle source (gsi `DROPSOURCE`): one particle per interval inside the window, at a uniformly random x within
/// the width, starting at rest. A spot where the new particle would overlap another body is retried and, failing
/// that, skipped.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Source {
    /// Centre of the insertion line, m (`POS`).
    pub position_m: [f64; 2],
    /// Width of the insertion line, m (`WIDTH`). Default 0.
    #[serde(default)]
    pub width_m: f64,
    /// How the insertion height is found (`TYPE`). Default `Absolute`.
    #[serde(default)]
    pub height: DropHeight,
    /// (t1, t2) during which particles are inserted, s (`TIME`). Default (0, 1).
    #[serde(default = "defaults::unit_window")]
    pub window_s: [f64; 2],
    /// Time between insertions, s (`DELTA_T`). Default 0.1.
    #[serde(default = "defaults::source_interval")]
    pub interval_s: f64,
    /// How each particle is drawn.
    pub shape: Recipe,
    /// The material's name. Default: the first material.
    #[serde(default)]
    pub material: Option<String>,
}

impl Source {
    /// A source at `position_m` drawing from `shape`, every other field at gc2d's default (width 0, `Absolute`,
    /// window (0, 1) s, one particle per 0.1 s, first material).
    pub fn new(position_m: [f64; 2], shape: Recipe) -> Self {
        Self {
            position_m,
            width_m: 0.0,
            height: DropHeight::Absolute,
            window_s: defaults::unit_window(),
            interval_s: defaults::source_interval(),
            shape,
            material: None,
        }
    }
}

/// Where a source inserts vertically.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum DropHeight {
    /// `ABS`: at the source's y.
    #[default]
    Absolute,
    /// `REL`: the source's y above the highest particle centroid within the width (0 if none).
    AboveHighest,
}
