//! Each class of scene error reaches the user of `gc2d-rs check` and `gc2d-rs run` as one diagnostic naming file,
//! line, column and field path, with exit code 2. The rendered diagnostics are snapshots (tests/snapshots/).

use assert_cmd::Command;
use std::path::Path;

/// Runs `gc2d-rs <command> <file>` from the directory of the bad scenes, so that the messages name relative paths.
fn diagnostic(command: &str, file: &str) -> String {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/bad");
    let output = Command::cargo_bin("gc2d-rs")
        .unwrap()
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .args([command, file, "--quiet"].iter().take(if command == "run" { 3 } else { 2 }))
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2), "{file}: exit code");
    assert!(output.stdout.is_empty(), "{file}: nothing on stdout");
    String::from_utf8(output.stderr).unwrap()
}

#[test]
fn every_error_class_is_located_and_exits_with_2() {
    for (file, location) in [
        ("syntax.ron", "syntax.ron:2:30"),
        ("unknown_field.ron", "unknown_field.ron:2:32"),
        ("wrong_type.ron", "wrong_type.ron:2:36"),
        ("negative_mu.ron", "negative_mu.ron:2:36"),
        ("zero_e.ron", "zero_e.ron:2:52"),
        ("non_convex.ron", "non_convex.ron:3:57"),
        ("overlap.ron", "overlap.ron:4:9"),
        ("unsafe_time_step.ron", "unsafe_time_step.ron:2:24"),
    ] {
        let message = diagnostic("check", file);
        assert!(message.contains(location), "{file}: expected {location} in\n{message}");
        insta::assert_snapshot!(file.trim_end_matches(".ron"), message);
    }
}

#[test]
fn run_refuses_a_bad_scene_the_same_way() {
    assert_eq!(diagnostic("run", "unknown_field.ron"), diagnostic("check", "unknown_field.ron"));
}

#[test]
fn errors_past_column_65535_are_reported_without_the_snippet() {
    // miette's renderer panics for underlines past column 65,535: such errors are shown without the source snippet.
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("long.ron");
    std::fs::write(&scene, format!("Scene(description: \"{}\", bogus: 1)", "x".repeat(70_000))).unwrap();
    for command in ["check", "run"] {
        let output = Command::cargo_bin("gc2d-rs")
            .unwrap()
            .current_dir(dir.path())
            .env("NO_COLOR", "1")
            .args([command, "long.ron"])
            .args(if command == "run" { &["--quiet", "--out", "out"][..] } else { &[] })
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{command}: {stderr}");
        assert!(stderr.contains("long.ron:1:70024: `bogus`: unknown field `bogus`"), "{command}: {stderr}");
        assert!(stderr.len() < 2_000, "{command}: no 70,000-character snippet, {} bytes", stderr.len());
    }
}

#[test]
fn thousands_of_errors_are_cut_to_a_readable_report() {
    let dir = tempfile::tempdir().unwrap();
    let materials: Vec<String> = (0..5_000).map(|i| format!("    (name: \"m{i}\", mu: -1),")).collect();
    std::fs::write(dir.path().join("many.ron"), format!("Scene(\n  materials: [\n{}\n  ],\n)", materials.join("\n")))
        .unwrap();
    let output = Command::cargo_bin("gc2d-rs")
        .unwrap()
        .current_dir(dir.path())
        .env("NO_COLOR", "1")
        .args(["check", "many.ron"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("many.ron:3:22: `materials[0].mu`"), "{stderr}");
    assert!(stderr.contains("… and 4980 more errors not shown (only the first 20 are listed)"), "{stderr}");
    assert_eq!(stderr.matches(".mu`: -1: the friction").count(), 20, "{stderr}");
    assert!(stderr.len() < 20_000, "{} bytes", stderr.len());
}

#[test]
fn an_automatic_time_step_longer_than_the_run_is_refused() {
    // A 1 m square of sand has an automatic Δt of 9.3e-4 s; an end time of 1e-4 s "completed" in 0 steps.
    let dir = tempfile::tempdir().unwrap();
    let text = "Scene(\n    run: (end_time_s: 1e-4),\n    particles: [(shape: Square(side_m: 1.0))],\n)\n";
    std::fs::write(dir.path().join("short.ron"), text).unwrap();
    let gc2d = |args: &[&str]| {
        let output =
            Command::cargo_bin("gc2d-rs").unwrap().current_dir(dir.path()).env("NO_COLOR", "1").args(args).output();
        output.unwrap()
    };
    for args in [&["check", "short.ron"][..], &["run", "short.ron", "--quiet", "--out", "out"]] {
        let output = gc2d(args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        // (miette wraps the message at 80 columns)
        let message: String = stderr.split_whitespace().filter(|w| *w != "│").collect::<Vec<_>>().join(" ");
        assert!(
            message.contains(
                "short.ron:2:23: `run.end_time_s`: the automatic time step 9.300e-4 s is longer than the run (end time \
                 1.000e-4 s)"
            ),
            "{args:?}: {stderr}"
        );
        assert!(stderr.contains("short.ron:3:17: `particles[0]`"), "{args:?}: the limiting particle: {stderr}");
    }
    assert!(!dir.path().join("out").exists(), "nothing written");
    // With --until beyond one step the run is long enough; a time step given in the scene is its author's choice.
    assert_eq!(gc2d(&["run", "short.ron", "--quiet", "--out", "out", "--until", "2e-3"]).status.code(), Some(0));
    std::fs::write(
        dir.path().join("given.ron"),
        text.replace("(end_time_s: 1e-4)", "(end_time_s: 1e-4, time_step_s: 5e-4)"),
    )
    .unwrap();
    assert_eq!(gc2d(&["check", "given.ron"]).status.code(), Some(0));
}

#[test]
fn a_run_of_more_steps_than_its_clock_counts_is_refused() {
    // An end time of 1e30 s was printed as 18446744073709551615 steps (a saturated u64), and its clock t + Δt would
    // have stopped advancing after 2^53 steps.
    let dir = tempfile::tempdir().unwrap();
    let text = "Scene(\n    run: (end_time_s: 1e30),\n    particles: [(shape: Square(side_m: 0.01))],\n)\n";
    std::fs::write(dir.path().join("long.ron"), text).unwrap();
    let gc2d = |args: &[&str]| {
        let output =
            Command::cargo_bin("gc2d-rs").unwrap().current_dir(dir.path()).env("NO_COLOR", "1").args(args).output();
        output.unwrap()
    };
    for args in [&["check", "long.ron"][..], &["run", "long.ron", "--quiet", "--out", "out"]] {
        let output = gc2d(args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        let message: String = stderr.split_whitespace().filter(|w| *w != "│").collect::<Vec<_>>().join(" ");
        assert!(message.contains("long.ron:2:23: `run.end_time_s`: the run to 1.000e30 s takes"), "{args:?}: {stderr}");
        assert!(message.contains("more than the 2^53"), "{args:?}: {stderr}");
    }
    assert!(!dir.path().join("out").exists(), "nothing written");
    let output = gc2d(&["run", "long.ron", "--quiet", "--out", "out", "--until", "1e25"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("--until: the run to 1.000e25 s takes"), "{stderr}");
    let output = gc2d(&["run", "long.ron", "--quiet", "--out", "out", "--until", "1e-3"]);
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
}
