//! The typed result of reading a gsi file, [`GsiScene`], in gc2d-rs conventions: SI units, angles counter-clockwise
//! positive, gc2d's defaults (reference §9.3–§9.8) filled in, every value with the line it came from.

use std::fmt;
use std::str::FromStr;

use gc2d_engine::motion::Waveform;
use gc2d_engine::schedules::GravityProfile;
use gc2d_engine::{DropHeight, TimeWindow};
use gc2d_geometry::{AngleMode, DVec2, Randomization};

use crate::schema::GridType;

/// Where a value of a [`GsiScene`] came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Origin {
    /// Written in the file at this 1-based line.
    Written {
        /// The line of the command.
        line: usize,
    },
    /// gc2d's default, for the object that starts at this line (1 for GENERAL).
    Default {
        /// The line of the object's name.
        object_line: usize,
    },
}

impl Origin {
    /// The line a message about this value should name: the command's line, or the object's for a default.
    pub fn line(self) -> usize {
        match self {
            Origin::Written { line } | Origin::Default { object_line: line } => line,
        }
    }

    /// Whether the value was written in the file.
    pub fn is_written(self) -> bool {
        matches!(self, Origin::Written { .. })
    }
}

/// A value and where it came from, so later validation can say `file:line`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sourced<T> {
    /// The value, converted to gc2d-rs conventions.
    pub value: T,
    /// Where it came from.
    pub origin: Origin,
}

impl<T> Sourced<T> {
    /// A value written at `line`.
    pub fn written(value: T, line: usize) -> Self {
        Self { value, origin: Origin::Written { line } }
    }

    /// A default for the object starting at `object_line`.
    pub fn default_for(value: T, object_line: usize) -> Self {
        Self { value, origin: Origin::Default { object_line } }
    }

    /// The line to name in messages about this value.
    pub fn line(&self) -> usize {
        self.origin.line()
    }

    /// The same origin with a converted value.
    pub fn map<U>(self, convert: impl FnOnce(T) -> U) -> Sourced<U> {
        Sourced { value: convert(self.value), origin: self.origin }
    }
}

/// A pair of numbers that gc2d reads as a range, e.g. `X_RANGE` or `VELOCITY_RANGE`, as written (not checked for
/// order here).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// The first value (the lower end when the file is correct).
    pub min: f64,
    /// The second value.
    pub max: f64,
}

/// The whole scene of a gsi file.
#[derive(Debug, Clone, PartialEq)]
pub struct GsiScene {
    /// Line 2, the identification text (it must match line 2 of the gci file, if any).
    pub identification: String,
    /// The GENERAL object.
    pub general: GsiGeneral,
    /// The last DISPLAY object, if any (only the last counts, §9.2).
    pub display: Option<GsiDisplay>,
    /// PARTICLE objects, in file order.
    pub particles: Vec<GsiParticle>,
    /// WALL objects, in file order.
    pub walls: Vec<GsiWall>,
    /// GENERATE_BLOCK objects, in file order.
    pub blocks: Vec<GsiBlock>,
    /// DROPSOURCE objects, in file order.
    pub drop_sources: Vec<GsiDropSource>,
    /// How PART_SIZE was read in this file (see [`super::PartSizeConvention`]).
    pub part_size_reading: PartSizeReading,
}

/// GENERAL (reference §9.3): time stepping, material, output, gravity and heating.
#[derive(Debug, Clone, PartialEq)]
pub struct GsiGeneral {
    /// `DELTA_T`, s (default 1e-4).
    pub time_step: Sourced<f64>,
    /// `TIME` start and end, s (default 0, 1).
    pub time: Sourced<TimeWindow>,
    /// `MUE_STATISCH` μ, the friction coefficient (default 0.6).
    pub friction: Sourced<f64>,
    /// `MUE_DYNAMISCH` (default 0.6): read, unused as in gc2d (erratum E41).
    pub dynamic_friction: Sourced<f64>,
    /// `E_MODUL` E, N/m (default 1e7).
    pub youngs_modulus: Sourced<f64>,
    /// `GAMMA` γ, the normal damping coefficient (default 0.5).
    pub damping: Sourced<f64>,
    /// `COHESION` k_coh, N/m (default 0).
    pub cohesion: Sourced<f64>,
    /// `STEPS_DATA`: steps between data outputs (default 10000).
    pub steps_data: Sourced<u64>,
    /// `STEPS_CHECKPOINT`: steps between overwritten checkpoints (default 10000).
    pub steps_checkpoint: Sourced<u64>,
    /// `STEPS_SETUP`: steps between numbered checkpoints (default ∞ = [`BIG_NUMBER`]).
    pub steps_setup: Sourced<u64>,
    /// `STEPS_DUMPLINE`: steps between trajectory lines (default ∞ = [`BIG_NUMBER`]).
    pub steps_dumpline: Sourced<u64>,
    /// `SEED`: the two RNG initialisation values (default 0, 0).
    pub seed: Sourced<[f64; 2]>,
    /// `BASENAME`: output base name, case preserved (default "default").
    pub basename: Sourced<String>,
    /// `NEXT_DATA_FILENUMBER` (System; default 1).
    pub next_data_file_number: Sourced<u64>,
    /// `NEXT_SETUP_FILENUMBER` (System; default 1).
    pub next_setup_file_number: Sourced<u64>,
    /// `G`, `G_TIME`, `G_PARAMETER`, `G_TYPE`.
    pub gravity: GsiGravity,
    /// `HEAT_*`, present when any HEAT_* command is written (heating is off otherwise).
    pub heating: Option<GsiHeating>,
}

/// gc2d's "∞" for step counts, `BIG_NUMBER` = 2³² − 1 (reference §9.2).
pub const BIG_NUMBER: u64 = 4_294_967_295;

/// Gravity g(t) along −y (reference §2.13).
#[derive(Debug, Clone, PartialEq)]
pub struct GsiGravity {
    /// g1, m/s² (`G`'s first value, default 9.81).
    pub start: Sourced<f64>,
    /// g2, m/s² (`G`'s second value; equal to g1 when `G` has one value).
    pub end: Sourced<f64>,
    /// `G_TIME` [t1, t2], s (default 0, 1).
    pub window: Sourced<TimeWindow>,
    /// `G_PARAMETER` p1 (number of steps, default 5) and p2 (ramp fraction, default 0.5).
    pub parameters: Sourced<[f64; 2]>,
    /// `G_TYPE` (default CONSTANT).
    pub profile: Sourced<GravityProfile>,
}

/// Global heating s(t) (reference §1.6, B.1/B.2).
#[derive(Debug, Clone, PartialEq)]
pub struct GsiHeating {
    /// `HEAT_TIME` [t1, t2], s (default ∞, ∞).
    pub window: Sourced<TimeWindow>,
    /// `HEAT_AMPLITUDE` a (default 0.01).
    pub amplitude: Sourced<f64>,
    /// `HEAT_FREQUENCE` f, 1/s (default 1).
    pub frequency: Sourced<f64>,
    /// `HEAT_SLOPE` S (default illegible in the thesis; gc2d-rs uses 4, erratum E26).
    pub slope: Sourced<f64>,
}

/// DISPLAY (reference §9.4): kept for image snapshots; a headless run needs none of it.
#[derive(Debug, Clone, PartialEq)]
pub struct GsiDisplay {
    /// Line of the DISPLAY keyword.
    pub line: usize,
    /// `X_RANGE`, m (default −0.1, 0.1).
    pub x_range: Sourced<Bounds>,
    /// `Y_RANGE`, m (default −0.1, 0.1).
    pub y_range: Sourced<Bounds>,
    /// `SCREEN` width and height in pixels (default 640, 0; ≤ 0 means "keep the aspect ratio").
    pub screen: Sourced<[i64; 2]>,
    /// `INTERVAL`: steps between redraws (default 100).
    pub interval: Sourced<u64>,
    /// `MODUS`: bit mask of what is drawn (default 3).
    pub modus: Sourced<u64>,
}

/// PARTICLE (reference §9.5): one free polygon.
#[derive(Debug, Clone, PartialEq)]
pub struct GsiParticle {
    /// Line of the PARTICLE keyword.
    pub line: usize,
    /// Body-frame corners: counter-clockwise, shifted so their area centroid is at the origin, not rotated. The
    /// origin is the CORNERS line.
    pub corners: Sourced<Vec<DVec2>>,
    /// Centroid position, m: `COM` (default 0, 0), or with POSITION_ABSOLUT the centroid of the corners as written.
    pub position: Sourced<DVec2>,
    /// Whether POSITION_ABSOLUT was given.
    pub position_absolute: bool,
    /// Orientation, rad, counter-clockwise (gc2d's clockwise `ANGLE` negated).
    pub angle: Sourced<f64>,
    /// `VELOCITY`, m/s (default 0).
    pub velocity: Sourced<DVec2>,
    /// `ACCELERATION` (also `VELOCITY_DOT`), m/s² (default 0).
    pub acceleration: Sourced<DVec2>,
    /// Angular velocity, 1/s, counter-clockwise (gc2d's `OMEGA` negated).
    pub angular_velocity: Sourced<f64>,
    /// Angular acceleration, 1/s², counter-clockwise (gc2d's `OMEGA_DOT` negated).
    pub angular_acceleration: Sourced<f64>,
    /// `PC_TRANS3`..`PC_TRANS5`: the 3rd to 5th time derivatives of the position (physical, not scaled), m/sⁿ.
    pub higher_translation: [Sourced<DVec2>; 3],
    /// `PC_ROT3`..`PC_ROT5`: the 3rd to 5th time derivatives of the angle, counter-clockwise, 1/sⁿ.
    pub higher_rotation: [Sourced<f64>; 3],
    /// `ID` (System), if given.
    pub id: Option<Sourced<u64>>,
    /// The drag spring, present when any DRAG_* command is written.
    pub drag: Option<GsiDrag>,
}

/// A particle's drag spring (reference §2.12). Directions are counter-clockwise from +x and passed through as
/// written (see `docs/model.md`, "Legacy gsi import").
#[derive(Debug, Clone, PartialEq)]
pub struct GsiDrag {
    /// `DRAG_ANGLE`, rad CCW from +x: direction of the pulling point's motion (default 0).
    pub direction_angle: Sourced<f64>,
    /// `DRAG_VELOCITY`, m/s: speed of the pulling point (default 0.1; gc2d's second slot is unused).
    pub speed: Sourced<f64>,
    /// `DRAG_K`, N/m (default 100).
    pub stiffness: Sourced<f64>,
    /// `DRAG_TIME` [t1, t2], s (default 0, 1).
    pub window: Sourced<TimeWindow>,
    /// `DRAG_FIXING_POINT`, m: attachment point relative to the centroid, in world axes at the start (default 0, 0).
    pub fixing_point: Sourced<DVec2>,
    /// `DRAG_PULLING_POINT`, m: absolute start of the pulling point (default 0, 0).
    pub pulling_point: Sourced<DVec2>,
}

/// WALL (reference §9.6): an immovable polygon, not recentred.
#[derive(Debug, Clone, PartialEq)]
pub struct GsiWall {
    /// Line of the WALL keyword.
    pub line: usize,
    /// World corners, counter-clockwise: as written, turned by `angle` about their area centroid, then moved by
    /// `offset`. The origin is the CORNERS line.
    pub corners: Sourced<Vec<DVec2>>,
    /// `OFFSET`, m (default 0, 0), already applied to `corners`.
    pub offset: Sourced<DVec2>,
    /// Rotation about the centroid, rad CCW (gc2d's clockwise `ANGLE` negated), already applied to `corners`.
    pub angle: Sourced<f64>,
    /// `VELOCITY`: the virtual surface velocity, m/s, acting only tangentially (default 0, 0).
    pub surface_velocity: Sourced<DVec2>,
    /// `ID` (System), if given.
    pub id: Option<Sourced<u64>>,
    /// How the wall moves.
    pub motion: GsiWallMotion,
}

/// A wall's motion: none, piston or vibration (gc2d forbids both at once).
#[derive(Debug, Clone, PartialEq)]
pub enum GsiWallMotion {
    /// The wall stays where it is.
    Static,
    /// Force-controlled piston, present when any PISTON_* command is written.
    Piston(GsiPiston),
    /// Vibration, present when any VIB_* command is written.
    Vibration(GsiVibration),
}

/// A piston wall (reference §2.11, B.1.5.1).
#[derive(Debug, Clone, PartialEq)]
pub struct GsiPiston {
    /// `PISTON_ANGLE`, rad CCW from +x: direction of motion (default 0).
    pub direction_angle: Sourced<f64>,
    /// `PISTON_FORCE`, N: target force along the direction (default 0).
    pub force: Sourced<f64>,
    /// `PISTON_V_MAX`, m/s (default 1).
    pub v_max: Sourced<f64>,
}

/// A vibrating wall (reference §2.11, B.1.5.2).
#[derive(Debug, Clone, PartialEq)]
pub struct GsiVibration {
    /// `VIB_ANGLE`, rad CCW from +x (default π/2: up).
    pub direction_angle: Sourced<f64>,
    /// `VIB_TIME` [t1, t2], s (default 0, ∞).
    pub window: Sourced<TimeWindow>,
    /// `VIB_WIDTH` W, m (default 1).
    pub amplitude: Sourced<f64>,
    /// `VIB_FREQUENCE` f, 1/s (default 1).
    pub frequency: Sourced<f64>,
    /// `VIB_TYPE` (default COSINUS).
    pub waveform: Sourced<Waveform>,
}

/// The particle-shape commands shared by GENERATE_BLOCK and DROPSOURCE (reference §1.2, §9.7).
#[derive(Debug, Clone, PartialEq)]
pub struct GsiShape {
    /// `PART_SIZE` (l_x, l_y) as written, m.
    pub part_size: Sourced<DVec2>,
    /// How `part_size` is read; [`GsiShape::semi_axes`] applies it.
    pub reading: PartSizeReading,
    /// `PART_VAR_SIZE` I (default 0.5 in GENERATE_BLOCK, 0.1 in DROPSOURCE).
    pub size_variation: Sourced<f64>,
    /// `RANDOM_SIZE` / `PART_RANDOM_SIZE` (default CONST).
    pub size_randomization: Sourced<Randomization>,
    /// `PART_NUM_CORNERS` N_E (default 6 in GENERATE_BLOCK, 8 in DROPSOURCE).
    pub corners: Sourced<u64>,
    /// `PART_VAR_CORNERS` N_I (default 2).
    pub corner_variation: Sourced<u64>,
    /// `RANDOM_NUM_CORNERS` / `PART_RANDOM_NUM_CORNERS` (default CONST).
    pub corner_randomization: Sourced<Randomization>,
    /// `PART_RANDOM_POS_CORNERS` / `RANDOM_POS_CORNERS` (default REGULAR).
    pub angle_mode: Sourced<AngleMode>,
    /// Nominal orientation φ₀, rad CCW (gc2d's clockwise `PART_ROT` negated; default 0).
    pub rotation: Sourced<f64>,
    /// `RANDOM_ROT` / `PART_RANDOM_ROT` (default CONST).
    pub rotation_randomization: Sourced<Randomization>,
}

impl GsiShape {
    /// The nominal ellipse semi-axes, m: `part_size` itself or half of it, per `reading`.
    pub fn semi_axes(&self) -> DVec2 {
        self.reading.semi_axes(self.part_size.value)
    }

    /// The largest semi-axis any draw can have, m: the larger nominal semi-axis, times (1 + I) when sizes vary.
    pub fn largest_semi_axis(&self) -> f64 {
        largest_semi_axis(self.semi_axes(), self)
    }

    /// The recipe the generators draw from, with gc2d-rs conventions (semi-axes, CCW rotation). Counts beyond
    /// `usize` saturate; [`gc2d_geometry::ShapeRecipe::validate`] rejects them.
    pub fn recipe(&self) -> gc2d_geometry::ShapeRecipe {
        let count = |value: u64| usize::try_from(value).unwrap_or(usize::MAX);
        gc2d_geometry::ShapeRecipe {
            semi_axes: self.semi_axes(),
            size_variation: self.size_variation.value,
            size_randomization: self.size_randomization.value,
            corners: count(self.corners.value),
            corner_variation: count(self.corner_variation.value),
            corner_randomization: self.corner_randomization.value,
            angle_mode: self.angle_mode.value,
            rotation: self.rotation.value,
            rotation_randomization: self.rotation_randomization.value,
        }
    }
}

/// The largest semi-axis of draws from `shape` if its nominal semi-axes were `semi_axes`.
pub(super) fn largest_semi_axis(semi_axes: DVec2, shape: &GsiShape) -> f64 {
    let spread = match shape.size_randomization.value {
        Randomization::Const => 0.0,
        Randomization::Equal | Randomization::Gauss => shape.size_variation.value.max(0.0),
    };
    semi_axes.x.max(semi_axes.y) * (1.0 + spread)
}

/// How a file's `PART_SIZE` values were read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PartSizeReading {
    /// PART_SIZE are the ellipse semi-axes (the thesis's particle "radius").
    SemiAxes,
    /// PART_SIZE are the full ellipse axes; the semi-axes are half of them.
    FullAxes,
}

impl PartSizeReading {
    /// The ellipse semi-axes for `part_size` under this reading.
    pub fn semi_axes(self, part_size: DVec2) -> DVec2 {
        match self {
            PartSizeReading::SemiAxes => part_size,
            PartSizeReading::FullAxes => 0.5 * part_size,
        }
    }
}

impl fmt::Display for PartSizeReading {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            PartSizeReading::SemiAxes => "semi-axes",
            PartSizeReading::FullAxes => "full axes",
        })
    }
}

impl FromStr for GridType {
    type Err = String;

    /// Parses gc2d's `GRID_TYPE` names (reference §9.7, Abb. B.6), ignoring case.
    fn from_str(name: &str) -> Result<Self, Self::Err> {
        match name.to_ascii_uppercase().as_str() {
            "RECT" => Ok(GridType::Rect),
            "RECT_GAUSS" => Ok(GridType::RectGauss),
            "RECT_EQUAL" => Ok(GridType::RectEqual),
            "FCC" => Ok(GridType::Fcc),
            "FCC_GAUSS" => Ok(GridType::FccGauss),
            "FCC_EQUAL" => Ok(GridType::FccEqual),
            _ => Err(format!(
                "unknown grid type `{name}`; expected one of RECT, RECT_GAUSS, RECT_EQUAL, FCC, FCC_GAUSS, FCC_EQUAL"
            )),
        }
    }
}

/// GENERATE_BLOCK (reference §9.7): particles on a lattice in a rectangle.
#[derive(Debug, Clone, PartialEq)]
pub struct GsiBlock {
    /// Line of the GENERATE_BLOCK keyword.
    pub line: usize,
    /// `X_RANGE`, m (default 0, 10).
    pub x_range: Sourced<Bounds>,
    /// `Y_RANGE`, m (default illegible in the thesis; gc2d-rs uses 0, 10 like X_RANGE).
    pub y_range: Sourced<Bounds>,
    /// `GRID_DISTANCE` (Δx, Δy), m (default 2, 2), checked finite and positive.
    pub grid_distance: Sourced<DVec2>,
    /// `GRID_TYPE` (default FCC).
    pub grid_type: Sourced<GridType>,
    /// The particle shapes.
    pub shape: GsiShape,
    /// `ANGLE_RANGE`, rad CCW from +x: the interval the initial velocity's direction is drawn from (default 0, 2π).
    pub velocity_direction_range: Sourced<Bounds>,
    /// `VELOCITY_RANGE`, m/s: the interval the initial speed is drawn from (default 0, 0).
    pub speed_range: Sourced<Bounds>,
}

/// DROPSOURCE (reference §9.8): inserts particles during the run.
#[derive(Debug, Clone, PartialEq)]
pub struct GsiDropSource {
    /// Line of the DROPSOURCE keyword.
    pub line: usize,
    /// `POS` (x, y), m (default 0, 0.01).
    pub position: Sourced<DVec2>,
    /// `WIDTH` b, m (default 0).
    pub width: Sourced<f64>,
    /// `TYPE` ABS or REL (default ABS).
    pub height: Sourced<DropHeight>,
    /// `TIME` [t1, t2], s (default 0, 1).
    pub window: Sourced<TimeWindow>,
    /// `DELTA_T`, s: the time between insertions (default 0.1).
    pub interval: Sourced<f64>,
    /// The particle shapes.
    pub shape: GsiShape,
}
