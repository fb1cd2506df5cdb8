//! Valid scenes: what they load and build to, defaults, determinism, and the RON round trip.

mod common;

use approx::assert_relative_eq;
use gc2d_engine::{BodyKind, World};
use gc2d_geometry::DVec2;
use gc2d_scene::{FALLBACK_TIME_STEP, Gravity, Material, Scene, Shape};

fn full() -> Scene {
    Scene::from_str(common::FULL_SCENE, "full.ron").unwrap_or_else(|e| panic!("{}", e.render_plain()))
}

#[test]
fn the_full_scene_builds_with_the_expected_counts() {
    let scene = full();
    assert_eq!(scene.initial_particle_count(), 4 + 202 + 11);
    let summary = scene.summary().unwrap_or_else(|e| panic!("{}", e.render_plain()));
    assert_eq!(summary.name, "full");
    assert_eq!(summary.materials, ["sand", "lead"]);
    assert_eq!(summary.wall_bodies, 5 + 24 + 2 + 3 + 4);
    assert_eq!(summary.moving_walls, 3);
    assert_eq!(summary.particles, 217);
    assert_eq!(summary.drag_springs, 1);
    assert_eq!(summary.sources, 1);
    // One insertion at t = 0 and one per millisecond up to the end time 0.01 s.
    assert_eq!(summary.planned_insertions, 11);
    assert_eq!(summary.time_step_s, 2e-6);
    assert!(!summary.time_step_is_automatic);
    // Its sources' flattest random shapes set a stable bound below the Δt it asks for, which is kept because it is
    // below the §3.6 bound where a run is refused (docs/model.md, "Automatic Δt").
    assert!(summary.stable_time_step_s.unwrap() < 2e-6);
    assert_eq!(summary.steps(), 5000);

    let world = scene.build().unwrap();
    let bodies = world.bodies();
    assert_eq!(bodies.kind.iter().filter(|k| **k == BodyKind::Wall).count(), 38);
    assert_eq!(bodies.particles().count(), 217);
    // The lead square, 1 cm × 1 cm at 20000 kg/m², is placed where its corners are written.
    let lead = bodies.particles().find(|id| bodies.mass[id.index()] > 1.9).unwrap();
    assert_relative_eq!(bodies.mass[lead.index()], 2.0, max_relative = 1e-12);
    assert_relative_eq!(bodies.pose[lead.index()].position, DVec2::new(-0.255, 0.015), epsilon = 1e-15);
    // The first explicit particle: its pose, velocities and the sand density (a regular 7-gon of circumradius 2 mm).
    let first = bodies.particles().next().unwrap().index();
    assert_eq!(bodies.pose[first].position, DVec2::new(-0.2, 0.01));
    assert_eq!((bodies.pose[first].angle, bodies.angular_velocity[first]), (0.3, 2.0));
    assert_eq!(bodies.velocity[first], DVec2::new(0.1, 0.0));
    let area_7gon = 3.5 * 0.002f64.powi(2) * (std::f64::consts::TAU / 7.0).sin();
    assert_relative_eq!(bodies.mass[first], 5000.0 * area_7gon, max_relative = 1e-12);
    // Block velocities: speed in [0, 0.05] m/s, direction in [0, 3.14].
    for id in bodies.particles().skip(4).take(202) {
        let v = bodies.velocity[id.index()];
        assert!(v.length() <= 0.05 + 1e-15 && v.y >= -1e-15, "{v}");
    }
    let config = world.config();
    assert_eq!(config.gravity.magnitude(0.0), 9.81);
    assert_relative_eq!(config.gravity.magnitude(1.1), 9.0, epsilon = 1e-12);
    assert!(config.heating.is_some() && config.domain.is_some());
    let law = config.interactions.models()[0].overlap_area().unwrap();
    assert_eq!(law.damping.unwrap().gamma, 0.75);
}

#[test]
fn the_full_scene_runs() {
    let mut world = full().build().unwrap();
    for _ in 0..200 {
        world.step().unwrap();
    }
    // The source inserted at t = 0 (after the first step).
    assert_eq!(world.stats().inserted, 1);
    assert_eq!(world.bodies().particles().count(), 218);
}

#[test]
fn defaults_apply() {
    let scene = Scene::from_str("Scene()", "empty.ron").unwrap();
    assert_eq!(scene.name, "empty");
    assert_eq!(scene.run.end_time_s, 1.0);
    assert_eq!(scene.run.frames_per_second, 100.0);
    assert_eq!((scene.run.seed, scene.run.allow_unsafe_time_step), (0, false));
    assert_eq!(scene.run.max_overlap_fraction, 0.05);
    assert_eq!(scene.gravity, Gravity::Constant(9.81));
    let world = scene.build().unwrap();
    assert_eq!(world.time_step(), FALLBACK_TIME_STEP);
    let law = world.config().interactions.models()[0].overlap_area().unwrap();
    assert_eq!(law.elastic.e_modulus, 1e7);
    assert_eq!(law.damping.unwrap().gamma, 0.5);
    assert_eq!(law.friction.unwrap().mu, 0.6);
    assert!(law.cohesion.is_none());
    assert_eq!(world.gravity(), 9.81);

    // One default particle: a square of side 1 cm at the origin with density 5000 kg/m² (m = 0.5 kg/m), and an
    // automatic Δt of 0.15 of (π/10)·sqrt(π·r²·ρ/E) = 6.2e-5 s with r = 5 mm, rounded down to two digits.
    let text = "Scene(particles: [(shape: Square(side_m: 0.01), material: \"default\")])";
    let scene = Scene::from_str(text, "one.ron").unwrap();
    let world = scene.build().unwrap();
    assert_eq!(world.bodies().mass[0], 0.5);
    assert_eq!(world.bodies().pose[0].position, DVec2::ZERO);
    let bound = std::f64::consts::PI / 10.0 * (std::f64::consts::PI * 0.005f64.powi(2) * 5000.0 / 1e7).sqrt();
    // The stable bound is that of two such squares meeting face on: flat-contact stiffness E·c/l = 4E and damping
    // γ·sqrt(E·m/2)·4 at γ = 0.5 give the same limit, 0.2·sqrt(m/(8E)) (docs/model.md, "Automatic Δt").
    assert_relative_eq!(world.stable_time_step().unwrap(), 0.2 * (0.5f64 / 8e7).sqrt(), max_relative = 1e-12);
    assert_relative_eq!(world.time_step(), 9.3e-6, max_relative = 1e-12);
    assert!(world.time_step() <= 0.15 * bound);
    let material = Material::named("x");
    assert_eq!((material.density_kg_m2, material.gamma, material.mu, material.cohesion_n_m), (5000.0, 0.5, 0.6, 0.0));
}

/// Every particle's shape, pose and velocity, bit for bit.
fn fingerprint(world: &World) -> Vec<u64> {
    let b = world.bodies();
    let mut bits = Vec::new();
    for i in 0..b.len() {
        let pose = b.pose[i];
        bits.extend(
            [pose.position.x, pose.position.y, pose.angle, b.velocity[i].x, b.velocity[i].y, b.mass[i]]
                .map(f64::to_bits),
        );
        bits.extend(
            b.body_vertices_of(gc2d_engine::BodyId(i as u32)).iter().flat_map(|v| [v.x.to_bits(), v.y.to_bits()]),
        );
    }
    bits
}

#[test]
fn the_same_seed_gives_an_identical_world_and_another_seed_does_not() {
    let scene = full();
    let (mut a, mut b) = (scene.build().unwrap(), scene.build().unwrap());
    assert_eq!(fingerprint(&a), fingerprint(&b));
    for _ in 0..600 {
        a.step().unwrap();
        b.step().unwrap();
    }
    assert_eq!(a.stats().inserted, 2);
    assert_eq!(fingerprint(&a), fingerprint(&b));
    let mut other = scene.clone();
    other.run.seed = 8;
    assert_ne!(fingerprint(&other.build().unwrap()), fingerprint(&scene.build().unwrap()));
}

#[test]
fn scenes_round_trip_through_ron_text() {
    let scene = full();
    let plain = ron::ser::to_string_pretty(&scene, ron::ser::PrettyConfig::default()).unwrap();
    for text in [scene.to_ron_string().unwrap(), plain] {
        let reloaded = Scene::from_str(&text, "full.ron").unwrap_or_else(|e| panic!("{}\n{text}", e.render_plain()));
        assert_eq!(Scene { source: None, ..reloaded }, Scene { source: None, ..scene.clone() });
    }
}

#[test]
fn constructors_fill_the_documented_defaults() {
    let recipe = gc2d_scene::Recipe::new([0.002, 0.002]);
    let text = "Scene(particles: [(shape: Random(recipe: (semi_axes_m: (0.002, 0.002))))],
        blocks: [(x_range_m: (0, 0.01), y_range_m: (0.01, 0.01), grid_spacing_m: (0.005, 0.005), shape: (semi_axes_m: (0.002, 0.002)))],
        sources: [(position_m: (0, 0.1), shape: (semi_axes_m: (0.002, 0.002)))])";
    let parsed = Scene::from_str(text, "defaults.ron").unwrap();
    let built = Scene {
        particles: vec![gc2d_scene::Particle::new(Shape::Random { recipe })],
        blocks: vec![gc2d_scene::Block::new([0.0, 0.01], [0.01, 0.01], [0.005, 0.005], recipe)],
        sources: vec![gc2d_scene::Source::new([0.0, 0.1], recipe)],
        name: "defaults".into(),
        ..Scene::default()
    };
    assert_eq!(Scene { source: None, ..parsed }, built);
    let spring: gc2d_scene::DragSpring = ron::from_str("()").unwrap();
    assert_eq!(spring, gc2d_scene::DragSpring::default());
}

#[test]
fn scenes_constructed_in_code_build_without_a_source_text() {
    let scene = Scene {
        particles: vec![gc2d_scene::Particle {
            shape: Shape::Regular { corners: 5, radius_m: 0.01 },
            position_m: Some([0.0, 0.1]),
            angle_rad: 0.0,
            velocity_m_s: [0.0, 0.0],
            angular_velocity_rad_s: 0.0,
            material: Some("nope".into()),
            drag_spring: None,
        }],
        ..Scene::default()
    };
    let error = scene.build().err().unwrap();
    assert_eq!(error.path(), "particles[0].material");
    assert_eq!(error.location(), None);
    assert_eq!(error.to_string(), "`particles[0].material`: unknown material `nope`");
}
