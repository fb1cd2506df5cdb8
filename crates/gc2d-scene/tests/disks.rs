//! Disks through the scene format: a block and a source of disks with a scattered radius, sphere-equivalent masses,
//! and the recipe errors that keep a disk recipe honest.

use gc2d_engine::{ShapeKind, World};
use gc2d_scene::{ErrorKind, Scene};

/// A chamber with a block of disks and a source of disks, radius 2.5 mm ± 10 %.
const SCENE: &str = r#"Scene(
    mass_model: SphereEquivalent,
    run: (time_step_s: 4e-7, seed: 7, max_impact_speed_m_s: 3.0),
    materials: [(name: "steel", density_kg_m3: 7850, youngs_modulus_pa: 196.2e9)],
    interactions: [(materials: ("steel", "steel"), law: Hertz(damping: Restitution(0.8)))],
    walls: [Wall(shape: InnerCircle(radius_m: 0.073))],
    blocks: [(x_range_m: (-0.03, 0.03), y_range_m: (-0.03, 0.0), grid_spacing_m: (0.008, 0.008),
              shape: (semi_axes_m: (0.0025, 0.0025), size_spread: Equal(0.1), disk: true))],
    sources: [(position_m: (0.0, 0.05), width_m: 0.1, window_s: (0.0, 0.001), interval_s: 0.0002,
               shape: (semi_axes_m: (0.0025, 0.0025), size_spread: Equal(0.1), disk: true))],
)"#;

#[test]
fn blocks_and_sources_make_disks_of_scattered_radius_and_sphere_mass() {
    let scene = Scene::from_str(SCENE, "disks.ron").unwrap();
    let mut world: World = scene.build().unwrap();
    let start = world.bodies().particles().count();
    assert_eq!(start, 8 * 4);
    world.run_until(0.0012).unwrap();
    let bodies = world.bodies();
    let particles: Vec<usize> = bodies.particles().map(|id| id.index()).collect();
    let stats = world.stats();
    assert_eq!(stats.inserted + stats.insertions_skipped, 5, "one insertion per 0.2 ms in the window [0, 1 ms)");
    assert!(stats.inserted >= 4, "only {} of 5 insertions found room", stats.inserted);
    assert_eq!(particles.len(), start + stats.inserted as usize);
    let radii: Vec<f64> = particles.iter().map(|&i| bodies.radius[i]).collect();
    for &i in &particles {
        assert_eq!(bodies.shape[i], ShapeKind::Disk);
        let r = bodies.radius[i];
        assert!((0.00225..=0.00275).contains(&r), "radius {r} outside 2.5 mm ± 10 %");
        let sphere = 7850.0 * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
        assert!((bodies.mass[i] - sphere).abs() < 1e-12 * sphere);
    }
    let spread =
        radii.iter().copied().fold(f64::NEG_INFINITY, f64::max) - radii.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(spread > 1e-4, "the radii scatter ({spread} m)");
}

#[test]
fn disk_recipes_refuse_polygon_fields_and_unequal_axes() {
    let error = |text: &str| Scene::from_str(text, "bad.ron").and_then(|s| s.build().map(drop)).unwrap_err();
    let unequal = "Scene(blocks: [(x_range_m: (0, 0.01), y_range_m: (0, 0.01), grid_spacing_m: (0.01, 0.01), shape: (semi_axes_m: (0.002, 0.003), disk: true))])";
    let e = error(unequal);
    assert_eq!((e.kind(), e.path()), (ErrorKind::Value, "blocks[0].shape.semi_axes_m"), "{}", e.render_plain());
    let corners =
        "Scene(sources: [(position_m: (0, 0), shape: (semi_axes_m: (0.002, 0.002), corners: 7, disk: true))])";
    let e = error(corners);
    assert_eq!((e.kind(), e.path()), (ErrorKind::Value, "sources[0].shape.corners"), "{}", e.render_plain());
    assert!(e.message().contains("does not apply to disks"), "{}", e.message());
}
