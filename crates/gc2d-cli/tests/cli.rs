//! The `gc2d-rs` binary as a user meets it: check, run, outputs, resume, interruption and bad input.

use assert_cmd::Command;
use predicates::prelude::PredicateBooleanExt;
use predicates::str::contains;
use std::path::{Path, PathBuf};

fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes").join(name)
}

fn gc2d() -> Command {
    Command::cargo_bin("gc2d-rs").unwrap()
}

/// `gc2d-rs run tests/scenes/tiny_pile.ron --quiet ARGS`: the run most tests start from.
fn run_tiny_pile(args: &[&str]) -> Command {
    let mut command = gc2d();
    command.args(["run", scene("tiny_pile.ron").to_str().unwrap(), "--quiet"]).args(args);
    command
}

/// Polls `done` until it holds, failing after a minute without `what` appearing (a run started in the background).
fn wait_for(what: &str, done: impl Fn() -> bool) {
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    while !done() {
        assert!(std::time::Instant::now() < deadline, "the run wrote no {what}");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
}

/// A PNG picture's width and height, pixels (its IHDR chunk, right after the signature).
fn png_size(path: &Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap();
    let word = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap());
    (word(16), word(20))
}

/// tiny_pile.ron run in one go, the reference for the resume tests.
fn unsplit_tiny_pile() -> tempfile::TempDir {
    let whole = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--out"]).arg(whole.path()).assert().success();
    whole
}

#[test]
fn check_prints_what_the_scene_contains() {
    gc2d()
        .args(["check", scene("tiny_pile.ron").to_str().unwrap()])
        .assert()
        .success()
        .stdout(contains("sources: 1"))
        .stdout(contains("stable bound"))
        .stdout(contains("memory (rough estimate): ").and(contains(" kB for up to 36 particles")))
        .stdout(contains("run time (rough estimate for one core): ").and(contains("particle-steps at 2 M/s")));
}

#[test]
fn run_writes_summary_series_and_final_checkpoint() {
    let out = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--out"]).arg(out.path()).assert().success().stderr(contains("Finished at t = 0.0"));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.path().join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["outcome"]["status"], "completed");
    assert!(summary["particles_inserted"].as_u64().unwrap() > 10);
    assert_eq!(summary["particles_removed"], 0);
    assert_eq!(summary["chatter"]["warned"], false, "a pour with impacts does not chatter: {}", summary["chatter"]);
    let series = std::fs::read_to_string(out.path().join("timeseries.csv")).unwrap();
    // A row every 1/100 s from 0 to 0.08.
    assert_eq!(series.lines().count(), 1 + 9);
    assert!(out.path().join("final.ckpt").exists());
}

#[test]
fn a_chattering_contact_is_warned_about_and_summarised() {
    let out = tempfile::tempdir().unwrap();
    gc2d()
        .args(["run", scene("chattering_plate.ron").to_str().unwrap(), "--quiet", "--out"])
        .arg(out.path())
        .assert()
        .success()
        .stderr(contains("warning: at t = ").and(contains("period-2 chatter")).and(contains("run.time_step_s")));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.path().join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["chatter"]["warned"], true);
    let largest = summary["chatter"]["largest_window"]["alternation"].as_f64().unwrap();
    assert!((largest - 1.0).abs() < 0.01, "force 0 and 2mg on alternate steps: alternation {largest}");
}

#[test]
fn a_resumed_run_keeps_the_chatter_of_the_processes_before_it() {
    // Issue 16: the summary of a resumed run described only its last process and lost an earlier warning. The plate
    // chatters from the start; the first process warns and stops at 0.01 s after checkpoints every 0.005 s, the
    // resumed one runs 0.002 s (645 steps, less than a window) and sees no window of its own.
    let out = tempfile::tempdir().unwrap();
    let path = scene("chattering_plate.ron");
    gc2d()
        .args(["run", path.to_str().unwrap(), "--quiet", "--until", "0.01", "--checkpoint-every", "0.005", "--out"])
        .arg(out.path())
        .assert()
        .success()
        .stderr(contains("period-2 chatter"));
    let read = || -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(out.path().join("summary.json")).unwrap()).unwrap()
    };
    let first = read()["chatter"]["largest_window"].clone();
    assert!(first["time_s"].as_f64().unwrap() <= 0.01, "{first}");
    // Continued in a new directory, the checkpoint carries on its run's watch too (QA determinism 5: it started afresh).
    let branch = tempfile::tempdir().unwrap();
    gc2d()
        .args(["run", path.to_str().unwrap(), "--quiet", "--until", "0.012", "--resume"])
        .arg(out.path().join("final.ckpt"))
        .arg("--out")
        .arg(branch.path())
        .assert()
        .success();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(branch.path().join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["chatter"]["largest_window"], first, "{}", summary["chatter"]);
    assert_eq!(summary["chatter"]["warned"], true, "{}", summary["chatter"]);
    gc2d()
        .args(["run", path.to_str().unwrap(), "--quiet", "--until", "0.012", "--resume"])
        .arg(out.path())
        .assert()
        .success();
    let summary = read();
    assert!((summary["time_s"].as_f64().unwrap() - 0.012).abs() < 4e-6, "the resumed process ran");
    let chatter = &summary["chatter"];
    assert_eq!(chatter["warned"], true, "{chatter}");
    assert_eq!(chatter["largest_window"], first, "the first process's largest window: {chatter}");
}

#[test]
fn a_run_split_by_resume_ends_bitwise_identical() {
    let whole = unsplit_tiny_pile();
    let split = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.025", "--out"]).arg(split.path()).assert().success();
    run_tiny_pile(&["--resume"]).arg(split.path().join("final.ckpt")).arg("--out").arg(split.path()).assert().success();
    let a = std::fs::read(whole.path().join("final.ckpt")).unwrap();
    let b = std::fs::read(split.path().join("final.ckpt")).unwrap();
    assert!(a == b, "the resumed run's final state differs from the unsplit run's");
    // The resumed run continued the time series instead of starting a new one.
    let series = std::fs::read_to_string(split.path().join("timeseries.csv")).unwrap();
    assert_eq!(series.lines().filter(|l| l.starts_with("time_s")).count(), 1);
}

/// `--resume DIR/final.ckpt` without `--out`, as the message of an interrupted run used to advise, continues into DIR
/// (it wrote the rest of the run to out/<scene> instead, leaving DIR's outputs stopped at the interruption).
#[test]
fn resuming_from_a_checkpoint_of_a_run_directory_continues_into_it() {
    let whole = unsplit_tiny_pile();
    let split = tempfile::tempdir().unwrap();
    let elsewhere = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.025", "--out"]).arg(split.path()).assert().success();
    run_tiny_pile(&["--resume"]).current_dir(elsewhere.path()).arg(split.path().join("final.ckpt")).assert().success();
    assert!(!elsewhere.path().join("out").exists(), "the resumed run wrote outside its run directory");
    let a = std::fs::read(whole.path().join("final.ckpt")).unwrap();
    let b = std::fs::read(split.path().join("final.ckpt")).unwrap();
    assert!(a == b, "the resumed run's final state differs from the unsplit run's");
    let series = std::fs::read_to_string(split.path().join("timeseries.csv")).unwrap();
    assert_eq!(series, std::fs::read_to_string(whole.path().join("timeseries.csv")).unwrap());
}

#[test]
fn resuming_from_an_earlier_checkpoint_rewrites_the_later_rows_of_the_series() {
    // A run stopped at 0.045 s after checkpoints at 0.02 and 0.04 s, then resumed from the 0.02 s one (as after a
    // crash whose newest checkpoint is damaged), with a half-written row at the end of its series: the series ends
    // byte-identical to an unsplit run's, with no time written twice.
    let whole = unsplit_tiny_pile();
    let split = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.045", "--checkpoint-every", "0.02", "--out"]).arg(split.path()).assert().success();
    let series_path = split.path().join("timeseries.csv");
    let mut series = std::fs::read_to_string(&series_path).unwrap();
    series.push_str("0.05,31,2");
    std::fs::write(&series_path, series).unwrap();
    let mut checkpoints: Vec<_> = std::fs::read_dir(split.path().join("checkpoints"))
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|p| p.file_name().unwrap().to_str().unwrap() != "checkpoint-0000000000.ckpt")
        .collect();
    checkpoints.sort();
    assert_eq!(checkpoints.len(), 2, "{checkpoints:?}");
    // Going back past the run's later states removes them: only with --go-back (QA: a finished run lost its final
    // state, later checkpoints, dumps and events without a word).
    let before = std::fs::read(&series_path).unwrap();
    run_tiny_pile(&["--resume"])
        .arg(&checkpoints[0])
        .arg("--out")
        .arg(split.path())
        .assert()
        .code(2)
        .stderr(contains("holds later states of the run").and(contains("checkpoint-")).and(contains("--go-back")));
    assert_eq!(std::fs::read(&series_path).unwrap(), before, "the refusal touched the run");
    assert!(checkpoints[1].is_file() && split.path().join("final.ckpt").is_file());
    run_tiny_pile(&["--go-back", "--resume"]).arg(&checkpoints[0]).arg("--out").arg(split.path()).assert().success();
    let expected = std::fs::read_to_string(whole.path().join("timeseries.csv")).unwrap();
    assert_eq!(std::fs::read_to_string(&series_path).unwrap(), expected);
}

/// The periodic checkpoints of `run_dir`, in step order, without the one of step 0.
fn periodic_checkpoints(run_dir: &Path) -> Vec<PathBuf> {
    let mut checkpoints: Vec<PathBuf> = std::fs::read_dir(run_dir.join("checkpoints"))
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|p| p.file_name().unwrap().to_str().unwrap() != "checkpoint-0000000000.ckpt")
        .collect();
    checkpoints.sort();
    checkpoints
}

#[test]
fn a_checkpoint_of_another_run_is_not_continued_in_a_run_directory() {
    // QA R12: a checkpoint of the same scene run with another seed, resumed with --out into the seed-1 run's
    // directory, was accepted: its time series held seed 1's rows up to the checkpoint and seed 2's after it.
    let seed_one = tempfile::tempdir().unwrap();
    let seed_two = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.025", "--checkpoint-every", "0.01", "--out"]).arg(seed_one.path()).assert().success();
    run_tiny_pile(&["--until", "0.025", "--checkpoint-every", "0.01", "--seed", "2", "--out"])
        .arg(seed_two.path())
        .assert()
        .success();
    let series = std::fs::read(seed_one.path().join("timeseries.csv")).unwrap();
    let foreign = &periodic_checkpoints(seed_two.path())[0];
    run_tiny_pile(&["--resume"])
        .arg(foreign)
        .arg("--out")
        .arg(seed_one.path())
        .assert()
        .code(2)
        .stderr(contains("is not one of the states of the run in").and(contains("Resuming").not()));
    assert_eq!(std::fs::read(seed_one.path().join("timeseries.csv")).unwrap(), series, "the run was touched");
    assert_eq!(periodic_checkpoints(seed_one.path()).len(), 2, "the run's later checkpoint was removed");
    // A copy of the run's own checkpoint, kept elsewhere, may go back in it; into a new directory, any may go on.
    let kept = tempfile::tempdir().unwrap();
    let copy = kept.path().join("settled.ckpt");
    std::fs::copy(&periodic_checkpoints(seed_one.path())[0], &copy).unwrap();
    run_tiny_pile(&["--go-back", "--resume"]).arg(&copy).arg("--out").arg(seed_one.path()).assert().success();
    let branch = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--resume"]).arg(foreign).arg("--out").arg(branch.path()).assert().success();
}

#[test]
fn a_checkpoint_outside_a_run_directory_does_not_cut_back_the_default_directory() {
    // QA R11: `--resume lone.ckpt` without --out went on in out/<scene>, and cut back the complete run there: its
    // later checkpoints removed, its time series truncated, its final.ckpt replaced.
    let work = tempfile::tempdir().unwrap();
    let default_dir = work.path().join("out").join("tiny_pile");
    run_tiny_pile(&["--until", "0.025", "--checkpoint-every", "0.01"]).current_dir(work.path()).assert().success();
    let final_state = std::fs::read(default_dir.join("final.ckpt")).unwrap();
    let lone = work.path().join("settled.ckpt");
    std::fs::copy(&periodic_checkpoints(&default_dir)[0], &lone).unwrap();
    run_tiny_pile(&["--resume"])
        .arg(&lone)
        .current_dir(work.path())
        .assert()
        .code(2)
        .stderr(contains("lies outside a run directory").and(contains("give --out")));
    assert_eq!(std::fs::read(default_dir.join("final.ckpt")).unwrap(), final_state, "the run there was cut back");
    assert_eq!(periodic_checkpoints(&default_dir).len(), 2);
}

#[test]
fn a_resume_does_not_silently_stop_the_events_or_dumps_of_the_parts_before() {
    // QA R5: resumed without --events (or --dump-every), a run left events.csv (the dumps) ending at the checkpoint
    // without a word, although the run went on to its end.
    let out = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.02", "--events", "--dump-every", "0.01", "--out"]).arg(out.path()).assert().success();
    let resume = |args: &[&str]| {
        let mut command = run_tiny_pile(&["--until", "0.03"]);
        command.args(args).arg("--resume").arg(out.path());
        command
    };
    resume(&["--dump-every", "0.01"]).assert().code(2).stderr(contains("add --events").and(contains("--no-events")));
    resume(&["--events"]).assert().code(2).stderr(contains("add --dump-every 0.01 --dump-format csv"));
    let series = std::fs::read(out.path().join("timeseries.csv")).unwrap();
    assert_eq!(std::fs::read(out.path().join("timeseries.csv")).unwrap(), series, "a refusal touched the run");
    resume(&["--no-events", "--dump-every", "0"]).assert().success();
}

#[test]
fn a_resume_does_not_silently_stop_the_pictures_of_the_parts_before() {
    // Resumed without --png-every, a run's frames ended at the checkpoint without a word; there was no --png-every 0.
    let out = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.02", "--png-every", "0.01", "--out"]).arg(out.path()).assert().success();
    let resume = |args: &[&str]| {
        let mut command = run_tiny_pile(&["--until", "0.03"]);
        command.args(args).arg("--resume").arg(out.path());
        command
    };
    resume(&[])
        .assert()
        .code(2)
        .stderr(contains("add --png-every 0.01").and(contains("--png-every 0 to let them end")));
    resume(&["--png-every", "0"]).assert().success();
    let frames = std::fs::read_dir(out.path().join("frames")).unwrap().flatten();
    let pictures = frames.filter(|entry| entry.file_name().to_string_lossy().ends_with(".png")).count();
    assert_eq!(pictures, 3, "the pictures at 0, 0.01 and 0.02 s stay, and no more are drawn");
    run_tiny_pile(&["--png-every", "-1", "--out"]).arg(out.path()).assert().code(2).stderr(contains("0: no pictures"));
}

#[test]
fn a_recording_and_a_snapshot_create_their_missing_folders_as_out_does() {
    // QA docs 22: --out created its folders, --record and snapshot -o failed on them (leaving a run folder that held
    // only its lock file).
    let dir = tempfile::tempdir().unwrap();
    let recording = dir.path().join("new/recordings/run.mcap");
    run_tiny_pile(&["--until", "0.005", "--record"])
        .arg(&recording)
        .arg("--out")
        .arg(dir.path().join("run"))
        .assert()
        .success();
    assert!(recording.is_file());
    let picture = dir.path().join("new/pictures/end.png");
    gc2d().arg("snapshot").arg(dir.path().join("run")).arg("-o").arg(&picture).assert().success();
    assert!(picture.is_file());
}

#[test]
fn a_checkpoint_continued_in_a_new_directory_draws_the_region_of_its_runs_pictures() {
    // QA determinism 3: without a view, the new directory's first picture fitted its own region, so that its frames
    // differed from the unsplit run's.
    let whole = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.03", "--png-every", "0.01", "--checkpoint-every", "0.02", "--out"])
        .arg(whole.path())
        .assert()
        .success();
    let branch = tempfile::tempdir().unwrap();
    let checkpoint = periodic_checkpoints(whole.path())[0].clone();
    run_tiny_pile(&["--until", "0.03", "--png-every", "0.01", "--resume"])
        .arg(&checkpoint)
        .arg("--out")
        .arg(branch.path())
        .assert()
        .success()
        .stderr(contains("neither a `view`").not());
    let cadence = |dir: &Path| std::fs::read_to_string(dir.join("frames/.gc2d-cadence")).unwrap();
    assert_eq!(cadence(branch.path()), cadence(whole.path()));
    let frame = |dir: &Path| std::fs::read(dir.join("frames/frame-00003.png")).unwrap();
    assert!(frame(branch.path()) == frame(whole.path()), "the last frame differs from the unsplit run's");
}

#[test]
fn events_and_no_events_together_are_refused() {
    // QA P2-10 k: the later flag won, and a mill run then told the user to add the --events it had been given.
    let out = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--events", "--no-events", "--out"])
        .arg(out.path())
        .assert()
        .code(2)
        .stderr(contains("'--events' cannot be used with '--no-events'"));
    assert!(!out.path().join("timeseries.csv").exists());
}

#[test]
fn a_checkpoint_continued_in_a_new_directory_writes_its_scene_there() {
    // QA R9: the new directory had every output but scene.ron, so it did not say what made it and `export` left the
    // particles' origins and materials empty.
    let first = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.02", "--checkpoint-every", "0.01", "--out"]).arg(first.path()).assert().success();
    let branch = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.03", "--resume"])
        .arg(&periodic_checkpoints(first.path())[0])
        .arg("--out")
        .arg(branch.path())
        .assert()
        .success();
    let copy = std::fs::read_to_string(branch.path().join("scene.ron")).unwrap();
    assert_eq!(copy, std::fs::read_to_string(first.path().join("scene.ron")).unwrap(), "the scene given, written out");
}

#[test]
fn a_recording_does_not_overwrite_the_scene_an_output_or_another_file() {
    // QA R3: `--record` replaced the scene being run with the recording; a path of the run's own outputs made the run
    // fail at its end, after removing the recording it had just opened as "the earlier run's" output.
    let dir = tempfile::tempdir().unwrap();
    let scene_copy = dir.path().join("pile.ron");
    std::fs::copy(scene("tiny_pile.ron"), &scene_copy).unwrap();
    let scene_text = std::fs::read(&scene_copy).unwrap();
    let out = dir.path().join("out");
    let notes = dir.path().join("notes.txt");
    std::fs::write(&notes, "the user's").unwrap();
    let record = |path: &Path| {
        let mut command = gc2d();
        command.args(["run", scene_copy.to_str().unwrap(), "--quiet", "--until", "0.005", "--out"]).arg(&out);
        command.arg("--record").arg(path);
        command
    };
    record(&scene_copy).assert().code(2).stderr(contains("the scene file being run"));
    assert_eq!(std::fs::read(&scene_copy).unwrap(), scene_text);
    record(&out.join("final.ckpt")).assert().code(2).stderr(contains("one of the run's own outputs"));
    record(&notes).assert().code(2).stderr(contains("not a recording"));
    assert_eq!(std::fs::read_to_string(&notes).unwrap(), "the user's");
    // A recording of an earlier run is replaced, as the run's other outputs are.
    let recording = dir.path().join("run.mcap");
    record(&recording).assert().success();
    record(&recording).assert().success();
}

#[test]
fn a_damaged_final_checkpoint_leaves_the_periodic_ones_to_resume_and_draw() {
    // QA R6: `--resume DIR` and `snapshot DIR` failed on a truncated final.ckpt, although an intact periodic
    // checkpoint was there (as `export` already used).
    let out = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.025", "--checkpoint-every", "0.01", "--out"]).arg(out.path()).assert().success();
    let final_checkpoint = out.path().join("final.ckpt");
    let bytes = std::fs::read(&final_checkpoint).unwrap();
    std::fs::write(&final_checkpoint, &bytes[..100]).unwrap();
    let picture = out.path().join("damaged.png");
    gc2d().arg("snapshot").arg(out.path()).arg("-o").arg(&picture).assert().success().stderr(
        contains("warning: cannot draw")
            .and(contains("newest periodic checkpoint is taken instead"))
            // QA docs 9: a damaged final.ckpt has no time to be "later than".
            .and(contains("later than").not()),
    );
    assert!(picture.is_file());
    gc2d()
        .arg("analyze")
        .arg(out.path())
        .assert()
        .code(2)
        .stderr(contains("periodic checkpoints are intact").and(contains("--resume")));
    run_tiny_pile(&["--until", "0.03", "--resume"])
        .arg(out.path())
        .assert()
        .success()
        .stderr(contains("newest periodic checkpoint is taken instead").and(contains("checkpoint-")));
    // The resumed run wrote a whole final.ckpt again.
    run_tiny_pile(&["--until", "0.035", "--resume"])
        .arg(out.path())
        .assert()
        .success()
        .stderr(contains("warning").not());
}

#[test]
fn a_snapshot_of_a_checkpoint_is_named_after_it() {
    // QA R13 b: every checkpoint was drawn into the same checkpoints/snapshot.png, each overwriting the one before.
    let out = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.025", "--checkpoint-every", "0.01", "--out"]).arg(out.path()).assert().success();
    let checkpoint = &periodic_checkpoints(out.path())[0];
    let stem = checkpoint.file_stem().unwrap().to_str().unwrap();
    gc2d().arg("snapshot").arg(checkpoint).assert().success();
    assert!(out.path().join(format!("snapshot-{stem}.png")).is_file());
    let elsewhere = tempfile::tempdir().unwrap();
    let copy = elsewhere.path().join("settled.ckpt");
    std::fs::copy(checkpoint, &copy).unwrap();
    gc2d().arg("snapshot").arg(&copy).assert().success();
    assert!(elsewhere.path().join("settled.png").is_file());
}

#[test]
fn resuming_a_run_directory_continues_from_its_newest_checkpoint() {
    // A run to 0.025 s (final.ckpt at 0.025), resumed to 0.045 s with checkpoints at 0.02 and 0.04 s and then
    // "killed": its final.ckpt is the stale one of the first part. `--resume DIR` without --out must pick the 0.04 s
    // checkpoint (more steps than the stale final.ckpt), write into DIR and end as the unsplit run.
    let whole = unsplit_tiny_pile();
    let split = tempfile::tempdir().unwrap();
    let part = |until: &str| {
        let mut command = run_tiny_pile(&["--until", until, "--checkpoint-every", "0.02", "--out"]);
        command.arg(split.path());
        command
    };
    part("0.025").assert().success();
    let stale_final = std::fs::read(split.path().join("final.ckpt")).unwrap();
    part("0.045").arg("--resume").arg(split.path().join("final.ckpt")).assert().success();
    std::fs::write(split.path().join("final.ckpt"), stale_final).unwrap();
    run_tiny_pile(&["--resume"])
        .arg(split.path())
        .assert()
        .success()
        .stderr(contains("checkpoint-").and(contains("Resuming from")));
    let a = std::fs::read(whole.path().join("final.ckpt")).unwrap();
    let b = std::fs::read(split.path().join("final.ckpt")).unwrap();
    assert!(a == b, "the run resumed from its directory differs from the unsplit run");
    // Now final.ckpt (at the end time) is newer than every periodic checkpoint, so it is the one resumed from.
    run_tiny_pile(&["--until", "0.08", "--resume"])
        .arg(split.path())
        .arg("--out")
        .arg(tempfile::tempdir().unwrap().path())
        .assert()
        .success()
        .stderr(contains("final.ckpt at t = 0.08"));
    let expected = std::fs::read_to_string(whole.path().join("timeseries.csv")).unwrap();
    assert_eq!(std::fs::read_to_string(split.path().join("timeseries.csv")).unwrap(), expected);
    // Three processes worked on the split run: segments.csv has a row for each, and the summary adds their times.
    let segments = std::fs::read_to_string(split.path().join("segments.csv")).unwrap();
    let rows: Vec<Vec<&str>> = segments.lines().skip(1).map(|l| l.splitn(10, ',').collect()).collect();
    assert_eq!(rows.len(), 3, "{segments}");
    let from: Vec<f64> = rows.iter().map(|r| r[2].parse().unwrap()).collect();
    assert!(
        (from[0] - 0.0).abs() < 1e-9 && (from[1] - 0.025).abs() < 1e-6 && (from[2] - 0.04).abs() < 1e-6,
        "{from:?}"
    );
    // The second process completed at 0.045 s, and the third went back to its checkpoint at 0.04 s: its row is cut
    // back to there and is no longer a completed part of the run.
    let statuses: Vec<&str> = rows.iter().map(|r| r[6]).collect();
    assert_eq!(statuses, ["completed", "superseded", "completed"], "{segments}");
    assert!(rows[0][9].is_empty() && rows[2][9].contains("checkpoint-"), "{segments}");
    let summed: f64 = rows.iter().map(|r| r[5].parse::<f64>().unwrap()).sum();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(split.path().join("summary.json")).unwrap()).unwrap();
    let total = summary["wall_time_all_segments_s"].as_f64().unwrap();
    assert!((total - summed).abs() < 0.01, "summary {total} s, rows {summed} s");
    assert!(total >= summary["wall_time_s"].as_f64().unwrap());
}

#[test]
fn a_killed_run_leaves_its_segment_row_with_the_time_so_far() {
    let out = tempfile::tempdir().unwrap();
    let bin = assert_cmd::cargo::cargo_bin("gc2d-rs");
    let mut child = std::process::Command::new(bin)
        .args(["run", scene("tiny_pile.ron").to_str().unwrap(), "--quiet", "--until", "1000"])
        .args(["--checkpoint-every", "0.01", "--out"])
        .arg(out.path())
        .spawn()
        .unwrap();
    let checkpoints = out.path().join("checkpoints");
    wait_for("checkpoints", || std::fs::read_dir(&checkpoints).map_or(0, |d| d.count()) >= 3);
    child.kill().unwrap();
    child.wait().unwrap();
    let segments = std::fs::read_to_string(out.path().join("segments.csv")).unwrap();
    let row: Vec<&str> = segments.lines().nth(1).expect("a row").splitn(8, ',').collect();
    assert_eq!(row[6], "running", "{segments}");
    assert!(row[3].parse::<f64>().unwrap() >= 0.01, "the row was updated on the checkpoints' cadence: {segments}");
    // Its analysis says why there is no final state and how to get one.
    gc2d()
        .arg("analyze")
        .arg(out.path())
        .assert()
        .code(2)
        .stderr(contains("only periodic checkpoints").and(contains("--resume")));
}

/// A second process into the directory of a run that still goes on is refused: the two used to interleave their
/// rows in one time series, with holes of zero bytes, and both ended with success.
#[test]
fn a_run_directory_in_use_is_refused() {
    let out = tempfile::tempdir().unwrap();
    let path = scene("tiny_pile.ron");
    let bin = assert_cmd::cargo::cargo_bin("gc2d-rs");
    let mut child = std::process::Command::new(bin)
        .args(["run", path.to_str().unwrap(), "--quiet", "--until", "1000", "--checkpoint-every", "0.01", "--out"])
        .arg(out.path())
        .spawn()
        .unwrap();
    let checkpoints = out.path().join("checkpoints");
    wait_for("checkpoints", || std::fs::read_dir(&checkpoints).map_or(0, |d| d.count()) >= 1);
    let second = run_tiny_pile(&["--resume"]).arg(out.path()).assert();
    child.kill().unwrap();
    child.wait().unwrap();
    second.code(2).stderr(contains("is in use by another gc2d-rs process (pid ").and(contains("choose another --out")));
    // Killed, the first process no longer holds the directory.
    run_tiny_pile(&["--until", "0.01", "--out"]).arg(out.path()).assert().success();
}

/// A checkpoint continued into another run's directory (`--out`) appended its rows to that run's time series, time
/// going backwards; it is refused when the directory's scene is not the scene given.
#[test]
fn resuming_into_the_directory_of_another_run_is_refused() {
    let (pile, plate) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    run_tiny_pile(&["--until", "0.01", "--out"]).arg(pile.path()).assert().success();
    gc2d()
        .args(["run", scene("chattering_plate.ron").to_str().unwrap(), "--quiet", "--until", "0.01", "--out"])
        .arg(plate.path())
        .assert()
        .success();
    let before = std::fs::read(plate.path().join("timeseries.csv")).unwrap();
    run_tiny_pile(&["--resume"])
        .arg(pile.path().join("final.ckpt"))
        .arg("--out")
        .arg(plate.path())
        .assert()
        .code(2)
        .stderr(contains("is not the scene the run in"));
    assert!(std::fs::read(plate.path().join("timeseries.csv")).unwrap() == before, "the other run was changed");
}

#[test]
fn resuming_a_directory_without_checkpoints_names_it() {
    let empty = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--resume"])
        .arg(empty.path())
        .assert()
        .code(2)
        .stderr(contains(empty.path().to_str().unwrap()).and(contains("neither final.ckpt")));
}

#[test]
fn a_seed_option_makes_another_member_of_the_ensemble() {
    let [scene_seed, same, other] = [(); 3].map(|_| tempfile::tempdir().unwrap());
    for (dir, seed) in [(&scene_seed, None), (&same, Some("3")), (&other, Some("4"))] {
        let mut command = run_tiny_pile(&["--out"]);
        command.arg(dir.path());
        if let Some(seed) = seed {
            command.args(["--seed", seed]);
        }
        command.assert().success();
    }
    let state = |dir: &tempfile::TempDir| std::fs::read(dir.path().join("final.ckpt")).unwrap();
    assert!(state(&scene_seed) == state(&same), "--seed 3 is the scene's own seed");
    assert!(state(&scene_seed) != state(&other), "another seed draws other shapes");
    // Each run directory keeps the scene it was made from, with the seed it used, and it reads back to that scene.
    let copy = gc2d_scene::Scene::from_path(other.path().join("scene.ron")).unwrap();
    let mut expected = gc2d_scene::Scene::from_path(scene("tiny_pile.ron")).unwrap();
    expected.run.seed = 4;
    assert_eq!(gc2d_scene::Scene { source: None, ..copy }, gc2d_scene::Scene { source: None, ..expected });
    run_tiny_pile(&["--seed", "4", "--resume"])
        .arg(scene_seed.path().join("final.ckpt"))
        .assert()
        .code(2)
        .stderr(contains("cannot be used with"));
}

#[test]
fn resuming_into_a_series_of_another_format_is_refused_without_touching_it() {
    let out = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.02", "--out"]).arg(out.path()).assert().success();
    let series_path = out.path().join("timeseries.csv");
    let foreign = "time_s,particles\n0,0\n";
    std::fs::write(&series_path, foreign).unwrap();
    run_tiny_pile(&["--resume"])
        .arg(out.path().join("final.ckpt"))
        .arg("--out")
        .arg(out.path())
        .assert()
        .code(2)
        .stderr(contains("timeseries.csv").and(contains("resume into a new --out directory")));
    assert_eq!(std::fs::read_to_string(&series_path).unwrap(), foreign);
}

#[test]
fn thread_count_does_not_change_the_result() {
    let one = tempfile::tempdir().unwrap();
    let two = tempfile::tempdir().unwrap();
    for (dir, threads) in [(&one, "1"), (&two, "2")] {
        run_tiny_pile(&["--threads", threads, "--out"]).arg(dir.path()).assert().success();
    }
    assert!(
        std::fs::read(one.path().join("final.ckpt")).unwrap() == std::fs::read(two.path().join("final.ckpt")).unwrap()
    );
}

#[test]
fn ctrl_c_stops_cleanly_with_readable_outputs() {
    stops_cleanly_with_readable_outputs_on("INT");
}

/// Batch systems end a job that reaches its time limit with SIGTERM before they kill it.
#[test]
fn sigterm_stops_cleanly_with_readable_outputs() {
    stops_cleanly_with_readable_outputs_on("TERM");
}

fn stops_cleanly_with_readable_outputs_on(signal: &str) {
    let out = tempfile::tempdir().unwrap();
    let bin = assert_cmd::cargo::cargo_bin("gc2d-rs");
    let child = std::process::Command::new(bin)
        .args(["run", scene("tiny_pile.ron").to_str().unwrap(), "--quiet", "--until", "1000", "--out"])
        .arg(out.path())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // Wait until the run has written its first rows, then interrupt it.
    let series = out.path().join("timeseries.csv");
    wait_for("time-series rows", || std::fs::read_to_string(&series).map_or(0, |s| s.lines().count()) >= 3);
    let killed =
        std::process::Command::new("kill").args([&format!("-{signal}"), &child.id().to_string()]).status().unwrap();
    assert!(killed.success());
    let output = child.wait_with_output().unwrap();
    assert_eq!(output.status.code(), Some(130));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("Interrupted at t ="), "{stderr}");
    assert!(stderr.contains(&format!("continue with `--resume {}`.", out.path().display())), "{stderr}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.path().join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["outcome"]["status"], "interrupted");
    let text = std::fs::read_to_string(&series).unwrap();
    let columns = text.lines().next().unwrap().split(',').count();
    assert!(text.lines().all(|l| l.split(',').count() == columns), "every row is complete");
    assert!(out.path().join("final.ckpt").exists());
}

#[test]
fn a_scene_named_scene_ron_in_its_own_output_directory_is_not_overwritten() {
    let out = tempfile::tempdir().unwrap();
    let own = out.path().join("scene.ron");
    std::fs::copy(scene("tiny_pile.ron"), &own).unwrap();
    let before = std::fs::read(&own).unwrap();
    gc2d()
        .args(["run", own.to_str().unwrap(), "--quiet", "--until", "0.01", "--out"])
        .arg(out.path())
        .assert()
        .success();
    assert!(std::fs::read(&own).unwrap() == before, "the user's scene file (with its comments) was rewritten");
}

/// `--out .` ended the run's last line with "Results in ..".
#[test]
fn a_run_into_the_current_folder_says_so() {
    let out = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.01", "--out", "."])
        .current_dir(out.path())
        .assert()
        .success()
        .stderr(contains("Results in the current folder.\n"));
    assert!(out.path().join("final.ckpt").exists());
}

/// A recording that cannot start left a run directory with a scene copy, a header-only time series and a segment
/// "running" for ever; the run directory is now left as it was.
#[test]
fn a_recording_that_cannot_start_leaves_the_run_directory_alone() {
    let out = tempfile::tempdir().unwrap();
    // A file where the recording's folder would be (a missing folder is created, as --out's is).
    std::fs::write(out.path().join("blocker"), "").unwrap();
    let recording = out.path().join("blocker/run.mcap");
    run_tiny_pile(&["--until", "0.01", "--record", recording.to_str().unwrap(), "--out"])
        .arg(out.path())
        .assert()
        .code(2)
        .stderr(contains("cannot create the folder").and(contains("blocker")));
    for file in ["scene.ron", "timeseries.csv", "segments.csv"] {
        assert!(!out.path().join(file).exists(), "{file} was written");
    }
}

#[test]
fn a_missing_scene_file_is_an_input_error() {
    gc2d().args(["check", "no/such/scene.ron"]).assert().code(2).stderr(contains("no/such/scene.ron"));
}

#[test]
fn zero_threads_is_refused() {
    run_tiny_pile(&["--threads", "0"]).assert().code(2).stderr(contains("--threads must be at least 1"));
}

/// A fresh run into a directory that holds an earlier run removes that run's checkpoints and dumps: they used to stay
/// beside the new run's outputs, and `export` and `--resume DIR` took the old run's later checkpoint for the newest
/// state of the new one.
#[test]
fn a_fresh_run_replaces_the_earlier_run_in_its_directory() {
    let out = tempfile::tempdir().unwrap();
    let run = |until: &str, extra: &[&str]| {
        let mut command = run_tiny_pile(&["--until", until]);
        command.args(extra).arg("--out").arg(out.path());
        command.assert().success()
    };
    run("0.045", &["--checkpoint-every", "0.02", "--dump-every", "0.02"]);
    assert!(out.path().join("checkpoints").read_dir().unwrap().count() > 1);
    std::fs::write(out.path().join("notes.txt"), "mine").unwrap();
    run("0.01", &[]).stderr(contains("Replacing the earlier run in"));
    assert!(!out.path().join("checkpoints").exists() && !out.path().join("dumps").exists());
    assert!(out.path().join("notes.txt").exists(), "a file of the user's was removed");
    run_tiny_pile(&["--until", "0.02", "--resume"])
        .arg(out.path())
        .assert()
        .success()
        .stderr(contains("at t = 0.010000 s"));
}

/// Pictures are numbered by their time on the cadence, so a resumed run adds to the earlier part's instead of
/// overwriting them from frame-00000.png on.
#[test]
fn a_resumed_run_numbers_its_pictures_on() {
    let out = tempfile::tempdir().unwrap();
    let part = |until: &str| run_tiny_pile(&["--png-every", "0.02", "--until", until]);
    part("0.025").arg("--out").arg(out.path()).assert().success();
    let first = std::fs::read(out.path().join("frames/frame-00000.png")).unwrap();
    // The resumed part keeps the first part's region, so it has nothing to warn of.
    part("0.045").arg("--resume").arg(out.path()).assert().success().stderr(contains("neither a `view`").not());
    let frames = || {
        let mut frames: Vec<String> = std::fs::read_dir(out.path().join("frames"))
            .unwrap()
            .map(|entry| entry.unwrap().file_name().into_string().unwrap())
            .filter(|name| name.starts_with("frame-"))
            .collect();
        frames.sort();
        frames
    };
    assert_eq!(frames(), ["frame-00000.png", "frame-00001.png", "frame-00002.png"]);
    assert!(std::fs::read(out.path().join("frames/frame-00000.png")).unwrap() == first, "the first picture changed");
    // The resumed part shows the region the first part's pictures fitted (recorded with their cadence): it fitted its
    // own, and one folder held two scales.
    let size = |name: &String| png_size(&out.path().join("frames").join(name));
    assert!(frames().iter().all(|f| size(f) == size(&frames()[0])), "the frames differ in size");
    // Another interval would number the resumed part's pictures on another clock: frame 2 at t = 0.02 after frame 2
    // at t = 0.04. It is refused before anything is touched; the same interval from an earlier checkpoint replaces the
    // pictures after it.
    let other = run_tiny_pile(&["--png-every", "0.01", "--until", "0.06", "--resume"]).arg(out.path()).assert();
    other.code(2).stderr(contains("interval of 0.02 s").and(contains("`--png-every 0.02`")));
    assert_eq!(frames(), ["frame-00000.png", "frame-00001.png", "frame-00002.png"]);
    let earlier = out.path().join("earlier.ckpt");
    run_tiny_pile(&["--until", "0.015", "--out"]).arg(out.path().join("early")).assert().success();
    std::fs::copy(out.path().join("early/final.ckpt"), &earlier).unwrap();
    part("0.015").arg("--go-back").arg("--resume").arg(&earlier).arg("--out").arg(out.path()).assert().success();
    assert_eq!(frames(), ["frame-00000.png"]);
}

/// A resumed run goes on with its checkpoint's state, so a scene edited since (or another scene) would be silently
/// ignored: it is refused, naming the line that differs. What a resumed run may change (its end time, the output
/// cadences) is accepted.
#[test]
fn resuming_with_another_scene_is_refused() {
    let out = tempfile::tempdir().unwrap();
    let path = scene("tiny_pile.ron");
    run_tiny_pile(&["--until", "0.01", "--out"]).arg(out.path()).assert().success();
    let text = std::fs::read_to_string(&path).unwrap();
    let edited = |from: &str, to: &str| {
        let edited = out.path().join("edited.ron");
        std::fs::write(&edited, text.replace(from, to)).unwrap();
        let mut command = gc2d();
        command.args(["run", edited.to_str().unwrap(), "--quiet", "--until", "0.02", "--resume"]).arg(out.path());
        command.assert()
    };
    edited("mu: 0.6", "mu: 0.1")
        .code(2)
        .stderr(contains("is not the scene the run in").and(contains("reads `mu: 0.1,` against `mu: 0.6,` there")));
    edited("end_time_s: 0.08, frames_per_second: 100", "end_time_s: 0.5, frames_per_second: 50").success();
}

/// A run ending between two rows of its time series (an end time off the frame cadence) wrote no row for its final
/// state: the series stopped at 0.01 s while summary.json and final.ckpt were at 0.013 s. And summary.json's energy
/// block now holds every term of the balance, so that it checks from the file alone.
#[test]
fn the_time_series_ends_at_the_final_state_and_the_summary_balances() {
    let out = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.013", "--out"]).arg(out.path()).assert().success();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.path().join("summary.json")).unwrap()).unwrap();
    let series = std::fs::read_to_string(out.path().join("timeseries.csv")).unwrap();
    let times: Vec<f64> = series.lines().skip(1).map(|line| line.split(',').next().unwrap().parse().unwrap()).collect();
    assert_eq!(times.len(), 3, "rows at 0, 0.01 and the end: {times:?}");
    assert_eq!(times[2], summary["time_s"].as_f64().unwrap());
    let e = |field: &str| summary["energy"][field].as_f64().unwrap();
    let stored = e("kinetic_j") + e("potential_j") + e("contact_stored_j") + e("drag_stored_j");
    let balance = stored - e("initial_total_j") - (e("work_in_j") - e("dissipated_j") - e("opening_residual_j"));
    assert!(
        (balance - e("balance_error_j")).abs() <= 1e-12 * e("work_in_j").abs(),
        "{balance} against {}",
        summary["energy"]
    );
    // Resumed from there to 0.03, the series is the unsplit run's: the off-cadence row is dropped again.
    run_tiny_pile(&["--until", "0.03", "--resume"]).arg(out.path()).assert().success();
    let whole = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.03", "--out"]).arg(whole.path()).assert().success();
    let read = |dir: &Path| std::fs::read_to_string(dir.join("timeseries.csv")).unwrap();
    assert!(read(out.path()) == read(whole.path()), "the split series differs from the unsplit one");
}

/// Resumed from an earlier checkpoint, a run left the later checkpoints of the stretch it went back from: `--resume
/// DIR`, `export` and `snapshot` then took the abandoned checkpoint at 0.02 s for the run's newest state, while
/// final.ckpt and the time series ended at 0.013 s. They are removed with that stretch's rows, dumps and frames.
#[test]
fn resuming_from_an_earlier_checkpoint_removes_the_later_ones() {
    let out = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.02", "--checkpoint-every", "0.01", "--out"]).arg(out.path()).assert().success();
    let checkpoints = out.path().join("checkpoints");
    let names = || {
        let mut names: Vec<String> =
            std::fs::read_dir(&checkpoints).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
        names.sort();
        names
    };
    // At 0, 0.01 and 0.02 s.
    assert_eq!(names().len(), 3, "{:?}", names());
    let earlier = checkpoints.join(&names()[1]);
    run_tiny_pile(&["--until", "0.013", "--go-back", "--resume"]).arg(&earlier).assert().success();
    assert_eq!(names(), ["checkpoint-0000000000.ckpt", earlier.file_name().unwrap().to_str().unwrap()]);
    run_tiny_pile(&["--until", "0.03", "--resume"])
        .arg(out.path())
        .assert()
        .success()
        .stderr(contains("final.ckpt at t = 0.013"));
    let whole = unsplit_tiny_pile();
    let series = |dir: &Path| std::fs::read_to_string(dir.join("timeseries.csv")).unwrap();
    let lines = |text: String| text.lines().take(4).map(str::to_owned).collect::<Vec<_>>();
    assert_eq!(lines(series(out.path())), lines(series(whole.path())), "the rows up to 0.03 s differ");
}

/// The run directory's own `scene.ron` edited by hand, or a checkpoint kept outside its run directory and resumed with
/// an edited scene, has no original to compare the scene with: the checkpoint itself is compared with the World the
/// scene builds.
#[test]
fn resuming_a_checkpoint_with_an_edited_scene_is_refused_without_its_run_directory() {
    let out = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.01", "--out"]).arg(out.path()).assert().success();
    let copy = out.path().join("scene.ron");
    let text = std::fs::read_to_string(&copy).unwrap();
    std::fs::write(&copy, text.replace("mu: 0.6", "mu: 0.1")).unwrap();
    let kept = tempfile::tempdir().unwrap();
    let resume = |scene: &Path, from: &Path| {
        let mut command = gc2d();
        command.args(["run", scene.to_str().unwrap(), "--quiet", "--until", "0.02", "--resume"]).arg(from);
        command.arg("--out").arg(kept.path().join("continued")).assert()
    };
    resume(&copy, out.path()).code(2).stderr(
        contains("does not continue")
            .and(contains("materials or interactions: `sand–sand: "))
            .and(contains("μ = 0.1"))
            .and(contains("`#0–#0: ")),
    );
    let checkpoint = kept.path().join("pile.ckpt");
    std::fs::copy(out.path().join("final.ckpt"), &checkpoint).unwrap();
    resume(&copy, &checkpoint).code(2).stderr(contains("does not continue"));
    std::fs::write(&copy, text).unwrap();
    resume(&copy, &checkpoint).success();
}

/// A source whose line lies closer to a wall than its particles' size finds no free spot: the run used to end
/// "completed" with no particle and no word, the skipped insertions only counted in summary.json. (A line inside the
/// wall is refused by `check`.)
#[test]
fn a_run_whose_sources_fed_nothing_warns() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("buried.ron");
    let text = "Scene(\n    run: (end_time_s: 0.2),\n    walls: [Wall(shape: Rectangle(width_m: 1, height_m: 0.2))],\n    \
                sources: [(position_m: (0, 0.102), width_m: 0.1, shape: (semi_axes_m: (0.005, 0.005)))],\n)";
    std::fs::write(&path, text).unwrap();
    gc2d()
        .args(["run", path.to_str().unwrap(), "--quiet", "--out"])
        .arg(dir.path().join("out"))
        .assert()
        .success()
        .stderr(contains("warning: no particle was inserted: the sources found no free spot"));
    run_tiny_pile(&["--until", "0.01", "--out"])
        .arg(dir.path().join("fed"))
        .assert()
        .success()
        .stderr(contains("no particle was inserted").not());
}

/// A resumed run cannot go back in time: `--until` before its checkpoint is refused instead of ending at once with a
/// zero-step segment and exit code 0.
#[test]
fn resuming_to_a_time_before_the_checkpoint_is_refused() {
    let split = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.025", "--out"]).arg(split.path()).assert().success();
    run_tiny_pile(&["--until", "0.01", "--resume"])
        .arg(split.path())
        .assert()
        .code(2)
        .stderr(contains("--until 0.01 s is before the time of").and(contains("t = 0.025000 s")));
}

/// Thousands of threads took minutes to start, with nothing printed; a count above the limit is refused before any
/// thread starts, by every command that takes one.
#[test]
fn thousands_of_threads_are_refused() {
    let tiny = scene("tiny_pile.ron");
    let tiny = tiny.to_str().unwrap();
    for args in [vec!["run", tiny, "--threads", "10000"], vec!["bench", "--threads", "1,10000"]] {
        gc2d().args(&args).assert().code(2).stderr(contains("--threads 10000 is more than the 1024 threads allowed"));
    }
}

#[test]
fn a_cadence_that_is_not_a_positive_time_is_refused() {
    for (flag, value) in [("--checkpoint-every", "0"), ("--checkpoint-every", "inf")] {
        run_tiny_pile(&[flag, value])
            .assert()
            .code(2)
            .stderr(contains(format!("{flag} must be a positive time in seconds")));
    }
    run_tiny_pile(&["--png-every", "nan"])
        .assert()
        .code(2)
        .stderr(contains("--png-every must be a time in seconds (0: no pictures), got NaN"));
    // A negative time is refused by the same check, not by clap's tip to write `-- -1`.
    for (flag, value, message) in [
        ("--checkpoint-every", "-1", "--checkpoint-every must be a positive time in seconds, got -1"),
        ("--until", "-1", "--until must be a non-negative time in seconds, got -1"),
        ("--until", "-1e-3", "--until must be a non-negative time in seconds, got -0.001"),
        ("--dump-every", "-inf", "--dump-every must be a time in seconds (0: no dumps), got -inf"),
    ] {
        run_tiny_pile(&[flag, value]).assert().code(2).stderr(contains(message));
    }
    gc2d().args(["export", ".", "--at", "nan"]).assert().code(2).stderr(contains("--at must be a finite time"));
    // Shorter than the time step: a file at every step (31,251 checkpoints for a 0.05 s run).
    let out = tempfile::tempdir().unwrap();
    for flag in ["--checkpoint-every", "--dump-every", "--png-every"] {
        run_tiny_pile(&[flag, "1e-9", "--out"])
            .arg(out.path())
            .assert()
            .code(2)
            .stderr(contains(format!("{flag} 1e-9 s is shorter than the time step")));
    }
}

/// A frame rate above one frame per step (1e11, a unit slip) was accepted by `check` and recorded a row at every
/// step, making a run of seconds take hours; `check` and `run` refuse it at the scene's field, as the other cadences.
#[test]
fn more_frames_per_second_than_steps_are_refused_at_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("fast_frames.ron");
    std::fs::write(
        &scene,
        "Scene(\n    run: (time_step_s: 1e-5, end_time_s: 0.01, frames_per_second: 1e11),\n    \
         particles: [(shape: Regular(corners: 6, radius_m: 0.002), position_m: (0, 0))],\n)\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    for args in [vec!["check"], vec!["run", "--out", out.to_str().unwrap()]] {
        gc2d()
            .args(&args)
            .arg(&scene)
            .assert()
            .code(2)
            .stderr(contains("fast_frames.ron:2:67").and(contains("more than one per time step of 1.000e-5 s")));
    }
}

#[test]
fn record_pictures_snapshot_and_analysis_of_a_run() {
    let out = tempfile::tempdir().unwrap();
    let recording = out.path().join("run.mcap");
    run_tiny_pile(&["--png-every", "0.04", "--record"])
        .arg(&recording)
        .arg("--out")
        .arg(out.path())
        .assert()
        .success()
        .stderr(contains("the scene has neither a `view` nor a `run.domain`"));
    // An MCAP file starts and ends with its magic; a finished recording has both.
    let bytes = std::fs::read(&recording).unwrap();
    let magic = b"\x89MCAP0\r\n";
    assert!(bytes.starts_with(magic) && bytes.ends_with(magic), "the recording is a finished MCAP file");
    // The scene is attached under its file name, not the path it was given as (QA outputs, 2026-11-29).
    let summary = mcap::Summary::read(&bytes).unwrap().expect("a finished recording has a summary");
    let names: Vec<&str> = summary.attachment_indexes.iter().map(|index| index.name.as_str()).collect();
    assert_eq!(names, ["tiny_pile.ron"]);
    // Pictures at t = 0, 0.04 and 0.08, all of one size: the scene has no view nor domain, so every picture shows the
    // region the first one fitted (each used to fit its own, and the size changed as the pile grew).
    let frames: Vec<PathBuf> = (0..3).map(|k| out.path().join(format!("frames/frame-{k:05}.png"))).collect();
    let sizes: Vec<(u32, u32)> = frames.iter().map(|f| png_size(f)).collect();
    assert!(sizes.iter().all(|size| *size == sizes[0]), "{sizes:?}");
    assert!(!out.path().join("frames/frame-00003.png").exists());
    gc2d().arg("snapshot").arg(out.path()).arg("--forces").assert().success().stderr(contains("snapshot.png"));
    let png = std::fs::read(out.path().join("snapshot.png")).unwrap();
    assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"));
    let analysed = gc2d().arg("analyze").arg(out.path()).assert().success().get_output().stdout.clone();
    let report: serde_json::Value = serde_json::from_slice(&analysed).unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.path().join("summary.json")).unwrap()).unwrap();
    assert_eq!(report["particles"], summary["particles"]);
    assert!(out.path().join("analysis/analysis.json").exists());
    // A cell far finer than the grid's limit of 1000 areas per axis was coarsened without a word.
    gc2d()
        .arg("analyze")
        .arg(out.path())
        .args(["--grid", "1e-9"])
        .assert()
        .success()
        .stderr(contains("--grid 1e-9 m would give more than 1000 test areas along an axis"));
}

/// The pile analysis of grains still falling (a run stopped early) warns that the pile has not formed, and of an
/// interrupted run that it did not complete: it used to report a "pile" of one grain, a packing fraction of 1 and an
/// angle of repose of 77° without a word.
#[test]
fn analysing_a_pile_that_has_not_formed_warns() {
    let out = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.01", "--out"]).arg(out.path()).assert().success();
    gc2d()
        .arg("analyze")
        .arg(out.path())
        .assert()
        .success()
        .stderr(contains("warning: only 1 of the 5 particles is in the pile").and(contains("did not complete").not()));
    let summary = out.path().join("summary.json");
    let text = std::fs::read_to_string(&summary).unwrap().replace("\"completed\"", "\"interrupted\"");
    std::fs::write(&summary, text).unwrap();
    gc2d()
        .arg("analyze")
        .arg(out.path())
        .assert()
        .success()
        .stderr(contains("did not complete (summary.json: interrupted)"));
}

#[test]
fn snapshot_of_a_missing_run_is_an_input_error() {
    gc2d().args(["snapshot", "no/such/run"]).assert().code(2).stderr(contains("no/such/run"));
    // A width the picture cannot have was changed without a word (0 gave 1 pixel, 100000 gave 16384).
    for width in ["0", "100000"] {
        gc2d()
            .args(["snapshot", "no/such/run", "--width", width])
            .assert()
            .code(2)
            .stderr(contains(format!("--width {width}: a picture is 1 to 16384 pixels wide")));
    }
}

/// A run killed without warning has periodic checkpoints and no final.ckpt: `snapshot` draws its newest state, as
/// `export` and `--resume DIR` take it (it failed on the missing final.ckpt). A file name other than .png, or one that
/// cannot be written, is an input error (exit 2).
#[test]
fn snapshot_draws_the_newest_state_of_a_killed_run() {
    let out = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.05", "--checkpoint-every", "0.02", "--out"]).arg(out.path()).assert().success();
    std::fs::remove_file(out.path().join("final.ckpt")).unwrap();
    gc2d()
        .arg("snapshot")
        .arg(out.path())
        .assert()
        .success()
        .stderr(contains("snapshot.png").and(contains("(t = 0.040000 s")));
    assert!(out.path().join("snapshot.png").is_file());
    let jpeg = out.path().join("picture.jpg");
    gc2d().arg("snapshot").arg(out.path()).arg("-o").arg(&jpeg).assert().code(2).stderr(contains("must end in .png"));
    let folder = out.path().join("folder.png");
    std::fs::create_dir(&folder).unwrap();
    gc2d().arg("snapshot").arg(out.path()).arg("-o").arg(&folder).assert().code(2).stderr(contains("cannot draw"));
}

/// `snapshot` of a run directory shows the region the scene's `view` names, as the frames of `--png-every` do (it
/// fitted the particles and walls, whatever the scene said).
#[test]
fn snapshot_shows_the_scenes_view() {
    let out = tempfile::tempdir().unwrap();
    run_tiny_pile(&["--until", "0.01", "--out"]).arg(out.path()).assert().success();
    let picture = out.path().join("fitted.png");
    gc2d().arg("snapshot").arg(out.path()).args(["--width", "400", "-o"]).arg(&picture).assert().success();
    assert_ne!(png_size(&picture), (400, 100));
    let copy = out.path().join("scene.ron");
    let text = std::fs::read_to_string(&copy).unwrap();
    let view = "view: Some((x_range_m: (-0.2, 0.2), y_range_m: (0.0, 0.1))),";
    std::fs::write(&copy, text.replace("view: None,", view)).unwrap();
    let picture = out.path().join("view.png");
    gc2d().arg("snapshot").arg(out.path()).args(["--width", "400", "-o"]).arg(&picture).assert().success();
    assert_eq!(png_size(&picture), (400, 100));
}

#[test]
fn check_and_run_warn_of_an_inlet_too_slow_for_its_rate() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("slow_inlet.ron");
    std::fs::write(
        &path,
        "Scene(\n    run: (time_step_s: 1e-3, end_time_s: 0.01, seed: 3),\n    gravity: Constant(0.0),\n    \
         materials: [(name: \"glass\", density_kg_m2: 1e4, youngs_modulus_n_m: 1e5)],\n    inlets: [(from_m: \
         (-0.05, 0.0), to_m: (0.05, 0.0), rate_per_s: 10, velocity_m_s: (3.0, 0.1),\n        shape: (semi_axes_m: \
         (0.01, 0.01), disk: true))],\n)\n",
    )
    .unwrap();
    let warning = || contains("warning:").and(contains("inlets[0].velocity_m_s")).and(contains("pile up"));
    gc2d().arg("check").arg(&path).assert().success().stderr(warning());
    let out = dir.path().join("out");
    gc2d().arg("run").arg(&path).arg("--quiet").arg("--out").arg(out).assert().success().stderr(warning());
}

/// QA outputs #8: `summary.json`'s `scene` and `segments.csv`'s `resumed_from` were the paths as typed, relative to the
/// shell the run was started from, so that they pointed nowhere from the run directory.
#[test]
fn the_scene_and_the_checkpoint_a_run_came_from_are_recorded_as_absolute_paths() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(scene("tiny_pile.ron"), dir.path().join("tiny.ron")).unwrap();
    let run = |extra: &[&str]| {
        gc2d()
            .current_dir(dir.path())
            .args(["run", "tiny.ron", "--quiet", "--out", "out"])
            .args(extra)
            .assert()
            .success();
    };
    run(&["--until", "0.01"]);
    run(&["--until", "0.02", "--resume", "out"]);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("out/summary.json")).unwrap()).unwrap();
    let recorded = Path::new(summary["scene"].as_str().unwrap());
    assert!(recorded.is_absolute() && recorded.ends_with("tiny.ron"), "{recorded:?}");
    assert!(std::fs::read_to_string(recorded).is_ok(), "{recorded:?} is the scene file");
    let segments = std::fs::read_to_string(dir.path().join("out/segments.csv")).unwrap();
    let resumed_from = Path::new(segments.lines().nth(2).unwrap().rsplit(',').next().unwrap());
    assert!(resumed_from.is_absolute() && resumed_from.ends_with("out/final.ckpt"), "{segments}");
}
