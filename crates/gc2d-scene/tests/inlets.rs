//! Inlets and outlets in scenes (issue 15 item 3): the exact feed of a built scene, located refusals of bad inlets
//! and outlets, the start-phase warning, and a scene copy that reads back equal.

use gc2d_scene::{ErrorKind, Scene, SceneError};

/// A scene with one inlet along the floor feeding upward (`inlet` is the inlet entry's inner fields) and an outlet
/// across the top, no gravity, Δt = 1 ms.
fn scene_text(inlet: &str) -> String {
    format!(
        "Scene(\n    run: (time_step_s: 1e-3, end_time_s: 1.0, seed: 3),\n    gravity: Constant(0.0),\n    materials: [(name: \"glass\", density_kg_m2: 1e4, youngs_modulus_n_m: 1e5)],\n    inlets: [\n        ({inlet}),\n    ],\n    outlets: [(name: \"top\", from_m: (0.05, 0.3), to_m: (-0.05, 0.3))],\n)\n"
    )
}

const GOOD: &str = "name: \"feed\", from_m: (-0.05, 0.0), to_m: (0.05, 0.0), rate_per_s: 10, velocity_m_s: (0.0, 1.0),\n         shape: (semi_axes_m: (0.01, 0.01), disk: true), material: \"glass\"";

fn error_of(text: &str) -> SceneError {
    match Scene::from_str(text, "bad.ron").and_then(|scene| scene.build().map(drop)) {
        Ok(()) => panic!("expected an error for {text}"),
        Err(error) => error,
    }
}

#[test]
fn ten_per_second_for_one_second_feed_ten_and_the_outlet_drains_them() {
    let scene = Scene::from_str(&scene_text(GOOD), "feed.ron").unwrap();
    assert!(scene.warnings().is_empty());
    let mut world = scene.build().unwrap();
    assert_eq!(world.inlets()[0].inlet().name, "feed");
    assert_eq!(world.outlets()[0].outlet().name, "top");
    let mut steps_of_injection = Vec::new();
    for _ in 0..1000 {
        let before = world.stats().injected;
        world.step().unwrap();
        let s = world.stats();
        if s.injected > before {
            steps_of_injection.push(world.steps());
        }
        assert_eq!(s.injected, world.bodies().particles().count() as u64 + s.removed_at_outlets);
    }
    assert_eq!(steps_of_injection, (0..10).map(|k| 1 + 100 * k).collect::<Vec<u64>>());
    // At 1 m/s a particle crosses y = 0.3 m on its 301st step: those fed at steps 1 to 601 are gone.
    assert_eq!(world.outlets()[0].counters().removed, 7);
    assert_eq!(world.bodies().particles().count(), 3);
}

#[test]
fn an_inlet_whose_velocity_points_out_of_the_domain_is_refused_at_that_field() {
    let text = scene_text(&GOOD.replace("velocity_m_s: (0.0, 1.0)", "velocity_m_s: (0.5, -1.0)"));
    let error = error_of(&text);
    assert_eq!(error.kind(), ErrorKind::Value);
    assert_eq!(error.path(), "inlets[0].velocity_m_s", "{}", error.render_plain());
    let location = error.location().expect("located");
    assert_eq!((location.line, location.column), (6, 95), "{}", error.render_plain());
    assert!(error.message().contains("does not point into the domain"), "{}", error.message());
}

#[test]
fn bad_segments_rates_materials_and_names_are_refused_where_they_are_written() {
    let cases = [
        (GOOD.replace("to_m: (0.05, 0.0)", "to_m: (-0.05, 0.0)"), "inlets[0].to_m", "zero length"),
        (GOOD.replace("rate_per_s: 10", "rate_per_s: 0"), "inlets[0].rate_per_s", "positive number"),
        (GOOD.replace("rate_per_s: 10", "rate_per_s: 1e9"), "inlets[0].rate_per_s", "more than the"),
        (GOOD.replace("\"glass\"", "\"glas\""), "inlets[0].material", "glass"),
        (GOOD.replace("\"feed\"", "\"feed,2\""), "inlets[0].name", "column name"),
        // An inlet without a name goes by its index: named `1` beside the unnamed inlets[1], or unnamed beside one
        // named `0`, the time series had the same columns twice.
        (
            format!("{}), ({}", GOOD.replace("\"feed\"", "\"1\""), GOOD.replace("name: \"feed\", ", "")),
            "inlets[1]",
            "go by its index, `1`",
        ),
        (
            format!("{}), ({}", GOOD.replace("name: \"feed\", ", ""), GOOD.replace("\"feed\"", "\"0\"")),
            "inlets[1].name",
            "used twice",
        ),
    ];
    for (inlet, path, words) in cases {
        let error = error_of(&scene_text(&inlet));
        assert_eq!(error.path(), path, "{}", error.render_plain());
        assert!(error.location().is_some());
        assert!(error.render_plain().contains(words), "{}", error.render_plain());
    }
    let text = scene_text(GOOD).replace("to_m: (-0.05, 0.3)", "to_m: (0.05, 0.3)");
    assert_eq!(error_of(&text).path(), "outlets[0].to_m");
}

#[test]
fn a_slow_inlet_is_warned_about_and_still_runs() {
    let slow = GOOD.replace("velocity_m_s: (0.0, 1.0)", "velocity_m_s: (3.0, 0.1)");
    let scene = Scene::from_str(&scene_text(&slow), "slow.ron").unwrap();
    let warnings = scene.warnings();
    assert_eq!(warnings.len(), 1);
    let field = scene_text(&slow).lines().position(|l| l.contains("velocity_m_s: (3.0, 0.1)")).unwrap() + 1;
    let place = format!("slow.ron:{field}:");
    assert!(warnings[0].starts_with(&place), "{warnings:?} should start with {place}");
    assert!(warnings[0].contains(": inlets[0].velocity_m_s: ") && warnings[0].contains("0.2 m/s"), "{warnings:?}");
    assert!(scene.build().is_ok());
}

#[test]
fn the_written_scene_reads_back_equal() {
    let scene = Scene::from_str(&scene_text(GOOD), "feed.ron").unwrap();
    let copy = Scene::from_str(&scene.to_ron_string().unwrap(), "copy.ron").unwrap();
    assert_eq!(copy.inlets, scene.inlets);
    assert_eq!(copy.outlets, scene.outlets);
    assert_eq!(copy.inlets[0].window_s, [0.0, f64::INFINITY]);
}

/// A source's drop line or an inlet's segment inside a wall fed nothing there: a line wholly inside walls is refused
/// at the field that places it, one partly inside is warned about with the share and the wall.
#[test]
fn feed_lines_inside_walls_are_refused_or_warned_about() {
    let block = "walls: [Wall(shape: Rectangle(width_m: 0.2, height_m: 0.1), position_m: (0.1, 0.5))],";
    let scene_with = |feeds: &str| format!("Scene(\n    {block}\n    {feeds}\n)\n");
    let source = |x: f64| {
        format!("sources: [(position_m: ({x}, 0.5), width_m: 0.1, shape: (semi_axes_m: (0.005, 0.005), disk: true))],")
    };
    let buried = scene_with(&source(0.1));
    let error = error_of(&buried);
    assert_eq!((error.kind(), error.path()), (ErrorKind::Value, "sources[0].position_m"), "{}", error.render_plain());
    assert!(error.message().contains("drop line lies entirely inside `walls[0]`"), "{}", error.message());
    let half = Scene::from_str(&scene_with(&source(0.0)), "half.ron").unwrap();
    assert!(half.build().is_ok());
    let warnings = half.warnings();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(warnings[0].starts_with("half.ron:3:"), "{warnings:?}");
    assert!(
        warnings[0].contains("sources[0].position_m: 50 % of its drop line lies inside `walls[0]`"),
        "{warnings:?}"
    );
    assert!(Scene::from_str(&scene_with(&source(-0.1)), "free.ron").unwrap().warnings().is_empty());
    // A source dropping above the pile is not checked: its height changes as the pile grows.
    let above = scene_with(&source(0.1).replace("width_m", "height: AboveHighest, width_m"));
    assert!(Scene::from_str(&above, "above.ron").unwrap().build().is_ok());
    let inlet = "inlets: [(from_m: (0.05, 0.5), to_m: (0.15, 0.5), rate_per_s: 10, velocity_m_s: (0, 1), \
                 shape: (semi_axes_m: (0.005, 0.005), disk: true))],";
    let error = error_of(&scene_with(inlet));
    assert_eq!(error.path(), "inlets[0].from_m", "{}", error.render_plain());
    assert!(error.message().contains("segment lies entirely inside `walls[0]`"), "{}", error.message());
}

/// A line along a wall's surface (a source on a floor, an inlet along a side) is outside the wall wherever it lies:
/// which side round-off put its points on decided between a refusal, a warning of 3.5 to 90 % and nothing.
#[test]
fn a_feed_line_on_a_wall_surface_is_outside_it() {
    for (wall_y, source_y) in [(-0.005, 0.0), (0.095, 0.1), (0.005, 0.01), (1e3 - 0.005, 1e3)] {
        for x in [0.0, 0.3, -7.1] {
            let text = format!(
                "Scene(\n    walls: [Wall(shape: Rectangle(width_m: 0.06, height_m: 0.01), position_m: ({x}, {wall_y}))],\n    \
                 sources: [(position_m: ({x}, {source_y}), width_m: 0.06, shape: (semi_axes_m: (0.001, 0.001)))],\n)"
            );
            let scene = Scene::from_str(&text, "floor.ron").unwrap();
            assert!(scene.build().is_ok(), "wall at ({x}, {wall_y})");
            assert!(scene.warnings().is_empty(), "wall at ({x}, {wall_y}): {:?}", scene.warnings());
        }
    }
    // A line wholly inside two walls names both, with their shares.
    let text = "Scene(\n    walls: [Wall(shape: Rectangle(width_m: 0.1, height_m: 0.1), position_m: (-0.05, 0)), \
                Wall(shape: Rectangle(width_m: 0.1, height_m: 0.1), position_m: (0.05, 0))],\n    sources: \
                [(position_m: (0, 0), width_m: 0.08, shape: (semi_axes_m: (0.001, 0.001)))],\n)";
    let error = error_of(text);
    assert!(error.message().contains("inside `walls[0]` (50 %), inside `walls[1]` (50 %)"), "{}", error.message());
}

/// An inlet outside `run.domain` fed particles the domain removed at their first step: 40 injected, 40 removed, and no
/// word from `check` or `run`. A line wholly outside is refused, one partly outside warned about, like a line inside
/// walls; an outlet wholly outside the domain, which can count nothing, is warned about.
#[test]
fn feed_lines_and_outlets_outside_the_domain_are_refused_or_warned_about() {
    let scene_with = |domain: &str| {
        scene_text(GOOD).replace("seed: 3)", &format!("seed: 3, domain: (x_range_m: {domain}, y_range_m: (0.01, 1)))"))
    };
    let outside = scene_with("(-1, 1)");
    let error = error_of(&outside);
    assert_eq!((error.kind(), error.path()), (ErrorKind::Value, "inlets[0].from_m"), "{}", error.render_plain());
    assert!(error.message().contains("segment lies entirely outside `run.domain`"), "{}", error.message());
    let half = Scene::from_str(&scene_with("(0.0, 1)").replace("(0.01, 1)", "(-1, 1)"), "half.ron").unwrap();
    assert!(half.build().is_ok());
    let warnings = half.warnings();
    assert!(
        warnings.iter().any(|w| w.contains("inlets[0].from_m: 50 % of its segment lies outside `run.domain`")),
        "{warnings:?}"
    );
    let along_a_side = Scene::from_str(&scene_with("(-1, 1)").replace("(0.01, 1)", "(0.0, 1)"), "side.ron").unwrap();
    assert!(along_a_side.build().is_ok() && along_a_side.warnings().is_empty(), "{:?}", along_a_side.warnings());
    let short = Scene::from_str(&scene_with("(-1, 1)").replace("(0.01, 1)", "(-1, 0.2)"), "short.ron").unwrap();
    let warnings = short.warnings();
    assert!(
        warnings.iter().any(|w| w.contains("outlets[0].from_m: its segment lies entirely outside `run.domain`")),
        "{warnings:?}"
    );
}

/// An inlet feeding at 1,000 m/s passed `check`, and the run stopped at the first insertion (travel limit). It is
/// refused at its velocity, as a particle that starts too fast is; with `allow_unsafe_time_step` the run decides.
#[test]
fn an_inlet_too_fast_for_the_time_step_is_refused_at_its_velocity() {
    let fast = GOOD.replace("velocity_m_s: (0.0, 1.0)", "velocity_m_s: (0.0, 20.0)");
    let error = error_of(&scene_text(&fast));
    assert_eq!((error.kind(), error.path()), (ErrorKind::Value, "inlets[0].velocity_m_s"), "{}", error.render_plain());
    assert!(error.message().contains("enter at 20 m/s and would move 2.000e-2 m"), "{}", error.message());
    assert!(error.help_text().is_some_and(|help| help.contains("below 5.000e-4 s")), "{}", error.render_plain());
    let unsafe_text = scene_text(&fast).replace("seed: 3)", "seed: 3, allow_unsafe_time_step: true)");
    assert!(Scene::from_str(&unsafe_text, "unsafe.ron").unwrap().build().is_ok());
    let spinning = GOOD.replace("material:", "angular_velocity_rad_s: 5000, material:");
    let error = error_of(&scene_text(&spinning));
    assert_eq!(error.path(), "inlets[0].velocity_m_s");
    assert!(error.message().contains("enter at 1 m/s spinning at 5000 rad/s"), "{}", error.message());
}

/// An inlet's window starting before the run fed the particles due before t = 0 as a backlog, which `check`'s
/// planned count did not include: refused. A window after the run's end (or an empty one) fed nothing without a word:
/// warned about, for sources too.
#[test]
fn inlet_and_source_windows_that_feed_nothing_or_start_before_the_run_are_told() {
    let early = scene_text(&format!("{GOOD}, window_s: (-1.0, 2.0)"));
    let error = error_of(&early);
    assert_eq!((error.kind(), error.path()), (ErrorKind::Value, "inlets[0].window_s"), "{}", error.render_plain());
    assert!(error.message().contains("starts before the run does"), "{}", error.message());
    for window in ["(5.0, 6.0)", "(0.5, 0.5)"] {
        let late = Scene::from_str(&scene_text(&format!("{GOOD}, window_s: {window}")), "late.ron").unwrap();
        let warnings = late.warnings();
        assert!(
            warnings.iter().any(|w| w.contains("inlets[0].window_s: no insertion is due between t = 0 and `run.end_time_s` = 1 s")),
            "{window}: {warnings:?}"
        );
    }
    let source = "sources: [(position_m: (0.0, 0.5), width_m: 0.1, window_s: (2.0, 3.0), \
                  shape: (semi_axes_m: (0.005, 0.005), disk: true))],";
    let late_source = Scene::from_str(&format!("Scene(run: (end_time_s: 1.0), {source})"), "source.ron").unwrap();
    let warnings = late_source.warnings();
    assert!(warnings.iter().any(|w| w.contains("sources[0].window_s: no insertion is due")), "{warnings:?}");
}

/// An outlet written the wrong way round (the domain on its outer side) removed nothing without a word: every inlet
/// lies behind it, so the particles fed cross it inward. Warned about at its `from_m`.
#[test]
fn an_outlet_that_every_inlet_lies_behind_is_warned_about() {
    let good = scene_text(GOOD);
    let reversed = good.replace("from_m: (0.05, 0.3), to_m: (-0.05, 0.3)", "from_m: (-0.05, 0.3), to_m: (0.05, 0.3)");
    assert_ne!(reversed, good);
    let warnings = Scene::from_str(&reversed, "reversed.ron").unwrap().warnings();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(warnings[0].starts_with("reversed.ron:"), "{warnings:?}");
    assert!(warnings[0].contains(": outlets[0].from_m: every inlet lies on the outlet's outer side"), "{warnings:?}");
    assert!(warnings[0].contains("swap `from_m` and `to_m`"), "{warnings:?}");
    assert!(Scene::from_str(&good, "good.ron").unwrap().warnings().is_empty());
}
