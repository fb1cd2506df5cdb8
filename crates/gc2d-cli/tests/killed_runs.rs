//! A run killed without warning (SIGKILL between writing a checkpoint and renaming it) and resumed from its directory:
//! the temporary file it left is removed, and `segments.csv` does not claim progress past the checkpoint the resume
//! continues from (issue 16).

use assert_cmd::Command;
use std::path::Path;

fn gc2d(dir: &Path, args: &[&str]) -> std::process::Output {
    Command::cargo_bin("gc2d-rs").unwrap().current_dir(dir).env("NO_COLOR", "1").args(args).output().unwrap()
}

#[test]
fn a_resume_after_a_kill_mid_checkpoint_removes_the_temporary_and_cuts_back_the_killed_row() {
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/tiny_pile.ron");
    std::fs::copy(&scene, dir.path().join("tiny_pile.ron")).unwrap();
    let first = gc2d(
        dir.path(),
        &["run", "tiny_pile.ron", "--quiet", "--out", "out", "--until", "0.06", "--checkpoint-every", "0.02"],
    );
    assert_eq!(first.status.code(), Some(0), "{}", String::from_utf8_lossy(&first.stderr));
    // What a SIGKILL while the checkpoint at t = 0.06 was being written leaves: that checkpoint still under its
    // temporary name, no final.ckpt, and the process's row as its last update wrote it (at t = 0.06, `running`).
    let out = dir.path().join("out");
    let checkpoints = out.join("checkpoints");
    let mut names: Vec<String> =
        std::fs::read_dir(&checkpoints).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    names.sort();
    assert_eq!(names.len(), 4, "t = 0, 0.02, 0.04, 0.06: {names:?}");
    let last = checkpoints.join(&names[3]);
    std::fs::rename(&last, checkpoints.join(format!("{}.tmp", names[3]))).unwrap();
    std::fs::remove_file(out.join("final.ckpt")).unwrap();
    std::fs::write(out.join("final.ckpt.tmp"), b"half a checkpoint").unwrap();
    std::fs::create_dir_all(out.join("frames")).unwrap();
    std::fs::write(out.join("frames/frame-000003.png.tmp"), b"half a picture").unwrap();
    let segments = std::fs::read_to_string(out.join("segments.csv")).unwrap();
    std::fs::write(out.join("segments.csv"), segments.replace(",completed,", ",running,")).unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let step = summary["time_step_s"].as_f64().unwrap();

    let resumed = gc2d(dir.path(), &["run", "tiny_pile.ron", "--quiet", "--resume", "out", "--until", "0.07"]);
    let stderr = String::from_utf8_lossy(&resumed.stderr);
    assert_eq!(resumed.status.code(), Some(0), "{stderr}");
    assert!(stderr.contains(&format!("Resuming from out/checkpoints/{}", names[2])), "{stderr}");
    let mut left: Vec<String> = std::fs::read_dir(&checkpoints)
        .unwrap()
        .chain(std::fs::read_dir(&out).unwrap())
        .chain(std::fs::read_dir(out.join("frames")).unwrap())
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|name| name.ends_with(".tmp"))
        .collect();
    left.sort();
    assert!(left.is_empty(), "temporary files left after the resume: {left:?}");

    // The killed row ends where the resumed one starts (the checkpoint at t = 0.04), with its steps cut to match.
    let segments = std::fs::read_to_string(out.join("segments.csv")).unwrap();
    let rows: Vec<Vec<&str>> = segments.lines().skip(1).map(|l| l.splitn(8, ',').collect()).collect();
    assert_eq!(rows.len(), 2, "{segments}");
    let number = |row: usize, column: usize| rows[row][column].parse::<f64>().unwrap();
    assert_eq!(rows[0][3], rows[1][2], "the killed row ends where the resume starts:\n{segments}");
    assert!((number(1, 2) - 0.04).abs() < 1e-5, "{segments}");
    assert_eq!(rows[0][6], "killed", "{segments}");
    assert!((number(0, 4) * step - 0.04).abs() < 2.0 * step, "steps of the killed row: {segments}");
    assert_eq!(rows[1][6], "completed", "{segments}");
    assert!((number(1, 3) - 0.07).abs() < step, "{segments}");
}

#[test]
fn resuming_into_the_recording_of_the_run_before_is_refused_and_its_frames_kept() {
    // It used to overwrite the frames recorded before the stop without a word (an MCAP file cannot be continued).
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/tiny_pile.ron");
    std::fs::copy(&scene, dir.path().join("tiny_pile.ron")).unwrap();
    let first = gc2d(
        dir.path(),
        &["run", "tiny_pile.ron", "--quiet", "--out", "out", "--until", "0.04", "--record", "run.mcap"],
    );
    assert_eq!(first.status.code(), Some(0), "{}", String::from_utf8_lossy(&first.stderr));
    let recorded = std::fs::read(dir.path().join("run.mcap")).unwrap();
    let series = std::fs::read_to_string(dir.path().join("out/timeseries.csv")).unwrap();
    let resumed = gc2d(dir.path(), &["run", "tiny_pile.ron", "--quiet", "--resume", "out", "--record", "run.mcap"]);
    let stderr = String::from_utf8_lossy(&resumed.stderr);
    assert_eq!(resumed.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("--record run.mcap: the file exists and holds the frames recorded before"), "{stderr}");
    assert!(stderr.contains("(say run.resumed.mcap)"), "{stderr}");
    assert_eq!(std::fs::read(dir.path().join("run.mcap")).unwrap(), recorded, "the recording is untouched");
    assert_eq!(std::fs::read_to_string(dir.path().join("out/timeseries.csv")).unwrap(), series, "so are the outputs");
    // Into a new file the resumed run records.
    let resumed =
        gc2d(dir.path(), &["run", "tiny_pile.ron", "--quiet", "--resume", "out", "--record", "run.resumed.mcap"]);
    assert_eq!(resumed.status.code(), Some(0), "{}", String::from_utf8_lossy(&resumed.stderr));
    assert!(std::fs::metadata(dir.path().join("run.resumed.mcap")).unwrap().len() > 0);
}

/// `analyze` on a run still in progress (its directory locked, periodic checkpoints and no final.ckpt yet) said the
/// run "was stopped without warning" and suggested `--resume` against the live run; it now says the run is still
/// being written. Once the lock is free, the same directory is a killed run and gets that hint.
#[test]
fn analysing_a_run_in_progress_says_so_instead_of_calling_it_killed() {
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/tiny_pile.ron");
    std::fs::copy(&scene, dir.path().join("tiny_pile.ron")).unwrap();
    let run = gc2d(
        dir.path(),
        &["run", "tiny_pile.ron", "--quiet", "--out", "out", "--until", "0.02", "--checkpoint-every", "0.01"],
    );
    assert_eq!(run.status.code(), Some(0), "{}", String::from_utf8_lossy(&run.stderr));
    let out = dir.path().join("out");
    std::fs::remove_file(out.join("final.ckpt")).unwrap();
    let lock = gc2d_cli::run_lock::lock_run_directory(&out).unwrap();
    let live = gc2d(dir.path(), &["analyze", "out"]);
    let stderr = String::from_utf8_lossy(&live.stderr);
    assert_eq!(live.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("a gc2d-rs run is still writing it") && !stderr.contains("--resume"), "{stderr}");
    drop(lock);
    let killed = gc2d(dir.path(), &["analyze", "out"]);
    let stderr = String::from_utf8_lossy(&killed.stderr);
    assert!(stderr.contains("stopped without warning") && stderr.contains("--resume"), "{stderr}");
}
