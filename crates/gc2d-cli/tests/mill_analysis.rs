//! `gc2d-rs analyze RUN --kind mill` on a short run of the bundled mill: collision classes with consistent statistics,
//! and the rotor's two powers equal.

mod common;

use assert_cmd::Command;
use std::path::Path;

#[test]
fn a_mill_run_is_analysed_into_collision_classes_and_a_power_balance() {
    let out = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/mill.ron");
    let gc2d = || Command::cargo_bin("gc2d-rs").unwrap();
    gc2d()
        .args(["run", scene.to_str().unwrap(), "--quiet", "--events", "--until", "0.02", "--out"])
        .arg(out.path())
        .assert()
        .success();
    // A run that ends between two flushes of events.csv (every 2 ms here) has written the file whole when its own
    // summary reads it: its last rows were left in the buffer, and the summary blamed a damaged file.
    let short = tempfile::tempdir().unwrap();
    let run = gc2d()
        .args(["run", scene.to_str().unwrap(), "--quiet", "--events", "--until", "0.005", "--out"])
        .arg(short.path())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success() && stderr.contains("Tables, maps and figures"), "{stderr}");
    // A run of no step (to look at the start) has nothing to summarise, and no warm-up to complain of.
    let start = gc2d()
        .args(["run", scene.to_str().unwrap(), "--quiet", "--until", "0", "--out"])
        .arg(short.path().join("start"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&start.stderr);
    assert!(start.status.success() && !stderr.contains("mill summary"), "{stderr}");
    let output = gc2d().arg("analyze").arg(out.path()).args(["--kind", "mill", "--warm-up", "0.005"]).output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    // Without --kind the run's scene.ron makes it a mill's analysis (QA P2-10 c: it ran the pile analysis).
    let auto = gc2d().arg("analyze").arg(out.path()).args(["--warm-up", "0.005"]).output().unwrap();
    assert!(
        String::from_utf8_lossy(&auto.stderr).contains("as a mill run"),
        "{}",
        String::from_utf8_lossy(&auto.stderr)
    );
    assert_eq!(serde_json::from_slice::<serde_json::Value>(&auto.stdout).unwrap(), report);
    // A time series without a power column is named as the file that lacks it (the message said events.csv).
    let series_path = out.path().join("timeseries.csv");
    let series = std::fs::read_to_string(&series_path).unwrap();
    std::fs::write(&series_path, series.replacen("rotor_work_j", "renamed", 1)).unwrap();
    let lacking =
        gc2d().arg("analyze").arg(out.path()).args(["--kind", "mill", "--warm-up", "0.005"]).output().unwrap();
    let message = String::from_utf8_lossy(&lacking.stderr);
    assert!(message.contains("timeseries.csv has no column `rotor_work_j`"), "{message}");
    std::fs::write(&series_path, series).unwrap();
    let classes = report["classes"].as_array().unwrap();
    let names: Vec<&str> = classes.iter().map(|c| c["class"].as_str().unwrap()).collect();
    assert!(
        names.contains(&"ball–ball") && names.contains(&"ball–chamber") && names.contains(&"ball–blade"),
        "{names:?}"
    );
    for class in classes {
        let q: Vec<f64> = class["quartiles_m_s"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        assert!(q[0] <= q[1] && q[1] <= q[2], "{q:?}");
        let above: Vec<f64> =
            class["fractions_above"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        assert!(above.windows(2).all(|w| w[0] >= w[1]) && above.iter().all(|f| (0.0..=1.0).contains(f)), "{above:?}");
        let edges: Vec<f64> = class["bin_edges_m_s"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        let densities: Vec<f64> = class["densities"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        let area: f64 = densities.iter().zip(edges.windows(2)).map(|(d, e)| d * (e[1] - e[0])).sum();
        assert!((area - 1.0).abs() < 1e-9, "histogram area {area}");
        assert!(class["collisions"].as_u64().unwrap() > 0);
    }
    let power = &report["power"];
    let (torque, work) = (power["mean_power_torque_w"].as_f64().unwrap(), power["mean_power_work_w"].as_f64().unwrap());
    assert!((torque - work).abs() <= 1e-9 * work.abs(), "ω·τ {torque} W against Σ F·v {work} W");
    for file in ["mill.json", "mill_collisions.csv", "mill_speed_histograms.csv"] {
        assert!(out.path().join("analysis").join(file).exists(), "{file} is missing");
    }
    // A damaged events file (a line cut short, as by an edit or a file cut mid-row) is an error naming the line; its
    // rows were left out in silence, with a third of the collisions counted.
    let events_path = out.path().join("events.csv");
    let events = std::fs::read_to_string(&events_path).unwrap();
    let mut lines: Vec<&str> = events.lines().collect();
    lines[3] = "garbage,line,here";
    std::fs::write(&events_path, lines.join("\n") + "\n").unwrap();
    let damaged =
        gc2d().arg("analyze").arg(out.path()).args(["--kind", "mill", "--warm-up", "0.005"]).output().unwrap();
    assert_eq!(damaged.status.code(), Some(2));
    let message = String::from_utf8_lossy(&damaged.stderr);
    assert!(message.contains("events.csv:4: 3 fields, expected") && message.contains("damaged"), "{message}");
    // A field that is not a number passed every comparison as NaN (an event with begin time `abc` was counted inside
    // the window), and a file cut inside its last field passed as whole.
    let analyze_with = |events: String| {
        std::fs::write(&events_path, events).unwrap();
        let output = gc2d().arg("analyze").arg(out.path()).args(["--kind", "mill", "--warm-up", "0.005"]).output();
        let output = output.unwrap();
        assert_eq!(output.status.code(), Some(2));
        String::from_utf8_lossy(&output.stderr).to_string()
    };
    let mut fields: Vec<String> = lines[5].split(',').map(str::to_owned).collect();
    fields[0] = "abc".to_owned();
    let mut edited = lines.clone();
    let row = fields.join(",");
    edited[3] = lines[4];
    edited[5] = &row;
    let message = analyze_with(edited.join("\n") + "\n");
    assert!(message.contains("events.csv:6: `abc` in column `begin_time_s` is not a number"), "{message}");
    let whole = events.trim_end();
    let message = analyze_with(whole[..whole.len() - 1].to_owned());
    assert!(message.contains("the last line ends without a line break"), "{message}");
    // Without an events file the analysis says how to get one.
    std::fs::remove_file(&events_path).unwrap();
    let missing =
        gc2d().arg("analyze").arg(out.path()).args(["--kind", "mill", "--warm-up", "0.005"]).output().unwrap();
    assert!(!missing.status.success());
    assert!(String::from_utf8_lossy(&missing.stderr).contains("--events"));
}

/// The mill summary at the end of `run` printed the numbers without the analysis's warnings, which `analyze` prints:
/// here that the dumps, only Parquet, are left out of the ball speeds.
#[test]
fn the_mill_summary_of_a_run_prints_the_analysis_warnings() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("mill4.ron");
    std::fs::write(&scene, common::FOUR_BALL_MILL).unwrap();
    let run = Command::cargo_bin("gc2d-rs")
        .unwrap()
        .arg("run")
        .arg(&scene)
        .args(["--quiet", "--events", "--dump-format", "parquet", "--out"])
        .arg(dir.path().join("run"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    let warning = "warning: ";
    let unreadable = "holds dumps in formats the analysis cannot read (5 in parquet, without a CSV copy)";
    let at = stderr.find(unreadable).unwrap_or_else(|| panic!("no warning about the dumps: {stderr}"));
    let line_start = stderr[..at].rfind('\n').map_or(0, |k| k + 1);
    assert!(stderr[line_start..].starts_with(warning), "{stderr}");
    let (summary, pointer) = (stderr.find("Mill over ").unwrap(), stderr.find("Tables, maps and figures").unwrap());
    assert!(summary < line_start && line_start < pointer, "the warning between the summary and the pointer: {stderr}");
}

/// Ore grains drawn as disks (`disk: true`, which the scene format allows) were counted as balls: the analysis told
/// the two apart by shape, and lost the ore's classes and stress-energy spectrum without a word. The balls are now the
/// bodies the run's scene builds from `mill.balls`.
#[test]
fn ore_grains_drawn_as_disks_are_not_taken_for_balls() {
    let dir = tempfile::tempdir().unwrap();
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/mill_ore.ron")).unwrap();
    let polygons = "size_spread: Equal(0.25), corners: 7, corner_positions: Rand1, orientation: Equal";
    assert!(text.contains(polygons));
    let scene = dir.path().join("disk_ore.ron");
    std::fs::write(&scene, text.replace(polygons, "size_spread: Equal(0.25), disk: true")).unwrap();
    let out = dir.path().join("run");
    let gc2d = || Command::cargo_bin("gc2d-rs").unwrap();
    gc2d().arg("run").arg(&scene).args(["--quiet", "--until", "0.01", "--out"]).arg(&out).assert().success();
    let output = gc2d().arg("analyze").arg(&out).args(["--kind", "mill", "--warm-up", "0.002"]).output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let report: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!((report["balls"].as_u64(), report["ore_grains"].as_u64()), (Some(100), Some(40)));
    let classes: Vec<&str> =
        report["classes"].as_array().unwrap().iter().map(|c| c["class"].as_str().unwrap()).collect();
    assert!(classes.iter().any(|c| c.starts_with("ore–") || *c == "ball–ore"), "{classes:?}");
    assert!(report["stress_energy"].is_object(), "{}", report["stress_energy"]);
    // Without its scene, or with one edited since, the run's balls are not known: taken by shape, with a warning.
    let analyze_with_scene = |text: Option<String>| {
        match &text {
            Some(text) => std::fs::write(out.join("scene.ron"), text).unwrap(),
            None => std::fs::remove_file(out.join("scene.ron")).unwrap(),
        }
        let output = gc2d().arg("analyze").arg(&out).args(["--kind", "mill", "--warm-up", "0.002"]).output().unwrap();
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
        let report: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
        (String::from_utf8_lossy(&output.stderr).to_string(), report["balls"].as_u64().unwrap())
    };
    let copy = std::fs::read_to_string(out.join("scene.ron")).unwrap();
    assert!(copy.contains("count: 100"));
    let (stderr, balls) = analyze_with_scene(Some(copy.replace("count: 100", "count: 90")));
    assert!(
        stderr.contains("is not the scene of the run's final.ckpt") && stderr.contains("disk particles"),
        "{stderr}"
    );
    assert_eq!(balls, 140, "taken by shape");
    let (stderr, _) = analyze_with_scene(None);
    assert!(stderr.contains("has no scene.ron") && stderr.contains("disk particles"), "{stderr}");
}

/// A run without a mill was analysed as one without a word: `balls: 0`, collision classes such as `ore–wall`, rates
/// per ball and a warm-up cut. It is refused, as a feed-pipe analysis of a scene without an outlet is.
#[test]
fn a_run_without_a_mill_is_refused_by_the_mill_analysis() {
    let out = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/incline.ron");
    let gc2d = || Command::cargo_bin("gc2d-rs").unwrap();
    gc2d()
        .arg("run")
        .arg(&scene)
        .args(["--quiet", "--events", "--until", "0.05", "--out"])
        .arg(out.path())
        .assert()
        .success();
    let output = gc2d().arg("analyze").arg(out.path()).args(["--kind", "mill"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("the run has no balls") && stderr.contains("no `mill`"), "{stderr}");
    assert!(!out.path().join("analysis/mill.json").exists());
}

/// `--warm-up` and `--bins` were ignored without a word by the pile and silo analyses, `--window` and `--grid` by the
/// mill's; and a scene file given for the run directory gave "…/final.ckpt: Not a directory".
#[test]
fn analyze_refuses_options_its_kind_does_not_read_and_a_file_for_the_run() {
    let gc2d = || Command::cargo_bin("gc2d-rs").unwrap();
    let dir = tempfile::tempdir().unwrap();
    for (args, message) in [
        (&["--warm-up", "0.1"][..], "--warm-up is read only by the mill and feed-pipe analyses"),
        (&["--kind", "pile", "--bins", "10"][..], "--bins is read only by the feed-pipe analysis"),
        (&["--kind", "mill", "--bins", "10"][..], "not by --kind mill"),
        (&["--kind", "feedpipe", "--grid", "0.01"][..], "--grid is read only by the pile and silo analyses"),
    ] {
        gc2d().arg("analyze").arg(dir.path()).args(args).assert().code(2).stderr(predicates::str::contains(message));
    }
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/incline.ron");
    gc2d()
        .arg("analyze")
        .arg(&scene)
        .assert()
        .code(2)
        .stderr(predicates::str::contains("is a file: give the run directory"));
}
