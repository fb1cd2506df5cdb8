//! `gc2d-rs run --events`: every finished contact episode in `events.csv`, the same for any thread count and for a
//! run stopped after a checkpoint and resumed from it, the bodies named as the scene names them (issue 19 item 5).

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
    let (kind_b, object_a, object_b) = (column("kind_b"), column("object_a"), column("object_b"));
    for row in &rows {
        for (kind, object) in [(row[kind_a], row[object_a]), (row[kind_b], row[object_b])] {
            let named =
                if kind == "particle" { object.starts_with("mill.balls #") } else { object.starts_with("mill.") };
            assert!(named, "a {kind} named `{object}`");
        }
    }

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

/// Disks dropped by a source onto a floor: their episodes name them by the source and their place in its order.
#[test]
fn particles_a_source_inserted_are_named_by_the_source() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("pour.ron");
    std::fs::write(
        &scene,
        "Scene(
            run: (end_time_s: 0.12),
            walls: [Wall(shape: Rectangle(width_m: 0.2, height_m: 0.01), position_m: (0, -0.005))],
            sources: [(position_m: (0, 0.02), width_m: 0.1, window_s: (0, 0.05), interval_s: 0.01,
                       shape: (semi_axes_m: (0.003, 0.003), disk: true))],
        )",
    )
    .unwrap();
    let out = dir.path().join("out");
    Command::cargo_bin("gc2d-rs")
        .unwrap()
        .args(["run", scene.to_str().unwrap(), "--quiet", "--events", "--out"])
        .arg(&out)
        .assert()
        .success();
    let text = events(&out);
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (a, b, object_a, object_b) = (column("a"), column("b"), column("object_a"), column("object_b"));
    let mut named = std::collections::BTreeMap::new();
    for line in lines {
        let row: Vec<&str> = line.split(',').collect();
        named.insert(row[a].parse::<u32>().unwrap(), row[object_a].to_string());
        named.insert(row[b].parse::<u32>().unwrap(), row[object_b].to_string());
    }
    // The floor is body 0; the source's disks are bodies 1, 2, … in the order it inserted them (5 insertions, at
    // 0, 0.01, …, 0.04 s), and every one lands on the floor.
    let expected: Vec<(u32, String)> = std::iter::once((0, "walls[0]".to_string()))
        .chain((0..5).map(|k| (k + 1, format!("sources[0] #{k}"))))
        .collect();
    assert_eq!(named.into_iter().collect::<Vec<_>>(), expected);
}
