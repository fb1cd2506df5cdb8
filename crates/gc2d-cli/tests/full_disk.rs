//! A recording whose writes fail (a full disk) ends the run with a message, not a panic (issue 16: `--record` to a
//! file whose first write fails panicked in the mcap writer's drop), and names the file and the system's reason;
//! `export` and `snapshot` on a full disk leave no truncated file behind (QA R10).

use assert_cmd::Command;
use std::path::Path;

/// Runs gc2d-rs with `args` in `dir` under a file-size limit of `kib` KiB (`ulimit -f`, SIGXFSZ ignored so that a
/// write past it fails with EFBIG, as on a full disk); `None` without bash.
#[cfg(unix)]
fn limited(dir: &Path, kib: u32, args: &[&str]) -> Option<std::process::Output> {
    std::process::Command::new("bash")
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .args(["-c", &format!("trap '' XFSZ; ulimit -f {kib}; exec \"$@\""), "bash"])
        .arg(assert_cmd::cargo::cargo_bin("gc2d-rs"))
        .args(args)
        .output()
        .ok()
}

/// A recording whose writes fail ends the run with a message, not a panic (issue 16: a failed write made the mcap
/// writer panic when dropped), and the message names the recording and the system's reason: mcap's own one, "I/O
/// error from writing, or reading a compression stream", said neither (QA R10). The disk fills at the first write
/// (a 4 KiB file-size limit, at t = 0) and mid-run (16 KiB, at t = 0.05 s, while the run's own files still fit).
/// `/dev/full`, which stood for a full disk here, is refused by `run` now as an existing file that is not a recording.
#[cfg(unix)]
#[test]
fn a_recording_that_fills_the_disk_fails_cleanly_naming_the_file_and_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/tiny_pile.ron");
    for kib in [4, 16] {
        let (record, out) = (format!("rec{kib}.mcap"), format!("out{kib}"));
        let args = ["run", scene.to_str().unwrap(), "--quiet", "--record", &record, "--out", &out];
        let Some(output) = limited(dir.path(), kib, &args) else {
            eprintln!("skipped: no bash to set a file-size limit with");
            return;
        };
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{kib} KiB: {stderr}");
        assert!(!stderr.contains("panicked"), "{kib} KiB: {stderr}");
        assert!(stderr.contains(&format!("recording: cannot write {record} (MCAP writer): ")), "{kib} KiB: {stderr}");
        assert!(stderr.contains(": File too large (os error 27)"), "{kib} KiB: {stderr}");
    }
}

/// A short run of the tiny pile in `dir/run`, with its final checkpoint.
#[cfg(unix)]
fn tiny_run(dir: &Path) {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/tiny_pile.ron");
    Command::cargo_bin("gc2d-rs")
        .unwrap()
        .args(["run", scene.to_str().unwrap(), "--until", "0.03", "--quiet", "--out"])
        .arg(dir.join("run"))
        .assert()
        .success();
}

/// The names of the files in `folder`, sorted.
#[cfg(unix)]
fn file_names(folder: &Path) -> Vec<String> {
    let mut names: Vec<String> =
        std::fs::read_dir(folder).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    names
}

/// An export whose outlines do not fit on the disk fails, leaves no truncated `.vtu` (nor its temporary file), and
/// lists the file in `.gc2d-export`, so that the next export there, at another time, has only its own files.
#[cfg(unix)]
#[test]
fn an_export_that_fills_the_disk_leaves_no_truncated_file_and_the_next_export_replaces_it() {
    let dir = tempfile::tempdir().unwrap();
    tiny_run(dir.path());
    let Some(output) = limited(dir.path(), 1, &["export", "run", "--format", "vtk", "--out", "exp"]) else {
        eprintln!("skipped: no bash to set a file-size limit with");
        return;
    };
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("cannot write exp/particles_") && stderr.contains("File too large"), "{stderr}");
    let exp = dir.path().join("exp");
    let left = file_names(&exp);
    assert_eq!(left, [".gc2d-export"], "only the manifest, no truncated or temporary file");
    let manifest = std::fs::read_to_string(exp.join(".gc2d-export")).unwrap();
    assert!(manifest.starts_with("particles_") && manifest.trim_end().ends_with(".vtu"), "{manifest}");
    // A killed export's temporary file goes with the next export, as the file the manifest lists.
    let temporary = format!("{}.tmp", manifest.trim_end());
    std::fs::write(exp.join(&temporary), "<VTKFile").unwrap();
    Command::cargo_bin("gc2d-rs")
        .unwrap()
        .current_dir(dir.path())
        .args(["export", "run", "--format", "csv", "--out", "exp"])
        .assert()
        .success();
    assert_eq!(file_names(&exp), [".gc2d-export", "contacts.csv", "particles.csv"]);
}

/// A snapshot that does not fit on the disk fails and leaves neither a truncated PNG nor its temporary file.
#[cfg(unix)]
#[test]
fn a_snapshot_that_fills_the_disk_leaves_no_truncated_picture() {
    let dir = tempfile::tempdir().unwrap();
    tiny_run(dir.path());
    std::fs::create_dir(dir.path().join("pictures")).unwrap();
    let Some(output) = limited(dir.path(), 1, &["snapshot", "run", "-o", "pictures/a.png"]) else {
        eprintln!("skipped: no bash to set a file-size limit with");
        return;
    };
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_ne!(output.status.code(), Some(0), "{stderr}");
    assert!(stderr.contains("cannot write pictures/a.png: File too large"), "{stderr}");
    assert_eq!(file_names(&dir.path().join("pictures")), Vec::<String>::new());
}

/// A disk that fills in the middle of a run, stood for by a file-size limit of 2 KiB (`ulimit -f 2`, with SIGXFSZ
/// ignored so that writes past it fail with EFBIG instead of killing the process): the time series stops growing,
/// the final checkpoint cannot be written, and the scene path is long enough (eight folders of 201 characters) that
/// summary.json, which records it as an absolute path, is larger than the limit as well. The run must say which files are missing instead of calling the
/// outputs complete, and leave no truncated summary.json.
#[cfg(unix)]
#[test]
fn a_disk_that_fills_mid_run_leaves_no_broken_summary_and_names_what_is_missing() {
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/tiny_pile.ron");
    let folders = (0..8).fold(std::path::PathBuf::new(), |path, k| path.join(format!("{k}{}", "d".repeat(200))));
    std::fs::create_dir_all(dir.path().join(&folders)).unwrap();
    let long_path = folders.join("tiny_pile.ron");
    std::fs::copy(&scene, dir.path().join(&long_path)).unwrap();
    let Some(output) = limited(dir.path(), 2, &["run", long_path.to_str().unwrap(), "--quiet", "--out", "out"]) else {
        eprintln!("skipped: no bash to set a file-size limit with");
        return;
    };
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(!stderr.contains("panicked") && !stderr.contains("complete up to this point"), "{stderr}");
    assert!(stderr.contains("could not write the time series: File too large"), "the first failure: {stderr}");
    assert!(stderr.contains("these files could not be written: out/final.ckpt"), "{stderr}");
    assert!(stderr.contains("out/summary.json (File too large"), "{stderr}");
    let out = dir.path().join("out");
    assert!(!out.join("summary.json").exists(), "no truncated summary.json");
    let left: Vec<_> = std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert!(left.iter().all(|name| !name.to_string_lossy().ends_with(".tmp")), "{left:?}");
    // The time series holds whole rows up to where the disk filled, and the row counter said so.
    let series = std::fs::read_to_string(out.join("timeseries.csv")).unwrap();
    assert!(series.len() <= 2048 && series.lines().count() >= 3, "{series}");
}
