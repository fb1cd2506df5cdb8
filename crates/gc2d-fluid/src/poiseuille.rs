//! Laminar Poiseuille flow across a straight channel (feedpipe.md §7.2 (b)).

use gc2d_geometry::DVec2;
use serde::{Deserialize, Serialize};

/// The parabolic profile u = U_c·(1 − (d/h)²)·e across a channel of half-width h, with d the distance from its
/// axis and e the flow direction; zero outside the channel (|d| > h). The mean speed is 2/3 of U_c.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Poiseuille {
    /// A point on the channel's axis, m.
    pub axis_point: DVec2,
    /// The flow direction along the axis (unit vector; [`Poiseuille::new`] normalises it).
    pub direction: DVec2,
    /// Half the channel's width, m (> 0).
    pub half_width_m: f64,
    /// The speed on the axis U_c, m/s (negative flows against `direction`).
    pub centre_speed_m_s: f64,
}

/// Parameters that make no channel.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum PoiseuilleError {
    /// The direction has no length or is not finite.
    #[error("the channel's direction ({0}, {1}) has no length or is not finite")]
    Direction(f64, f64),
    /// The half-width is not positive and finite.
    #[error("the channel's half-width {0} m must be > 0 and finite")]
    HalfWidth(f64),
    /// The axis point or the speed is not finite.
    #[error("the channel's axis point and centre speed must be finite")]
    NonFinite,
}

impl Poiseuille {
    /// A channel along `direction` (normalised here) through `axis_point`.
    pub fn new(
        axis_point: DVec2,
        direction: DVec2,
        half_width_m: f64,
        centre_speed_m_s: f64,
    ) -> Result<Self, PoiseuilleError> {
        let length = direction.length();
        if !(length > 0.0 && length.is_finite()) {
            return Err(PoiseuilleError::Direction(direction.x, direction.y));
        }
        if !(half_width_m > 0.0 && half_width_m.is_finite()) {
            return Err(PoiseuilleError::HalfWidth(half_width_m));
        }
        if !(axis_point.is_finite() && centre_speed_m_s.is_finite()) {
            return Err(PoiseuilleError::NonFinite);
        }
        Ok(Poiseuille { axis_point, direction: direction / length, half_width_m, centre_speed_m_s })
    }

    /// The velocity at `x`, m/s.
    pub fn velocity(&self, x: DVec2) -> DVec2 {
        let d = self.direction.perp_dot(x - self.axis_point) / self.half_width_m;
        if d.abs() > 1.0 {
            return DVec2::ZERO;
        }
        self.centre_speed_m_s * (1.0 - d * d) * self.direction
    }
}
