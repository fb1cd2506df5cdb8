//! `transits.csv` (issue 15 item 5): one row per particle an outlet removed, with its inlet and times; the same for
//! any thread count and for a run stopped after a checkpoint and resumed from it.

use assert_cmd::Command;
use gc2d_cli::transits::{TRANSIT_COLUMNS, TRANSITS_FILE};
use std::path::Path;

/// Disks fed upward at 1 m/s, 20 per second, without gravity; an outlet 0.2 m up: each crosses it 0.2 s after it came in.
const SCENE: &str = r#"Scene(
    run: (time_step_s: 1e-3, end_time_s: 0.5, checkpoint_interval_s: 0.1),
    gravity: Constant(0.0),
    materials: [(name: "glass", density_kg_m2: 1e4, youngs_modulus_n_m: 1e5)],
    inlets: [(name: "feed", from_m: (-0.05, 0.0), to_m: (0.05, 0.0), rate_per_s: 20, velocity_m_s: (0.0, 1.0),
              shape: (semi_axes_m: (0.01, 0.01), disk: true))],
    outlets: [(name: "top", from_m: (0.05, 0.2), to_m: (-0.05, 0.2))],
)"#;

fn run(scene: &Path, out: &Path, until: &str, extra: &[&str]) {
    Command::cargo_bin("gc2d-rs")
        .unwrap()
        .args(["run", scene.to_str().unwrap(), "--quiet", "--until", until])
        .args(extra)
        .arg("--out")
        .arg(out)
        .assert()
        .success();
}

fn transits(out: &Path) -> String {
    std::fs::read_to_string(out.join(TRANSITS_FILE)).unwrap()
}

#[test]
fn transits_are_written_identically_for_any_thread_count_and_across_a_resume() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("feed.ron");
    std::fs::write(&scene, SCENE).unwrap();
    let one = dir.path().join("one");
    run(&scene, &one, "0.5", &["--threads", "1"]);
    let text = transits(&one);
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap().split(',').collect::<Vec<_>>(), TRANSIT_COLUMNS);
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    // Fed at steps 1, 51, 101, …: those fed by t = 0.3 s (7 of them) have crossed by 0.5 s.
    assert_eq!(rows.len(), 6, "{text}");
    for row in &rows {
        assert_eq!((row[1], row[3]), ("feed", "top"));
        let (entered, left, transit): (f64, f64, f64) =
            (row[2].parse().unwrap(), row[4].parse().unwrap(), row[5].parse().unwrap());
        assert_eq!(transit, left - entered);
        assert!((transit - 0.2).abs() <= 1.5e-3, "0.2 m at 1 m/s: {transit} s");
    }

    let two = dir.path().join("two");
    run(&scene, &two, "0.5", &["--threads", "2"]);
    assert!(transits(&two) == text, "transits differ between one and two threads");

    let split = dir.path().join("split");
    run(&scene, &split, "0.3", &[]);
    Command::cargo_bin("gc2d-rs")
        .unwrap()
        .args(["run", scene.to_str().unwrap(), "--quiet", "--until", "0.5", "--resume"])
        .arg(&split)
        .assert()
        .success();
    assert!(transits(&split) == text, "transits differ across a resume:\n{}\n{text}", transits(&split));
}
