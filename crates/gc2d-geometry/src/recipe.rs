//! The particle-shape parameters shared by gsi's GENERATE_BLOCK and DROPSOURCE objects (reference §9.7, §9.8,
//! App. B.1.6) and the draw of one particle from them.

use crate::randomize::Randomization;
use crate::shapes::{AngleMode, ShapeError, corner_count, ellipse_polygon};
use crate::{ConvexPolygon, DVec2, MAX_VERTICES};
use rand::Rng;
use serde::{Deserialize, Serialize};

/// How to make one randomly varied particle: an ellipse-inscribed polygon with scattered size, corner count, corner
/// positions and orientation (reference §1.2). Field names follow the gsi commands in their doc comments.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ShapeRecipe {
    /// `PART_SIZE` (l_x, l_y): the nominal ellipse **semi-axes** in m (the thesis's particle "radius").
    pub semi_axes: DVec2,
    /// `PART_VAR_SIZE` I: relative size spread; each semi-axis is drawn in [l(1 − I), l(1 + I)]. Ignored for `Const`.
    pub size_variation: f64,
    /// `RANDOM_SIZE`: how the two semi-axes are drawn (independently of each other, so the aspect ratio varies too).
    pub size_randomization: Randomization,
    /// `PART_NUM_CORNERS` N_E: the nominal corner count.
    pub corners: usize,
    /// `PART_VAR_CORNERS` N_I: the corner count is drawn in [N_E − N_I, N_E + N_I]. Ignored for `Const`.
    pub corner_variation: usize,
    /// `RANDOM_NUM_CORNERS` (also spelled `PART_RANDOM_NUM_CORNERS`): how the corner count is drawn.
    pub corner_randomization: Randomization,
    /// `PART_RANDOM_POS_CORNERS` (also spelled `RANDOM_POS_CORNERS`): where the corners sit on the ellipse.
    pub angle_mode: AngleMode,
    /// `PART_ROT` φ₀ in radians, **counter-clockwise** (the gsi importer converts gc2d's clockwise angle).
    pub rotation: f64,
    /// `RANDOM_ROT`: how the orientation is drawn around φ₀.
    pub rotation_randomization: Randomization,
}

impl ShapeRecipe {
    /// Checks that every draw from this recipe has admissible parameters: finite positive semi-axes; a size spread
    /// in [0, 1) when sizes vary (so no axis can reach zero); corner counts that stay within 3 to 64 over the whole
    /// drawn range; a finite nominal rotation.
    pub fn validate(&self) -> Result<(), ShapeError> {
        for (parameter, value) in [("semi_axes.x", self.semi_axes.x), ("semi_axes.y", self.semi_axes.y)] {
            if !(value.is_finite() && value > 0.0) {
                return Err(ShapeError::InvalidValue { parameter, value, reason: "must be a finite positive length" });
            }
        }
        if self.size_randomization != Randomization::Const && !(0.0..1.0).contains(&self.size_variation) {
            return Err(ShapeError::InvalidValue {
                parameter: "size_variation",
                value: self.size_variation,
                reason: "the relative size spread must lie in [0, 1)",
            });
        }
        corner_count("corners", self.corners)?;
        if self.corner_randomization != Randomization::Const
            && (self.corners < 3 + self.corner_variation || self.corners + self.corner_variation > MAX_VERTICES)
        {
            return Err(ShapeError::InvalidCount {
                parameter: "corner_variation",
                value: self.corner_variation,
                reason: "corners ± corner_variation must stay within 3 to 64",
            });
        }
        if !self.rotation.is_finite() {
            return Err(ShapeError::InvalidValue {
                parameter: "rotation",
                value: self.rotation,
                reason: "must be a finite angle",
            });
        }
        Ok(())
    }

    /// Draws one particle: its body-frame polygon and its orientation (radians, CCW) for the caller's [`crate::Pose`].
    ///
    /// The draws are made in a fixed order so that a seed reproduces a scene: semi-axis x, semi-axis y, corner count,
    /// corner angles, orientation. `Const` options draw nothing.
    pub fn draw<R: Rng + ?Sized>(&self, rng: &mut R) -> Result<(ConvexPolygon, f64), ShapeError> {
        self.validate()?;
        let semi_x = self.size_randomization.draw_size(self.semi_axes.x, self.size_variation, rng);
        let semi_y = self.size_randomization.draw_size(self.semi_axes.y, self.size_variation, rng);
        let corners = self.corner_randomization.draw_count(self.corners, self.corner_variation, rng);
        let polygon = ellipse_polygon(corners, semi_x, semi_y, self.angle_mode, rng)?;
        let angle = self.rotation_randomization.draw_rotation(self.rotation, rng);
        Ok((polygon, angle))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    /// The B.1.6 example's particles: semi-axes 3 mm, ±20 % sizes, 6 ± 2 corners on RAND1 positions.
    fn varied() -> ShapeRecipe {
        ShapeRecipe {
            semi_axes: DVec2::splat(0.003),
            size_variation: 0.2,
            size_randomization: Randomization::Equal,
            corners: 6,
            corner_variation: 2,
            corner_randomization: Randomization::Equal,
            angle_mode: AngleMode::Rand1,
            rotation: 0.3,
            rotation_randomization: Randomization::Gauss,
        }
    }

    #[test]
    fn const_recipe_gives_the_nominal_ellipse_polygon_and_angle() {
        let recipe = ShapeRecipe {
            size_randomization: Randomization::Const,
            corner_randomization: Randomization::Const,
            angle_mode: AngleMode::Regular,
            rotation_randomization: Randomization::Const,
            semi_axes: DVec2::new(0.002, 0.001),
            ..varied()
        };
        let (polygon, angle) = recipe.draw(&mut ChaCha8Rng::seed_from_u64(0)).unwrap();
        let expected = ellipse_polygon(6, 0.002, 0.001, AngleMode::Regular, &mut ChaCha8Rng::seed_from_u64(1)).unwrap();
        assert_eq!(polygon, expected);
        assert_eq!(angle, 0.3);
    }

    #[test]
    fn equal_sizes_vary_each_semi_axis_independently_within_range() {
        // With REGULAR and 4 corners the polygon is the rhombus (±a, 0), (0, ±b): its half-extents are the axes.
        let recipe = ShapeRecipe {
            corner_randomization: Randomization::Const,
            corners: 4,
            angle_mode: AngleMode::Regular,
            size_variation: 0.5,
            ..varied()
        };
        let mut rng = ChaCha8Rng::seed_from_u64(21);
        let draws = 20_000;
        let axes: Vec<DVec2> = (0..draws)
            .map(|_| {
                let (polygon, _) = recipe.draw(&mut rng).unwrap();
                let bounds = crate::Aabb::of_points(polygon.vertices());
                (bounds.max - bounds.min) / 2.0
            })
            .collect();
        let (low, high) = (0.0015, 0.0045);
        assert!(axes.iter().all(|a| a.min_element() >= low * (1.0 - 1e-12) && a.max_element() <= high * (1.0 + 1e-12)));
        let mean = axes.iter().copied().sum::<DVec2>() / draws as f64;
        let centred: Vec<DVec2> = axes.iter().map(|a| *a - mean).collect();
        let var = centred.iter().map(|c| *c * *c).sum::<DVec2>() / draws as f64;
        let covariance = centred.iter().map(|c| c.x * c.y).sum::<f64>() / draws as f64;
        // Uniform on [low, high]: mean 0.003, variance (high − low)²/12; independent axes: correlation ≈ 0 (σ ≈ 0.007).
        assert!((mean - DVec2::splat(0.003)).abs().max_element() < 2e-5, "{mean}");
        let uniform_var = (high - low) * (high - low) / 12.0;
        assert!(((var / uniform_var) - DVec2::ONE).abs().max_element() < 0.03, "{var}");
        assert!((covariance / (var.x * var.y).sqrt()).abs() < 0.03);
    }

    #[test]
    fn drawn_corner_counts_and_angles_stay_in_range() {
        let recipe = varied();
        let mut rng = ChaCha8Rng::seed_from_u64(22);
        let mut seen = [false; MAX_VERTICES + 1];
        for _ in 0..5_000 {
            let (polygon, angle) = recipe.draw(&mut rng).unwrap();
            assert!((4..=8).contains(&polygon.len()));
            seen[polygon.len()] = true;
            assert!((angle - 0.3).abs() < std::f64::consts::FRAC_PI_2);
            assert!(polygon.bounding_radius() <= 0.0036 * 2.0);
        }
        assert!(seen[4..=8].iter().all(|s| *s));
    }

    #[test]
    fn same_seed_gives_identical_shapes_and_another_seed_does_not() {
        let recipe = ShapeRecipe { size_randomization: Randomization::Gauss, angle_mode: AngleMode::Full, ..varied() };
        let draw_all = |seed| {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            (0..200).map(|_| recipe.draw(&mut rng).unwrap()).collect::<Vec<_>>()
        };
        assert_eq!(draw_all(5), draw_all(5));
        assert_ne!(draw_all(5), draw_all(6));
    }

    #[test]
    fn inadmissible_recipes_are_named() {
        let parameter = |recipe: ShapeRecipe| match recipe.validate().unwrap_err() {
            ShapeError::InvalidValue { parameter, .. } | ShapeError::InvalidCount { parameter, .. } => parameter,
            ShapeError::Degenerate(error) => panic!("unexpected {error}"),
        };
        assert_eq!(parameter(ShapeRecipe { semi_axes: DVec2::new(0.0, 1.0), ..varied() }), "semi_axes.x");
        assert_eq!(parameter(ShapeRecipe { semi_axes: DVec2::new(1.0, f64::NAN), ..varied() }), "semi_axes.y");
        assert_eq!(parameter(ShapeRecipe { size_variation: 1.0, ..varied() }), "size_variation");
        assert_eq!(parameter(ShapeRecipe { corners: 2, corner_variation: 0, ..varied() }), "corners");
        assert_eq!(parameter(ShapeRecipe { corners: 4, corner_variation: 2, ..varied() }), "corner_variation");
        assert_eq!(parameter(ShapeRecipe { corners: 63, corner_variation: 2, ..varied() }), "corner_variation");
        assert_eq!(parameter(ShapeRecipe { rotation: f64::INFINITY, ..varied() }), "rotation");
        // Spreads are ignored where the option is CONST, as in gc2d.
        let constant = ShapeRecipe {
            size_variation: 7.0,
            size_randomization: Randomization::Const,
            corners: 3,
            corner_variation: 9,
            corner_randomization: Randomization::Const,
            ..varied()
        };
        assert_eq!(constant.validate(), Ok(()));
        assert!(varied().draw(&mut ChaCha8Rng::seed_from_u64(0)).is_ok());
    }
}
