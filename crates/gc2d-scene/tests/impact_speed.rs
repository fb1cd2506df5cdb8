//! The impact speed a Hertz contact's time-step bound is taken at: the scene's own value, twice a mill rotor's tip
//! speed (or a fall across the chamber for a slow rotor) when a mill scene leaves it out, else the engine's 10 m/s.

use gc2d_scene::Scene;
use std::f64::consts::PI;

/// A small mill at `rpm` with an automatic Δt; `extra_run` goes into the `run` section.
fn mill(rpm: f64, extra_run: &str) -> Scene {
    let text = format!(
        r#"Scene(
    mass_model: SphereEquivalent,
    run: (end_time_s: 0.01, seed: 3, {extra_run}),
    materials: [(name: "steel", density_kg_m3: 7850, youngs_modulus_pa: 196.2e9, poisson_ratio: 0.3)],
    interactions: [(materials: ("steel", "steel"), law: Hertz(damping: SteelReichardt))],
    mill: (rotor: (rpm: {rpm}), balls: (count: 10)),
)"#
    );
    Scene::from_str(&text, "mill.ron").unwrap()
}

#[test]
fn a_mill_takes_its_hertz_bound_at_twice_the_tip_speed() {
    let scene = mill(1700.0, "");
    let tip_speed = 1700.0 * 2.0 * PI / 60.0 * 0.058;
    assert!((scene.max_impact_speed() - 2.0 * tip_speed).abs() < 1e-12);
    let summary = scene.summary().unwrap();
    assert_eq!(summary.max_impact_speed_m_s, 2.0 * tip_speed);
    assert!(summary.to_string().contains("impacts expected up to 20.651 m/s"), "{summary}");

    // A Hertz contact stiffens with the impact speed: the bound at 20.7 m/s is shorter than at 10 m/s, by (v1/v2)^(1/5).
    let at_ten = mill(1700.0, "max_impact_speed_m_s: 10.0").summary().unwrap();
    let ratio = summary.stable_time_step_s.unwrap() / at_ten.stable_time_step_s.unwrap();
    assert!((ratio - (10.0 / (2.0 * tip_speed)).powf(0.2)).abs() < 1e-9, "ratio {ratio}");
    assert!(summary.time_step_s <= summary.stable_time_step_s.unwrap());
}

#[test]
fn a_slow_mill_takes_a_fall_across_the_chamber_and_other_scenes_ten_metres_per_second() {
    // At 40 rpm the tips move at 0.24 m/s; a ball falling 146 mm reaches 1.69 m/s.
    let fall = (2.0 * 9.81 * 0.146_f64).sqrt();
    assert!((mill(40.0, "").max_impact_speed() - fall).abs() < 1e-12);
    assert_eq!(mill(1700.0, "max_impact_speed_m_s: 3.5").max_impact_speed(), 3.5);
    let plain = Scene::from_str("Scene(materials: [(name: \"a\")])", "plain.ron").unwrap();
    assert_eq!(plain.max_impact_speed(), 10.0);
}
