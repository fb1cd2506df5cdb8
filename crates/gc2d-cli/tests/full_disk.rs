//! A recording whose writes fail (a full disk) ends the run with a message, not a panic (issue 16: `--record` to a
//! file whose first write fails panicked in the mcap writer's drop).

use assert_cmd::Command;
use predicates::prelude::*;
use predicates::str::contains;
use std::path::Path;

#[test]
fn recording_to_a_full_device_fails_cleanly() {
    let full = Path::new("/dev/full");
    if !full.exists() {
        eprintln!("skipped: this system has no /dev/full to stand for a full disk");
        return;
    }
    let out = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/pile.ron");
    Command::cargo_bin("gc2d-rs")
        .unwrap()
        .args(["run", scene.to_str().unwrap(), "--until", "0.001", "--quiet", "--record", "/dev/full", "--out"])
        .arg(out.path())
        .assert()
        .failure()
        .stderr(contains("cannot record to /dev/full").and(contains("panicked").not()));
}
