//! A run split by `--resume` reports what the unsplit run does: the same time series and contact events byte for
//! byte, and the same chatter watch in `summary.json` (QA R8: its windows were counted from the resume step).

use assert_cmd::Command;
use std::path::Path;

fn gc2d(dir: &Path, args: &[&str]) {
    let output =
        Command::cargo_bin("gc2d-rs").unwrap().current_dir(dir).env("NO_COLOR", "1").args(args).output().unwrap();
    assert_eq!(output.status.code(), Some(0), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn chatter(run: &Path) -> serde_json::Value {
    let summary: serde_json::Value = serde_json::from_str(&read(&run.join("summary.json"))).unwrap();
    summary["chatter"].clone()
}

#[test]
fn a_split_run_reports_the_unsplit_runs_chatter() {
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/tiny_pile.ron");
    std::fs::copy(&scene, dir.path().join("tiny_pile.ron")).unwrap();
    let options = ["--quiet", "--events", "--checkpoint-every", "0.02"];
    gc2d(dir.path(), &[&["run", "tiny_pile.ron", "--out", "whole"][..], &options].concat());
    // Δt = 1.6 µs: the split at t = 0.03 s lies at step 18750, inside the window of steps 18001–19000.
    gc2d(dir.path(), &[&["run", "tiny_pile.ron", "--out", "split", "--until", "0.03"][..], &options].concat());
    gc2d(dir.path(), &[&["run", "tiny_pile.ron", "--resume", "split"][..], &options].concat());
    let (whole, split) = (dir.path().join("whole"), dir.path().join("split"));
    for file in ["timeseries.csv", "events.csv"] {
        assert!(read(&whole.join(file)) == read(&split.join(file)), "{file} differs across the resume");
    }
    let expected = chatter(&whole);
    let largest = expected["largest_window"]["time_s"].as_f64().unwrap();
    // The unsplit run's largest window lies after the split, where the resumed process's windows used to be shifted.
    assert!(largest > 0.031, "largest window at {largest} s: {expected}");
    assert_eq!(chatter(&split), expected);
}
