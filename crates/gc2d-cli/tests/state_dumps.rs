//! `gc2d-rs run --dump-every`: per-particle state in `dumps/particles_<k>.csv`, on by default for a mill (with
//! events), the same bytes for any thread count and across a resume (and so the mill statistics made from them), and
//! the mill summary at the end of the run.

use assert_cmd::Command;
use gc2d_analysis::particle_state::csv::{PARTICLE_STATE_COLUMNS, read_csv};
use gc2d_analysis::{ParticleShape, particle_states};
use gc2d_engine::World;
use std::path::{Path, PathBuf};

/// The bundled mill with six balls (a few milliseconds of it take well under a second in release).
fn small_mill(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/mill.ron")).unwrap();
    assert!(text.contains("count: 130"));
    let path = dir.join("mill6.ron");
    std::fs::write(&path, text.replace("count: 130", "count: 6")).unwrap();
    path
}

fn gc2d() -> Command {
    Command::cargo_bin("gc2d-rs").unwrap()
}

/// Runs `scene` to `until` into `out` with the extra arguments; returns stderr.
fn run(scene: &Path, out: &Path, until: &str, extra: &[&str]) -> String {
    let output = gc2d()
        .arg("run")
        .arg(scene)
        .args(["--quiet", "--until", until])
        .args(extra)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert!(output.status.success(), "{stderr}");
    stderr
}

/// The dump files of a run directory, name and content as text, in order.
fn dumps(out: &Path) -> Vec<(String, String)> {
    dump_bytes(out).into_iter().map(|(name, bytes)| (name, String::from_utf8(bytes).unwrap())).collect()
}

#[test]
fn a_mill_run_dumps_its_balls_at_the_frame_rate_and_the_last_dump_is_the_final_state() {
    let dir = tempfile::tempdir().unwrap();
    let scene = small_mill(dir.path());
    let out = dir.path().join("one");
    let stderr = run(&scene, &out, "0.01", &["--threads", "1"]);
    // 500 frames per second: dumps 0 … 5 at t = 0, 2, …, 10 ms, and events by default.
    let files = dumps(&out);
    let names: Vec<&str> = files.iter().map(|f| f.0.as_str()).collect();
    assert_eq!(names, (0..=5).map(|k| format!("particles_{k:06}.csv")).collect::<Vec<_>>());
    // The interval the dumps are numbered on, which a resumed part must keep.
    assert_eq!(
        std::fs::read_to_string(out.join("dumps/.gc2d-cadence")).unwrap(),
        "interval_s = 0.002\nformats = csv\n"
    );
    assert!(out.join("events.csv").exists());
    let first = read_csv(&out.join("dumps/particles_000000.csv")).unwrap();
    assert_eq!(files[0].1.lines().next().unwrap(), PARTICLE_STATE_COLUMNS.join(","));
    assert_eq!(first.len(), 6);
    for ball in &first {
        // The scene's start: 1 m/s in a random direction, no contact, inside the chamber (73 mm less a radius).
        assert_eq!(ball.time_s, 0.0);
        assert!((ball.speed() - 1.0).abs() < 1e-12, "{}", ball.speed());
        assert_eq!((ball.shape, ball.material.as_str(), ball.contacts), (ParticleShape::Disk, "steel", 0));
        assert!(ball.x_m.hypot(ball.y_m) <= 0.073 - 0.0025);
    }
    for (k, (_, text)) in files.iter().enumerate() {
        let rows = text.lines().count() - 1;
        assert_eq!(rows, 6, "dump {k}");
    }
    // The last dump is the final checkpoint's state, bit for bit.
    let world = World::load_checkpoint_file(out.join("final.ckpt")).unwrap();
    let last = read_csv(&out.join("dumps/particles_000005.csv")).unwrap();
    assert_eq!(last, particle_states(&world, &["steel".to_string()]));
    assert_eq!(last[0].time_s, world.time());
    assert!(last.iter().all(|b| b.id as usize >= world.bodies().len() - 6), "balls come after the walls");
    // The summary at the end of the run names the window, the speeds and powers, and the analysis command.
    assert!(stderr.contains("Mill over") && stderr.contains("median ball speed"), "{stderr}");
    assert!(stderr.contains("blade hits per revolution") && stderr.contains("gc2d-rs analyze"), "{stderr}");

    // Two threads write the same bytes; so does a run stopped at 4 ms and resumed.
    let two = dir.path().join("two");
    run(&scene, &two, "0.01", &["--threads", "2"]);
    assert!(dumps(&two) == files, "dumps differ between one and two threads");
    let split = dir.path().join("split");
    run(&scene, &split, "0.004", &[]);
    let resumed =
        gc2d().arg("run").arg(&scene).args(["--quiet", "--until", "0.01", "--resume"]).arg(&split).output().unwrap();
    assert!(resumed.status.success(), "{}", String::from_utf8_lossy(&resumed.stderr));
    assert!(dumps(&split) == files, "dumps differ across a resume");

    // So the mill statistics are the same too: every table, figure and mill.json, byte for byte.
    let analysis = |run_dir: &Path| {
        let done = gc2d().arg("analyze").arg(run_dir).args(["--kind", "mill", "--warm-up", "0.002"]).output().unwrap();
        assert!(done.status.success(), "{}", String::from_utf8_lossy(&done.stderr));
        let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(run_dir.join("analysis"))
            .unwrap()
            .map(|e| e.unwrap())
            .map(|e| (e.file_name().into_string().unwrap(), std::fs::read(e.path()).unwrap()))
            .collect();
        files.sort();
        files
    };
    let statistics = analysis(&out);
    assert!(statistics.iter().any(|(name, _)| name == "mill.json"));
    assert!(analysis(&two) == statistics, "the mill statistics differ between one and two threads");
    assert!(analysis(&split) == statistics, "the mill statistics differ across a resume");
}

#[test]
fn dumps_and_events_can_be_switched_off_for_a_mill_and_on_for_any_scene() {
    let dir = tempfile::tempdir().unwrap();
    let scene = small_mill(dir.path());
    let off = dir.path().join("off");
    let stderr = run(&scene, &off, "0.002", &["--dump-every", "0", "--no-events"]);
    assert!(!off.join("dumps").exists() && !off.join("events.csv").exists());
    assert!(stderr.contains("No mill summary") && stderr.contains("events.csv is missing"), "{stderr}");
    // Every 1 ms instead of the frame rate: t = 0, 1, 2 ms.
    let fine = dir.path().join("fine");
    run(&scene, &fine, "0.002", &["--dump-every", "0.001"]);
    assert_eq!(dumps(&fine).len(), 3);
    let bad = gc2d().arg("run").arg(&scene).args(["--dump-every=-1"]).output().unwrap();
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("--dump-every"));

    // A scene without a mill dumps only when asked.
    let balls = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/balls.ron");
    let plain = dir.path().join("plain");
    run(&balls, &plain, "0.0", &[]);
    assert!(!plain.join("dumps").exists() && !plain.join("events.csv").exists());
    // A dump format without dumps was ignored without a word.
    let formats_only = gc2d()
        .arg("run")
        .arg(&balls)
        .args(["--quiet", "--until", "0", "--dump-format", "parquet", "--out"])
        .arg(dir.path().join("formats_only"))
        .output()
        .unwrap();
    assert_eq!(formats_only.status.code(), Some(2));
    let message = String::from_utf8_lossy(&formats_only.stderr);
    assert!(
        message.contains("--dump-format is given, but this run writes no dumps") && message.contains("--dump-every"),
        "{message}"
    );
    run(&balls, &plain, "0.0", &["--dump-every", "0.01"]);
    let rows = read_csv(&plain.join("dumps/particles_000000.csv")).unwrap();
    let world = World::load_checkpoint_file(plain.join("final.ckpt")).unwrap();
    assert_eq!(rows.len(), world.bodies().particles().count());
}

/// Every file of a run's dumps folder but its record of the interval, name and bytes, in order.
fn dump_bytes(out: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(out.join("dumps"))
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| e.file_name() != ".gc2d-cadence")
        .map(|e| (e.file_name().into_string().unwrap(), std::fs::read(e.path()).unwrap()))
        .collect();
    files.sort();
    files
}

#[test]
fn parquet_and_vtk_dumps_with_their_collection_are_the_same_for_any_thread_count_and_across_a_resume() {
    let dir = tempfile::tempdir().unwrap();
    let scene = small_mill(dir.path());
    let formats = ["--dump-format", "csv,parquet,vtk"];
    let one = dir.path().join("one");
    run(&scene, &one, "0.01", &[&["--threads", "1"][..], &formats[..]].concat());
    let files = dump_bytes(&one);
    let names: Vec<&str> = files.iter().map(|f| f.0.as_str()).collect();
    for k in 0..=5 {
        for extension in ["csv", "parquet", "vtu"] {
            assert!(names.contains(&format!("particles_{k:06}.{extension}").as_str()), "{names:?}");
        }
    }
    let pvd = String::from_utf8(files.iter().find(|f| f.0 == "particles.pvd").unwrap().1.clone()).unwrap();
    assert_eq!(pvd.matches("<DataSet ").count(), 6, "{pvd}");
    assert!(pvd.contains(r#"timestep="1e-2" group="" part="0" file="particles_000005.vtu""#), "{pvd}");
    let two = dir.path().join("two");
    run(&scene, &two, "0.01", &[&["--threads", "2", "--checkpoint-every", "0.004"][..], &formats[..]].concat());
    assert!(dump_bytes(&two) == files, "dumps differ between one and two threads");
    let split = dir.path().join("split");
    run(&scene, &split, "0.004", &formats);
    let resumed = gc2d()
        .arg("run")
        .arg(&scene)
        .args(["--quiet", "--until", "0.01", "--resume"])
        .arg(&split)
        .args(formats)
        .output()
        .unwrap();
    assert!(resumed.status.success(), "{}", String::from_utf8_lossy(&resumed.stderr));
    assert!(dump_bytes(&split) == files, "dumps differ across a resume");
    // Resumed at t = 0.004 and run to 0.006: the dumps from 0.004 on are the resumed part's, in every format, and the
    // earlier part's later ones (0.008, 0.01) are gone with the stretch the run went back from; particles.pvd lists
    // what is left.
    // A copy of the run's own checkpoint of t = 0.004, kept outside it (only a state of the run may go on in it).
    let checkpoint = dir.path().join("at_0.004.ckpt");
    let mut own: Vec<_> = std::fs::read_dir(two.join("checkpoints")).unwrap().map(|e| e.unwrap().path()).collect();
    own.sort();
    std::fs::copy(&own[1], &checkpoint).unwrap();
    let resume_from_checkpoint = |extra: &[&str]| {
        gc2d()
            .arg("run")
            .arg(&scene)
            .args(["--quiet", "--until", "0.006", "--go-back", "--resume"])
            .arg(&checkpoint)
            .arg("--out")
            .arg(&two)
            .args(extra)
            .output()
            .unwrap()
    };
    let shorter = resume_from_checkpoint(&formats);
    assert!(shorter.status.success(), "{}", String::from_utf8_lossy(&shorter.stderr));
    let now = dump_bytes(&two);
    for (name, bytes) in &files {
        let k: u64 =
            name.strip_prefix("particles_").and_then(|n| n.split('.').next()).map_or(0, |k| k.parse().unwrap());
        let kept = now.iter().find(|f| &f.0 == name);
        if name.starts_with("particles_") && k > 3 {
            assert!(kept.is_none(), "{name} of the abandoned stretch is still there");
        } else if name.starts_with("particles_") {
            assert!(kept.is_some_and(|f| &f.1 == bytes), "{name} differs from the unsplit run's");
        }
    }
    let pvd = std::fs::read_to_string(two.join("dumps/particles.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet ").count(), 4, "{pvd}");
    // Other formats would leave no format covering the whole run (an analysis reads the CSV dumps): refused.
    let other = resume_from_checkpoint(&["--dump-format", "csv"]);
    assert_eq!(other.status.code(), Some(2));
    let message = String::from_utf8_lossy(&other.stderr);
    assert!(
        message.contains("holds files in parquet,csv,vtk") && message.contains("`--dump-format parquet,csv,vtk`"),
        "{message}"
    );
    // Another interval is refused, naming the one the files are numbered on.
    let other = resume_from_checkpoint(&[&formats[..], &["--dump-every", "0.001"]].concat());
    assert_eq!(other.status.code(), Some(2));
    let message = String::from_utf8_lossy(&other.stderr);
    assert!(message.contains("interval of 0.002 s") && message.contains("`--dump-every 0.002`"), "{message}");
}
