//! Time ramps: a factor from 0 to 1 that switches a fluid field on (feedpipe.md §7.2: "flow developed after 0.5 s").

use serde::{Deserialize, Serialize};

/// How a ramp rises between its start and end.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum RampShape {
    /// Straight: s = (t − t₀)/(t₁ − t₀).
    #[default]
    Linear,
    /// Smoothstep 3s² − 2s³: starts and ends with zero slope, so the drag it scales has no kink in time.
    Smooth,
}

/// A factor 0 before `start_s`, 1 after `end_s`, rising between as `shape` says.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TimeRamp {
    /// When the ramp leaves 0, s.
    pub start_s: f64,
    /// When it reaches 1, s (≥ `start_s`; equal makes a step at that time).
    pub end_s: f64,
    /// How it rises.
    pub shape: RampShape,
}

impl TimeRamp {
    /// The factor at time `t` (s), in [0, 1].
    pub fn factor(&self, t: f64) -> f64 {
        if t >= self.end_s {
            return 1.0;
        }
        if t <= self.start_s {
            return 0.0;
        }
        let s = (t - self.start_s) / (self.end_s - self.start_s);
        match self.shape {
            RampShape::Linear => s,
            RampShape::Smooth => s * s * (3.0 - 2.0 * s),
        }
    }
}
