//! The interaction table: the contact law of a pair of materials (docs/scene-format.md, "Interactions").
//!
//! A pair the table does not list interacts by gc2d's overlap-area law with parameters mixed from its two materials
//! (docs/model.md, "Materials and mixing rules"); an entry overrides that for its pair, with the overlap-area law or
//! a penetration law (a linear spring or Hertz, docs/model.md, "Penetration laws").

pub use gc2d_contact::AreaFormulation;
use serde::{Deserialize, Serialize};

/// One entry of the scene's `interactions` list.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Interaction {
    /// The two materials (names; either order; may be the same twice).
    pub materials: [String; 2],
    /// The pair's contact law.
    pub law: InteractionLaw,
}

/// The contact law of one material pair.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum InteractionLaw {
    /// gc2d's overlap-area law (reference §2.4–§2.11). A parameter left out is mixed from the two materials.
    OverlapArea {
        /// Young's modulus E (2D), N/m. Default: mixed.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        youngs_modulus_n_m: Option<f64>,
        /// Normal damping γ. Default: mixed.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        gamma: Option<f64>,
        /// Friction coefficient μ. Default: mixed.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        mu: Option<f64>,
        /// Cohesion k_coh, N/m. Default: mixed.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        cohesion_n_m: Option<f64>,
        /// The elastic force law: `Thesis` (gc2d's F⊥ = E·A/l at the chord midpoint), `Conservative` (the exact
        /// gradient of the potential E·A²/(2l²), which keeps the energy of elastic collisions) or `Winkler` (E·A/l at
        /// the overlap centroid with dashpots along the chord: flat contacts resist rocking, so blocks rest on slopes
        /// below the friction angle). Default: `Thesis`.
        #[serde(default, skip_serializing_if = "is_thesis")]
        formulation: AreaFormulation,
    },
    /// A linear spring on the penetration depth: F = k·δ.
    Linear {
        /// Normal stiffness k, N/m.
        stiffness_n_m: f64,
        /// Normal damping. Default none.
        #[serde(default)]
        damping: Damping,
        /// Tangential spring and Coulomb friction. Default none (frictionless).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        friction: Option<Friction>,
        /// Rolling resistance. Default none.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        rolling: Option<Rolling>,
        /// Floor the total normal force at zero (no pull while separating). Default false, as in the theses, and
        /// the restitution mappings assume it off.
        #[serde(default)]
        tensile_clamp: bool,
    },
    /// Hertz's sphere law F = 4/3·E*·√R*·δ^{3/2}, E* from the materials' `youngs_modulus_pa` and `poisson_ratio`,
    /// R* from the two bodies' radii at the contact.
    Hertz {
        /// Normal damping. Default none.
        #[serde(default)]
        damping: Damping,
        /// Tangential spring and Coulomb friction. Default none (frictionless).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        friction: Option<Friction>,
        /// Rolling resistance. Default none.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        rolling: Option<Rolling>,
        /// Floor the total normal force at zero. Default false.
        #[serde(default)]
        tensile_clamp: bool,
    },
}

/// Normal damping of a penetration law.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub enum Damping {
    /// Undamped (elastic).
    #[default]
    None,
    /// Lehr's damping ratio D: a dashpot 2·D·√(m*·k_n(δ)).
    Ratio(f64),
    /// A constant coefficient of restitution e ∈ [0, 1], mapped exactly to D for the law.
    Restitution(f64),
    /// Reichardt's measured steel law e(v) = 0.985/(v + 0.9494)^0.291 at the impact speed of each contact.
    SteelReichardt,
    /// e(v) = a/(v + b)^c at the impact speed (v in m/s).
    PowerLaw {
        /// Prefactor a.
        a: f64,
        /// Offset b, m/s (> 0).
        b: f64,
        /// Exponent c.
        c: f64,
    },
    /// e(v) interpolated linearly in measured `(speed_m_s, e)` points (1 to 32, speeds rising), constant beyond.
    Table(Vec<(f64, f64)>),
}

/// Tangential spring and Coulomb friction of a penetration law.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Friction {
    /// Friction coefficient μ.
    pub mu: f64,
    /// How stiff the tangential spring is. Default: `Mindlin` for Hertz, `Ratio(0.2857…)` (2/7) for the linear law.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<FrictionStiffness>,
    /// Tangential damping ratio D_t. Default 0.
    #[serde(default)]
    pub damping_ratio: f64,
}

/// The tangential stiffness of a penetration law.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum FrictionStiffness {
    /// k_t = ratio·k_n(δ) (Cundall–Strack).
    Ratio(f64),
    /// Mindlin: k_t = 8·G*·√(R*·δ), G* from the materials' `youngs_modulus_pa` and `poisson_ratio`.
    Mindlin,
}

/// Rolling resistance of a penetration law: a rotational spring k_r = ratio·k_n·R*², capped at μ_r·R*·F_n, with a
/// dashpot.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rolling {
    /// Rolling friction coefficient μ_r.
    pub mu_r: f64,
    /// k_r/(k_n·R*²). Default 0.25.
    #[serde(default = "default_rolling_stiffness_ratio")]
    pub stiffness_ratio: f64,
    /// Rolling damping ratio D_r. Default 0.
    #[serde(default)]
    pub damping_ratio: f64,
}

fn default_rolling_stiffness_ratio() -> f64 {
    0.25
}

/// True for the default formulation (left out when a scene is written).
fn is_thesis(formulation: &AreaFormulation) -> bool {
    *formulation == AreaFormulation::Thesis
}
