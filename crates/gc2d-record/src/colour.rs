//! Colour maps shared by the Foxglove recording and the PNG snapshots, so both show a quantity the same way.
//!
//! - Scalar quantities (speed, pressure, age) use **viridis**: perceptually uniform, readable in grey and by
//!   colour-blind viewers. Nine stops (R's `viridis(9)`), interpolated linearly in sRGB.
//! - Categories (materials) use the **Okabe–Ito** palette without its black, which is reserved for small forces.
//! - Force networks use gc2d's ramp (reference §5.5): small forces black, medium red, large yellow.

/// A colour with red, green, blue and alpha in [0, 1] (sRGB).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rgba {
    /// Red.
    pub r: f64,
    /// Green.
    pub g: f64,
    /// Blue.
    pub b: f64,
    /// Opacity.
    pub a: f64,
}

impl Rgba {
    /// An opaque colour from its 24-bit hex code 0xRRGGBB.
    pub const fn hex(code: u32) -> Self {
        Self {
            r: ((code >> 16) & 0xff) as f64 / 255.0,
            g: ((code >> 8) & 0xff) as f64 / 255.0,
            b: (code & 0xff) as f64 / 255.0,
            a: 1.0,
        }
    }

    /// The same colour with opacity `a`.
    pub const fn with_alpha(self, a: f64) -> Self {
        Self { a, ..self }
    }

    /// The colour a fraction `t` of the way from `self` to `other`.
    pub fn mix(self, other: Rgba, t: f64) -> Self {
        let lerp = |x: f64, y: f64| x + (y - x) * t;
        Self { r: lerp(self.r, other.r), g: lerp(self.g, other.g), b: lerp(self.b, other.b), a: lerp(self.a, other.a) }
    }

    /// The colour darkened towards black by `factor` in [0, 1] (0 keeps it, 1 is black).
    pub fn darkened(self, factor: f64) -> Self {
        let k = 1.0 - factor.clamp(0.0, 1.0);
        Self { r: self.r * k, g: self.g * k, b: self.b * k, a: self.a }
    }
}

/// Walls: a neutral grey that no colour map uses.
pub const WALL_GREY: Rgba = Rgba::hex(0x8c8c8c);

/// Viridis at nine equally spaced stops (R's `viridis(9)`).
const VIRIDIS: [Rgba; 9] = [
    Rgba::hex(0x440154),
    Rgba::hex(0x472d7b),
    Rgba::hex(0x3b528b),
    Rgba::hex(0x2c728e),
    Rgba::hex(0x21908c),
    Rgba::hex(0x27ad81),
    Rgba::hex(0x5dc863),
    Rgba::hex(0xaadc32),
    Rgba::hex(0xfde725),
];

/// Okabe–Ito's colour-blind-safe palette without black, for categories.
const OKABE_ITO: [Rgba; 7] = [
    Rgba::hex(0xe69f00),
    Rgba::hex(0x56b4e9),
    Rgba::hex(0x009e73),
    Rgba::hex(0xf0e442),
    Rgba::hex(0x0072b2),
    Rgba::hex(0xd55e00),
    Rgba::hex(0xcc79a7),
];

/// gc2d's force ramp: black, red, yellow.
const FORCE_RAMP: [Rgba; 3] = [Rgba::hex(0x000000), Rgba::hex(0xff0000), Rgba::hex(0xffff00)];

/// Piecewise-linear interpolation through equally spaced stops; `t` is clamped to [0, 1] and NaN maps to 0.
fn ramp(stops: &[Rgba], t: f64) -> Rgba {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let segments = (stops.len() - 1) as f64;
    let x = t * segments;
    let i = (x.floor() as usize).min(stops.len() - 2);
    stops[i].mix(stops[i + 1], x - i as f64)
}

/// Viridis at `t` in [0, 1] (clamped): dark purple at 0, yellow at 1.
pub fn viridis(t: f64) -> Rgba {
    ramp(&VIRIDIS, t)
}

/// The colour of category `index`; the palette repeats after seven categories.
pub fn category(index: usize) -> Rgba {
    OKABE_ITO[index % OKABE_ITO.len()]
}

/// gc2d's force colour at `t` = |F| / F_max in [0, 1] (clamped): black, red at ½, yellow at 1.
pub fn force_colour(t: f64) -> Rgba {
    ramp(&FORCE_RAMP, t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    #[test]
    fn viridis_hits_its_stops_and_interpolates_between_them() {
        assert_eq!(viridis(0.0), Rgba::hex(0x440154));
        assert_eq!(viridis(1.0), Rgba::hex(0xfde725));
        assert_eq!(viridis(0.5), Rgba::hex(0x21908c));
        let halfway = viridis(1.0 / 16.0);
        assert_abs_diff_eq!(halfway.r, 0.5 * (0x44 as f64 + 0x47 as f64) / 255.0, epsilon = 1e-12);
        assert_abs_diff_eq!(halfway.g, 0.5 * (0x01 as f64 + 0x2d as f64) / 255.0, epsilon = 1e-12);
    }

    #[test]
    fn out_of_range_and_nan_inputs_are_clamped() {
        assert_eq!(viridis(-3.0), viridis(0.0));
        assert_eq!(viridis(7.0), viridis(1.0));
        assert_eq!(viridis(f64::NAN), viridis(0.0));
        assert_eq!(force_colour(f64::INFINITY), Rgba::hex(0xffff00));
    }

    #[test]
    fn force_ramp_is_black_red_yellow() {
        assert_eq!(force_colour(0.0), Rgba::hex(0x000000));
        assert_eq!(force_colour(0.5), Rgba::hex(0xff0000));
        assert_eq!(force_colour(0.75), Rgba { r: 1.0, g: 0.5, b: 0.0, a: 1.0 });
    }

    #[test]
    fn categories_repeat_after_the_palette() {
        assert_eq!(category(0), category(7));
        assert_ne!(category(0), category(1));
    }
}
