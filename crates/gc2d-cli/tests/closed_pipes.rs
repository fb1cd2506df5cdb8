//! `gc2d-rs check scene.ron | head -0` and friends: output into a pipe whose reader has gone ends the program
//! quietly (exit code 0 for a closed stdout, as ripgrep does) instead of panicking.
#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes").join(name)
}

/// The write end of a pipe that nobody reads any more: its read end was the stdin of a child that has already
/// exited. Writing to it fails with EPIPE every time, so the tests do not race a reader.
fn closed_pipe() -> Stdio {
    let mut reader = Command::new("true").stdin(Stdio::piped()).spawn().expect("spawn `true`");
    let writer = reader.stdin.take().expect("a piped stdin");
    reader.wait().expect("`true` exits");
    Stdio::from(writer)
}

fn gc2d(args: &[&str], stdout: Stdio, stderr: Stdio) -> Output {
    Command::new(assert_cmd::cargo::cargo_bin("gc2d-rs"))
        .args(args)
        .env("NO_COLOR", "1")
        .stdin(Stdio::null())
        .stdout(stdout)
        .stderr(stderr)
        .output()
        .expect("gc2d-rs runs")
}

#[test]
fn check_into_a_closed_pipe_exits_quietly() {
    let path = scene("tiny_pile.ron");
    let output = gc2d(&["check", path.to_str().unwrap()], closed_pipe(), Stdio::piped());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "stderr:\n{stderr}");
    assert!(stderr.is_empty(), "nothing on stderr, found:\n{stderr}");
}

#[test]
fn errors_into_a_closed_pipe_keep_their_exit_code() {
    let path = scene("bad/unknown_field.ron");
    // `gc2d-rs check bad.ron 2>&1 | true`: the diagnostic cannot be shown, the exit code still says what happened.
    let output = gc2d(&["check", path.to_str().unwrap()], Stdio::piped(), closed_pipe());
    assert_eq!(output.status.code(), Some(2));
    assert!(output.stdout.is_empty());
}
