//! The scene types: what a RON scene file says, one Rust type per RON structure (see `docs/scene-format.md`).
//!
//! Every field is public and every type has a documented default where the field may be omitted, so a scene can be
//! written by hand, loaded from RON, or constructed in code (the gsi importer fills these types). Units are part of
//! the field names (`time_step_s`, `density_kg_m2`); dimensionless fields name the thesis symbol (`gamma`, `mu`).
//! Positions and vectors are `(x, y)` pairs, `[f64; 2]` in Rust. Angles are radians, counter-clockwise from +x.

mod bodies;
mod fluid;
mod inlets;
mod interactions;
mod mill;
mod shapes;
mod walls;

pub use bodies::{Block, DragSpring, DropHeight, GridType, Particle, Source};
pub use fluid::{Drag, Field, Fluid, Ramp, VtkSnapshot};
pub use inlets::{Inlet, Outlet};
pub use interactions::{AreaFormulation, Damping, Friction, FrictionStiffness, Interaction, InteractionLaw, Rolling};
pub use mill::{BallPlacement, Balls, Chamber, Mill, Ore, Rotor};
pub use shapes::{CornerPositions, CountSpread, Orientation, Recipe, Shape, SizeSpread};
pub use walls::{Motion, WallItem, Waveform};

use crate::source::SourceText;
pub use gc2d_engine::MassModel;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// A time window `(t1, t2)` in seconds; `inf` is allowed for an open end.
pub type Window = [f64; 2];

/// A whole scene: run settings, gravity and heating, materials, walls, particles, lattice blocks and sources.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// A short name (outputs are named after it). Default: the file name without `.ron`.
    #[serde(default)]
    pub name: String,
    /// Free text saying what the scene shows.
    #[serde(default)]
    pub description: String,
    /// Time step, end time, seed, output cadence and safety options.
    #[serde(default)]
    pub run: Run,
    /// g(t), acting along −y. Default `Constant(9.81)`.
    #[serde(default)]
    pub gravity: Gravity,
    /// Global particle size cycling s(t) (gsi `HEAT_*`). Default: none.
    #[serde(default)]
    pub heating: Option<Heating>,
    /// How particle masses follow from shape and density: `PerUnitThickness` (gc2d; densities in kg/m²) or
    /// `SphereEquivalent` (spheres moving in the plane; densities in kg/m³, `density_kg_m3`). Default
    /// `PerUnitThickness`.
    #[serde(default, skip_serializing_if = "is_default")]
    pub mass_model: MassModel,
    /// Named materials. Default: one material named `default` with the default values.
    #[serde(default)]
    pub materials: Vec<Material>,
    /// The contact law of material pairs that do not use the overlap-area law mixed from their two materials.
    /// Default: none (every pair mixes).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub interactions: Vec<Interaction>,
    /// Walls: single polygons and the wall-builder macros (drum, funnel, silo, box).
    #[serde(default)]
    pub walls: Vec<WallItem>,
    /// Individually placed particles (gsi `PARTICLE`).
    #[serde(default)]
    pub particles: Vec<Particle>,
    /// Particles on a lattice in a rectangle (gsi `GENERATE_BLOCK`).
    #[serde(default)]
    pub blocks: Vec<Block>,
    /// Particle sources that insert particles during the run (gsi `DROPSOURCE`).
    #[serde(default)]
    pub sources: Vec<Source>,
    /// Segments that feed particles at a rate (docs/scene-format.md "inlets and outlets"). Default: none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub inlets: Vec<Inlet>,
    /// Segments that remove the particles crossing them outward. Default: none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub outlets: Vec<Outlet>,
    /// The fluid the particles move in: drag, buoyancy and its velocity field (docs/scene-format.md "fluid").
    /// Default: none (particles move in vacuum).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fluid: Option<Fluid>,
    /// A ball mill: chamber, rotor and balls, expanded into walls and particles. Default: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mill: Option<Mill>,
    /// The region a picture of the scene should show (gsi `DISPLAY` `X_RANGE`/`Y_RANGE`). Default: none.
    #[serde(default)]
    pub view: Option<Area>,
    /// The text the scene was loaded from, for error spans; `None` for scenes constructed in code.
    #[serde(skip)]
    pub source: Option<Arc<SourceText>>,
}

/// How long, how finely and how safely to run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Run {
    /// Δt in s. Default (omitted): the smaller of 0.15 of the §3.6 bound of the particles (each against the stiffest
    /// contact law its material meets: (π/10)·sqrt(m/E) for the overlap-area law) and their stable bound, rounded down
    /// to two significant digits, or 1e-4 s when the scene has no particles.
    #[serde(default)]
    pub time_step_s: Option<f64>,
    /// Simulated time at which the run ends, s. Default 1.
    #[serde(default = "defaults::end_time")]
    pub end_time_s: f64,
    /// Recorded frames per simulated second (gsi `STEPS_DATA` = 1/(Δt·frames_per_second)). Default 100.
    #[serde(default = "defaults::frames_per_second")]
    pub frames_per_second: f64,
    /// Simulated time between two numbered checkpoints, s (gsi `STEPS_SETUP`·Δt). Default: no checkpoints.
    #[serde(default)]
    pub checkpoint_interval_s: Option<f64>,
    /// Seed of every random draw (random shapes, block scatter, sources). Default 0.
    #[serde(default)]
    pub seed: u64,
    /// Particles whose centroid leaves this box are removed. Default: none (particles are kept wherever they go).
    #[serde(default)]
    pub domain: Option<Area>,
    /// Run even if Δt is above the stable bound (for experiments on instability). Default false.
    #[serde(default)]
    pub allow_unsafe_time_step: bool,
    /// Largest overlap allowed during the run: for the overlap-area law its area as a fraction of the smaller
    /// particle's area, for a penetration law (`Linear`, `Hertz`) its depth as a fraction of the smaller particle's
    /// diameter. Default 0.05. (At the start no overlap beyond round-off is allowed: docs/scene-format.md, "Checks and
    /// errors".)
    #[serde(default = "defaults::max_overlap_fraction")]
    pub max_overlap_fraction: f64,
    /// Largest unexplained energy gain, as a fraction of the run's energy scale, before the run stops. Default 1.0 (the engine's).
    #[serde(default = "defaults::max_energy_gain_fraction")]
    pub max_energy_gain_fraction: f64,
    /// Gear corrector coefficient c₀. Default `VelocityDependent` (3/16).
    #[serde(default)]
    pub corrector: Corrector,
    /// The highest normal impact speed the scene expects, m/s: a Hertz contact stiffens with depth, so its time-step
    /// bound depends on how hard bodies hit. Default: twice the rotor's tip speed for a mill (a ball thrown by a
    /// blade meets the next blade head-on), at least 10 m/s; 10 m/s otherwise (`Scene::max_impact_speed`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_impact_speed_m_s: Option<f64>,
}

impl Default for Run {
    fn default() -> Self {
        Self {
            time_step_s: None,
            end_time_s: defaults::end_time(),
            frames_per_second: defaults::frames_per_second(),
            checkpoint_interval_s: None,
            seed: 0,
            domain: None,
            allow_unsafe_time_step: false,
            max_overlap_fraction: defaults::max_overlap_fraction(),
            max_energy_gain_fraction: defaults::max_energy_gain_fraction(),
            corrector: Corrector::default(),
            max_impact_speed_m_s: None,
        }
    }
}

/// The Gear corrector coefficient c₀ (reference §3.4, decision D4 in `docs/model.md`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Corrector {
    /// c₀ = 3/16, for velocity-dependent forces (damping, friction).
    #[default]
    VelocityDependent,
    /// c₀ = 3/20, Gear's coefficient for position-dependent forces only.
    PositionDependent,
}

/// An axis-aligned rectangle given by its x and y ranges, m.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Area {
    /// (x_min, x_max), m.
    pub x_range_m: [f64; 2],
    /// (y_min, y_max), m.
    pub y_range_m: [f64; 2],
}

impl Area {
    /// The rectangle as a box, m.
    pub fn aabb(&self) -> gc2d_geometry::Aabb {
        gc2d_geometry::Aabb {
            min: gc2d_geometry::DVec2::new(self.x_range_m[0], self.y_range_m[0]),
            max: gc2d_geometry::DVec2::new(self.x_range_m[1], self.y_range_m[1]),
        }
    }
}

/// The magnitude of gravity over time; it acts along −y (gsi `G`, `G_TIME`, `G_PARAMETER`, `G_TYPE`, §2.13).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Gravity {
    /// g in m/s², constant.
    Constant(f64),
    /// g changes from `from_m_s2` to `to_m_s2` over `window_s`, following `profile`.
    Varying {
        /// How g changes.
        profile: GravityProfile,
        /// g1, m/s², before and at t1.
        from_m_s2: f64,
        /// g2, m/s², from t2 on.
        to_m_s2: f64,
        /// (t1, t2), s.
        window_s: Window,
        /// p1: number of steps for `Step` and `SmoothStep`. Default 5.
        #[serde(default = "defaults::gravity_steps")]
        steps: u32,
        /// p2: the ramp's share of each step for `SmoothStep`, in [0, 1]. Default 0.5.
        #[serde(default = "defaults::ramp_fraction")]
        ramp_fraction: f64,
    },
}

impl Default for Gravity {
    fn default() -> Self {
        Gravity::Constant(defaults::GRAVITY)
    }
}

/// The shape of a gravity change (gsi `G_TYPE`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum GravityProfile {
    /// Linear from g1 to g2.
    Linear,
    /// p1 equal jumps.
    Step,
    /// p1 equal steps, each ending with a linear ramp over the fraction p2 of the step.
    SmoothStep,
}

impl Gravity {
    /// The largest |g| the scene reaches, m/s².
    pub fn largest_magnitude(&self) -> f64 {
        match *self {
            Gravity::Constant(g) => g.abs(),
            Gravity::Varying { from_m_s2, to_m_s2, .. } => from_m_s2.abs().max(to_m_s2.abs()),
        }
    }
}

/// Global size cycling of all particles, s(t) = 1 + a·(½ − ½·tanh(S·cos 2πft)) (gsi `HEAT_*`, §1.6, B.2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Heating {
    /// (t1, t2) during which the size cycles, s.
    pub window_s: Window,
    /// a, the relative size change; must exceed −1. Default 0.01.
    #[serde(default = "defaults::heat_amplitude")]
    pub amplitude: f64,
    /// f, Hz. Default 1.
    #[serde(default = "defaults::one")]
    pub frequency_hz: f64,
    /// S, the steepness of the switch between cold and hot. Default 4.
    #[serde(default = "defaults::heat_slope")]
    pub slope: f64,
}

/// A named material. Two bodies interact by the law the scene's `interactions` give their pair, or else by the
/// overlap-area law with E, γ, μ and k_coh mixed from their two materials (docs/model.md, "Materials and mixing
/// rules"); walls have materials too.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// The name particles, blocks and sources refer to.
    pub name: String,
    /// Area density ρ, kg/m², of the `PerUnitThickness` mass model. Default 5000 (the thesis's value, eq. 3.5).
    #[serde(default = "defaults::density")]
    pub density_kg_m2: f64,
    /// Density ρ, kg/m³, of the `SphereEquivalent` mass model (required there, refused with the other model).
    /// Default: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density_kg_m3: Option<f64>,
    /// Young's modulus E (2D), N/m. Default 1e7.
    #[serde(default = "defaults::youngs_modulus")]
    pub youngs_modulus_n_m: f64,
    /// Normal damping γ, dimensionless. Default 0.5.
    #[serde(default = "defaults::gamma")]
    pub gamma: f64,
    /// Friction coefficient μ (gsi `MUE_STATISCH`). Default 0.6.
    #[serde(default = "defaults::mu")]
    pub mu: f64,
    /// Cohesion k_coh, N/m. Default 0.
    #[serde(default)]
    pub cohesion_n_m: f64,
    /// Young's modulus E (3D), Pa, of the Hertz and Mindlin laws (required by pairs that use them). Default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub youngs_modulus_pa: Option<f64>,
    /// Poisson's ratio ν of the Hertz and Mindlin laws. Default 0.3.
    #[serde(default = "defaults::poisson_ratio", skip_serializing_if = "is_default_poisson_ratio")]
    pub poisson_ratio: f64,
}

/// True for the default Poisson ratio, which the scene as written out leaves away.
fn is_default_poisson_ratio(value: &f64) -> bool {
    *value == defaults::poisson_ratio()
}

impl Material {
    /// The material a scene that declares none has (named `default`, with the default values): every body is of it.
    pub fn implicit() -> Self {
        Self::named(defaults::MATERIAL)
    }

    /// A material with the default values.
    pub fn named(name: &str) -> Self {
        Self {
            name: name.to_owned(),
            density_kg_m2: defaults::density(),
            density_kg_m3: None,
            youngs_modulus_n_m: defaults::youngs_modulus(),
            gamma: defaults::gamma(),
            mu: defaults::mu(),
            cohesion_n_m: 0.0,
            youngs_modulus_pa: None,
            poisson_ratio: defaults::poisson_ratio(),
        }
    }
}

/// True for a field at its type's default, which the scene as written out leaves away.
fn is_default<T: Default + PartialEq>(value: &T) -> bool {
    *value == T::default()
}

/// Default values of omitted fields (serde's `default = "…"` needs functions).
pub(crate) mod defaults {
    /// g, m/s².
    pub const GRAVITY: f64 = 9.81;
    /// The name of the implicit material of a scene that declares none.
    pub const MATERIAL: &str = "default";

    pub fn end_time() -> f64 {
        1.0
    }
    pub fn frames_per_second() -> f64 {
        100.0
    }
    pub fn max_overlap_fraction() -> f64 {
        gc2d_engine::SafetyLimits::default().max_overlap_fraction
    }
    pub fn max_energy_gain_fraction() -> f64 {
        gc2d_engine::SafetyLimits::default().max_energy_gain_fraction
    }
    pub fn gravity_steps() -> u32 {
        5
    }
    pub fn ramp_fraction() -> f64 {
        0.5
    }
    pub fn heat_amplitude() -> f64 {
        0.01
    }
    pub fn heat_slope() -> f64 {
        4.0
    }
    pub fn one() -> f64 {
        1.0
    }
    pub fn density() -> f64 {
        5000.0
    }
    pub fn youngs_modulus() -> f64 {
        1e7
    }
    pub fn gamma() -> f64 {
        0.5
    }
    pub fn mu() -> f64 {
        0.6
    }
    pub fn poisson_ratio() -> f64 {
        0.3
    }
    pub fn chamber_radius() -> f64 {
        0.073
    }
    pub fn hub_radius() -> f64 {
        0.008
    }
    pub fn tip_radius() -> f64 {
        0.058
    }
    pub fn blade_width() -> f64 {
        0.008
    }
    pub fn one_bar() -> Vec<f64> {
        vec![0.0, std::f64::consts::PI]
    }
    pub fn ball_radius() -> f64 {
        0.0025
    }
    pub fn half_pi() -> f64 {
        std::f64::consts::FRAC_PI_2
    }
    pub fn open_window() -> super::Window {
        [0.0, f64::INFINITY]
    }
    pub fn unit_window() -> super::Window {
        [0.0, 1.0]
    }
    pub fn full_turn() -> [f64; 2] {
        [0.0, std::f64::consts::TAU]
    }
    pub fn corners() -> usize {
        6
    }
    pub fn drag_stiffness() -> f64 {
        100.0
    }
    pub fn drag_speed() -> f64 {
        0.1
    }
    pub fn source_interval() -> f64 {
        0.1
    }
}
