//! The ball mill section: chamber, rotor and balls as the scene builds them, and its located errors.

use gc2d_engine::{BodyKind, ShapeKind};
use gc2d_scene::{ErrorKind, Scene};
use std::path::PathBuf;

fn mill_scene() -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/mill.ron");
    Scene::from_path(path).unwrap()
}

#[test]
fn the_mill_builds_a_chamber_a_turning_rotor_and_scattered_moving_balls() {
    let world = mill_scene().build().unwrap();
    let b = world.bodies();
    let walls: Vec<usize> = (0..b.len()).filter(|&i| b.kind[i] == BodyKind::Wall).collect();
    let shapes: Vec<ShapeKind> = walls.iter().map(|&i| b.shape[i]).collect();
    assert_eq!(shapes, [ShapeKind::InnerCircle, ShapeKind::Disk, ShapeKind::Capsule, ShapeKind::Capsule]);
    let balls: Vec<usize> = b.particles().map(|id| id.index()).collect();
    assert_eq!(balls.len(), 130);
    for (k, &i) in balls.iter().enumerate() {
        let p = b.pose[i].position;
        assert!(p.length() + 0.0025 <= 0.073, "ball {k} pokes out of the chamber");
        assert!((b.velocity[i].length() - 1.0).abs() < 1e-12, "ball {k} starts at 1 m/s");
        assert!((b.mass[i] - 0.514e-3).abs() < 0.001e-3, "a 5 mm steel ball weighs 0.514 g, not {}", b.mass[i]);
        for &j in &balls[k + 1..] {
            assert!(p.distance(b.pose[j].position) >= 0.005, "balls {i} and {j} overlap");
        }
    }
    // The same seed places the same balls.
    let again = mill_scene().build().unwrap();
    assert!(balls.iter().all(|&i| again.bodies().pose[i] == b.pose[i] && again.bodies().velocity[i] == b.velocity[i]));
}

#[test]
fn the_rotor_turns_at_its_rpm_and_the_chamber_stands() {
    let mut world = mill_scene().build().unwrap();
    let rest: Vec<f64> = (0..4).map(|i| world.bodies().pose[i].angle).collect();
    for _ in 0..100 {
        world.step().unwrap();
    }
    let b = world.bodies();
    let omega = 1700.0 * std::f64::consts::TAU / 60.0;
    assert_eq!(b.angular_velocity[0], 0.0, "the chamber stands");
    for (rotor, rest_angle) in rest.iter().enumerate().skip(1) {
        assert!((b.angular_velocity[rotor] - omega).abs() < 1e-9 * omega, "rotor part {rotor}");
        let turned = b.pose[rotor].angle - rest_angle;
        assert!((turned - omega * world.time()).abs() < 1e-9, "rotor part {rotor} turned {turned} rad");
    }
}

#[test]
fn mill_errors_name_the_field() {
    let scene = |rotor: &str, balls: &str| {
        format!(
            "Scene(mass_model: SphereEquivalent, materials: [(name: \"steel\", density_kg_m3: 7850)], mill: (rotor: ({rotor}), balls: ({balls})))"
        )
    };
    let error = |text: String| Scene::from_str(&text, "bad.ron").and_then(|s| s.build().map(drop)).unwrap_err();
    let e = error(scene("rpm: 1000, tip_radius_m: 0.08", "count: 10"));
    assert_eq!((e.kind(), e.path()), (ErrorKind::Value, "mill.rotor.tip_radius_m"), "{}", e.render_plain());
    let e = error(scene("rpm: 1000", "count: 5000"));
    assert_eq!((e.kind(), e.path()), (ErrorKind::Value, "mill.balls.count"), "{}", e.render_plain());
    assert!(e.message().contains("found room"), "{}", e.message());
    let e = error(scene("rpm: 1000", "count: 10, material: \"stel\""));
    assert_eq!(e.path(), "mill.balls.material", "{}", e.render_plain());
}

#[test]
fn the_rotor_power_from_torque_equals_its_work_on_the_balls_at_every_step() {
    let mut world = mill_scene().build().unwrap();
    let mut driving_steps = 0;
    for _ in 0..20_000 {
        world.step().unwrap();
        let drive = world.rotor_power();
        let scale = drive.power_from_work.abs().max(drive.power_from_torque.abs());
        assert!(
            (drive.power_from_torque - drive.power_from_work).abs() <= 1e-9 * scale,
            "t = {}: ω·τ = {} W, Σ F·v = {} W",
            world.time(),
            drive.power_from_torque,
            drive.power_from_work
        );
        driving_steps += usize::from(scale > 0.0);
    }
    assert!(driving_steps > 100, "the rotor hit balls on {driving_steps} steps");
}
