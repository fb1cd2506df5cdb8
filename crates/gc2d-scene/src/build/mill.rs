//! The ball mill section to walls and particles: the chamber as an inner-circle wall, the rotor as a hub disk and one
//! capsule per blade arm, all turning about the chamber's centre, and the balls placed at random without overlap
//! (ballmill.md §7.2: r = R·√u, φ = 2π·u', overlaps with balls, hub and blades rejected).

use super::PlannedParticle;
use super::walls::PlacedWall;
use crate::checks::{finite, finite_pair, non_negative, positive};
use crate::error::SceneError;
use crate::schema::{MassModel, Mill};
use crate::spans::field_path;
use crate::validate::Materials;
use gc2d_engine::motion::Rotation;
use gc2d_engine::{BodyShape, MaterialId, TimeWindow, WallMotion, shape_view};
use gc2d_geometry::{DVec2, Pose, area_contact};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::f64::consts::TAU;

/// Placement attempts per ball before the mill is declared too full.
const PLACEMENT_ATTEMPTS_PER_BALL: usize = 1000;

/// The speed of the blade tips at the rotor's full speed, m/s.
pub(crate) fn tip_speed(mill: &Mill) -> f64 {
    (mill.rotor.rpm * TAU / 60.0 * mill.rotor.tip_radius_m).abs()
}

/// Checks the mill's numbers, each at its field.
pub(crate) fn check(mill: &Mill, path: &str) -> Result<(), SceneError> {
    let at = |field: &str| field_path(path, field);
    let rotor = |field: &str| field_path(&at("rotor"), field);
    let balls = |field: &str| field_path(&at("balls"), field);
    finite_pair(&at("centre_m"), mill.centre_m)?;
    positive(&at("chamber_radius_m"), mill.chamber_radius_m)?;
    finite(&rotor("rpm"), mill.rotor.rpm)?;
    non_negative(&rotor("spin_up_s"), mill.rotor.spin_up_s)?;
    positive(&rotor("hub_radius_m"), mill.rotor.hub_radius_m)?;
    positive(&rotor("blade_width_m"), mill.rotor.blade_width_m)?;
    let tip = mill.rotor.tip_radius_m;
    if !(tip.is_finite() && tip > mill.rotor.hub_radius_m && tip < mill.chamber_radius_m) {
        return Err(SceneError::value(
            rotor("tip_radius_m"),
            format!("{tip}: the blade tips must reach beyond the hub and stay inside the chamber"),
        ));
    }
    for (k, &arm) in mill.rotor.arms_rad.iter().enumerate() {
        finite(&format!("{}[{k}]", rotor("arms_rad")), arm)?;
    }
    positive(&balls("radius_m"), mill.balls.radius_m)?;
    non_negative(&balls("speed_m_s"), mill.balls.speed_m_s)?;
    if 2.0 * mill.balls.radius_m >= mill.chamber_radius_m - tip {
        return Err(SceneError::value(
            balls("radius_m"),
            format!(
                "{}: a ball must fit between the blade tips and the chamber ({} m)",
                mill.balls.radius_m,
                mill.chamber_radius_m - tip
            ),
        ));
    }
    Ok(())
}

/// The chamber, hub and blades, at rest pose at t = 0; the rotor parts turn at the rotor's speed.
pub(crate) fn walls(mill: &Mill, path: &str) -> Vec<PlacedWall> {
    let centre = DVec2::from_array(mill.centre_m);
    let rotor = &mill.rotor;
    let motion = WallMotion::Rotating(Rotation {
        pivot: centre,
        angular_velocity: rotor.rpm * TAU / 60.0,
        window: TimeWindow::new(0.0, f64::INFINITY),
        spin_up: rotor.spin_up_s,
    });
    let placed = |shape, pose, motion, material: &Option<String>, part: &str| PlacedWall {
        shape,
        pose,
        surface_velocity: DVec2::ZERO,
        motion,
        material: material.clone(),
        path: field_path(path, part),
    };
    let mut walls = vec![
        placed(
            BodyShape::InnerCircle { radius: mill.chamber_radius_m },
            Pose::new(centre, 0.0),
            WallMotion::Static,
            &mill.chamber_material,
            "chamber_radius_m",
        ),
        placed(
            BodyShape::Disk { radius: rotor.hub_radius_m },
            Pose::new(centre, 0.0),
            motion,
            &mill.rotor_material,
            "rotor",
        ),
    ];
    // Each arm: a capsule from the hub's centre out to the tip, its round end reaching the tip radius.
    let radius = 0.5 * rotor.blade_width_m;
    let outer = rotor.tip_radius_m - radius;
    for &arm in &rotor.arms_rad {
        let direction = DVec2::from_angle(arm);
        let shape = BodyShape::Capsule { half_length: 0.5 * outer, radius };
        let pose = Pose::new(centre + 0.5 * outer * direction, arm);
        walls.push(placed(shape, pose, motion, &mill.rotor_material, "rotor.arms_rad"));
    }
    walls
}

/// The balls, placed uniformly at random in the chamber without overlapping each other or `walls`, each moving at
/// the mill's ball speed in a random direction. Draws from `rng` in a fixed order (position, then direction, per
/// ball), so the same seed places the same balls.
pub(crate) fn balls(
    mill: &Mill,
    walls: &[PlacedWall],
    materials: &Materials,
    mass_model: MassModel,
    rng: &mut ChaCha8Rng,
    path: &str,
) -> Result<Vec<PlannedParticle>, SceneError> {
    let balls = &mill.balls;
    let balls_path = field_path(path, "balls");
    let material_path = field_path(&balls_path, "material");
    let material = materials.resolve(balls.material.as_deref(), &material_path)?;
    let material_id = MaterialId(materials.index_of(balls.material.as_deref(), &material_path)? as u16);
    let density = Materials::density(material, mass_model);
    let centre = DVec2::from_array(mill.centre_m);
    let r = balls.radius_m;
    let reach = mill.chamber_radius_m - r;
    let world_walls: Vec<(Vec<DVec2>, &PlacedWall)> =
        walls.iter().map(|w| (w.shape.body_points().iter().map(|&p| w.pose.apply(p)).collect(), w)).collect();
    let mut placed: Vec<DVec2> = Vec::with_capacity(balls.count);
    let mut planned = Vec::with_capacity(balls.count);
    let mut attempts = 0;
    while placed.len() < balls.count {
        attempts += 1;
        if attempts > PLACEMENT_ATTEMPTS_PER_BALL * balls.count.max(1) {
            return Err(SceneError::value(
                field_path(&balls_path, "count"),
                format!(
                    "only {} of {} balls found room in the chamber after {attempts} attempts",
                    placed.len(),
                    balls.count
                ),
            )
            .with_help("use fewer or smaller balls, or a larger chamber"));
        }
        let radial = reach * rng.random::<f64>().sqrt();
        let position = centre + radial * DVec2::from_angle(TAU * rng.random::<f64>());
        let disk = gc2d_geometry::ShapeView::Disk { center: position, radius: r };
        let free_of_balls = placed.iter().all(|&other| other.distance(position) >= 2.0 * r);
        let free_of_walls = world_walls.iter().all(|(points, wall)| {
            let view = shape_view(wall.shape.kind(), points, wall.shape.radius() * wall.pose.scale);
            area_contact(disk, view).is_none()
        });
        if !(free_of_balls && free_of_walls) {
            continue;
        }
        let velocity = balls.speed_m_s * DVec2::from_angle(TAU * rng.random::<f64>());
        placed.push(position);
        planned.push(PlannedParticle {
            shape: BodyShape::Disk { radius: r },
            pose: Pose::new(position, 0.0),
            velocity,
            angular_velocity: 0.0,
            density,
            material: material_id,
            drag_spring: None,
            path: balls_path.clone(),
        });
    }
    Ok(planned)
}
