//! Scene shapes to geometry: outlines through gc2d-geometry's generators, recipes to `ShapeRecipe`, and their errors
//! named by field path.

use crate::error::SceneError;
use crate::schema::{CornerPositions, CountSpread, Orientation, Recipe, Shape, SizeSpread};
use crate::spans::field_path;
use gc2d_engine::{BodyShape, DiskRecipe, ParticleRecipe};
use gc2d_geometry::{
    AngleMode, ConvexPolygon, DVec2, PolygonError, Randomization, ShapeError, ShapeRecipe, cut_rectangle,
    ellipse_polygon, rectangle, regular_polygon, rounded_rectangle, square, square_cut, square_round,
};
use rand_chacha::ChaCha8Rng;

/// A body-frame shape and how it sits as written.
pub(crate) struct Outline {
    /// The shape, centroid at the origin.
    pub shape: BodyShape,
    /// Where the written corners put the centroid: their centroid for `Polygon`, the origin for macro shapes.
    pub written_centroid: DVec2,
    /// Orientation drawn by a `Random` shape (0 for the others), radians CCW.
    pub drawn_angle: f64,
}

/// Makes the outline of `shape` at field path `path` (`rng` draws `Random` shapes).
pub(crate) fn outline(shape: &Shape, path: &str, rng: &mut ChaCha8Rng) -> Result<Outline, SceneError> {
    let fixed = |result: Result<ConvexPolygon, ShapeError>| {
        result
            .map(|polygon| Outline { shape: polygon.into(), written_centroid: DVec2::ZERO, drawn_angle: 0.0 })
            .map_err(|e| shape_error(&e, path))
    };
    match shape {
        Shape::Polygon { corners_m } => {
            let corners: Vec<DVec2> = corners_m.iter().map(|c| DVec2::from_array(*c)).collect();
            let (polygon, written_centroid) =
                ConvexPolygon::new(&corners).map_err(|e| polygon_error(&e, &field_path(path, "corners_m")))?;
            Ok(Outline { shape: polygon.into(), written_centroid, drawn_angle: 0.0 })
        }
        Shape::Regular { corners, radius_m } => fixed(regular_polygon(*corners, *radius_m)),
        Shape::Ellipse { corners, semi_axes_m } => {
            fixed(ellipse_polygon(*corners, semi_axes_m[0], semi_axes_m[1], AngleMode::Regular, rng))
        }
        Shape::Rectangle { width_m, height_m } => fixed(rectangle(*width_m, *height_m)),
        Shape::CutRectangle { width_m, height_m, cut } => fixed(cut_rectangle(*width_m, *height_m, *cut)),
        Shape::RoundRectangle { width_m, height_m, radius_m, corners_per_rounding } => {
            fixed(rounded_rectangle(*width_m, *height_m, *radius_m, *corners_per_rounding))
        }
        Shape::Square { side_m } => fixed(square(*side_m)),
        Shape::CutSquare { side_m, cut } => fixed(square_cut(*side_m, *cut)),
        Shape::RoundSquare { side_m, radius_m, corners_per_rounding } => {
            fixed(square_round(*side_m, *radius_m, *corners_per_rounding))
        }
        Shape::Random { recipe } => {
            let recipe = shape_recipe(recipe, path)?;
            let (polygon, angle) = recipe.draw(rng).map_err(|e| shape_error(&e, path))?;
            Ok(Outline { shape: polygon.into(), written_centroid: DVec2::ZERO, drawn_angle: angle })
        }
        Shape::Disk { radius_m } => round(BodyShape::Disk { radius: *radius_m }, "radius_m", path),
        Shape::Capsule { length_m, radius_m } => {
            if !(*length_m >= 0.0 && length_m.is_finite()) {
                return Err(SceneError::value(
                    field_path(path, "length_m"),
                    format!("{length_m}: a capsule's length must be a finite number ≥ 0 (m)"),
                ));
            }
            round(BodyShape::Capsule { half_length: 0.5 * length_m, radius: *radius_m }, "radius_m", path)
        }
        Shape::InnerCircle { radius_m } => round(BodyShape::InnerCircle { radius: *radius_m }, "radius_m", path),
    }
}

/// The outline of a particle's `shape` at `path`: any shape but the wall-only capsule and inner circle.
pub(crate) fn particle_outline(shape: &Shape, path: &str, rng: &mut ChaCha8Rng) -> Result<Outline, SceneError> {
    let outline = outline(shape, path, rng)?;
    outline.shape.validate(true).map_err(|e| {
        SceneError::value(path, e.to_string())
            .with_help("particles are polygons or disks; capsules and inner circles are walls")
            .with_label("a wall shape")
    })?;
    Ok(outline)
}

/// A disk, capsule or inner circle whose radius is the field `radius_field` of the shape at `path`, checked.
fn round(shape: BodyShape, radius_field: &str, path: &str) -> Result<Outline, SceneError> {
    if !(shape.radius() > 0.0 && shape.radius().is_finite()) {
        return Err(SceneError::value(
            field_path(path, radius_field),
            format!("{}: a radius must be a positive finite number (m)", shape.radius()),
        ));
    }
    Ok(Outline { shape, written_centroid: DVec2::ZERO, drawn_angle: 0.0 })
}

/// The geometry crate's recipe for a scene recipe at `path`, validated.
pub(crate) fn shape_recipe(recipe: &Recipe, path: &str) -> Result<ShapeRecipe, SceneError> {
    let (size_randomization, size_variation) = match recipe.size_spread {
        SizeSpread::Const => (Randomization::Const, 0.0),
        SizeSpread::Equal(i) => (Randomization::Equal, i),
        SizeSpread::Gauss(i) => (Randomization::Gauss, i),
    };
    let (corner_randomization, corner_variation) = match recipe.corner_spread {
        CountSpread::Const => (Randomization::Const, 0),
        CountSpread::Equal(n) => (Randomization::Equal, n),
        CountSpread::Gauss(n) => (Randomization::Gauss, n),
    };
    let (rotation_randomization, rotation) = match recipe.orientation {
        Orientation::Const(angle) => (Randomization::Const, angle),
        Orientation::Equal => (Randomization::Equal, 0.0),
        Orientation::Gauss(angle) => (Randomization::Gauss, angle),
    };
    let angle_mode = match recipe.corner_positions {
        CornerPositions::Regular => AngleMode::Regular,
        CornerPositions::Rand1 => AngleMode::Rand1,
        CornerPositions::Rand2 => AngleMode::Rand2,
        CornerPositions::Full => AngleMode::Full,
        CornerPositions::SpecialRectangle => AngleMode::SpecialRectangle,
    };
    let shape_recipe = ShapeRecipe {
        semi_axes: DVec2::from_array(recipe.semi_axes_m),
        size_variation,
        size_randomization,
        corners: recipe.corners,
        corner_variation,
        corner_randomization,
        angle_mode,
        rotation,
        rotation_randomization,
    };
    shape_recipe.validate().map_err(|e| shape_error(&e, path))?;
    Ok(shape_recipe)
}

/// What a block or source draws from the scene recipe at `path`: a disk recipe when it says `disk: true` (equal
/// semi-axes, the corner and orientation fields at their defaults), else the polygon recipe, validated.
pub(crate) fn particle_recipe(recipe: &Recipe, path: &str) -> Result<ParticleRecipe, SceneError> {
    if !recipe.disk {
        return shape_recipe(recipe, path).map(ParticleRecipe::Polygon);
    }
    let [a, b] = recipe.semi_axes_m;
    if a != b {
        return Err(SceneError::value(
            field_path(path, "semi_axes_m"),
            format!("({a}, {b}): a disk recipe needs equal semi-axes, its radius"),
        )
        .with_help("write the radius twice, e.g. `semi_axes_m: (0.0025, 0.0025)`"));
    }
    let defaults = Recipe::new(recipe.semi_axes_m);
    let polygon_only = [
        ("corners", recipe.corners != defaults.corners),
        ("corner_spread", recipe.corner_spread != defaults.corner_spread),
        ("corner_positions", recipe.corner_positions != defaults.corner_positions),
        ("orientation", recipe.orientation != defaults.orientation),
    ];
    if let Some((field, _)) = polygon_only.iter().find(|(_, set)| *set) {
        return Err(SceneError::value(field_path(path, field), format!("`{field}` does not apply to disks"))
            .with_help("remove it, or set `disk: false` to draw polygons"));
    }
    let polygon = shape_recipe(&Recipe { disk: false, ..*recipe }, path)?;
    let disk = ParticleRecipe::Disk(DiskRecipe {
        radius: a,
        size_randomization: polygon.size_randomization,
        size_variation: polygon.size_variation,
    });
    disk.validate().map_err(|e| shape_error(&e, path))?;
    Ok(disk)
}

/// A generator's error at the field it names.
fn shape_error(error: &ShapeError, path: &str) -> SceneError {
    match error {
        ShapeError::InvalidValue { parameter, value, reason } => {
            SceneError::value(field_path(path, field_name(parameter)), format!("{value} is not allowed: {reason}"))
        }
        ShapeError::InvalidCount { parameter, value, reason } => {
            SceneError::value(field_path(path, field_name(parameter)), format!("{value} is not allowed: {reason}"))
        }
        ShapeError::Degenerate(polygon) => SceneError::value(path, format!("the shape is degenerate: {polygon}"))
            .with_help("parameters this extreme give an outline with coinciding or collinear corners"),
    }
}

/// The scene field that carries a generator parameter.
fn field_name(parameter: &str) -> &str {
    match parameter {
        "n" => "corners",
        "circumradius" | "radius" => "radius_m",
        "semi_x" | "semi_y" | "semi_axes.x" | "semi_axes.y" => "semi_axes_m",
        "width" => "width_m",
        "height" => "height_m",
        "side" => "side_m",
        "size_variation" => "size_spread",
        "corner_variation" => "corner_spread",
        "rotation" => "orientation",
        other => other,
    }
}

/// A polygon validation error at the corner it names (`corners_path[i]`), or at the corner list.
pub(crate) fn polygon_error(error: &PolygonError, corners_path: &str) -> SceneError {
    let at = |i: usize| format!("{corners_path}[{i}]");
    let path = match error {
        PolygonError::NotFinite(i) | PolygonError::Collinear(i) | PolygonError::NotConvex(i) => at(*i),
        PolygonError::ZeroLengthEdge(_, j) => at(*j),
        PolygonError::TooFewVertices(_) | PolygonError::TooManyVertices(_) | PolygonError::SelfIntersecting => {
            corners_path.to_owned()
        }
    };
    let help = match error {
        PolygonError::NotConvex(_) => "particles and walls must be convex; split a concave outline into convex walls",
        PolygonError::Collinear(_) | PolygonError::ZeroLengthEdge(..) => "remove the redundant corner",
        _ => "a polygon has 3 to 64 distinct corners, in order around its outline",
    };
    SceneError::value(path, error.to_string()).with_help(help)
}
