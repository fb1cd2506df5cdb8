//! Rolling-resistance sub-model of the penetration laws: a capped rotational spring–dashpot between the two bodies
//! (feedpipe.md §2.8, §7.1 item 12).

use super::damping::non_negative;
use super::{NormalSpring, PenetrationLawError};
use serde::{Deserialize, Serialize};

/// Rolling resistance: a rotational spring, dashpot and slider between the two bodies (feedpipe.md §2.8 (3.56),
/// (3.59); §7.1 item 12), in the elastic–plastic spring–dashpot form (a spring truncated at a rolling-friction
/// cap, with a dashpot; "EPSD" in Ai et al. 2011).
///
/// The relative rotation rate is ω_i − ω_j (a pair turning together rolls nothing; a disk rolling on a wall has
/// ω_j = 0). Per step: the stored moment M grows by −k_r·(ω_i − ω_j)·Δt with k_r = ratio·k_n(δ)·R*² (N·m/rad;
/// k_n the secant normal stiffness), truncated to the cap |M| ≤ μ_r·R*·F_n (F_n as for friction); the dashpot adds
/// −c_r·(ω_i − ω_j) with c_r = 2·D_r·√(J*·k_r) (feedpipe.md §7.1 item 12), J* the pair's rolling inertia; the moment
/// on i is clamp(M − c_r·(ω_i − ω_j), ±cap), and j receives its opposite. The thesis gives no formula for k_r
/// (feedpipe.md §2.8): the ratio is the user's calibration, scaled with k_n·R*² so that one value fits all sizes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RollingResistance {
    /// Rolling friction coefficient μ_r (dimensionless): the largest moment is μ_r·R*·F_n.
    pub mu_r: f64,
    /// k_r/(k_n·R*²) (dimensionless).
    pub stiffness_ratio: f64,
    /// Rolling damping ratio D_r (thesis key `#Dr`).
    pub damping_ratio: f64,
}

impl RollingResistance {
    /// k_r = ratio·k_n(δ)·R*² in N·m/rad at depth `depth` (m); 0 for δ ≤ 0.
    #[inline]
    pub fn stiffness(&self, normal: &NormalSpring, depth: f64, radius: f64) -> f64 {
        if depth <= 0.0 {
            return 0.0;
        }
        self.stiffness_ratio * normal.secant_stiffness(depth, radius) * radius * radius
    }

    /// Checks the parameters, naming the first one out of range.
    pub fn validate(&self) -> Result<(), PenetrationLawError> {
        non_negative("rolling.mu_r", self.mu_r)?;
        non_negative("rolling.stiffness_ratio", self.stiffness_ratio)?;
        non_negative("rolling.damping_ratio", self.damping_ratio)
    }
}
