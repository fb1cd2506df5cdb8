//! A contact law per pair of materials, through the scene: two square blocks of different materials on one incline
//! of a third; the interaction table gives each block–incline pair its own μ. At 21° the block whose pair has μ = 0.5
//! (arctan μ = 26.6°) rests and the one whose pair has μ = 0.3 (16.7°) slides with Coulomb's acceleration
//! g·(sin θ − μ·cos θ).

use gc2d_geometry::DVec2;
use gc2d_scene::{Interaction, InteractionLaw, Material, Particle, Scene, Shape, WallItem};

/// Incline angle, rad.
const SLOPE: f64 = 21.0 * std::f64::consts::PI / 180.0;
/// Block side, m.
const SIDE: f64 = 0.01;

/// A scene with an incline of material `ramp` and two blocks, `grippy` up the slope and `slippery` further down.
fn scene() -> Scene {
    let along = DVec2::from_angle(SLOPE);
    let normal = along.perp();
    let thickness = 0.01;
    let ramp_centre = DVec2::ZERO;
    let surface = |s: f64| ramp_centre + 0.5 * thickness * normal + s * along;
    let block = |s: f64, material: &str| Particle {
        position_m: Some((surface(s) + (0.5 * SIDE + 1e-7) * normal).to_array()),
        angle_rad: SLOPE,
        material: Some(material.to_owned()),
        ..Particle::new(Shape::Square { side_m: SIDE })
    };
    let pair = |a: &str, mu: f64| Interaction {
        materials: [a.to_owned(), "ramp".to_owned()],
        law: InteractionLaw::OverlapArea {
            youngs_modulus_n_m: None,
            gamma: None,
            mu: Some(mu),
            cohesion_n_m: None,
            formulation: Default::default(),
        },
    };
    Scene {
        name: "per_pair_friction".into(),
        materials: vec![Material::named("ramp"), Material::named("grippy"), Material::named("slippery")],
        interactions: vec![pair("grippy", 0.5), pair("slippery", 0.3)],
        walls: vec![WallItem::Wall {
            shape: Shape::Rectangle { width_m: 0.4, height_m: thickness },
            position_m: Some(ramp_centre.to_array()),
            angle_rad: SLOPE,
            surface_velocity_m_s: [0.0, 0.0],
            motion: Default::default(),
            material: None,
        }],
        particles: vec![block(0.1, "grippy"), block(-0.05, "slippery")],
        ..Scene::default()
    }
}

#[test]
fn each_block_obeys_the_friction_of_its_own_pair() {
    let mut world = scene().build().unwrap();
    let bodies = world.bodies();
    let (grippy, slippery) = (1, 2);
    assert_eq!(bodies.material[grippy].0, 1);
    assert_eq!(bodies.material[slippery].0, 2);
    // Settle, then measure over 0.2 s.
    world.run_until(0.05).unwrap();
    let along = DVec2::from_angle(SLOPE);
    let position = |w: &gc2d_engine::World, i: usize| w.bodies().pose[i].position.dot(along);
    let speed = |w: &gc2d_engine::World, i: usize| w.bodies().velocity[i].dot(along);
    let (grippy_start, slippery_speed_start, t0) = (position(&world, grippy), speed(&world, slippery), world.time());
    world.run_until(0.25).unwrap();
    let grippy_travel = (position(&world, grippy) - grippy_start).abs();
    assert!(grippy_travel < 1e-6, "the μ = 0.5 block moved {grippy_travel:e} m at 21°");
    let acceleration = -(speed(&world, slippery) - slippery_speed_start) / (world.time() - t0);
    let coulomb = 9.81 * (SLOPE.sin() - 0.3 * SLOPE.cos());
    assert!(
        (acceleration - coulomb).abs() < 0.03 * coulomb,
        "the μ = 0.3 block slides at {acceleration} m/s², Coulomb's {coulomb} m/s²"
    );
}

#[test]
fn the_summary_lists_the_law_of_every_pair() {
    let summary = scene().summary().unwrap();
    assert_eq!(summary.interactions.len(), 6, "{:?}", summary.interactions);
    assert!(summary.interactions.iter().any(|line| line.starts_with("ramp–grippy:") && line.contains("μ = 0.5")));
    assert!(summary.interactions.iter().any(|line| line.starts_with("ramp–slippery:") && line.contains("μ = 0.3")));
    assert!(summary.interactions.iter().any(|line| line.starts_with("grippy–slippery:") && line.contains("μ = 0.6")));
}
