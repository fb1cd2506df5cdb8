//! The overlap-area law's `formulation` through the scene format (issue 19, item 1): an `interactions` entry may
//! select `Conservative`; pairs without one, and entries that leave it out, keep gc2d's `Thesis` law; the
//! conservative pair's stable time step follows its stiffness E·c²/l².

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

    // The conservative pair's stable time step: the smallest of the §3.6 bound times sqrt(r_in/(4R)), the flat limit
    // 0.2/sqrt(2E·κ²/m) and the damping limit 0.2/(γ·κ·sqrt(2E/m)), κ = 4·tan(π/7) for a regular 7-gon.
    let (e, rho, gamma, r) = (1e7, 5000.0, 0.5, 0.005);
    let angle = std::f64::consts::PI / 7.0;
    let inscribed = r * angle.cos();
    let mass = 3.5 * r * r * (2.0 * angle).sin() * rho;
    let reference = std::f64::consts::PI / 10.0 * (std::f64::consts::PI * inscribed * inscribed * rho / e).sqrt();
    let kappa = 4.0 * angle.tan();
    let limits = [
        reference * (inscribed / (4.0 * r)).sqrt(),
        0.2 / (2.0 * e * kappa * kappa / mass).sqrt(),
        0.2 / (gamma * kappa * (2.0 * e / mass).sqrt()),
    ];
    let expected = limits.into_iter().fold(f64::INFINITY, f64::min);
    let conservative_dt = conservative.build().unwrap().stable_time_step().unwrap();
    assert!((conservative_dt / expected - 1.0).abs() < 1e-9, "{conservative_dt} against {limits:?}");
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
