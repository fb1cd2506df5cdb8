//! `gc2d-rs sweep --slurm` end to end on a real single-node Slurm (scripts/slurm-local.sh installs, configures and
//! starts it): a two-point sweep submitted with sbatch, one task stopped by its time limit (Slurm's SIGTERM ahead of
//! it), requeued and resumed to the same final state as an uninterrupted run, then `--collect`.
//!
//! Opt-in: it needs root and takes five to ten minutes (Slurm holds a requeued job for two minutes before it starts it
//! again). Run it with `cargo test --release -p gc2d-cli --test slurm -- --ignored`. Where Slurm cannot be started it
//! prints why and passes without checking anything.

use assert_cmd::Command;
use std::path::Path;
use std::time::{Duration, Instant};

/// A copy of the program in `folder`: the tasks run it minutes later, when the build directory's binary may have been
/// rebuilt from other sources (all parts of a resumed run must be one program to end bitwise alike).
fn program_in(folder: &Path) -> std::path::PathBuf {
    let copy = folder.join("gc2d-rs");
    std::fs::copy(assert_cmd::cargo::cargo_bin("gc2d-rs"), &copy).unwrap();
    copy
}

/// Each task's time limit, minutes.
const TIME_LIMIT_MIN: u32 = 2;

/// Seconds before the limit at which Slurm signals the task: 30 s into it, or up to a minute later (Slurm checks
/// its limits periodically).
const SIGNAL_BEFORE_S: u32 = 90;

/// Wall time the long point takes on one thread: longer than the time to the signal (15 to 30 s seen here), well short
/// of the limit.
const LONG_POINT_WALL_S: f64 = 40.0;

/// Starts the local cluster; the reason when it cannot.
fn start_slurm() -> Result<(), String> {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scripts/slurm-local.sh");
    let output = std::process::Command::new("bash").arg(script).output().map_err(|e| format!("cannot run it: {e}"))?;
    if output.status.success() { Ok(()) } else { Err(String::from_utf8_lossy(&output.stderr).trim().to_owned()) }
}

/// Simulated seconds of tiny_pile.ron that take about `wall_s` on one thread here (measured on its first 0.5 s).
fn simulated_time_for(program: &Path, folder: &Path, wall_s: f64) -> f64 {
    let started = Instant::now();
    Command::new(program)
        .arg("run")
        .arg(folder.join("tiny_pile.ron"))
        .args(["--quiet", "--threads", "1", "--until", "0.5", "--out"])
        .arg(folder.join("calibration"))
        .assert()
        .success();
    let rate = 0.5 / started.elapsed().as_secs_f64();
    (rate * wall_s).clamp(1.0, 200.0).round()
}

#[test]
#[ignore = "needs root and five to ten minutes: cargo test --release -p gc2d-cli --test slurm -- --ignored"]
fn a_sweep_runs_through_slurm_and_a_task_stopped_by_its_time_limit_resumes() {
    if let Err(reason) = start_slurm() {
        println!("skipped: Slurm cannot be started here: {reason}");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/tiny_pile.ron");
    std::fs::copy(scene, dir.path().join("tiny_pile.ron")).unwrap();
    let program = program_in(dir.path());
    let gc2d = || Command::new(&program);
    let long = simulated_time_for(&program, dir.path(), LONG_POINT_WALL_S);
    std::fs::write(
        dir.path().join("sweep.ron"),
        format!(
            "Sweep(scene: \"tiny_pile.ron\", out: \"out\", run: (checkpoint_every_s: 0.5),\n    parameters: [(path: \
             \"run.end_time_s\", name: \"end\", values: List([0.05, {long:.1}]))])\n"
        ),
    )
    .unwrap();
    gc2d()
        .current_dir(dir.path())
        .args(["sweep", "sweep.ron", "--slurm", "--time", &TIME_LIMIT_MIN.to_string()])
        .args(["--signal-before", &SIGNAL_BEFORE_S.to_string()])
        .assert()
        .success();
    let out = dir.path().join("out");
    let submitted = std::process::Command::new("sbatch")
        .arg("--parsable")
        .arg(out.join("slurm/sweep.sbatch"))
        .output()
        .expect("sbatch runs");
    assert!(submitted.status.success(), "sbatch: {}", String::from_utf8_lossy(&submitted.stderr));
    let job = String::from_utf8_lossy(&submitted.stdout).trim().to_owned();

    // Wait for the array to leave the queue (each requeue waits two minutes before it starts again).
    let deadline = Instant::now() + Duration::from_secs(900);
    loop {
        let queue = std::process::Command::new("squeue").args(["-h", "-j", &job]).output().expect("squeue runs");
        if String::from_utf8_lossy(&queue.stdout).trim().is_empty() {
            break;
        }
        assert!(Instant::now() < deadline, "job {job} is still queued after 15 minutes");
        std::thread::sleep(Duration::from_secs(5));
    }

    let short = out.join("end=0.05_seed=3");
    let long_point = out.join(format!("end={long:.1}_seed=3"));
    for point in [&short, &long_point] {
        let summary: serde_json::Value =
            serde_json::from_slice(&std::fs::read(point.join("summary.json")).unwrap()).unwrap();
        assert_eq!(summary["outcome"]["status"], "completed", "{}", point.display());
    }
    // The long point was stopped by the time limit's signal and finished by a requeued task.
    let segments = std::fs::read_to_string(long_point.join("segments.csv")).unwrap();
    let statuses: Vec<&str> = segments.lines().skip(1).map(|l| l.split(',').nth(6).unwrap_or("")).collect();
    assert!(statuses.len() >= 2 && statuses[0] == "interrupted", "segments.csv:\n{segments}");
    assert_eq!(statuses.last(), Some(&"completed"), "segments.csv:\n{segments}");
    let log = std::fs::read_to_string(out.join("slurm/task-1.log")).unwrap();
    assert!(log.contains("requeued"), "task-1.log:\n{log}");

    // The same point run in one go ends in the same state.
    let reference = dir.path().join("reference");
    gc2d()
        .arg("run")
        .arg(long_point.join("scene.ron"))
        .args(["--quiet", "--threads", "1", "--checkpoint-every", "0.5", "--out"])
        .arg(&reference)
        .assert()
        .success();
    assert!(
        std::fs::read(long_point.join("final.ckpt")).unwrap() == std::fs::read(reference.join("final.ckpt")).unwrap(),
        "the point resumed under Slurm ends in another state than the uninterrupted run"
    );

    gc2d().current_dir(dir.path()).args(["sweep", "sweep.ron", "--collect"]).assert().success();
    let table = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    assert_eq!(table.lines().count(), 3, "{table}");
    assert_eq!(table.lines().skip(1).filter(|l| l.contains(",completed,")).count(), 2, "{table}");
}
