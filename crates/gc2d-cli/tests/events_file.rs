//! `gc2d-rs run --events`: every finished contact episode in `events.csv`, the same for any thread count and for a
//! run stopped after a checkpoint and resumed from it.

use assert_cmd::Command;
use std::path::{Path, PathBuf};

/// The bundled mill: balls hit each other, the chamber and the rotor within milliseconds.
fn mill() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/mill.ron")
}

/// Runs the mill to `until` with `--events` and the extra arguments into `out`.
fn run(out: &Path, until: &str, extra: &[&str]) {
    Command::cargo_bin("gc2d-rs")
        .unwrap()
        .args(["run", mill().to_str().unwrap(), "--quiet", "--events", "--until", until])
        .args(extra)
        .arg("--out")
        .arg(out)
        .assert()
        .success();
}

fn events(out: &Path) -> String {
    std::fs::read_to_string(out.join("events.csv")).unwrap()
}

#[test]
fn episodes_are_written_identically_for_any_thread_count_and_across_a_resume() {
    let one = tempfile::tempdir().unwrap();
    run(one.path(), "0.004", &["--threads", "1"]);
    let text = events(one.path());
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header, gc2d_cli::events::EVENT_COLUMNS);
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert!(rows.len() > 50, "only {} episodes ended", rows.len());
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (begin, end, kind_a, speed) =
        (column("begin_time_s"), column("end_time_s"), column("kind_a"), column("impact_normal_speed_m_s"));
    for row in &rows {
        assert_eq!(row.len(), header.len());
        assert!(row[begin].parse::<f64>().unwrap() <= row[end].parse::<f64>().unwrap());
        assert!(row[speed].parse::<f64>().unwrap().is_finite());
    }
    assert!(rows.iter().any(|r| r[kind_a] == "wall"), "balls meet the chamber and the rotor");
    assert!(rows.iter().any(|r| r[kind_a] == "particle"), "balls meet each other");

    let two = tempfile::tempdir().unwrap();
    run(two.path(), "0.004", &["--threads", "2"]);
    assert!(events(two.path()) == text, "events differ between one and two threads");

    let split = tempfile::tempdir().unwrap();
    run(split.path(), "0.002", &[]);
    Command::cargo_bin("gc2d-rs")
        .unwrap()
        .args(["run", mill().to_str().unwrap(), "--quiet", "--events", "--until", "0.004", "--resume"])
        .arg(split.path())
        .assert()
        .success();
    assert!(events(split.path()) == text, "events differ across a resume");
}
