//! Outlines of particles and walls: explicit corners, the shape macros of gc2d's Perl libraries (§1.8, App. D.3–D.5)
//! and the random recipe of GENERATE_BLOCK and DROPSOURCE (§1.2, §9.7).

use super::defaults;
use serde::{Deserialize, Serialize};

/// One outline. Every variant but `Polygon` is centred on its centroid; `Polygon` corners are written where they
/// are (see `position_m` of [`super::Particle`] and [`super::WallItem::Wall`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Shape {
    /// Explicit corners, m: convex, 3 to 64 of them, either orientation (gsi `CORNERS … END`).
    Polygon {
        /// The corners in order.
        corners_m: Vec<[f64; 2]>,
    },
    /// A regular polygon, first corner on +x before rotation (`gc2d_sphere`).
    Regular {
        /// Number of corners, 3 to 64.
        corners: usize,
        /// Circumradius, m.
        radius_m: f64,
    },
    /// A polygon with evenly spaced corner angles on an ellipse (`gc2d_ellipse`).
    Ellipse {
        /// Number of corners, 3 to 64.
        corners: usize,
        /// Semi-axes (a along x, b along y), m.
        semi_axes_m: [f64; 2],
    },
    /// A rectangle (`gc2d_rectangle`).
    Rectangle {
        /// Side along x, m.
        width_m: f64,
        /// Side along y, m.
        height_m: f64,
    },
    /// A rectangle with bevelled corners (`gc2d_rectangle_cut`): the sides shrink to width·(1 − 2·cut) and
    /// height·(1 − 2·cut).
    CutRectangle {
        /// Side along x, m.
        width_m: f64,
        /// Side along y, m.
        height_m: f64,
        /// Cut fraction, strictly between 0 and 0.5.
        cut: f64,
    },
    /// A rectangle with quarter-circle corners (`gc2d_rectangle_round`).
    RoundRectangle {
        /// Side along x, m.
        width_m: f64,
        /// Side along y, m.
        height_m: f64,
        /// Rounding radius, m, less than half the shorter side.
        radius_m: f64,
        /// Corners per rounding, 2 to 16.
        corners_per_rounding: usize,
    },
    /// A square (`gc2d_square`).
    Square {
        /// Side, m.
        side_m: f64,
    },
    /// A square with bevelled corners (`gc2d_square_cut`).
    CutSquare {
        /// Side, m.
        side_m: f64,
        /// Cut fraction, strictly between 0 and 0.5.
        cut: f64,
    },
    /// A square with quarter-circle corners (`gc2d_square_round`).
    RoundSquare {
        /// Side, m.
        side_m: f64,
        /// Rounding radius, m, less than half the side.
        radius_m: f64,
        /// Corners per rounding, 2 to 16.
        corners_per_rounding: usize,
    },
    /// An exact circle (particles and walls), centred on its position.
    Disk {
        /// Radius, m.
        radius_m: f64,
    },
    /// A segment of length `length_m` along x swept by `radius_m`: a stadium (walls only: rotor blades, rounded
    /// wall ends). The rotation turns it about its centre.
    Capsule {
        /// Distance between the centres of the two round ends, m (0 gives a disk-shaped wall).
        length_m: f64,
        /// Radius, m (half the width).
        radius_m: f64,
    },
    /// The boundary of a circular chamber or drum (walls only): solid everywhere outside the circle, so particles
    /// stay inside it.
    InnerCircle {
        /// Radius of the chamber, m.
        radius_m: f64,
    },
    /// A random polygon drawn from a recipe with the scene's seed (particles only).
    Random {
        /// How to draw it.
        recipe: Recipe,
    },
}

/// How to draw random particles: a polygon inscribed in an ellipse with scattered size, corner count, corner
/// positions and orientation (reference §1.2; gsi `PART_*` and `RANDOM_*` of GENERATE_BLOCK and DROPSOURCE).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Recipe {
    /// Nominal ellipse semi-axes (l_x, l_y), m: the thesis's particle "radius" (`PART_SIZE`).
    pub semi_axes_m: [f64; 2],
    /// How each semi-axis scatters (`RANDOM_SIZE`, `PART_VAR_SIZE`). Default `Const`.
    #[serde(default)]
    pub size_spread: SizeSpread,
    /// Nominal corner count, 3 to 64 (`PART_NUM_CORNERS`). Default 6.
    #[serde(default = "defaults::corners")]
    pub corners: usize,
    /// How the corner count scatters (`RANDOM_NUM_CORNERS`, `PART_VAR_CORNERS`). Default `Const`.
    #[serde(default)]
    pub corner_spread: CountSpread,
    /// Where the corners sit on the ellipse (`PART_RANDOM_POS_CORNERS`). Default `Regular`.
    #[serde(default)]
    pub corner_positions: CornerPositions,
    /// The orientation (`PART_ROT`, `RANDOM_ROT`). Default `Const(0.0)`.
    #[serde(default)]
    pub orientation: Orientation,
    /// Draw exact disks instead of polygons: the radius is `semi_axes_m`'s (both must be equal), scattered by
    /// `size_spread` (one draw per disk); the corner and orientation fields do not apply. Default false.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub disk: bool,
}

impl Recipe {
    /// A recipe with the given semi-axes and every other field at its default (6 regular corners, no scatter).
    pub fn new(semi_axes_m: [f64; 2]) -> Self {
        Self {
            semi_axes_m,
            size_spread: SizeSpread::Const,
            corners: defaults::corners(),
            corner_spread: CountSpread::Const,
            corner_positions: CornerPositions::Regular,
            orientation: Orientation::default(),
            disk: false,
        }
    }
}

/// Scatter of a size: each semi-axis drawn independently in [l·(1 − I), l·(1 + I)] with 0 ≤ I < 1.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub enum SizeSpread {
    /// The nominal size.
    #[default]
    Const,
    /// Uniform with relative spread I.
    Equal(f64),
    /// gc2d's truncated Gaussian with relative spread I.
    Gauss(f64),
}

/// Scatter of the corner count: drawn in [N − N_I, N + N_I], which must stay within 3 to 64.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum CountSpread {
    /// The nominal count.
    #[default]
    Const,
    /// Uniform over the 2·N_I + 1 counts.
    Equal(usize),
    /// gc2d's truncated Gaussian over the counts.
    Gauss(usize),
}

/// Where the corners of a random polygon sit on its ellipse (reference §1.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum CornerPositions {
    /// φ_i = i·2π/N.
    #[default]
    Regular,
    /// φ_i uniform within ±½ of the regular spacing.
    Rand1,
    /// φ_i uniform within ±1 of the regular spacing.
    Rand2,
    /// φ_i uniform on the whole ellipse.
    Full,
    /// A rectangle with bevelled corners.
    SpecialRectangle,
}

/// The orientation of a random polygon, radians CCW.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Orientation {
    /// Always this angle.
    Const(f64),
    /// Uniform in [0, 2π).
    Equal,
    /// gc2d's truncated Gaussian in ]φ₀ − π/2, φ₀ + π/2[ around this angle.
    Gauss(f64),
}

impl Default for Orientation {
    fn default() -> Self {
        Orientation::Const(0.0)
    }
}
