//! `gc2d-rs analyze` of a pile or a silo says on stderr where its numbers mean little: a silo analysis of a run
//! whose side walls carry no force (QA docs 3, 12), and a grid so fine it is capped, naming the squares used (QA docs
//! 13).

use assert_cmd::Command;
use std::path::{Path, PathBuf};

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
