//! Walls to engine walls: single walls with their motion, and the wall-builder macros expanded into convex polygons
//! (drum after `gc2d_drum`, D.7; funnel; silo; box).

use super::shapes::{outline, polygon_error};
use crate::checks::{finite, finite_pair, non_negative, ordered_range, positive, window};
use crate::error::SceneError;
use crate::schema::{Motion, Shape, WallItem, Waveform};
use crate::spans::field_path;
use gc2d_engine::motion::{Piston, Rotation, Vibration, Waveform as EngineWaveform};
use gc2d_engine::{BodyShape, TimeWindow, WallMotion};
use gc2d_geometry::{ConvexPolygon, DVec2, Pose};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{FRAC_PI_2, TAU};

/// Most segments a drum may have.
pub const MAX_DRUM_SEGMENTS: usize = 10_000;

/// One wall polygon ready for `World::add_wall`.
pub(crate) struct PlacedWall {
    pub shape: BodyShape,
    pub pose: Pose,
    pub surface_velocity: DVec2,
    pub motion: WallMotion,
    /// The material's name (`None`: the first material).
    pub material: Option<String>,
    /// The field path of the scene entry it came from.
    pub path: String,
}

/// The wall polygons of one `walls` entry at `path`.
pub(crate) fn expand(item: &WallItem, path: &str, rng: &mut ChaCha8Rng) -> Result<Vec<PlacedWall>, SceneError> {
    let mut walls = match item {
        WallItem::Wall { shape, position_m, angle_rad, surface_velocity_m_s, motion, .. } => {
            let placement =
                Placement { position: *position_m, angle: *angle_rad, surface_velocity: *surface_velocity_m_s };
            Ok(vec![single(shape, &placement, motion, path, rng)?])
        }
        WallItem::Drum { centre_m, inner_radius_m, thickness_m, surface_speed_m_s, segments, .. } => {
            drum_walls(*centre_m, *inner_radius_m, *thickness_m, *surface_speed_m_s, *segments, path)
        }
        WallItem::Funnel { outlet_m, opening_m, slope_rad, length_m, thickness_m, .. } => {
            funnel_walls(*outlet_m, *opening_m, *slope_rad, *length_m, *thickness_m, path)
        }
        WallItem::Silo { x_range_m, y_range_m, thickness_m, .. } => {
            box_walls(*x_range_m, *y_range_m, *thickness_m, false, path)
        }
        WallItem::Enclosure { x_range_m, y_range_m, thickness_m, .. } => {
            box_walls(*x_range_m, *y_range_m, *thickness_m, true, path)
        }
    }?;
    for wall in &mut walls {
        wall.material = item.material().map(str::to_owned);
    }
    Ok(walls)
}

/// Where a single wall sits and how its surface moves.
struct Placement {
    position: Option<[f64; 2]>,
    angle: f64,
    surface_velocity: [f64; 2],
}

fn single(
    shape: &Shape,
    placement: &Placement,
    motion_spec: &Motion,
    path: &str,
    rng: &mut ChaCha8Rng,
) -> Result<PlacedWall, SceneError> {
    if matches!(shape, Shape::Random { .. }) {
        return Err(SceneError::value(field_path(path, "shape"), "a wall cannot have a random shape")
            .with_help("draw random shapes for particles only; give walls explicit corners or a shape macro"));
    }
    let outline = outline(shape, &field_path(path, "shape"), rng)?;
    if let Some(position) = placement.position {
        finite_pair(&field_path(path, "position_m"), position)?;
    }
    finite(&field_path(path, "angle_rad"), placement.angle)?;
    finite_pair(&field_path(path, "surface_velocity_m_s"), placement.surface_velocity)?;
    let position = placement.position.map_or(outline.written_centroid, DVec2::from_array);
    Ok(PlacedWall {
        shape: outline.shape,
        pose: Pose::new(position, placement.angle),
        surface_velocity: DVec2::from_array(placement.surface_velocity),
        motion: motion(motion_spec, &field_path(path, "motion"))?,
        material: None,
        path: path.to_owned(),
    })
}

/// The engine motion of a wall, its parameters checked.
fn motion(motion: &Motion, path: &str) -> Result<WallMotion, SceneError> {
    let at = |field: &str| field_path(path, field);
    Ok(match *motion {
        Motion::Static => WallMotion::Static,
        Motion::Vibration { amplitude_m, frequency_hz, direction_rad, waveform, window_s } => {
            finite(&at("amplitude_m"), amplitude_m)?;
            positive(&at("frequency_hz"), frequency_hz)?;
            finite(&at("direction_rad"), direction_rad)?;
            window(&at("window_s"), window_s)?;
            WallMotion::Vibrating(Vibration {
                direction_angle: direction_rad,
                window: TimeWindow::new(window_s[0], window_s[1]),
                amplitude: amplitude_m,
                frequency: frequency_hz,
                waveform: match waveform {
                    Waveform::Cosine => EngineWaveform::Cosine,
                    Waveform::Sawtooth => EngineWaveform::Sawtooth,
                    Waveform::Tapping => EngineWaveform::Tapping,
                    Waveform::Triangle => EngineWaveform::Triangle,
                },
            })
        }
        Motion::Rotation { pivot_m, angular_velocity_rad_s, window_s, spin_up_s } => {
            finite_pair(&at("pivot_m"), pivot_m)?;
            finite(&at("angular_velocity_rad_s"), angular_velocity_rad_s)?;
            window(&at("window_s"), window_s)?;
            finite(&at("window_s"), window_s[0])?;
            non_negative(&at("spin_up_s"), spin_up_s)?;
            WallMotion::Rotating(Rotation {
                pivot: DVec2::from_array(pivot_m),
                angular_velocity: angular_velocity_rad_s,
                window: TimeWindow::new(window_s[0], window_s[1]),
                spin_up: spin_up_s,
            })
        }
        Motion::Piston { direction_rad, force_n, max_speed_m_s } => {
            finite(&at("direction_rad"), direction_rad)?;
            finite(&at("force_n"), force_n)?;
            positive(&at("max_speed_m_s"), max_speed_m_s)?;
            WallMotion::Piston(Piston::new(direction_rad, force_n, max_speed_m_s))
        }
    })
}

/// A static wall from absolute corners; `corners_path` names the scene entry for errors.
fn fixed_wall(corners: &[DVec2], surface_velocity: DVec2, path: &str) -> Result<PlacedWall, SceneError> {
    let (polygon, centroid) = ConvexPolygon::new(corners).map_err(|e| {
        let error = polygon_error(&e, path);
        SceneError::value(path, format!("a generated wall is degenerate: {}", error.message()))
            .with_help("the dimensions are too extreme for a wall polygon")
    })?;
    Ok(PlacedWall {
        shape: polygon.into(),
        pose: Pose::new(centroid, 0.0),
        surface_velocity,
        motion: WallMotion::Static,
        material: None,
        path: path.to_owned(),
    })
}

/// `segments` trapezoids between radius r and r + d; each carries the surface velocity v·t̂ with t̂ the CCW tangent
/// at its middle angle, which is tangential to its inner face.
fn drum_walls(
    centre: [f64; 2],
    inner_radius: f64,
    thickness: f64,
    surface_speed: f64,
    segments: usize,
    path: &str,
) -> Result<Vec<PlacedWall>, SceneError> {
    let at = |field: &str| field_path(path, field);
    finite_pair(&at("centre_m"), centre)?;
    positive(&at("inner_radius_m"), inner_radius)?;
    positive(&at("thickness_m"), thickness)?;
    finite(&at("surface_speed_m_s"), surface_speed)?;
    if !(3..=MAX_DRUM_SEGMENTS).contains(&segments) {
        return Err(SceneError::value(
            at("segments"),
            format!("{segments} segments: a drum needs 3 to {MAX_DRUM_SEGMENTS}"),
        ));
    }
    let centre = DVec2::from_array(centre);
    let (inner, outer) = (inner_radius, inner_radius + thickness);
    let n = segments as f64;
    (0..segments)
        .map(|k| {
            let (a0, a1) = (TAU * k as f64 / n, TAU * (k + 1) as f64 / n);
            let (u0, u1) = (DVec2::from_angle(a0), DVec2::from_angle(a1));
            let corners = [centre + inner * u0, centre + outer * u0, centre + outer * u1, centre + inner * u1];
            let tangent = DVec2::from_angle(0.5 * (a0 + a1) + FRAC_PI_2);
            fixed_wall(&corners, surface_speed * tangent, path)
        })
        .collect()
}

/// Two slabs rising at `slope` from the edges of the opening, thickness added outside the funnel.
fn funnel_walls(
    outlet: [f64; 2],
    opening: f64,
    slope: f64,
    length: f64,
    thickness: f64,
    path: &str,
) -> Result<Vec<PlacedWall>, SceneError> {
    let at = |field: &str| field_path(path, field);
    finite_pair(&at("outlet_m"), outlet)?;
    if !(opening >= 0.0 && opening.is_finite()) {
        return Err(SceneError::value(at("opening_m"), format!("{opening}: the opening must be ≥ 0 m")));
    }
    if !(slope > 0.0 && slope <= FRAC_PI_2) {
        return Err(SceneError::value(
            at("slope_rad"),
            format!("{slope}: the slope must lie in (0, π/2] (radians from the horizontal)"),
        ));
    }
    positive(&at("length_m"), length)?;
    positive(&at("thickness_m"), thickness)?;
    let outlet = DVec2::from_array(outlet);
    let (sin, cos) = slope.sin_cos();
    let half = 0.5 * opening;
    let (l, t) = (length, thickness);
    let side = |sign: f64| {
        let start = outlet + DVec2::new(sign * half, 0.0);
        let along = DVec2::new(sign * cos, sin);
        let outward = DVec2::new(sign * sin, -cos);
        let corners = [start, start + l * along, start + l * along + t * outward, start + t * outward];
        fixed_wall(&corners, DVec2::ZERO, path)
    };
    Ok(vec![side(-1.0)?, side(1.0)?])
}

/// Floor and side walls around the inner rectangle, and a lid if `closed`.
fn box_walls(
    x: [f64; 2],
    y: [f64; 2],
    thickness: f64,
    closed: bool,
    path: &str,
) -> Result<Vec<PlacedWall>, SceneError> {
    let at = |field: &str| field_path(path, field);
    ordered_range(&at("x_range_m"), x, true)?;
    ordered_range(&at("y_range_m"), y, true)?;
    positive(&at("thickness_m"), thickness)?;
    let t = thickness;
    let rectangle = |x0: f64, y0: f64, x1: f64, y1: f64| {
        let corners = [DVec2::new(x0, y0), DVec2::new(x1, y0), DVec2::new(x1, y1), DVec2::new(x0, y1)];
        fixed_wall(&corners, DVec2::ZERO, path)
    };
    let mut walls = vec![
        rectangle(x[0] - t, y[0] - t, x[1] + t, y[0])?,
        rectangle(x[0] - t, y[0], x[0], y[1])?,
        rectangle(x[1], y[0], x[1] + t, y[1])?,
    ];
    if closed {
        walls.push(rectangle(x[0] - t, y[1], x[1] + t, y[1] + t)?);
    }
    Ok(walls)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The polygon of a macro wall (the macros make polygons only).
    fn polygon_of(wall: &PlacedWall) -> &ConvexPolygon {
        match &wall.shape {
            BodyShape::Polygon(polygon) => polygon,
            other => panic!("a macro wall is a polygon, got {other:?}"),
        }
    }
    use approx::assert_relative_eq;
    use rand::SeedableRng;

    #[test]
    fn drum_segments_form_a_ring_with_tangential_surface_speed() {
        let walls = drum_walls([0.1, 0.2], 0.05, 0.01, 0.3, 12, "walls[0]").unwrap();
        assert_eq!(walls.len(), 12);
        let centre = DVec2::new(0.1, 0.2);
        let mut area = 0.0;
        for wall in &walls {
            area += polygon_of(wall).area();
            let radial = (wall.pose.position - centre).normalize();
            assert_relative_eq!(wall.surface_velocity.length(), 0.3, epsilon = 1e-12);
            assert!(wall.surface_velocity.dot(radial).abs() < 1e-12);
            // CCW: the tangent is the radial direction turned by +90°.
            assert!(gc2d_geometry::cross(radial, wall.surface_velocity) > 0.0);
            for v in polygon_of(wall).vertices() {
                let r = (wall.pose.apply(*v) - centre).length();
                assert!((r - 0.05).abs() < 1e-12 || (r - 0.06).abs() < 1e-12, "{r}");
            }
        }
        // Ring of 12 trapezoids: ½·sin(2π/12)·12·(R² − r²).
        assert_relative_eq!(area, 6.0 * (TAU / 12.0).sin() * (0.06f64.powi(2) - 0.05f64.powi(2)), max_relative = 1e-12);
    }

    #[test]
    fn funnel_slabs_leave_the_opening_free_and_rise_at_the_slope() {
        let walls = funnel_walls([0.0, 0.3], 0.02, 1.0, 0.1, 0.005, "walls[1]").unwrap();
        let world = |w: &PlacedWall| polygon_of(w).vertices().iter().map(|v| w.pose.apply(*v)).collect::<Vec<_>>();
        let (left, right) = (world(&walls[0]), world(&walls[1]));
        let max_x_left = left.iter().map(|v| v.x).fold(f64::MIN, f64::max);
        let min_x_right = right.iter().map(|v| v.x).fold(f64::MAX, f64::min);
        assert_relative_eq!(max_x_left, -0.01, epsilon = 1e-12);
        assert_relative_eq!(min_x_right, 0.01, epsilon = 1e-12);
        let top = right.iter().map(|v| v.y).fold(f64::MIN, f64::max);
        assert_relative_eq!(top, 0.3 + 0.1 * 1f64.sin(), epsilon = 1e-12);
        assert_relative_eq!(polygon_of(&walls[0]).area(), 0.1 * 0.005, max_relative = 1e-12);
    }

    #[test]
    fn silo_is_open_and_box_is_closed() {
        let (x_range_m, y_range_m, thickness_m) = ([0.0, 0.1], [0.0, 0.4], 0.01);
        let mut rng = ChaCha8Rng::seed_from_u64(0);
        let open = expand(&WallItem::Silo { x_range_m, y_range_m, thickness_m, material: None }, "walls[0]", &mut rng)
            .unwrap();
        assert_eq!(open.len(), 3);
        assert_relative_eq!(polygon_of(&open[0]).area(), 0.12 * 0.01, max_relative = 1e-12);
        let walls =
            expand(&WallItem::Enclosure { x_range_m, y_range_m, thickness_m, material: None }, "walls[0]", &mut rng)
                .unwrap();
        assert_eq!(walls.len(), 4);
        assert_relative_eq!(walls[3].pose.position.y, 0.405, epsilon = 1e-12);
        let reversed = WallItem::Silo { x_range_m: [0.1, 0.0], y_range_m, thickness_m, material: None };
        let error = expand(&reversed, "walls[0]", &mut rng).err().unwrap();
        assert_eq!(error.path(), "walls[0].x_range_m");
    }
}
