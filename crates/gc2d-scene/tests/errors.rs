//! Every error class: the kind, field path and file:line:column of the error, and the rendered diagnostic
//! (snapshots in `tests/snapshots/`).

use gc2d_scene::{ErrorKind, Scene, SceneError};

/// Loads and builds `text` as `bad.ron` and returns the error.
fn error_of(text: &str) -> SceneError {
    match Scene::from_str(text, "bad.ron").and_then(|scene| scene.build().map(drop)) {
        Ok(()) => panic!("expected an error for {text}"),
        Err(error) => error,
    }
}

/// Asserts kind, path and location, and snapshots the rendered report.
fn check(name: &str, text: &str, kind: ErrorKind, path: &str, line_column: (usize, usize)) -> SceneError {
    let error = error_of(text);
    assert_eq!(error.kind(), kind, "{}", error.render_plain());
    assert_eq!(error.path(), path, "{}", error.render_plain());
    let location = error.location().cloned().expect("located");
    assert_eq!((location.file.as_str(), location.line, location.column), ("bad.ron", line_column.0, line_column.1));
    assert!(error.to_string().starts_with(&format!("bad.ron:{}:{}: `{path}`: ", line_column.0, line_column.1)));
    insta::assert_snapshot!(name, error.render_plain());
    error
}

#[test]
fn syntax_errors_name_the_position() {
    check("syntax", "Scene(\n    run: (seed: 1 2),\n)", ErrorKind::Syntax, "run", (2, 19));
}

#[test]
fn unknown_fields_suggest_the_closest_name() {
    let text = "Scene(\n    materials: [(name: \"sand\", gamm: 0.5)],\n)";
    let error = check("unknown_field", text, ErrorKind::UnknownName, "materials[0].gamm", (2, 32));
    assert!(error.message().contains("unknown field `gamm`, did you mean `gamma`?"));
}

#[test]
fn unknown_variants_suggest_the_spelling_ignoring_case() {
    let text = "Scene(\n    blocks: [(x_range_m: (0, 1), y_range_m: (0, 1), grid_spacing_m: (0.1, 0.1), grid: FCC_GAUSS,\n    shape: (semi_axes_m: (0.01, 0.01)))],\n)";
    let error = check("unknown_variant", text, ErrorKind::UnknownName, "blocks[0].grid", (2, 87));
    assert!(error.message().ends_with("did you mean `FccGauss`?"));
}

#[test]
fn missing_fields_name_the_structure() {
    let text = "Scene(\n    sources: [(position_m: (0, 1))],\n)";
    check("missing_field", text, ErrorKind::MissingField, "sources[0].shape", (2, 34));
}

#[test]
fn wrong_types_show_what_was_found() {
    let text = "Scene(\n    run: (end_time_s: \"long\"),\n)";
    let error = check("wrong_type", text, ErrorKind::Type, "run.end_time_s", (2, 23));
    assert!(error.message().contains("found `\"long\"`"), "{}", error.message());
    let text = "Scene(\n    particles: [(shape: Square(side_m: 0.01), position_m: (0, 1, 2))],\n)";
    check("wrong_length", text, ErrorKind::Type, "particles[0].position_m", (2, 66));
}

/// Numbers ron reads in pieces are told as written: `seed: -1` read "out of bounds, found `1`", `seed: 1.5` read
/// "expected comma", `gravity: 9.81` suggested the raw identifier `r#9.81`, and a NUL byte was shown as a blank.
#[test]
fn misread_numbers_are_reported_as_written() {
    let cases = [
        ("Scene(\n    run: (seed: -1),\n)", "run.seed", (2, 17), "found `-1`: this field takes a whole number ≥ 0"),
        ("Scene(\n    run: (seed: 1.5),\n)", "run.seed", (2, 17), "expected a whole number, found `1.5`"),
        ("Scene(\n    run: (seed: 2e3),\n)", "run.seed", (2, 17), "expected a whole number, found `2e3`"),
        (
            "Scene(\n    gravity: 9.81,\n)",
            "gravity",
            (2, 14),
            "expected one of this field's variants, found the number `9.81`",
        ),
        ("Scene(\n    run: (seed:\u{0} 1),\n)", "run.seed", (2, 16), "expected integer, found `U+0000`"),
    ];
    for (text, path, (line, column), message) in cases {
        let error = error_of(text);
        assert_eq!((error.kind(), error.path()), (ErrorKind::Type, path), "{}", error.render_plain());
        let location = error.location().cloned().expect("located");
        assert_eq!((location.line, location.column), (line, column), "{}", error.render_plain());
        assert_eq!(error.message(), message, "{}", error.render_plain());
    }
    assert!(error_of(cases[3].0).help_text().is_some_and(|help| help.contains("`gravity: Constant(9.81)`")));
}

/// A UTF-8 byte-order mark, which some editors write, is not part of the scene.
#[test]
fn a_byte_order_mark_is_skipped() {
    let scene = Scene::from_str("\u{FEFF}Scene(\n    run: (seed: 7),\n)", "bom.ron").unwrap();
    assert_eq!(scene.run.seed, 7);
    let error = error_of("\u{FEFF}Scene(\n    run: (seed: -7),\n)");
    assert_eq!(error.location().map(|l| (l.line, l.column)), Some((2, 17)));
}

#[test]
fn out_of_range_values_point_at_the_value() {
    let text = "Scene(\n    materials: [(name: \"sand\", mu: -0.1)],\n)";
    check("negative_mu", text, ErrorKind::Value, "materials[0].mu", (2, 36));
    let text = "Scene(\n    materials: [(name: \"sand\", youngs_modulus_n_m: 0)],\n)";
    check("zero_e", text, ErrorKind::Value, "materials[0].youngs_modulus_n_m", (2, 52));
}

#[test]
fn non_convex_corners_name_the_vertex() {
    let text = "Scene(\n    walls: [\n        Wall(shape: Polygon(corners_m: [(0, 0), (1, 0), (0.2, 0.2), (0, 1)])),\n    ],\n)";
    let error = check("non_convex", text, ErrorKind::Value, "walls[0].shape.corners_m[2]", (3, 57));
    assert_eq!(error.message(), "the polygon is not convex at vertex 2");
}

#[test]
fn unknown_materials_suggest_a_declared_one() {
    let text = "Scene(\n    materials: [(name: \"sand\")],\n    particles: [(shape: Square(side_m: 0.01), material: \"snad\")],\n)";
    let error = check("unknown_material", text, ErrorKind::Value, "particles[0].material", (3, 57));
    assert!(error.message().ends_with("did you mean `sand`?"));
}

#[test]
fn interactions_name_declared_materials_once_each() {
    let text = "Scene(\n    materials: [(name: \"sand\"), (name: \"steel\")],\n    interactions: [(materials: (\"sand\", \"stel\"), law: OverlapArea(mu: 0.3))],\n)";
    let error = check("unknown_interaction_material", text, ErrorKind::Value, "interactions[0].materials.1", (3, 41));
    assert!(error.message().ends_with("did you mean `steel`?"), "{}", error.message());
    let text = "Scene(\n    materials: [(name: \"sand\"), (name: \"steel\")],\n    interactions: [\n        (materials: (\"sand\", \"steel\"), law: OverlapArea(mu: 0.3)),\n        (materials: (\"steel\", \"sand\"), law: OverlapArea(mu: 0.2)),\n    ],\n)";
    check("duplicate_interaction", text, ErrorKind::Value, "interactions[1].materials", (5, 21));
}

#[test]
fn hertz_needs_the_materials_youngs_modulus_in_pascal() {
    let text = "Scene(\n    materials: [(name: \"steel\")],\n    interactions: [(materials: (\"steel\", \"steel\"), law: Hertz())],\n)";
    let error = check("hertz_without_modulus", text, ErrorKind::Value, "interactions[0].law", (3, 57));
    assert!(error.message().contains("`youngs_modulus_pa`"), "{}", error.message());
}

/// A penetration law's numbers are reported at their own fields in the scene's words: `friction: (mu: -0.2)` was
/// reported as the engine's `tangential.mu` at the whole law. A material's own bad modulus is reported once, not again
/// as an effective modulus of 0 at every law that uses it.
#[test]
fn penetration_law_numbers_are_named_by_their_scene_fields() {
    let law = |law: &str| {
        format!(
            "Scene(\n    mass_model: SphereEquivalent,\n    materials: [(name: \"steel\", density_kg_m3: 7850, youngs_modulus_pa: 2e11)],\n    interactions: [(materials: (\"steel\", \"steel\"), law: {law})],\n)"
        )
    };
    for (text, path) in [
        ("Hertz(friction: (mu: -0.2))", "interactions[0].law.friction.mu"),
        ("Hertz(friction: (mu: 0.2, damping_ratio: -1))", "interactions[0].law.friction.damping_ratio"),
        ("Hertz(friction: (mu: 0.2, stiffness: Ratio(-1)))", "interactions[0].law.friction.stiffness.0"),
        ("Hertz(damping: Restitution(1.5))", "interactions[0].law.damping.0"),
        ("Hertz(damping: Ratio(-0.1))", "interactions[0].law.damping.0"),
        ("Hertz(damping: PowerLaw(a: 1, b: 0, c: 0.3))", "interactions[0].law.damping.b"),
        ("Hertz(damping: Table([]))", "interactions[0].law.damping.0"),
        ("Hertz(damping: Table([(0, 0.9), (0, 0.8)]))", "interactions[0].law.damping.0[1]"),
        ("Hertz(damping: Table([(0, 1.5)]))", "interactions[0].law.damping.0[0]"),
        ("Hertz(rolling: (mu_r: -1))", "interactions[0].law.rolling.mu_r"),
        ("Linear(stiffness_n_m: 0)", "interactions[0].law.stiffness_n_m"),
    ] {
        let error = error_of(&law(text));
        assert_eq!((error.kind(), error.path()), (ErrorKind::Value, path), "{text}: {}", error.render_plain());
        assert!(error.location().is_some(), "{text}: not located");
        assert!(!error.render_plain().contains("tangential.") && !error.render_plain().contains("normal."), "{text}");
    }
    let text = law("Hertz()").replace("youngs_modulus_pa: 2e11", "youngs_modulus_pa: NaN");
    let report = error_of(&text).render_plain();
    assert!(report.contains("materials[0].youngs_modulus_pa"), "{report}");
    assert!(!report.contains("effective_modulus"), "{report}");
}

#[test]
fn densities_follow_the_mass_model() {
    let text = "Scene(\n    materials: [(name: \"steel\", density_kg_m3: 7850)],\n)";
    check("density_of_the_other_model", text, ErrorKind::Value, "materials[0].density_kg_m3", (2, 48));
    let text = "Scene(\n    mass_model: SphereEquivalent,\n    materials: [(name: \"steel\")],\n)";
    check("sphere_density_missing", text, ErrorKind::Value, "materials[0].name", (3, 24));
}

#[test]
fn wall_shapes_are_refused_for_particles() {
    let text = "Scene(\n    particles: [(shape: Capsule(length_m: 0.01, radius_m: 0.002))],\n)";
    let error = check("capsule_particle", text, ErrorKind::Value, "particles[0].shape", (2, 25));
    assert!(error.message().contains("can only be a wall"), "{}", error.message());
    // "a inner circle" was the message's article.
    let error = error_of("Scene(particles: [(shape: InnerCircle(radius_m: 0.05))])");
    assert!(error.message().starts_with("an inner circle can only be a wall, not a particle"), "{}", error.message());
}

#[test]
fn time_steps_above_the_bound_name_the_limiting_particle() {
    let text =
        "Scene(\n    run: (time_step_s: 1e-4),\n    particles: [(shape: Regular(corners: 6, radius_m: 0.002))],\n)";
    let error = check("unsafe_time_step", text, ErrorKind::TimeStep, "run.time_step_s", (2, 24));
    // A regular hexagon of circumradius 2 mm has inscribed radius √3 mm: (π/10)·sqrt(π·3e-6·5000/1e7) = 2.157e-5 s,
    // where a run is refused; the stable bound offered is that of two hexagons face on (docs/model.md,
    // "Automatic Δt").
    assert!(error.message().contains("above 2.157e-5 s"), "{}", error.message());
    assert!(error.message().contains("stable bound is 6.708e-6 s"), "{}", error.message());
    assert_eq!(error.related_errors().len(), 1);
    assert_eq!(error.related_errors()[0].path(), "particles[0]");
    // Allowed explicitly, the same scene builds.
    let allowed = text.replace("time_step_s: 1e-4", "time_step_s: 1e-4, allow_unsafe_time_step: true");
    assert!(Scene::from_str(&allowed, "ok.ron").unwrap().build().is_ok());
}

#[test]
fn overlapping_initial_particles_are_refused() {
    let text = "Scene(\n    particles: [\n        (shape: Square(side_m: 0.01)),\n        (shape: Square(side_m: 0.01), position_m: (0.008, 0)),\n    ],\n)";
    let error = check("overlap", text, ErrorKind::Overlap, "particles[1]", (4, 9));
    assert!(error.message().contains("20.00 %"), "{}", error.message());
}

/// A chamber (an inner-circle wall) is solid everywhere outside its circle, also beyond its bounding box, where the
/// broadphase never pairs it with anything: a particle placed there used to fall freely through the "solid".
#[test]
fn a_particle_outside_a_chamber_is_refused_as_lying_in_its_wall() {
    let text = "Scene(\n    walls: [Wall(shape: InnerCircle(radius_m: 0.05), position_m: (1, 0))],\n    particles: [(shape: Disk(radius_m: 0.005))],\n)";
    let error = check("outside_chamber", text, ErrorKind::Overlap, "particles[0]", (3, 17));
    assert!(error.message().contains("100.00 %") && error.message().contains("`walls[0]`"), "{}", error.message());
    let inside = text.replace("position_m: (1, 0)", "position_m: (0, 0)");
    assert!(Scene::from_str(&inside, "ok.ron").unwrap().build().is_ok());
}

/// A particle whose size gives no usable mass (a radius of 1e-300 m or 1e300 m) blew up at step 1 with advice to
/// reduce the time step, and one that starts faster than the first step allows stopped there: both are refused at
/// the entry, so that `check` does not pass what `run` refuses at its start.
#[test]
fn particles_the_first_step_would_lose_are_refused_at_their_entry() {
    for radius in ["1e-300", "1e300"] {
        let text = format!("Scene(\n    particles: [(shape: Disk(radius_m: {radius}))],\n)");
        let error = error_of(&text);
        assert_eq!((error.kind(), error.path()), (ErrorKind::Value, "particles[0]"), "{}", error.render_plain());
        assert!(error.message().contains("not positive finite numbers"), "{}", error.message());
    }
    let text = "Scene(\n    particles: [(shape: Disk(radius_m: 0.005), velocity_m_s: (1000, 0))],\n)";
    let error = error_of(text);
    assert_eq!((error.kind(), error.path()), (ErrorKind::Value, "particles[0]"), "{}", error.render_plain());
    assert!(error.message().contains("it starts at 1000 m/s and would move"), "{}", error.message());
    let slower = text.replace("(1000, 0)", "(10, 0)");
    assert!(Scene::from_str(&slower, "ok.ron").unwrap().build().is_ok());
    // A spin alone: the message said "starts at 0 m/s and would move 1.4e7 m" without a word of the spin.
    let spinning = "Scene(\n    particles: [(shape: Disk(radius_m: 0.005), angular_velocity_rad_s: 1e15)],\n)";
    let error = error_of(spinning);
    assert!(
        error.message().contains(
            "it starts at 0 m/s spinning at 1e15 rad/s (`angular_velocity_rad_s`; its outermost \
             point at 5.000e12 m/s)"
        ),
        "{}",
        error.message()
    );
}

/// A particle that starts outside `run.domain` was removed at the first step without a word: the run had one particle
/// fewer than the scene. It is refused, once per entry (a block half outside gives one error).
#[test]
fn particles_starting_outside_the_domain_are_refused() {
    let text = "Scene(\n    run: (domain: (x_range_m: (-0.1, 0.1), y_range_m: (0, 0.2))),\n    particles: [(shape: \
                Disk(radius_m: 0.005), position_m: (0.15, 0.05))],\n    blocks: [(x_range_m: (0, 0.3), y_range_m: (0.05, \
                0.06), grid_spacing_m: (0.02, 0.02), shape: (semi_axes_m: (0.005, 0.005)))],\n)";
    let error = error_of(text);
    assert_eq!((error.kind(), error.path()), (ErrorKind::Value, "particles[0]"), "{}", error.render_plain());
    assert!(error.message().contains("starts at (0.15, 0.05) m, outside `run.domain`"), "{}", error.message());
    let related: Vec<&str> = error.related_errors().iter().map(|e| e.path()).collect();
    assert_eq!(related, ["blocks[0]"], "{}", error.render_plain());
    let inside = text.replace("(0.15, 0.05)", "(0.05, 0.05)").replace("(0, 0.3)", "(0, 0.09)");
    assert!(Scene::from_str(&inside, "ok.ron").unwrap().build().is_ok());
}

/// A Poisson ratio outside (−1, 0.5] gave a negative or infinite E* or G*, reported against the interaction law that
/// used it ("got 0"); a stepped change of g with `steps: 0` acted as one step. Both are refused at their field.
#[test]
fn poisson_ratios_and_gravity_steps_out_of_range_are_refused_at_their_field() {
    for nu in ["1", "-1", "0.6", "NaN"] {
        let text = format!(
            "Scene(\n    mass_model: SphereEquivalent,\n    materials: [(name: \"steel\", density_kg_m3: 7850, \
             youngs_modulus_pa: 2e11, poisson_ratio: {nu})],\n    interactions: [(materials: (\"steel\", \"steel\"), \
             law: Hertz(damping: Restitution(0.9)))],\n)"
        );
        let error = error_of(&text);
        assert_eq!(error.path(), "materials[0].poisson_ratio", "ν = {nu}: {}", error.render_plain());
        assert!(error.message().contains("lies in (−1, 0.5]"), "{}", error.message());
        let steel = text.replace(&format!("poisson_ratio: {nu}"), "poisson_ratio: 0.5");
        assert!(Scene::from_str(&steel, "ok.ron").unwrap().validate().is_ok());
    }
    let text =
        "Scene(\n    gravity: Varying(profile: Step, from_m_s2: 9.81, to_m_s2: 0, window_s: (0, 1), steps: 0),\n)";
    let error = error_of(text);
    assert_eq!(error.path(), "gravity.steps", "{}", error.render_plain());
    assert!(Scene::from_str(&text.replace("steps: 0", "steps: 1"), "ok.ron").unwrap().validate().is_ok());
    let linear = text.replace("Step", "Linear");
    assert!(Scene::from_str(&linear, "ok.ron").unwrap().validate().is_ok(), "a linear change has no steps");
}

/// A particle 1e-20 m across got an automatic Δt of about 1e-23 s, below the femtosecond a scene may give itself.
/// It is refused at the entry that needs it.
#[test]
fn an_automatic_time_step_below_a_femtosecond_is_refused_at_the_particle() {
    let text = "Scene(\n    particles: [(shape: Disk(radius_m: 0.005)), (shape: Disk(radius_m: 1e-20), position_m: (0.1, 0))],\n)";
    let error = error_of(text);
    assert_eq!((error.kind(), error.path()), (ErrorKind::TimeStep, "particles[1]"), "{}", error.render_plain());
    assert!(error.message().contains("below the shortest a scene may have (1e-15 s)"), "{}", error.message());
    assert!(Scene::from_str(&text.replace("1e-20", "1e-4"), "ok.ron").unwrap().build().is_ok());
}

/// A drag spring of 1e15 N/m stopped the run at step 1 with advice that did not name the spring: its stiffness was not
/// in the time-step bound. It is now, with the effective mass at the point it pulls: the automatic Δt follows it, and a
/// given Δt above it is refused with the spring as the limiting entry.
#[test]
fn a_stiff_drag_spring_bounds_the_time_step() {
    let text = "Scene(\n    gravity: Constant(0),\n    particles: [(shape: Square(side_m: 0.01), drag_spring: \
                (stiffness_n_m: 1e9, fixing_point_m: (0.005, 0), speed_m_s: 0.01))],\n)";
    let scene = Scene::from_str(text, "spring.ron").unwrap();
    let summary = scene.summary().unwrap();
    assert_eq!(summary.limiting_entry.as_deref(), Some("particles[0].drag_spring.stiffness_n_m"));
    // m = 5000 kg/m² · 1e-4 m² = 0.5 kg, I = m·a²/6; at the middle of an edge 1/m_eff = 1/m + (a/2)²/I = 2.5/m.
    let bound = std::f64::consts::PI / 10.0 * (0.2f64 / 1e9).sqrt();
    assert!((summary.stable_time_step_s.unwrap() / bound - 1.0).abs() < 1e-12, "{summary:?}");
    assert!(summary.time_step_s <= 0.15 * bound);
    let mut world = scene.build().unwrap();
    for _ in 0..2000 {
        world.step().unwrap();
    }
    let given = text.replace("gravity: Constant(0),", "gravity: Constant(0),\n    run: (time_step_s: 1e-5),");
    let error = error_of(&given);
    assert_eq!((error.kind(), error.path()), (ErrorKind::TimeStep, "run.time_step_s"), "{}", error.render_plain());
    let limiting: Vec<&str> = error.related_errors().iter().map(|e| e.path()).collect();
    assert_eq!(limiting, ["particles[0].drag_spring.stiffness_n_m"], "{}", error.render_plain());
}

/// A start of more than a million particles is refused at the entry that gives the most, naming every one.
#[test]
fn too_many_particles_at_the_start_are_refused_at_the_largest_entry() {
    let block = |height: f64| {
        format!(
            "(x_range_m: (0, 0.8), y_range_m: (0, {height}), grid_spacing_m: (0.001, 0.001), shape: (semi_axes_m: \
             (0.0004, 0.0004)))"
        )
    };
    let text = format!("Scene(\n    blocks: [{}, {}],\n)", block(0.5), block(1.0));
    let error = error_of(&text);
    assert_eq!((error.kind(), error.path()), (ErrorKind::Value, "blocks[1]"), "{}", error.render_plain());
    assert!(error.message().contains("from `blocks[1]`, ") && error.message().contains("from `blocks[0]`)"));
}

/// Two walls with the same outline at the same place (a floor given twice) made every contact with it twice as stiff:
/// contacts lasted 1/√2 as long, without a word. They are refused; walls that only touch or overlap are not.
#[test]
fn a_wall_given_twice_is_refused() {
    let floor = "Wall(shape: Rectangle(width_m: 0.2, height_m: 0.01), position_m: (0, -0.005))";
    let text = format!("Scene(\n    walls: [\n        {floor},\n        {floor},\n    ],\n)");
    let error = error_of(&text);
    assert_eq!((error.kind(), error.path()), (ErrorKind::Value, "walls[1]"), "{}", error.render_plain());
    assert!(error.message().contains("lies exactly on `walls[0]`"), "{}", error.message());
    let shifted = text.replacen("position_m: (0, -0.005)", "position_m: (0.1, -0.005)", 1);
    assert!(Scene::from_str(&shifted, "ok.ron").unwrap().build().is_ok());
}

/// A material's name is printed by `check` and written into the events and the dumps: a line break or a character that
/// reverses the text would break those lines or make them read wrongly.
#[test]
fn material_names_with_invisible_characters_are_refused() {
    for name in ["sand\\nstone", "sand\\u{202E}enots"] {
        let text = format!("Scene(\n    materials: [(name: \"{name}\")],\n)");
        let error = error_of(&text);
        assert_eq!((error.kind(), error.path()), (ErrorKind::Value, "materials[0].name"), "{}", error.render_plain());
        assert!(error.message().contains("invisible character U+"), "{}", error.message());
        // The scene's own name is printed by `check` and written into recordings as well.
        let error = error_of(&format!("Scene(\n    name: \"{name}\",\n)"));
        assert_eq!((error.kind(), error.path()), (ErrorKind::Value, "name"), "{}", error.render_plain());
    }
}

#[test]
fn all_errors_of_a_pass_are_reported_together() {
    let text = "Scene(\n    run: (end_time_s: -1),\n    materials: [(name: \"sand\", gamma: -0.5)],\n    heating: (window_s: (2, 1)),\n)";
    let error = check("several", text, ErrorKind::Value, "run.end_time_s", (2, 23));
    let paths: Vec<&str> = error.related_errors().iter().map(|e| e.path()).collect();
    assert_eq!(paths, ["heating.window_s", "materials[0].gamma"]);
    assert_eq!(error.related_errors()[1].location().map(|l| (l.line, l.column)), Some((3, 39)));
}

#[test]
fn unreadable_files_are_io_errors() {
    let error = Scene::from_path("/nonexistent/scene.ron").err().unwrap();
    assert_eq!(error.kind(), ErrorKind::Io);
    assert!(error.to_string().contains("/nonexistent/scene.ron"));
}

#[test]
fn errors_far_along_a_long_line_are_shown_without_the_snippet() {
    // miette's renderer panics for underlines past column 65,535; the message keeps file:line:column instead.
    let text = format!("Scene(description: \"{}\", bogus: 1)", "x".repeat(70_000));
    let error = error_of(&text);
    assert_eq!(error.kind(), ErrorKind::UnknownName);
    assert_eq!(error.path(), "bogus");
    let location = error.location().cloned().expect("located");
    assert_eq!((location.line, location.column), (1, 70_024));
    let rendered = error.render_plain();
    assert!(rendered.contains("bad.ron:1:70024: `bogus`: unknown field `bogus`"), "{rendered}");
    assert!(rendered.len() < 2_000, "no 70,000-character snippet: {} bytes", rendered.len());
    // The same error on a short line still shows its snippet.
    let short = error_of("Scene(description: \"x\", bogus: 1)").render_plain();
    assert!(short.contains("╭─[bad.ron:1:25]"), "{short}");
    // Related errors far along a line are rendered the same way.
    let several = format!(
        "Scene(description: \"{}\", run: (end_time_s: -1, seed: 1), materials: [(name: \"a\", mu: -1)])",
        "y".repeat(70_000)
    );
    let rendered = error_of(&several).render_plain();
    assert!(rendered.contains("`materials[0].mu`"), "{rendered}");
}

#[test]
fn long_lists_of_errors_are_cut_with_a_count_of_the_rest() {
    let materials: Vec<String> = (0..5_000).map(|i| format!("    (name: \"m{i}\", mu: -1),")).collect();
    let text = format!("Scene(\n  materials: [\n{}\n  ],\n)", materials.join("\n"));
    let error = error_of(&text);
    assert_eq!(error.path(), "materials[0].mu");
    assert_eq!(error.related_errors().len(), gc2d_scene::error::MAX_REPORTED_ERRORS - 1);
    assert_eq!(error.related_errors()[18].path(), "materials[19].mu");
    assert_eq!(error.omitted_errors(), 4_980);
    let rendered = error.render_plain();
    assert!(rendered.contains("× … and 4980 more errors not shown (only the first 20 are listed)"), "{rendered}");
    assert_eq!(rendered.matches("must be a finite number ≥ 0").count(), 20, "{rendered}");
    assert!(rendered.len() < 20_000, "{} bytes", rendered.len());
    // At the limit nothing is cut and no count is shown.
    let twenty = format!("Scene(\n  materials: [\n{}\n  ],\n)", materials[..20].join("\n"));
    let error = error_of(&twenty);
    assert_eq!((error.related_errors().len(), error.omitted_errors()), (19, 0));
    assert!(!error.render_plain().contains("more error"));
}

/// A scene with one source of `interval_s` over `window_s` (and `end_time_s` 1 s).
fn source_scene(interval: &str, window: &str) -> String {
    format!(
        "Scene(\n    sources: [(position_m: (0, 1), window_s: {window}, shape: (semi_axes_m: (0.01, 0.01)),\n        interval_s: {interval})],\n)"
    )
}

#[test]
fn sources_may_not_plan_more_insertions_than_a_scene_may_hold() {
    // 1e-320 s passed validation and made `run` spin forever (t + interval == t); it is now refused at the field.
    let error = check(
        "source_interval",
        &source_scene("1e-320", "(0, inf)"),
        ErrorKind::Value,
        "sources[0].interval_s",
        (3, 21),
    );
    assert_eq!(error.message(), "1e-320 s: the interval between insertions must be a finite time of at least 1e-9 s");
    // 10^9 insertions in the scene's one second.
    let error = check(
        "source_insertions",
        &source_scene("1e-9", "(0, inf)"),
        ErrorKind::Value,
        "sources[0].interval_s",
        (3, 21),
    );
    assert!(
        error.message().starts_with("the source would insert 1e9 particles before the end time 1 s"),
        "{}",
        error.message()
    );
    // The same interval in a window of a millisecond plans 10^6 + 1 insertions, still one too many; 10^-5 s is fine.
    assert!(Scene::from_str(&source_scene("1e-9", "(0, 1e-3)"), "bad.ron").is_err());
    assert!(Scene::from_str(&source_scene("1e-5", "(0, 1e-3)"), "ok.ron").is_ok());
    // Together: two sources of 600,000 insertions each.
    let text = "Scene(\n    run: (end_time_s: 6),\n    sources: [\n        (position_m: (0, 1), window_s: (0, 6), shape: (semi_axes_m: (0.01, 0.01)), interval_s: 1e-5),\n        (position_m: (1, 1), window_s: (0, 6), shape: (semi_axes_m: (0.01, 0.01)), interval_s: 1e-5),\n    ],\n)";
    let error = check("sources_together", text, ErrorKind::Value, "sources", (3, 14));
    assert!(error.message().starts_with("the sources would insert 1200002 particles"), "{}", error.message());
}

#[test]
fn densities_and_gravity_must_be_physically_sensible() {
    // 1e-320 kg/m² made masses 0 and the first step NaN; 1e23 gave an automatic Δt of 4e4 s.
    let text = "Scene(\n    materials: [(name: \"sand\", density_kg_m2: 1e-320)],\n)";
    let error = check("tiny_density", text, ErrorKind::Value, "materials[0].density_kg_m2", (2, 47));
    assert!(error.message().starts_with("1e-320 kg/m²: the area density must lie between 0.001 and 100000 kg/m²"));
    let text = "Scene(\n    materials: [(name: \"sand\", density_kg_m2: 1e23)],\n)";
    assert_eq!(error_of(text).path(), "materials[0].density_kg_m2");
    let text =
        "Scene(\n    mass_model: SphereEquivalent,\n    materials: [(name: \"steel\", density_kg_m3: 1e-320)],\n)";
    check("tiny_sphere_density", text, ErrorKind::Value, "materials[0].density_kg_m3", (3, 48));
    // Gravity of 1e308 m/s² overflowed to NaN at the first step.
    let text = "Scene(\n    gravity: Constant(1e308),\n)";
    let error = check("huge_gravity", text, ErrorKind::Value, "gravity", (2, 23));
    assert_eq!(error.message(), "1e308 m/s²: gravity must lie between -1e7 and 1e7 m/s²");
    let text = "Scene(\n    gravity: Varying(profile: Linear, from_m_s2: 9.81, to_m_s2: -2e7, window_s: (0, 1)),\n)";
    assert_eq!(error_of(text).path(), "gravity.to_m_s2");
    // The edges of the ranges are allowed.
    let edges = "Scene(\n    gravity: Constant(-1e7),\n    materials: [(name: \"a\", density_kg_m2: 1e-3), (name: \"b\", density_kg_m2: 1e5)],\n)";
    assert!(Scene::from_str(edges, "ok.ron").is_ok());
}

#[test]
fn tiny_time_steps_are_refused_at_the_field() {
    // The engine refused 1e-320 s, located at `Scene(` and printed with 330 digits.
    let text = "Scene(\n    run: (time_step_s: 1e-320),\n)";
    let error = check("tiny_time_step", text, ErrorKind::Value, "run.time_step_s", (2, 24));
    assert!(error.message().starts_with("1e-320 s: the time step must be a finite time of at least 1e-15 s"));
    assert!(Scene::from_str("Scene(run: (time_step_s: 1e-15))", "ok.ron").is_ok());
}

#[test]
fn extreme_numbers_are_printed_short() {
    let text = "Scene(\n    run: (end_time_s: -1e-300, frames_per_second: 1e300, max_overlap_fraction: -1e-320),\n    materials: [(name: \"a\", mu: -1e-310)],\n    heating: (window_s: (0, 1), amplitude: -1e30),\n)";
    let error = error_of(text);
    let messages: Vec<&str> =
        std::iter::once(error.message()).chain(error.related_errors().iter().map(|e| e.message())).collect();
    assert_eq!(
        messages,
        [
            "-1e-300: must be a finite number ≥ 0",
            "-1e-320: must be a positive finite number",
            "-1e30: must be a finite number above −1 (particles cannot shrink to nothing)",
            "-1e-310: the friction coefficient μ must be a finite number ≥ 0",
        ]
    );
}

#[test]
fn invalid_utf8_is_located_at_its_first_byte() {
    let dir = std::env::temp_dir().join(format!("gc2d-scene-utf8-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bad.ron");
    std::fs::write(&path, b"Scene(\n    name: \"ab\xff\xfe\",\n)").unwrap();
    let error = Scene::from_path(&path).err().unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(error.kind(), ErrorKind::Syntax, "{}", error.render_plain());
    assert_eq!(error.path(), "name");
    let location = error.location().cloned().expect("located");
    assert_eq!((location.line, location.column), (2, 14));
    assert_eq!(error.message(), "invalid UTF-8 at byte 20 (0xff): scene files are UTF-8 text");
    insta::assert_snapshot!("invalid_utf8", error.render_plain().replace(&path.display().to_string(), "bad.ron"));
}

#[test]
fn youngs_moduli_must_be_physically_sensible() {
    // 1e-320 N/m gave an infinite automatic Δt and 1e300 N/m one of 5.6e-152 s: both were refused by the engine at
    // `Scene(`, the second printed with 150 digits.
    let text = "Scene(\n    materials: [(name: \"sand\", youngs_modulus_n_m: 1e-320)],\n)";
    let error = check("tiny_youngs_modulus", text, ErrorKind::Value, "materials[0].youngs_modulus_n_m", (2, 52));
    assert!(error.message().starts_with("1e-320 N/m: Young's modulus E must lie between 1 and 1e13 N/m"));
    let text = "Scene(\n    materials: [(name: \"sand\", youngs_modulus_n_m: 1e300)],\n)";
    assert_eq!(error_of(text).path(), "materials[0].youngs_modulus_n_m");
    let text = "Scene(\n    materials: [(name: \"steel\", youngs_modulus_pa: 1e300)],\n)";
    let error = error_of(text);
    assert_eq!(
        (error.path(), error.message()),
        ("materials[0].youngs_modulus_pa", "1e300 Pa: Young's modulus must lie between 1000 and 1e13 Pa")
    );
    let text = "Scene(\n    materials: [(name: \"a\")],\n    interactions: [(materials: (\"a\", \"a\"), law: OverlapArea(youngs_modulus_n_m: 1e-300))],\n)";
    assert_eq!(error_of(text).path(), "interactions[0].law.youngs_modulus_n_m");
    let edges =
        "Scene(\n    materials: [(name: \"a\", youngs_modulus_n_m: 1), (name: \"b\", youngs_modulus_n_m: 1e13)],\n)";
    assert!(Scene::from_str(edges, "ok.ron").is_ok());
}

#[test]
fn a_time_step_the_integrator_cannot_use_is_located_at_the_field() {
    // Δt = 1e100 s passes validation and, with `allow_unsafe_time_step`, the bound; the engine refuses it (Δt⁵
    // overflows). The error was located at `Scene(` and printed the step with 101 digits.
    let text = "Scene(\n    run: (time_step_s: 1e100, allow_unsafe_time_step: true),\n    particles: [(shape: Square(side_m: 0.01))],\n)";
    let error = check("unusable_time_step", text, ErrorKind::TimeStep, "run.time_step_s", (2, 24));
    assert!(error.message().starts_with("the time step 1e100 s is not usable"), "{}", error.message());
}

#[test]
fn check_prints_extreme_numbers_short() {
    let text = "Scene(\n    run: (end_time_s: 1e300),\n    materials: [(name: \"a\", gamma: 1e300, mu: 1e-320)],\n)";
    let summary = Scene::from_str(text, "big.ron").unwrap().summary().unwrap().to_string();
    assert!(summary.contains("γ = 1e300, μ = 1e-320"), "{summary}");
    assert!(summary.contains("end time: 1e300 s ("), "{summary}");
    assert!(summary.len() < 1_000, "{summary}");
}

/// An overlap with a wall builder's piece or a block's particle named only the entries (`walls[0]`, `blocks[0]`), while
/// events.csv and `export` name the bodies (`walls[0] #1`, `blocks[0] #3`): a Silo makes a floor and two side walls.
#[test]
fn start_overlaps_name_the_piece_and_the_particle_as_the_outputs_do() {
    let text = "Scene(\n    walls: [Silo(x_range_m: (-0.05, 0.05), y_range_m: (0.0, 0.2), thickness_m: 0.005)],\n    \
                blocks: [(x_range_m: (-0.06, -0.02), y_range_m: (0.02, 0.03), grid_spacing_m: (0.008, 0.008), \
                shape: (semi_axes_m: (0.002, 0.002), corners: 6))],\n)";
    let error = error_of(text);
    assert_eq!((error.kind(), error.path()), (ErrorKind::Overlap, "blocks[0]"), "{}", error.render_plain());
    assert!(error.message().contains("`blocks[0] #1` and `walls[0] #1`"), "{}", error.message());
}

/// The located error of `text` as `bad.ron`, with its kind, path and file:line:column checked.
fn located_error(text: &str, kind: ErrorKind, path: &str, line_column: (usize, usize)) -> SceneError {
    let error = error_of(text);
    assert_eq!((error.kind(), error.path()), (kind, path), "{}", error.render_plain());
    let location = error.location().cloned().expect("located");
    assert_eq!((location.line, location.column), line_column, "{}", error.render_plain());
    error
}

#[test]
fn a_checkpoint_interval_below_the_given_time_step_is_located_at_its_field() {
    let text = "Scene(run: (time_step_s: 1e-5, checkpoint_interval_s: 1e-7, end_time_s: 0.001))";
    let error = located_error(text, ErrorKind::Value, "run.checkpoint_interval_s", (1, 55));
    assert!(error.message().starts_with("1e-7 s is shorter than the time step, 1e-5 s: "), "{}", error.message());
    assert!(error.render_plain().contains("give at least the time step, 1e-5 s"), "{}", error.render_plain());
}

#[test]
fn a_checkpoint_interval_below_the_automatic_time_step_is_located_at_its_field() {
    let text = "Scene(\n    run: (checkpoint_interval_s: 1e-9),\n    particles: [(shape: Disk(radius_m: 0.01))],\n)";
    let error = located_error(text, ErrorKind::Value, "run.checkpoint_interval_s", (2, 34));
    assert!(error.message().starts_with("1e-9 s is shorter than the time step, "), "{}", error.message());
    assert!(error.message().contains("chosen from the particles"), "{}", error.message());
    // One of a step or more passes.
    let fine = "Scene(run: (time_step_s: 1e-5, checkpoint_interval_s: 1e-5, end_time_s: 0.001))";
    Scene::from_str(fine, "fine.ron").unwrap().build().unwrap();
}

#[test]
fn a_block_whose_neighbours_overlap_gives_one_error_at_its_spacing() {
    let text = "Scene(blocks: [(x_range_m: (0, 0.1), y_range_m: (0, 0.1), grid_spacing_m: (0.004, 0.004), \
                shape: (semi_axes_m: (0.003, 0.003)))])";
    let error = located_error(text, ErrorKind::Overlap, "blocks[0].grid_spacing_m", (1, 75));
    assert!(error.message().starts_with("neighbouring particles of this block overlap"), "{}", error.message());
    assert!(error.message().contains("its grid spacing is (0.004, 0.004) m"), "{}", error.message());
    let report = error.render_plain();
    assert!(report.contains("use a grid spacing of at least (0.006, 0.0052) m"), "{report}");
    assert_eq!(report.matches("gc2d_scene::overlap").count(), 1, "{report}");
}

#[test]
fn overlapping_pairs_list_the_first_20_errors_and_count_the_rest() {
    let particles: Vec<String> = (0..25)
        .flat_map(|k| {
            [0.0, 0.001].map(|dx| format!("(shape: Disk(radius_m: 0.01), position_m: ({}, 0))", k as f64 * 0.1 + dx))
        })
        .collect();
    let text = format!("Scene(particles: [{}])", particles.join(", "));
    let error = error_of(&text);
    assert_eq!(error.kind(), ErrorKind::Overlap);
    assert_eq!(error.omitted_errors(), 5, "{}", error.render_plain());
    assert!(error.render_plain().contains("… and 5 more errors not shown"), "{}", error.render_plain());
}

#[test]
fn a_wall_written_without_its_kind_lists_the_kinds_a_wall_entry_is_written_as() {
    // QA docs 6: `(shape: …)` is how a particle may be written, not a wall; the error gave no help.
    let text = "Scene(walls: [(shape: Square(side_m: 0.1))])";
    let error = located_error(text, ErrorKind::Type, "walls[0]", (1, 15));
    let plain = error.render_plain();
    assert!(plain.contains("a wall entry names its kind before its parentheses: `Wall(…)`"), "{plain}");
    // Elsewhere the help is the general one.
    let plain = error_of("Scene(run: (gravity: (9.81)))").render_plain();
    assert!(!plain.contains("a wall entry"), "{plain}");
}

#[test]
fn a_file_that_ends_with_brackets_open_names_them_where_they_were_opened() {
    // QA docs 6: `Scene(run: (seed: 1)` gave ron's bare "expected comma" at the end of the file.
    let error = error_of("Scene(run: (seed: 1)\n");
    assert_eq!(error.kind(), ErrorKind::Syntax);
    assert_eq!(error.to_string(), "bad.ron:1:1: the file ends before `Scene(` opened at 1:1 is closed");
    // ron reports this one at the last `)`, which closes `run`.
    let error = error_of("Scene(\n    run: (seed: 1,\n)");
    assert_eq!(error.kind(), ErrorKind::Syntax);
    assert_eq!(error.to_string(), "bad.ron:1:1: the file ends before `Scene(` opened at 1:1 is closed");
    assert_eq!(error.help_text(), Some("close it with `)`"));

    let error = error_of("Scene(\n  walls: [Wall(shape: Square(side_m: 0.1)),\n    Wall(shape: Square(side_m: 0.2)\n");
    assert_eq!(error.path(), "walls[1]", "{}", error.render_plain());
    assert_eq!(
        error.to_string(),
        "bad.ron:3:5: `walls[1]`: the file ends before `Wall(` opened at 3:5, `[` opened at 2:10 and `Scene(` opened \
         at 1:1 are closed"
    );
    assert_eq!(error.help_text(), Some("close them with `)])`, innermost first, where their values end"));
}

#[test]
fn a_bracket_left_open_inside_the_file_is_not_told_as_the_end_of_the_file() {
    // The scan stops at `;` before the end: ron's own message stands.
    let error = error_of("Scene(run: (seed: 1; name: \"x\"\n");
    assert!(!error.message().contains("the file ends"), "{}", error.render_plain());
    // Brackets inside strings and comments do not count.
    let error = error_of("// (\nScene(name: \"a(b[\", /* { */ run: (seed: 1)\n");
    assert_eq!(error.to_string(), "bad.ron:2:1: the file ends before `Scene(` opened at 2:1 is closed");
}
