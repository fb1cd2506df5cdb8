//! Drag and buoyancy on a particle in a fluid (feedpipe.md §2.10, §4.1, §7.1 item 10), as pure functions.
//!
//! Sign convention: the slip velocity is w = u(x) − v_p, the fluid's velocity relative to the particle, and the
//! drag F = ½·ρ_f·c_w·A·|w|·w points along w: it pulls the particle towards the fluid's velocity. (The thesis
//! writes the same force as −½·ρ_f·c_w·A·|v_r|·v_r with v_r = v_p − u.)

use gc2d_geometry::DVec2;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The drag coefficient of a sphere the thesis uses (feedpipe.md §4.1).
pub const SPHERE_DRAG_COEFFICIENT: f64 = 0.47;

/// The Reynolds number above which Schiller–Naumann's c_w is the constant 0.44.
pub const SCHILLER_NAUMANN_LIMIT: f64 = 1000.0;

/// The fluid's material.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FluidProperties {
    /// ρ_f, kg/m³ (air 1.25, water 1000).
    pub density_kg_m3: f64,
    /// η, the dynamic viscosity, Pa·s (air 1.8e-5, water 1.0e-3); only Schiller–Naumann reads it.
    pub dynamic_viscosity_pa_s: f64,
}

/// The drag coefficient c_w.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum DragCoefficient {
    /// A constant c_w (the thesis: 0.47 for a sphere, no Reynolds-number dependence).
    Constant(f64),
    /// Schiller–Naumann's sphere correlation: c_w = 24/Re·(1 + 0.15·Re^0.687) for Re < 1000, 0.44 above, with
    /// Re = ρ_f·|w|·2R/η. It tends to Stokes drag 6π·η·R·w as Re → 0. At Re = 1000 it jumps from 0.4383 to 0.44
    /// (+0.39 %), as the correlation is written.
    SchillerNaumann,
}

impl Default for DragCoefficient {
    fn default() -> Self {
        DragCoefficient::Constant(SPHERE_DRAG_COEFFICIENT)
    }
}

impl DragCoefficient {
    /// c_w at Reynolds number `re` (> 0 for Schiller–Naumann).
    pub fn at_reynolds(self, re: f64) -> f64 {
        match self {
            DragCoefficient::Constant(c) => c,
            DragCoefficient::SchillerNaumann if re < SCHILLER_NAUMANN_LIMIT => {
                24.0 / re * (1.0 + 0.15 * re.powf(0.687))
            }
            DragCoefficient::SchillerNaumann => 0.44,
        }
    }
}

/// What the fluid sees of a particle: its radius, projected area and displaced volume.
///
/// Two models, matching the engine's mass models: sphere-equivalent (a sphere of radius R moving in the plane:
/// A = π·R², V = 4/3·π·R³; the thesis) and per unit thickness (a prism of unit depth: A = 2R, the width across the
/// flow per metre of depth, and V = the shape's area, so forces are N per metre of depth like the masses). For a
/// polygon, R is the equal-area radius √(area/π) ([`equivalent_radius`]), and A does not follow the polygon's
/// orientation: drag treats it as the disk of equal area.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ImmersedBody {
    /// R, m: the disk's radius or a polygon's equal-area radius.
    pub radius_m: f64,
    /// A, the area the flow meets: m² (sphere-equivalent) or m per metre of depth (per unit thickness).
    pub projected_area_m2: f64,
    /// V, the displaced volume: m³ (sphere-equivalent) or m² per metre of depth (per unit thickness).
    pub volume_m3: f64,
}

impl ImmersedBody {
    /// A sphere of radius `radius_m`.
    pub fn sphere_equivalent(radius_m: f64) -> Self {
        ImmersedBody {
            radius_m,
            projected_area_m2: PI * radius_m * radius_m,
            volume_m3: 4.0 / 3.0 * PI * radius_m.powi(3),
        }
    }

    /// A prism of unit depth whose cross-section has equal-area radius `radius_m` and area `area_m2` (π·R² for a
    /// disk).
    pub fn per_unit_thickness(radius_m: f64, area_m2: f64) -> Self {
        ImmersedBody { radius_m, projected_area_m2: 2.0 * radius_m, volume_m3: area_m2 }
    }
}

/// The radius of the disk with the same area as a shape: √(area/π), m.
pub fn equivalent_radius(area_m2: f64) -> f64 {
    (area_m2 / PI).sqrt()
}

/// The particle Reynolds number Re = ρ_f·|w|·2R/η for slip speed `slip_speed_m_s`.
pub fn reynolds_number(fluid: &FluidProperties, radius_m: f64, slip_speed_m_s: f64) -> f64 {
    fluid.density_kg_m3 * slip_speed_m_s * 2.0 * radius_m / fluid.dynamic_viscosity_pa_s
}

/// The drag on `body` for slip velocity `slip` = u(x) − v_p (m/s): ½·ρ_f·c_w·A·|w|·w, N (or N/m per unit
/// thickness). Zero at zero slip. Schiller–Naumann below Re = 1000 is evaluated as 6·η·(A/R)·(1 + 0.15·Re^0.687)·w
/// (the same force with 24/Re multiplied out), which stays finite as the slip goes to zero.
pub fn drag_force(fluid: &FluidProperties, coefficient: DragCoefficient, body: &ImmersedBody, slip: DVec2) -> DVec2 {
    let speed = slip.length();
    if speed == 0.0 {
        return DVec2::ZERO;
    }
    match coefficient {
        DragCoefficient::SchillerNaumann => {
            let re = reynolds_number(fluid, body.radius_m, speed);
            if re < SCHILLER_NAUMANN_LIMIT {
                let stokes = 6.0 * fluid.dynamic_viscosity_pa_s * body.projected_area_m2 / body.radius_m;
                return stokes * (1.0 + 0.15 * re.powf(0.687)) * slip;
            }
            0.5 * fluid.density_kg_m3 * 0.44 * body.projected_area_m2 * speed * slip
        }
        DragCoefficient::Constant(c) => 0.5 * fluid.density_kg_m3 * c * body.projected_area_m2 * speed * slip,
    }
}

/// Static buoyancy −ρ_f·V·g (Archimedes, feedpipe.md §2.10) for gravity `gravity` (m/s², e.g. (0, −9.81)), N (or
/// N/m per unit thickness): it points against gravity.
pub fn buoyancy_force(fluid_density_kg_m3: f64, body: &ImmersedBody, gravity: DVec2) -> DVec2 {
    -fluid_density_kg_m3 * body.volume_m3 * gravity
}

/// The terminal speed w_t of a particle of mass `mass_kg` (kg, or kg/m per unit thickness) falling through still
/// fluid under gravity `g` (m/s², its magnitude) with a constant c_w, where drag balances weight less buoyancy:
/// w_t = √(2·(m − ρ_f·V)·g / (ρ_f·c_w·A)), m/s; 0 where the particle is not heavier than the fluid it displaces.
/// For a sphere of density ρ_p this is √(8·R·g·(ρ_p − ρ_f)/(3·ρ_f·c_w)) (3.4993 m/s for the thesis's styrofoam
/// ball, feedpipe.md §7.2); per unit thickness √(π·R·g·(ρ_p − ρ_f)/(ρ_f·c_w)).
pub fn terminal_speed(
    fluid_density_kg_m3: f64,
    mass_kg: f64,
    body: &ImmersedBody,
    drag_coefficient: f64,
    g: f64,
) -> f64 {
    let net_weight = (mass_kg - fluid_density_kg_m3 * body.volume_m3) * g;
    if net_weight <= 0.0 {
        return 0.0;
    }
    (2.0 * net_weight / (fluid_density_kg_m3 * drag_coefficient * body.projected_area_m2)).sqrt()
}
