//! Snapshots of Worlds with round bodies: disks and the chamber circle reach the analyses as traced outlines.

use gc2d_analysis::Snapshot;
use gc2d_contact::ContactLaw;
use gc2d_engine::schedules::GravitySchedule;
use gc2d_engine::{BodyShape, InteractionTable, MassModel, WallMotion, World, WorldConfig};
use gc2d_geometry::{CIRCLE_SEGMENTS, DVec2, Pose};

#[test]
fn disks_and_chamber_walls_are_traced_at_their_radius() {
    let config = WorldConfig {
        time_step: 1e-5,
        integrator: Default::default(),
        interactions: InteractionTable::uniform(ContactLaw::elastic(1e7)),
        mass_model: MassModel::PerUnitThickness,
        gravity: GravitySchedule::constant(9.81),
        heating: None,
        safety: Default::default(),
        domain: None,
        seed: 1,
    };
    let mut world = World::new(config).unwrap();
    let chamber = DVec2::new(0.01, 0.02);
    world.add_wall(BodyShape::InnerCircle { radius: 0.05 }, Pose::new(chamber, 0.0), DVec2::ZERO, WallMotion::Static);
    let centre = DVec2::new(0.02, 0.0);
    world.add_particle(BodyShape::Disk { radius: 0.003 }, Pose::new(centre, 0.0), 5000.0, DVec2::ZERO, 0.0).unwrap();
    let snapshot = Snapshot::from_world(&world);
    let disk = &snapshot.particles[0];
    assert_eq!(disk.vertices.len(), CIRCLE_SEGMENTS);
    assert!(disk.vertices.iter().all(|v| (v.distance(centre) - 0.003).abs() < 1e-15));
    assert!((disk.area - std::f64::consts::PI * 9e-6).abs() < 1e-18);
    // A single disk filled 1.0029 of the hull of its inscribed polygon; the hull now takes the circumscribed one:
    // πr² over n·r²·tan(π/n), just below 1.
    let n = CIRCLE_SEGMENTS as f64;
    let expected = std::f64::consts::PI / (n * (std::f64::consts::PI / n).tan());
    let packing = gc2d_analysis::bulk_packing_fraction(&snapshot);
    assert!(packing <= 1.0 && (packing - expected).abs() < 1e-12, "{packing} against {expected}");
    let wall = &snapshot.walls[0];
    assert!(wall.vertices.len() >= CIRCLE_SEGMENTS);
    assert!(wall.vertices.iter().all(|v| (v.distance(chamber) - 0.05).abs() < 1e-15));
}
