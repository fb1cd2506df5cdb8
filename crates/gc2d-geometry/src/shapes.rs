//! Body-frame outlines for particles and walls: regular polygons, polygons inscribed in an ellipse (reference §1.2,
//! App. B.1.6) and the rectangle family of gc2d's Perl shape macros (§1.8, App. D.3–D.5).
//!
//! The macros' placement arguments (x, y, φ) are not taken here: every generator returns a validated polygon in its
//! body frame (centroid at the origin), and the caller places it with a [`crate::Pose`].

mod angles;

pub use angles::{AngleMode, MAX_REDRAWS, MIN_GAP_FRACTION};

use crate::{ConvexPolygon, DVec2, MAX_VERTICES, PolygonError};
use rand::Rng;
use std::f64::consts::{FRAC_PI_2, TAU};
use thiserror::Error;

/// Why a shape could not be generated: a parameter out of range (named, with the reason), or, for parameters at the
/// edge of their range, an outline too degenerate to validate.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ShapeError {
    /// A real-valued parameter is out of range.
    #[error("{parameter} = {value}: {reason}")]
    InvalidValue {
        /// The parameter's name as in the generator's signature.
        parameter: &'static str,
        /// The value given.
        value: f64,
        /// What the value must satisfy.
        reason: &'static str,
    },
    /// A count (corners) is out of range.
    #[error("{parameter} = {value}: {reason}")]
    InvalidCount {
        /// The parameter's name as in the generator's signature.
        parameter: &'static str,
        /// The value given.
        value: usize,
        /// What the value must satisfy.
        reason: &'static str,
    },
    /// The parameters are in range but so extreme that the outline fails validation (for example a nearly flat
    /// ellipse, or a cut fraction within 10⁻⁹ of ½).
    #[error("the generated outline is not an admissible polygon: {0}")]
    Degenerate(#[from] PolygonError),
}

/// Checks that a length is finite and positive.
fn positive(parameter: &'static str, value: f64) -> Result<f64, ShapeError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ShapeError::InvalidValue { parameter, value, reason: "must be a finite positive length" })
    }
}

/// Checks a polygon's corner count: 3 (the least with an overlap area, §1.1) to [`MAX_VERTICES`].
pub(crate) fn corner_count(parameter: &'static str, value: usize) -> Result<usize, ShapeError> {
    if (3..=MAX_VERTICES).contains(&value) {
        Ok(value)
    } else {
        Err(ShapeError::InvalidCount { parameter, value, reason: "a polygon needs 3 to 64 corners" })
    }
}

/// Validates an outline and drops the centroid offset: the body-frame polygon.
fn body_frame(outline: &[DVec2]) -> Result<ConvexPolygon, ShapeError> {
    Ok(ConvexPolygon::new(outline)?.0)
}

/// A point at angle `phi` on the ellipse with semi-axes `semi_x`, `semi_y` (reference eqs. B.4, B.5).
fn on_ellipse(semi_x: f64, semi_y: f64, phi: f64) -> DVec2 {
    let (sin, cos) = phi.sin_cos();
    DVec2::new(semi_x * cos, semi_y * sin)
}

/// A regular `n`-gon with circumradius `circumradius`, first corner on the +x axis (gc2d's `gc2d_sphere`, §1.8).
pub fn regular_polygon(n: usize, circumradius: f64) -> Result<ConvexPolygon, ShapeError> {
    let n = corner_count("n", n)?;
    let radius = positive("circumradius", circumradius)?;
    let mut outline = [DVec2::ZERO; MAX_VERTICES];
    for (i, vertex) in outline[..n].iter_mut().enumerate() {
        *vertex = on_ellipse(radius, radius, TAU * i as f64 / n as f64);
    }
    body_frame(&outline[..n])
}

/// An `n`-gon inscribed in the ellipse with semi-axes `semi_x`, `semi_y`, its corners at angles chosen by `mode`
/// (reference §1.2: vertices (a cos φ_i, b sin φ_i) for ascending φ_i). The polygon is recentred on its centroid,
/// which for random modes is not the ellipse's centre. `rng` is used only by the random modes.
pub fn ellipse_polygon<R: Rng + ?Sized>(
    n: usize,
    semi_x: f64,
    semi_y: f64,
    mode: AngleMode,
    rng: &mut R,
) -> Result<ConvexPolygon, ShapeError> {
    let n = corner_count("n", n)?;
    let semi_x = positive("semi_x", semi_x)?;
    let semi_y = positive("semi_y", semi_y)?;
    let mut outline = [DVec2::ZERO; MAX_VERTICES];
    ellipse_outline(semi_x, semi_y, mode, rng, &mut outline[..n]);
    body_frame(&outline[..n])
}

/// Fills `outline` (one entry per corner) with corners on the ellipse, centred on the ellipse's centre.
fn ellipse_outline<R: Rng + ?Sized>(semi_x: f64, semi_y: f64, mode: AngleMode, rng: &mut R, outline: &mut [DVec2]) {
    let mut angles = [0.0; MAX_VERTICES];
    let angles = &mut angles[..outline.len()];
    angles::corner_angles(mode, rng, angles);
    for (vertex, &phi) in outline.iter_mut().zip(angles.iter()) {
        *vertex = on_ellipse(semi_x, semi_y, phi);
    }
}

/// A `width` × `height` rectangle, sides along the axes (`gc2d_rectangle`, §1.8).
pub fn rectangle(width: f64, height: f64) -> Result<ConvexPolygon, ShapeError> {
    let x = positive("width", width)? / 2.0;
    let y = positive("height", height)? / 2.0;
    body_frame(&[DVec2::new(-x, -y), DVec2::new(x, -y), DVec2::new(x, y), DVec2::new(-x, y)])
}

/// A square of side `side` (`gc2d_square`, §1.8).
pub fn square(side: f64) -> Result<ConvexPolygon, ShapeError> {
    positive("side", side)?;
    rectangle(side, side)
}

/// A `width` × `height` rectangle whose corners are bevelled into an octagon (`gc2d_rectangle_cut`, §1.8): each corner
/// loses a right triangle with legs `cut`·width along x and `cut`·height along y, so the sides shrink to
/// width·(1 − 2·cut) and height·(1 − 2·cut), each bevel is `cut`·√(width² + height²) long and the area is
/// width·height·(1 − 2·cut²). `cut` must lie strictly between 0 and ½.
pub fn cut_rectangle(width: f64, height: f64, cut: f64) -> Result<ConvexPolygon, ShapeError> {
    let x = positive("width", width)? / 2.0;
    let y = positive("height", height)? / 2.0;
    if !(cut > 0.0 && cut < 0.5) {
        return Err(ShapeError::InvalidValue {
            parameter: "cut",
            value: cut,
            reason: "the cut fraction must lie strictly between 0 and 0.5",
        });
    }
    let (dx, dy) = (cut * width, cut * height);
    body_frame(&[
        DVec2::new(-x + dx, -y),
        DVec2::new(x - dx, -y),
        DVec2::new(x, -y + dy),
        DVec2::new(x, y - dy),
        DVec2::new(x - dx, y),
        DVec2::new(-x + dx, y),
        DVec2::new(-x, y - dy),
        DVec2::new(-x, -y + dy),
    ])
}

/// A square of side `side` with bevelled corners (`gc2d_square_cut`, §1.8); see [`cut_rectangle`].
pub fn square_cut(side: f64, cut: f64) -> Result<ConvexPolygon, ShapeError> {
    positive("side", side)?;
    cut_rectangle(side, side, cut)
}

/// Most corners a rounding may have: four roundings must fit in [`MAX_VERTICES`].
pub const MAX_CORNERS_PER_ROUNDING: usize = MAX_VERTICES / 4;

/// A `width` × `height` rectangle whose corners are quarter circles of radius `radius`, each drawn with
/// `corners_per_rounding` vertices from one tangent point to the other (`gc2d_rectangle_round`, §1.8).
///
/// The straight sides are width − 2r and height − 2r long, the arc chords 2r·sin(π/(4(k − 1))) for k corners, and the
/// area is wh − 4r² + 2(k − 1)r²·sin(π/(2(k − 1))), which tends to wh − (4 − π)r² as k grows. Requires
/// 0 < r < min(width, height)/2 (at r = min/2 the straight sides would vanish) and 2 ≤ k ≤
/// [`MAX_CORNERS_PER_ROUNDING`] (k = 2 is a bevel).
pub fn rounded_rectangle(
    width: f64,
    height: f64,
    radius: f64,
    corners_per_rounding: usize,
) -> Result<ConvexPolygon, ShapeError> {
    let x = positive("width", width)? / 2.0;
    let y = positive("height", height)? / 2.0;
    let r = positive("radius", radius)?;
    if r >= x.min(y) {
        return Err(ShapeError::InvalidValue {
            parameter: "radius",
            value: radius,
            reason: "the rounding radius must be less than half the shorter side",
        });
    }
    let k = corners_per_rounding;
    if !(2..=MAX_CORNERS_PER_ROUNDING).contains(&k) {
        return Err(ShapeError::InvalidCount {
            parameter: "corners_per_rounding",
            value: k,
            reason: "a rounding needs 2 to 16 corners (four roundings share at most 64)",
        });
    }
    let centres =
        [DVec2::new(x - r, -y + r), DVec2::new(x - r, y - r), DVec2::new(-x + r, y - r), DVec2::new(-x + r, -y + r)];
    let step = FRAC_PI_2 / (k - 1) as f64;
    let mut outline = [DVec2::ZERO; MAX_VERTICES];
    for (quarter, centre) in centres.iter().enumerate() {
        let start = (quarter as f64 - 1.0) * FRAC_PI_2;
        for j in 0..k {
            outline[quarter * k + j] = *centre + on_ellipse(r, r, start + j as f64 * step);
        }
    }
    body_frame(&outline[..4 * k])
}

/// A square of side `side` with rounded corners (`gc2d_square_round`, §1.8); see [`rounded_rectangle`].
pub fn square_round(side: f64, radius: f64, corners_per_rounding: usize) -> Result<ConvexPolygon, ShapeError> {
    positive("side", side)?;
    rounded_rectangle(side, side, radius, corners_per_rounding)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;
    use std::f64::consts::PI;

    const ALL_MODES: [AngleMode; 5] =
        [AngleMode::Regular, AngleMode::Rand1, AngleMode::Rand2, AngleMode::Full, AngleMode::SpecialRectangle];

    fn edge_lengths(polygon: &ConvexPolygon) -> Vec<f64> {
        let v = polygon.vertices();
        (0..v.len()).map(|i| (v[(i + 1) % v.len()] - v[i]).length()).collect()
    }

    #[test]
    fn regular_polygon_has_its_corners_on_the_circle_and_the_closed_form_area() {
        for n in [3, 4, 7, 20, 64] {
            let r = 0.0015;
            let polygon = regular_polygon(n, r).unwrap();
            assert_eq!(polygon.len(), n);
            for v in polygon.vertices() {
                assert_relative_eq!(v.length(), r, max_relative = 1e-12);
            }
            assert_relative_eq!(polygon.vertices()[0], DVec2::new(r, 0.0), epsilon = 1e-15);
            let nf = n as f64;
            assert_relative_eq!(polygon.area(), 0.5 * nf * r * r * (TAU / nf).sin(), max_relative = 1e-12);
            for length in edge_lengths(&polygon) {
                assert_relative_eq!(length, 2.0 * r * (PI / nf).sin(), max_relative = 1e-12);
            }
        }
    }

    #[test]
    fn ellipse_corners_lie_on_the_ellipse_in_every_mode() {
        let (a, b) = (0.004, 0.0025);
        for mode in ALL_MODES {
            for n in [3, 5, 8, 13, 64] {
                let mut rng = ChaCha8Rng::seed_from_u64(n as u64);
                let mut outline = vec![DVec2::ZERO; n];
                ellipse_outline(a, b, mode, &mut rng.clone(), &mut outline);
                for v in &outline {
                    assert!((v.x * v.x / (a * a) + v.y * v.y / (b * b) - 1.0).abs() < 1e-12, "{mode:?} {v}");
                }
                // The polygon is the outline moved to its centroid, corners in the same order.
                let polygon = ellipse_polygon(n, a, b, mode, &mut rng).unwrap();
                let (expected, _) = ConvexPolygon::new(&outline).unwrap();
                assert_eq!(polygon, expected);
                for (p, q) in polygon.vertices().iter().zip(&outline) {
                    assert_relative_eq!(*p - polygon.vertices()[0], *q - outline[0], epsilon = 1e-15);
                }
            }
        }
    }

    #[test]
    fn regular_mode_on_a_circle_is_the_regular_polygon() {
        let mut rng = ChaCha8Rng::seed_from_u64(0);
        for n in [3, 6, 11, 64] {
            let from_ellipse = ellipse_polygon(n, 0.01, 0.01, AngleMode::Regular, &mut rng).unwrap();
            let regular = regular_polygon(n, 0.01).unwrap();
            for (p, q) in from_ellipse.vertices().iter().zip(regular.vertices()) {
                assert_relative_eq!(*p, *q, epsilon = 1e-15);
            }
        }
    }

    #[test]
    fn special_rectangle_with_four_corners_is_the_rectangle_on_the_diagonals() {
        let (a, b) = (3.0, 1.0);
        let polygon = ellipse_polygon(4, a, b, AngleMode::SpecialRectangle, &mut ChaCha8Rng::seed_from_u64(0)).unwrap();
        // `rectangle` starts at the lower left corner, SPECIAL_RECTANGLE at the upper right (angle π/4).
        let expected = rectangle(a * 2f64.sqrt(), b * 2f64.sqrt()).unwrap();
        for (i, p) in polygon.vertices().iter().enumerate() {
            assert_relative_eq!(*p, expected.vertices()[(i + 2) % 4], epsilon = 1e-14);
        }
    }

    #[test]
    fn hundred_thousand_random_draws_all_validate() {
        let mut rng = ChaCha8Rng::seed_from_u64(2024);
        let mut failures = Vec::new();
        for draw in 0..100_000 {
            let n = 3 + draw % (MAX_VERTICES - 2);
            let mode = ALL_MODES[(draw / (MAX_VERTICES - 2)) % ALL_MODES.len()];
            // Axis ratios from 1:20 to 20:1.
            let semi_x = 0.001 * (1.0 + rng.random::<f64>());
            let semi_y = semi_x * 20f64.powf(2.0 * rng.random::<f64>() - 1.0);
            if let Err(error) = ellipse_polygon(n, semi_x, semi_y, mode, &mut rng) {
                failures.push((draw, n, mode, error));
            }
        }
        assert!(failures.is_empty(), "{} failures, first {:?}", failures.len(), failures.first());
    }

    #[test]
    fn cut_rectangle_has_the_stated_edges_and_area() {
        let (w, h, c) = (0.3, 0.1, 0.2);
        let polygon = cut_rectangle(w, h, c).unwrap();
        let bevel = c * (w * w + h * h).sqrt();
        let expected = [w * (1.0 - 2.0 * c), bevel, h * (1.0 - 2.0 * c), bevel];
        for (i, length) in edge_lengths(&polygon).iter().enumerate() {
            assert_relative_eq!(*length, expected[i % 4], max_relative = 1e-12);
        }
        assert_relative_eq!(polygon.area(), w * h * (1.0 - 2.0 * c * c), max_relative = 1e-12);
        let bounds = crate::Aabb::of_points(polygon.vertices());
        assert_relative_eq!(bounds.max - bounds.min, DVec2::new(w, h), max_relative = 1e-12);
        let square = square_cut(0.2, 0.25).unwrap();
        assert_relative_eq!(square.area(), 0.04 * (1.0 - 2.0 * 0.0625), max_relative = 1e-12);
    }

    #[test]
    fn rounded_rectangle_has_the_stated_edges_and_area() {
        let (w, h, r) = (0.5, 0.2, 0.05);
        for k in [2, 3, 5, 16] {
            let polygon = rounded_rectangle(w, h, r, k).unwrap();
            assert_eq!(polygon.len(), 4 * k);
            let step = FRAC_PI_2 / (k - 1) as f64;
            let chord = 2.0 * r * (step / 2.0).sin();
            let lengths = edge_lengths(&polygon);
            for quarter in 0..4 {
                let straight = if quarter % 2 == 0 { h - 2.0 * r } else { w - 2.0 * r };
                for j in 0..k - 1 {
                    assert_relative_eq!(lengths[quarter * k + j], chord, max_relative = 1e-12);
                }
                assert_relative_eq!(lengths[quarter * k + k - 1], straight, max_relative = 1e-12);
            }
            let area = w * h - 4.0 * r * r + 2.0 * (k - 1) as f64 * r * r * step.sin();
            assert_relative_eq!(polygon.area(), area, max_relative = 1e-12);
        }
        // The polygonal arcs approach the quarter circles: with m = k − 1 the area deficit against wh − (4 − π)r² is
        // r²(π − 2m·sin(π/(2m))) ≈ π³r²/(24m²), shrinking about fourfold per doubling of m.
        let limit = w * h - (4.0 - PI) * r * r;
        let errors: Vec<f64> =
            [2, 4, 8, 16].iter().map(|&k| limit - rounded_rectangle(w, h, r, k).unwrap().area()).collect();
        assert!(errors.windows(2).all(|e| e[1] > 0.0 && e[1] < e[0] / 3.5), "{errors:?}");
        assert_relative_eq!(errors[3], PI.powi(3) * r * r / (24.0 * 225.0), max_relative = 0.01);
        let square = square_round(0.2, 0.05, 2).unwrap();
        assert_relative_eq!(square.area(), 0.04 - 2.0 * 0.0025, max_relative = 1e-12);
    }

    #[test]
    fn bad_parameters_are_named() {
        let mut rng = ChaCha8Rng::seed_from_u64(0);
        let named = |result: Result<ConvexPolygon, ShapeError>| match result.unwrap_err() {
            ShapeError::InvalidValue { parameter, .. } | ShapeError::InvalidCount { parameter, .. } => parameter,
            ShapeError::Degenerate(error) => panic!("unexpected {error}"),
        };
        assert_eq!(named(regular_polygon(2, 1.0)), "n");
        assert_eq!(named(regular_polygon(65, 1.0)), "n");
        assert_eq!(named(regular_polygon(5, 0.0)), "circumradius");
        assert_eq!(named(ellipse_polygon(5, f64::NAN, 1.0, AngleMode::Full, &mut rng)), "semi_x");
        assert_eq!(named(ellipse_polygon(5, 1.0, -1.0, AngleMode::Full, &mut rng)), "semi_y");
        assert_eq!(named(rectangle(f64::INFINITY, 1.0)), "width");
        assert_eq!(named(square(-1.0)), "side");
        assert_eq!(named(cut_rectangle(1.0, 0.0, 0.2)), "height");
        assert_eq!(named(cut_rectangle(1.0, 1.0, 0.5)), "cut");
        assert_eq!(named(cut_rectangle(1.0, 1.0, 0.0)), "cut");
        assert_eq!(named(square_cut(1.0, f64::NAN)), "cut");
        assert_eq!(named(rounded_rectangle(1.0, 0.4, 0.2, 4)), "radius");
        assert_eq!(named(rounded_rectangle(1.0, 0.4, 0.1, 1)), "corners_per_rounding");
        assert_eq!(named(square_round(1.0, 0.1, 17)), "corners_per_rounding");
        let message = cut_rectangle(1.0, 1.0, 0.7).unwrap_err().to_string();
        assert_eq!(message, "cut = 0.7: the cut fraction must lie strictly between 0 and 0.5");
        // In range but too close to the edge for the outline to validate.
        assert!(matches!(cut_rectangle(1.0, 1.0, 0.5 - 1e-13), Err(ShapeError::Degenerate(_))));
    }
}
