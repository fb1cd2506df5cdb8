//! Tangential sub-model of the penetration laws: a Coulomb-capped spring–dashpot whose stiffness is a ratio of the
//! normal stiffness (Cundall–Strack) or Mindlin's k_t = 8·G*·√(R*·δ) (feedpipe.md §2.5–§2.7, §7.1 item 4).

use super::damping::{non_negative, positive};
use super::{NormalSpring, PenetrationLawError};
use serde::{Deserialize, Serialize};

/// How the tangential stiffness k_t depends on the contact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum TangentialStiffness {
    /// k_t = ratio·k_n(δ), k_n(δ) the secant normal stiffness F(δ)/δ: a constant k_t for the linear spring,
    /// ratio·(4/3)·E*·√(R*·δ) for Hertz (Cundall & Strack 1979 with a stiffness ratio).
    CundallStrack {
        /// k_t/k_n (dimensionless, ≥ 0); 2/7 is the area law's choice, 2(1 − ν)/(2 − ν) Mindlin's at equal ν.
        stiffness_ratio: f64,
    },
    /// Mindlin (no-slip): k_t = 8·G*·√(R*·δ) (feedpipe.md (3.48) corrected as in §2.5 (a); Mindlin 1949), G* from
    /// [`crate::penetration::effective_shear_modulus`].
    Mindlin {
        /// Effective shear modulus G* in Pa.
        effective_shear_modulus_pa: f64,
    },
}

/// Tangential spring, dashpot and Coulomb slider (feedpipe.md §2.5–§2.7; decisions as the area law's
/// [`crate::CundallStrack`]).
///
/// Per step, with the sliding velocity v_t of i relative to j at the contact point along the tangent and the
/// stiffness k_t(δ): the stored spring force S (rescaled when k_t falls, see `spring_step`) grows by −k_t·v_t·Δt
/// (feedpipe.md (3.47), (3.52)); the cap is C = μ·F_n (3.55) with F_n the total normal force of the step (elastic +
/// damping, after the tensile clamp) floored at 0, so an attracting or clamped contact carries no friction; S is
/// truncated to ±C while sliding (feedpipe.md §7.1 item 4, not in the thesis); the dashpot adds
/// −c_t·v_t with c_t = 2·D_t·√(m_t·k_t) (the damping ratio of the tangential oscillator of mass m_t; the thesis'
/// (3.53) uses k_n instead of k_t); the force on i along the tangent is clamp(S − c_t·v_t, ±C) (4.9).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TangentialSpring {
    /// Friction coefficient μ (feedpipe.md (3.55); thesis keys `#MU`, `#WM`).
    pub mu: f64,
    /// The stiffness model.
    pub stiffness: TangentialStiffness,
    /// Tangential damping ratio D_t (thesis key `#Dt`, feedpipe.md (3.53)); 0 switches the dashpot off.
    pub damping_ratio: f64,
}

impl TangentialSpring {
    /// k_t in N/m at depth `depth` (m) for effective radius `radius` (m) and normal spring `normal`; 0 for δ ≤ 0.
    #[inline]
    pub fn stiffness(&self, normal: &NormalSpring, depth: f64, radius: f64) -> f64 {
        if depth <= 0.0 {
            return 0.0;
        }
        match self.stiffness {
            TangentialStiffness::CundallStrack { stiffness_ratio } => {
                stiffness_ratio * normal.secant_stiffness(depth, radius)
            }
            TangentialStiffness::Mindlin { effective_shear_modulus_pa } => {
                8.0 * effective_shear_modulus_pa * (radius * depth).sqrt()
            }
        }
    }

    /// Checks the parameters, naming the first one out of range.
    pub fn validate(&self) -> Result<(), PenetrationLawError> {
        non_negative("tangential.mu", self.mu)?;
        non_negative("tangential.damping_ratio", self.damping_ratio)?;
        match self.stiffness {
            TangentialStiffness::CundallStrack { stiffness_ratio } => {
                non_negative("tangential.stiffness_ratio", stiffness_ratio)
            }
            TangentialStiffness::Mindlin { effective_shear_modulus_pa } => {
                positive("tangential.effective_shear_modulus_pa", effective_shear_modulus_pa)
            }
        }
    }
}
