//! `analyze_run` end to end: small piles and silos settled by the engine, saved as `final.ckpt`, analysed.

use gc2d_analysis::*;
use gc2d_contact::{ContactLaw, CundallStrack, NormalDamping, NormalElastic};
use gc2d_engine::schedules::GravitySchedule;
use gc2d_engine::{InteractionTable, MassModel, World, WorldConfig};
use gc2d_geometry::{DVec2, Pose, rectangle, regular_polygon};
use std::path::PathBuf;

const R: f64 = 1.5e-3;
const G: f64 = 9.81;

fn world() -> World {
    let contact_law = ContactLaw {
        elastic: NormalElastic::thesis(1e6),
        damping: Some(NormalDamping { gamma: 0.75 }),
        friction: Some(CundallStrack { mu: 0.6 }),
        cohesion: None,
    };
    let config = WorldConfig {
        // 0.3 of the stable bound (1.7e-5 s for these grains). At 3e-5 s, above the bound, the contact forces
        // alternated by 54 % from step to step and a single step's floor force was 0.88–1.15 W.
        time_step: 5e-6,
        integrator: Default::default(),
        interactions: InteractionTable::uniform(contact_law),
        mass_model: MassModel::PerUnitThickness,
        gravity: GravitySchedule::constant(G),
        heating: None,
        safety: Default::default(),
        domain: None,
        seed: 3,
    };
    World::new(config).expect("valid configuration")
}

fn add_wall(world: &mut World, min: DVec2, max: DVec2) {
    let size = max - min;
    let shape = rectangle(size.x, size.y).expect("wall");
    world.add_wall(&shape, Pose::new(0.5 * (min + max), 0.0), DVec2::ZERO, Default::default());
}

fn add_heptagon(world: &mut World, at: DVec2, turn: f64) {
    let shape = regular_polygon(7, R).expect("heptagon");
    world.add_particle(&shape, Pose::new(at, turn), 5000.0, DVec2::ZERO, 0.0).expect("particle");
}

fn run_dir(name: &str, mut world: World, until: f64) -> PathBuf {
    world.run_until(until).expect("run");
    // The analyses read one step's contact forces: they mean something only when consecutive steps agree.
    let alternation = world.force_alternation().ratio();
    assert!(alternation < 0.01, "{name}: the last step's contact forces alternate by {alternation} (chatter)");
    let dir = std::env::temp_dir().join(format!("gc2d-analysis-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("run directory");
    world.save_checkpoint_file(dir.join("final.ckpt")).expect("checkpoint");
    dir
}

#[test]
fn a_settled_pile_is_analysed_and_its_floor_carries_its_weight() {
    let mut world = world();
    add_wall(&mut world, DVec2::new(-0.1, -0.01), DVec2::new(0.1, 0.0));
    let spacing = 2.2 * R;
    let rows = 8;
    for j in 0..rows {
        for i in 0..(rows - j) * 2 {
            let x = (i as f64 - (rows - j) as f64 + 0.5) * spacing;
            add_heptagon(&mut world, DVec2::new(x, R + 0.0002 + j as f64 * spacing), 0.3 * (i + j) as f64);
        }
    }
    let dir = run_dir("pile", world, 0.6);
    let report = analyze_run(&dir, &AnalyzeOptions::default()).expect("analysis");
    assert_eq!(report.scene, SceneKind::Pile);
    let pile = report.pile.as_ref().expect("pile report");
    assert_eq!(pile.particles + pile.left_out, report.particles);
    let floor = pile.floor.as_ref().expect("floor pressure");
    // The floor carries the weight of the pile (§5.2): 0.99984 W at 0.6 s (the exact balance is pinned on synthetic
    // snapshots, column.rs).
    assert!((floor.total_normal_force / floor.weight - 1.0).abs() < 0.01, "{floor:?}");
    assert!(pile.height > 0.0 && pile.width > pile.height, "{pile:?}");
    assert!(report.mean_coordination > 2.0 && report.mean_coordination < 6.0, "{}", report.mean_coordination);
    assert!(report.packing_fraction > 0.5 && report.packing_fraction < 1.0, "{}", report.packing_fraction);
    for file in ["analysis.json", "floor_pressure.csv", "floor_pressure.svg", "surface.svg", "stress_grid.csv"] {
        assert!(report.files.iter().any(|f| f == file), "{file} not listed");
        assert!(dir.join("analysis").join(file).is_file(), "{file} not written");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("analysis/analysis.json")).unwrap()).unwrap();
    assert_eq!(json["scene"], "pile");
    let svg = std::fs::read_to_string(dir.join("analysis/floor_pressure.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("polyline"), "floor_pressure.svg is not a line chart");
    // Analysed as a silo, a pile has no wall pressure to fit: said so, instead of a "fit" with μ_J at its bound.
    let as_silo = analyze_run(&dir, &AnalyzeOptions { scene: SceneKind::Silo, ..Default::default() }).unwrap();
    let silo = as_silo.silo.as_ref().expect("silo report");
    assert!(silo.janssen.is_none() && silo.janssen_free_k.is_none(), "{silo:?}");
    assert!(silo.janssen_error.as_deref().is_some_and(|e| e.contains("no side wall carries a force")), "{silo:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_filled_silo_is_detected_and_fitted() {
    let mut world = world();
    let width = 0.02;
    add_wall(&mut world, DVec2::new(-0.01, -0.01), DVec2::new(width + 0.01, 0.0));
    add_wall(&mut world, DVec2::new(-0.01, 0.0), DVec2::new(0.0, 0.2));
    add_wall(&mut world, DVec2::new(width, 0.0), DVec2::new(width + 0.01, 0.2));
    let spacing = 2.15 * R;
    let per_row = (width / spacing) as usize;
    for j in 0..30 {
        let offset = if j % 2 == 0 { 0.0 } else { 0.3 * R };
        for i in 0..per_row {
            let at = DVec2::new(spacing * (i as f64 + 0.5) + offset, R + 0.0003 + j as f64 * spacing);
            add_heptagon(&mut world, at, 0.7 * (i * 3 + j) as f64);
        }
    }
    let dir = run_dir("silo", world, 0.3);
    let options = AnalyzeOptions { window_half_width: Some(2.0 * R), ..Default::default() };
    let report = analyze_run(&dir, &options).expect("analysis");
    assert_eq!(report.scene, SceneKind::Silo);
    let silo = report.silo.as_ref().expect("silo report");
    assert!((silo.half_width - 0.5 * width).abs() < 0.001, "{silo:?}");
    assert!(silo.left_wall_forces > 10 && silo.right_wall_forces > 10, "{silo:?}");
    let fit = silo.janssen.as_ref().expect("Janssen fit");
    assert!(fit.points >= 10, "{fit:?}");
    assert!(fit.mu_j > 0.01 && fit.mu_j < 10.0, "{fit:?}");
    assert!(silo.k > 0.0 && silo.k.is_finite(), "{silo:?}");
    // The free-k fit is either done or says why not.
    assert_ne!(silo.janssen_free_k.is_some(), silo.janssen_free_k_error.is_some(), "{silo:?}");
    let table = std::fs::read_to_string(dir.join("analysis").join("wall_pressure.csv")).unwrap();
    assert!(table.lines().next().unwrap().ends_with("janssen_sigma_xx,janssen_free_k_sigma_xx"), "{table}");
    for file in ["wall_pressure.csv", "wall_pressure.svg", "silo_rows.csv", "k_profile.svg", "density_profile.svg"] {
        assert!(dir.join("analysis").join(file).is_file(), "{file} not written");
    }
    // Forcing the pile analyses on the same state works too.
    let forced = analyze_run(&dir, &AnalyzeOptions { scene: SceneKind::Pile, ..Default::default() }).unwrap();
    assert_eq!(forced.scene, SceneKind::Pile);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_options_and_missing_checkpoints_are_errors() {
    let missing = std::env::temp_dir().join("gc2d-analysis-no-such-run");
    assert!(matches!(analyze_run(&missing, &AnalyzeOptions::default()), Err(AnalysisError::Checkpoint { .. })));
    let empty = Snapshot::default();
    let out = std::env::temp_dir().join(format!("gc2d-analysis-{}-empty", std::process::id()));
    assert!(matches!(analyze_snapshot(&empty, &AnalyzeOptions::default(), &out), Err(AnalysisError::NotEnoughData(_))));
    let bad = AnalyzeOptions { window_half_width: Some(-1.0), ..Default::default() };
    assert!(matches!(analyze_snapshot(&empty, &bad, &out), Err(AnalysisError::InvalidParameter(_))));
}
