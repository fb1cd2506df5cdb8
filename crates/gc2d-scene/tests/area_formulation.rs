//! The overlap-area law's `formulation` through the scene format (issue 19, item 1): an `interactions` entry may
//! select `Conservative`; pairs without one, and entries that leave it out, keep gc2d's `Thesis` law; the
//! conservative pair's time-step bound is the thesis's times sqrt(r_in/(4R)).

use gc2d_contact::AreaFormulation;
use gc2d_scene::Scene;

/// A scene of two materials, `a` and `b`, one 7-gon of each; `entry` is the text of its `interactions` list.
fn scene(entry: &str) -> Scene {
    let text = format!(
        r#"Scene(
    name: "formulation",
    materials: [(name: "a"), (name: "b")],
    interactions: [{entry}],
    particles: [
        (shape: Regular(corners: 7, radius_m: 0.005), position_m: (0.0, 0.0), material: "a"),
        (shape: Regular(corners: 7, radius_m: 0.005), position_m: (0.02, 0.0), material: "b"),
    ],
)"#
    );
    Scene::from_str(&text, "formulation.ron").expect("valid scene")
}

/// The formulations of the pairs (a, a), (a, b) and (b, b) of the built World.
fn formulations(scene: &Scene) -> Vec<AreaFormulation> {
    let world = scene.build().expect("the scene builds");
    world.config().interactions.models().iter().map(|m| m.overlap_area().unwrap().elastic.formulation).collect()
}

#[test]
fn an_interaction_selects_the_conservative_formulation_and_the_rest_keep_the_thesis_law() {
    let conservative = scene(r#"(materials: ("a", "b"), law: OverlapArea(formulation: Conservative))"#);
    let listed = formulations(&conservative);
    assert!(listed.contains(&AreaFormulation::Conservative));
    assert_eq!(listed.iter().filter(|f| **f == AreaFormulation::Conservative).count(), 1, "{listed:?}");
    let default = scene(r#"(materials: ("a", "b"), law: OverlapArea(mu: 0.3))"#);
    assert!(formulations(&default).iter().all(|f| *f == AreaFormulation::Thesis));

    // The conservative pair lowers the stable time step by sqrt(r_in/(4R)) = sqrt(cos(π/7)/4).
    let thesis_dt = default.build().unwrap().stable_time_step().unwrap();
    let conservative_dt = conservative.build().unwrap().stable_time_step().unwrap();
    let factor = ((std::f64::consts::PI / 7.0).cos() / 4.0).sqrt();
    assert!((conservative_dt / thesis_dt - factor).abs() < 1e-9, "{}", conservative_dt / thesis_dt);
}

#[test]
fn a_misspelt_formulation_is_refused_at_its_field() {
    let text = r#"Scene(
    name: "formulation",
    materials: [(name: "a")],
    interactions: [(materials: ("a", "a"), law: OverlapArea(formulation: Conservativ))],
)"#;
    let error = Scene::from_str(text, "formulation.ron").unwrap_err().to_string();
    assert!(error.contains("Conservativ"), "{error}");
}
