//! A scene whose bodies overlap slightly at the start (issues 16 and 19 item 5): `check` used to pass it (it allowed
//! `run.max_overlap_fraction`, 5 %) while `run` refused it before its first step (beyond round-off). Both now refuse
//! it alike, at the scene entry, naming both objects.

use assert_cmd::Command;

/// Two 1 cm squares side by side, overlapping by 1 % of their area (0.1 mm).
const SCENE: &str = "Scene(
    run: (end_time_s: 0.01),
    particles: [
        (shape: Square(side_m: 0.01), position_m: (0, 0.1)),
        (shape: Square(side_m: 0.01), position_m: (0.0099, 0.1)),
    ],
)
";

#[test]
fn check_and_run_refuse_a_small_start_overlap_alike() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("touching.ron");
    std::fs::write(&scene, SCENE).unwrap();
    let refusal = |command: &str| {
        let mut cmd = Command::cargo_bin("gc2d-rs").unwrap();
        cmd.arg(command).arg(&scene);
        if command == "run" {
            cmd.arg("--out").arg(dir.path().join("out"));
        }
        let output = cmd.env("NO_COLOR", "1").output().unwrap();
        assert!(!output.status.success(), "{command} accepted an overlapping start");
        String::from_utf8_lossy(&output.stderr).to_string()
    };
    let (check, run) = (refusal("check"), refusal("run"));
    for message in [&check, &run] {
        // The report wraps its lines; compare the words.
        let words = message.replace('│', " ").split_whitespace().collect::<Vec<_>>().join(" ");
        assert!(words.contains("overlap by 1.00 % of the smaller particle's area"), "{message}");
        assert!(message.contains("`particles[1]`") && message.contains("`particles[0]`"), "{message}");
        assert!(message.contains("touching.ron:5:9"), "located at the second particle: {message}");
    }
}
