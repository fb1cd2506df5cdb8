//! Every scene in `scenes/` loads, builds and runs a few hundred steps.

use gc2d_scene::Scene;
use std::path::PathBuf;

fn scene_files() -> Vec<PathBuf> {
    let directory = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&directory)
        .expect("scenes/ exists")
        .map(|entry| entry.expect("readable").path())
        .filter(|path| path.extension().is_some_and(|e| e == "ron"))
        .collect();
    files.sort();
    files
}

#[test]
fn every_scene_file_loads_builds_and_runs() {
    let files = scene_files();
    let names: Vec<String> = files.iter().map(|p| p.file_stem().unwrap().to_string_lossy().into_owned()).collect();
    for expected in ["drum", "pile", "piston", "silo"] {
        assert!(names.iter().any(|n| n == expected), "scenes/{expected}.ron is missing");
    }
    for file in &files {
        let scene = Scene::from_path(file).unwrap_or_else(|e| panic!("{}", e.render_plain()));
        assert!(scene.source.as_ref().unwrap().text().starts_with("// "), "{} needs a comment header", file.display());
        assert!(!scene.description.is_empty());
        let summary = scene.summary().unwrap_or_else(|e| panic!("{}", e.render_plain()));
        let mut world = scene.build().unwrap();
        assert_eq!(world.time_step(), summary.time_step_s);
        for _ in 0..300 {
            world.step().unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        }
        assert!(world.bodies().particles().count() > 0, "{} has no particles after 300 steps", file.display());
    }
}

#[test]
fn the_bundled_scenes_contain_what_their_headers_say() {
    let load = |name: &str| {
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("../../scenes/{name}.ron"));
        Scene::from_path(path).unwrap().summary().unwrap()
    };
    let pile = load("pile");
    assert_eq!((pile.wall_bodies, pile.sources, pile.particles), (3, 1, 0));
    assert!(pile.planned_insertions > 200);
    let silo = load("silo");
    assert_eq!((silo.wall_bodies, silo.sources), (3, 1));
    let drum = load("drum");
    assert_eq!((drum.wall_bodies, drum.sources, drum.particles), (40, 0, 100));
    let piston = load("piston");
    assert_eq!((piston.wall_bodies, piston.moving_walls, piston.sources, piston.particles), (4, 1, 0, 1251));
    for summary in [&pile, &silo, &drum, &piston] {
        assert!(summary.time_step_is_automatic);
        assert!(summary.time_step_s <= summary.stable_time_step_s.unwrap());
    }
}

#[test]
fn the_example_in_the_format_documentation_loads_and_builds() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/scene-format.md");
    let doc = std::fs::read_to_string(path).expect("docs/scene-format.md exists");
    let examples: Vec<&str> = doc.split("```ron\n").skip(1).map(|rest| rest.split("```").next().unwrap()).collect();
    assert!(!examples.is_empty());
    let summaries: Vec<_> = examples
        .iter()
        .map(|example| {
            let scene = Scene::from_str(example, "example.ron").unwrap_or_else(|e| panic!("{}", e.render_plain()));
            scene.summary().unwrap_or_else(|e| panic!("{}", e.render_plain()))
        })
        .collect();
    // The first: the box (4 walls) and a lattice of 11 × 3 hexagons.
    assert_eq!((summaries[0].wall_bodies, summaries[0].particles), (4, 33));
}
