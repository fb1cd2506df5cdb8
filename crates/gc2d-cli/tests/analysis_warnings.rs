//! `gc2d-rs analyze` says what it cannot use or had to assume, and where its numbers mean little: dumps in formats it
//! cannot read and a feed-pipe window that falls back to the whole run (QA P2-10 d, g), a silo analysis of a run whose
//! side walls carry no force (QA docs 3, 12) and a grid so fine it is capped (QA docs 13). Each warning is on stderr
//! and in the report.

mod common;

use assert_cmd::Command;
use std::path::{Path, PathBuf};

/// Writes the scene `text` into `dir` and runs it with `args`; returns the run directory.
fn run(dir: &Path, text: &str, args: &[&str]) -> PathBuf {
    let scene_path = dir.join("scene_under_test.ron");
    std::fs::write(&scene_path, text).unwrap();
    let out = dir.join("run");
    Command::cargo_bin("gc2d-rs")
        .unwrap()
        .arg("run")
        .arg(&scene_path)
        .args(["--quiet", "--out"])
        .arg(&out)
        .args(args)
        .assert()
        .success();
    out
}

/// `analyze RUN ARGS`: the report (stdout) and stderr.
fn analyze(run: &Path, args: &[&str]) -> (serde_json::Value, String) {
    let output = Command::cargo_bin("gc2d-rs")
        .unwrap()
        .arg("analyze")
        .arg(run)
        .args(args)
        .assert()
        .success()
        .get_output()
        .clone();
    (serde_json::from_slice(&output.stdout).unwrap(), String::from_utf8(output.stderr).unwrap())
}

/// QA P2-10 d: `analyze --kind mill` of a run dumped only as Parquet gave `"ball_speeds": null` without a word.
#[test]
fn a_mill_run_dumped_only_as_parquet_is_told_to_dump_csv() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(dir.path(), common::FOUR_BALL_MILL, &["--events", "--dump-format", "parquet"]);
    let (report, stderr) = analyze(&out, &["--kind", "mill"]);
    assert!(report["ball_speeds"].is_null());
    let warning = report["warnings"][0].as_str().unwrap_or_default();
    assert!(
        warning.contains("holds dumps in formats the analysis cannot read (5 in parquet, without a CSV copy)")
            && warning.contains("run with `--dump-format csv` (csv is what `analyze` reads"),
        "{report}"
    );
    assert!(stderr.contains(&format!("warning: {warning}")), "{stderr}");
}

/// QA P2-10 g: `analyze --kind feedpipe` of a run in which nothing has left yet took the whole run as its window
/// without a word.
#[test]
fn a_feed_pipe_without_a_removal_yet_says_its_window_is_the_whole_run() {
    let scene = r#"Scene(
    mass_model: SphereEquivalent,
    run: (time_step_s: 1e-4, end_time_s: 0.1, frames_per_second: 20, max_impact_speed_m_s: 2.0),
    materials: [(name: "styrofoam", density_kg_m3: 15, youngs_modulus_pa: 1e5)],
    interactions: [(materials: ("styrofoam", "styrofoam"), law: Hertz(damping: Restitution(0.5)))],
    inlets: [(name: "feed", from_m: (-0.2, 0.0), to_m: (0.2, 0.0), rate_per_s: 20, velocity_m_s: (0.0, 1.0),
              shape: (semi_axes_m: (0.02, 0.02), disk: true))],
    outlets: [(name: "top", from_m: (0.25, 1.0), to_m: (-0.25, 1.0))],
    fluid: (density_kg_m3: 1.25, field: Uniform((0.0, 5.0))),
)"#;
    let dir = tempfile::tempdir().unwrap();
    let out = run(dir.path(), scene, &[]);
    let (report, stderr) = analyze(&out, &["--kind", "feedpipe"]);
    assert_eq!(report["window_s"][0].as_f64(), Some(0.0));
    assert_eq!(report["outlets"][0]["removed_total"].as_u64(), Some(0));
    let warning = report["warnings"][0].as_str().unwrap_or_default();
    assert!(
        warning.starts_with("no particle has left through an outlet yet")
            && warning.contains("it falls back to the whole run")
            && warning.contains("give --warm-up T"),
        "{report}"
    );
    assert!(stderr.contains(&format!("warning: {warning}")), "{stderr}");
    // A window given with --warm-up is no fallback.
    let output = Command::cargo_bin("gc2d-rs")
        .unwrap()
        .args(["analyze", out.to_str().unwrap(), "--kind", "feedpipe", "--warm-up", "0.02"])
        .assert()
        .success()
        .get_output()
        .clone();
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(report["warnings"].as_array().map(Vec::len), Some(0), "{report}");
}

/// Runs the tiny pile of the command-line tests into `dir`; returns the run directory.
fn tiny_pile(dir: &Path) -> PathBuf {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/tiny_pile.ron");
    let out = dir.join("run");
    Command::cargo_bin("gc2d-rs")
        .unwrap()
        .args(["run", scene.to_str().unwrap(), "--quiet", "--out", out.to_str().unwrap()])
        .assert()
        .success();
    out
}

#[test]
fn a_pile_analysed_as_a_silo_and_a_capped_grid_are_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let run = tiny_pile(dir.path());
    let (report, stderr) = analyze(&run, &["--kind", "silo"]);
    let warnings = report["silo"]["warnings"].as_array().expect("silo warnings").clone();
    assert_eq!(warnings.len(), 1, "{report}");
    let warning = warnings[0].as_str().unwrap();
    assert!(warning.starts_with("no side wall carries a force"), "{warning}");
    assert!(stderr.contains(&format!("warning: {warning}")), "{stderr}");

    let (report, stderr) = analyze(&run, &["--grid", "1e-7"]);
    let pile = &report["pile"];
    assert_eq!(pile["grid_capped"], true, "{report}");
    let side = pile["grid_cell"].as_f64().unwrap();
    let [nx, ny] = [0, 1].map(|k| pile["grid_size"][k].as_u64().unwrap());
    assert!(nx == 1000 || ny == 1000, "{report}");
    assert!(stderr.contains(&format!("use {nx} × {ny} squares of ")), "{stderr}");
    // Every test area in density_grid.csv is a square of the side reported.
    let table = std::fs::read_to_string(run.join("analysis/density_grid.csv")).unwrap();
    assert_eq!(table.lines().count() as u64, nx * ny + 1);
    for line in table.lines().skip(1) {
        let fields: Vec<f64> = line.split(',').map(|f| f.parse().unwrap()).collect();
        assert!((fields[2] - side).abs() <= 1e-9 * side && (fields[3] - side).abs() <= 1e-9 * side, "{line}");
    }
}
