//! How far apart a pair of bodies was last known to be, in the two bytes its record has for it.

use serde::{Deserialize, Serialize};

/// A distance ≥ 0, m, kept as the upper half of its single-precision bits (a bfloat16: 8 bits of exponent, 8 of
/// precision) and always rounded down, so that it never claims more room than there was; 0 when nothing is known.
/// Rounding down loses at most 1/128 of the distance each time it is stored.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Clearance(u16);

impl Clearance {
    /// Nothing known: no room at all.
    pub const NONE: Self = Self(0);

    /// The largest clearance not above `distance` (NaN and non-positive distances give [`Self::NONE`]).
    #[inline]
    pub fn at_most(distance: f64) -> Self {
        if distance.is_nan() || distance <= 0.0 {
            return Self::NONE;
        }
        // The conversion to single precision rounds to nearest and overflows to infinity: step one unit down where
        // it went up (the bits of a positive number count up with it; infinity's predecessor is the largest finite
        // number), then drop the low 16 bits, which rounds a positive number towards zero.
        let mut bits = (distance as f32).to_bits();
        if f64::from(f32::from_bits(bits)) > distance || f32::from_bits(bits).is_infinite() {
            bits -= 1;
        }
        Self((bits >> 16) as u16)
    }

    /// The distance, m.
    #[inline]
    pub fn metres(self) -> f64 {
        f64::from(f32::from_bits(u32::from(self.0) << 16))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn nothing_known_is_no_room() {
        assert_eq!(Clearance::default(), Clearance::NONE);
        assert_eq!(Clearance::NONE.metres(), 0.0);
        for distance in [0.0, -1e-3, f64::NAN, f64::NEG_INFINITY] {
            assert_eq!(Clearance::at_most(distance), Clearance::NONE);
        }
        let unbounded = Clearance::at_most(f64::INFINITY).metres();
        assert!(unbounded.is_finite() && unbounded == Clearance::at_most(1e300).metres());
    }

    proptest! {
        /// Never above the distance, and within 1/128 of it over the range of lengths a scene has.
        #[test]
        fn rounds_down_by_less_than_a_128th(mantissa in 1.0f64..10.0, exponent in -30i32..30) {
            let distance = mantissa * 10f64.powi(exponent);
            let kept = Clearance::at_most(distance).metres();
            prop_assert!(kept <= distance);
            prop_assert!(kept >= distance * (1.0 - 1.0 / 128.0));
        }
    }
}
