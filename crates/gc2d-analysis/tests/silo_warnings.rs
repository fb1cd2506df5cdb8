//! The silo analysis says why its numbers mean little: no side wall carrying a force, or a fill too shallow for a
//! wall-pressure profile; a window centred above the fill surface is no wall-pressure point (QA docs 3, 12).

mod common;

use common::{DENSITY, G, block_of_squares, contact, rectangle, wall};
use gc2d_analysis::{AnalyzeOptions, BodyRef, SceneKind, Snapshot, analyze_snapshot};
use gc2d_geometry::DVec2;

const D: f64 = 0.002;

fn silo_options(window: Option<f64>) -> AnalyzeOptions {
    AnalyzeOptions { scene: SceneKind::Silo, window_half_width: window, ..Default::default() }
}

fn out_dir(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("gc2d-analysis-{}-{name}", std::process::id()))
}

/// One layer of 5 squares of side [`D`] on a floor between two side walls that press on the outer two.
fn shallow_silo() -> Snapshot {
    let mut layer = block_of_squares(5, 1, D, 0.0);
    layer.walls = vec![
        wall(0, rectangle(DVec2::new(-D, -D), DVec2::new(6.0 * D, 0.0))),
        wall(1, rectangle(DVec2::new(-D, 0.0), DVec2::new(0.0, 10.0 * D))),
        wall(2, rectangle(DVec2::new(5.0 * D, 0.0), DVec2::new(6.0 * D, 10.0 * D))),
    ];
    let weight = DENSITY * D * D * G;
    for i in 0..5 {
        let at = DVec2::new((i as f64 + 0.5) * D, 0.0);
        layer.contacts.push(contact(BodyRef::Particle(i), BodyRef::Wall(0), DVec2::new(0.0, weight), at));
    }
    let side = 0.4 * weight;
    let (left, right) = (DVec2::new(0.0, 0.5 * D), DVec2::new(5.0 * D, 0.5 * D));
    layer.contacts.push(contact(BodyRef::Particle(0), BodyRef::Wall(1), DVec2::new(side, 0.0), left));
    layer.contacts.push(contact(BodyRef::Particle(4), BodyRef::Wall(2), DVec2::new(-side, 0.0), right));
    layer
}

#[test]
fn a_heap_analysed_as_a_silo_warns_that_no_side_wall_carries_a_force() {
    let out = out_dir("silo-no-walls");
    let report = analyze_snapshot(&block_of_squares(6, 3, D, 0.0), &silo_options(None), &out).expect("analysis");
    let silo = report.silo.expect("silo report");
    assert_eq!(silo.warnings.len(), 1, "{:?}", silo.warnings);
    assert!(silo.warnings[0].starts_with("no side wall carries a force"), "{:?}", silo.warnings);
    assert!(silo.warnings[0].contains("the Janssen fits mean nothing (is it a silo?"), "{:?}", silo.warnings);
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_fill_shallower_than_the_window_warns_and_writes_no_point_above_its_surface() {
    let out = out_dir("silo-shallow");
    // b = 2 D over a fill of D: the only window is centred D above the fill surface.
    let report = analyze_snapshot(&shallow_silo(), &silo_options(Some(2.0 * D)), &out).expect("analysis");
    let silo = report.silo.expect("silo report");
    assert_eq!((silo.left_wall_forces, silo.right_wall_forces), (1, 1));
    assert!((silo.fill_height - D).abs() < 1e-9, "{silo:?}");
    assert!(silo.janssen.is_none() && silo.janssen_free_k.is_none(), "{silo:?}");
    assert_eq!(silo.warnings.len(), 1, "{:?}", silo.warnings);
    let warning = &silo.warnings[0];
    assert!(warning.starts_with("the fill is 2.000e-3 m deep, against a pressure window 2b = 8.000e-3 m"), "{warning}");
    assert!(
        warning.contains("0 wall-pressure point(s) below the fill surface, too few for the Janssen fits"),
        "{warning}"
    );
    let table = std::fs::read_to_string(out.join("wall_pressure.csv")).unwrap();
    assert_eq!(table.lines().count(), 1, "a row above the fill surface was written:\n{table}");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_fill_deep_enough_for_points_has_none_above_its_surface() {
    let out = out_dir("silo-points");
    // b = D / 4 over a fill of D: windows every D / 8 from b above the floor up to the surface.
    let report = analyze_snapshot(&shallow_silo(), &silo_options(Some(0.25 * D)), &out).expect("analysis");
    let silo = report.silo.expect("silo report");
    assert!(!silo.warnings.iter().any(|w| w.contains("too few")), "{:?}", silo.warnings);
    let table = std::fs::read_to_string(out.join("wall_pressure.csv")).unwrap();
    let depths: Vec<f64> = table.lines().skip(1).map(|l| l.split(',').next().unwrap().parse().unwrap()).collect();
    assert!(depths.len() >= 2 && depths.iter().all(|&z| z >= 0.0), "{depths:?}");
    let _ = std::fs::remove_dir_all(&out);
}
