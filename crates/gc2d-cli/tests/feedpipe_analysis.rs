//! `gc2d-rs analyze RUN --kind feedpipe` (issue 15 item 5) end to end: styrofoam balls fed into a uniform upward
//! stream at exactly U − w_t cross a 1 m riser at that speed, so every transit time is 1 m/(U − w_t), the throughput
//! is the feed rate, and the slip is −w_t everywhere.

use assert_cmd::Command;

const U: f64 = 5.0;
const RATE: f64 = 5.0;

/// The thesis's styrofoam ball (R = 20 mm, 15 kg/m³) in air (1.25 kg/m³, c_w = 0.47, buoyancy on).
fn terminal_speed() -> f64 {
    (8.0f64 * 0.02 * 9.81 * (15.0 - 1.25) / (3.0 * 1.25 * 0.47)).sqrt()
}

fn scene() -> String {
    let start = U - terminal_speed();
    format!(
        r#"Scene(
    mass_model: SphereEquivalent,
    run: (time_step_s: 1e-4, end_time_s: 2.0, frames_per_second: 20, max_impact_speed_m_s: 2.0),
    materials: [(name: "styrofoam", density_kg_m3: 15, youngs_modulus_pa: 1e5)],
    interactions: [(materials: ("styrofoam", "styrofoam"), law: Hertz(damping: Restitution(0.5)))],
    inlets: [(name: "feed", from_m: (-0.2, 0.0), to_m: (0.2, 0.0), rate_per_s: {RATE}, velocity_m_s: (0.0, {start:.17}),
              shape: (semi_axes_m: (0.02, 0.02), disk: true))],
    outlets: [(name: "top", from_m: (0.25, 1.0), to_m: (-0.25, 1.0))],
    fluid: (density_kg_m3: 1.25, field: Uniform((0.0, {U}))),
)"#
    )
}

/// Writes the scene `text` into `dir` and runs it; returns the run directory.
fn run(dir: &std::path::Path, text: &str) -> std::path::PathBuf {
    let scene_path = dir.join("scene_under_test.ron");
    std::fs::write(&scene_path, text).unwrap();
    let out = dir.join("run");
    Command::cargo_bin("gc2d-rs")
        .unwrap()
        .arg("run")
        .arg(&scene_path)
        .args(["--quiet", "--out"])
        .arg(&out)
        .assert()
        .success();
    out
}

#[test]
fn balls_at_terminal_slip_cross_the_riser_at_u_minus_w_t() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(dir.path(), &scene());
    assert!(out.join("dumps").is_dir(), "a scene with a fluid writes dumps by default");
    let output = Command::cargo_bin("gc2d-rs")
        .unwrap()
        .args(["analyze", out.to_str().unwrap(), "--kind", "feedpipe", "--bins", "4"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let report: serde_json::Value = serde_json::from_slice(&output).unwrap();
    let w_t = terminal_speed();
    let expected_transit = 1.0 / (U - w_t);
    let transit = &report["transit_times"];
    assert!(transit["count"].as_u64().unwrap() >= 5);
    // Every ball takes the same time, so the mean and the quantiles agree; the record is exact to a step.
    let quantiles = transit["quantiles_s"].as_array().unwrap().iter().map(|q| q.as_f64().unwrap());
    for t in quantiles.chain([transit["mean_s"].as_f64().unwrap()]) {
        assert!((t - expected_transit).abs() < 2e-4, "{t} against {expected_transit}");
    }
    // The window starts at the first removal (0.666 s) and ends at 2 s: the 6 removals after the one that opens it (a
    // ball every 0.2 s) in 1.334 s, 4.5 per second, the feed's 5 less the window's ragged end (it counted 7, 5.25/s).
    let outlet = &report["outlets"][0];
    assert_eq!(outlet["outlet"], "top");
    let rate = outlet["particles_per_second"].as_f64().unwrap();
    assert!((rate - 6.0 / 1.334).abs() < 0.01 && (rate - RATE).abs() < 1.0, "{rate}");
    // QA P2-1: `removed` was the run's 7 while the rate counts 6 in the window; both are named now.
    let removals = std::fs::read_to_string(out.join("transits.csv")).unwrap().lines().count() - 1;
    assert_eq!((outlet["removed_in_window"].as_u64(), outlet["removed_total"].as_u64()), (Some(6), Some(7)));
    assert_eq!(removals, 7);
    let slip = report["mean_slip_m_s"][0].as_f64().unwrap();
    assert!((slip + w_t).abs() < 1e-6, "slip {slip} against −w_t = {}", -w_t);
    for bin in report["profile"].as_array().unwrap() {
        if bin["samples"].as_u64().unwrap() > 0 {
            assert!((bin["slip_m_s"].as_f64().unwrap() + w_t).abs() < 1e-6, "{bin}");
            assert!((bin["fluid_velocity_m_s"].as_f64().unwrap() - U).abs() < 1e-12, "{bin}");
        }
    }
    for file in ["feedpipe.json", "feedpipe_profile.csv", "feedpipe_throughput.svg", "feedpipe_transit_times.svg"] {
        assert!(out.join("analysis").join(file).is_file(), "{file} written");
    }
    at_a_step_time_a_hair_below_the_warm_up(&out);
    // A warm-up before the start widened the window and lowered the rate; 1e11 bins aborted on 2.4 TB.
    for (option, value, message) in [
        ("--warm-up=-1", "", "the warm-up -1 s must lie between 0 and the run's end, 2 s"),
        ("--bins", "100000000000", "100000000000 bins: the profiles take 1 to 10000 bins"),
    ] {
        let mut args = vec!["analyze", out.to_str().unwrap(), "--kind", "feedpipe", option];
        args.extend((!value.is_empty()).then_some(value));
        let refused = Command::cargo_bin("gc2d-rs").unwrap().args(&args).assert().failure();
        let stderr = String::from_utf8_lossy(&refused.get_output().stderr).to_string();
        assert!(stderr.contains(message), "{option} {value}: {stderr}");
    }
    // transits.csv is read strictly: a row through an outlet the run does not have was left out of the throughput
    // and counted among the transit times; a row removed changed the rate without a word.
    let transits = out.join("transits.csv");
    let text = std::fs::read_to_string(&transits).unwrap();
    let analyze = || {
        let mut command = Command::cargo_bin("gc2d-rs").unwrap();
        command.args(["analyze", out.to_str().unwrap(), "--kind", "feedpipe"]);
        String::from_utf8_lossy(&command.assert().code(2).get_output().stderr).to_string()
    };
    std::fs::write(&transits, text.replacen(",top,", ",nowhere,", 1)).unwrap();
    let stderr = analyze();
    assert!(stderr.contains("transits.csv:2: outlet `nowhere` is not one of the run's outlets (top)"), "{stderr}");
    let mut lines: Vec<&str> = text.lines().collect();
    lines.remove(1);
    std::fs::write(&transits, lines.join("\n") + "\n").unwrap();
    let stderr = analyze();
    assert!(stderr.contains("passages through outlet `top`, and the run's final state counts"), "{stderr}");
    // Rows the run cannot have written changed the statistics without a word: each is refused at its line.
    let lines: Vec<&str> = text.lines().collect();
    let first: Vec<&str> = lines[1].split(',').collect();
    let second: Vec<&str> = lines[2].split(',').collect();
    let edited = |field: usize, value: &str| {
        let mut row = first.clone();
        row[field] = value;
        row.join(",")
    };
    let (entered, left) = (first[2], first[4]);
    let swapped = {
        let mut row = first.clone();
        (row[2], row[4]) = (left, entered);
        row.join(",")
    };
    let twice = {
        let mut row = second.clone();
        row[0] = first[0];
        row.join(",")
    };
    for (row, line, message) in [
        (swapped, 2, "a particle enters at"),
        (edited(5, "5.0"), 2, "a transit time of 5 s between"),
        (edited(4, "7.0"), 2, "a particle leaves at 7 s, outside the run"),
        (edited(6, "-1e-5"), 2, "a mass of -0.00001 kg"),
        (edited(1, "nosuch"), 2, "inlet `nosuch` is not one of the run's inlets (feed)"),
        (twice, 3, "leaves twice"),
    ] {
        let mut damaged = lines.clone();
        let at = line - 1;
        damaged[at] = &row;
        std::fs::write(&transits, damaged.join("\n") + "\n").unwrap();
        let stderr = analyze();
        assert!(stderr.contains(&format!("transits.csv:{line}: ")) && stderr.contains(message), "{row}: {stderr}");
    }
}

/// QA #20: a run from which only one particle has left gave `particles_per_second: 0` without a word: its removal
/// opens the default window and is not counted. The rate is null, with a warning; `--warm-up` counts it.
#[test]
fn a_single_removal_that_opens_the_window_gives_no_rate_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    // The first ball leaves at 0.666 s, the second would at 0.866 s.
    let out = run(dir.path(), &scene().replace("end_time_s: 2.0", "end_time_s: 0.75"));
    let assert = Command::cargo_bin("gc2d-rs")
        .unwrap()
        .args(["analyze", out.to_str().unwrap(), "--kind", "feedpipe"])
        .assert()
        .success();
    let report: serde_json::Value = serde_json::from_slice(&assert.get_output().stdout).unwrap();
    let stderr = String::from_utf8_lossy(&assert.get_output().stderr).to_string();
    let outlet = &report["outlets"][0];
    assert_eq!((outlet["removed_in_window"].as_u64(), outlet["removed_total"].as_u64()), (Some(0), Some(1)));
    assert!(outlet["particles_per_second"].is_null() && outlet["mass_per_second"].is_null(), "{report}");
    let start = report["window_s"][0].as_f64().unwrap();
    assert!((start - 1.0 / (U - terminal_speed())).abs() < 2e-4, "{start}");
    let warnings = report["warnings"].as_array().unwrap();
    assert_eq!(warnings.len(), 1, "{report}");
    let warning = warnings[0].as_str().unwrap();
    // The time to 9 significant digits, as messages give it (0.6665 s, not 0.66650000000123 s).
    let shown: f64 = format!("{start:.8e}").parse().unwrap();
    assert!(
        warning.starts_with(&format!("only one particle has left through an outlet, at {shown} s: its removal opens"))
            && warning.contains("particles_per_second and mass_per_second are null")
            && warning.contains("give --warm-up T"),
        "{warning}"
    );
    assert!(stderr.contains(&format!("warning: {warning}")), "{stderr}");
    // From a window given, the removal counts: one in 0.25 s.
    let given = analyse_from(&out, 0.5);
    let outlet = &given["outlets"][0];
    assert_eq!(outlet["removed_in_window"].as_u64(), Some(1));
    assert!((outlet["particles_per_second"].as_f64().unwrap() - 4.0).abs() < 1e-6, "{given}");
    assert_eq!(given["warnings"].as_array().map(Vec::len), Some(0), "{given}");
}

#[test]
fn a_run_without_outlets_is_refused_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(dir.path(), "Scene(run: (end_time_s: 0.01), particles: [(shape: Disk(radius_m: 0.01))])");
    let assert = Command::cargo_bin("gc2d-rs")
        .unwrap()
        .args(["analyze", out.to_str().unwrap(), "--kind", "feedpipe"])
        .assert()
        .failure();
    let stderr = String::from_utf8_lossy(&assert.get_output().stderr).to_string();
    assert!(stderr.contains("no outlet"), "{stderr}");
}

/// The `feedpipe.json` of `analyze RUN --kind feedpipe --warm-up T`.
fn analyse_from(out: &std::path::Path, warm_up: f64) -> serde_json::Value {
    let mut command = Command::cargo_bin("gc2d-rs").unwrap();
    command.args(["analyze", out.to_str().unwrap(), "--kind", "feedpipe", &format!("--warm-up={warm_up}")]);
    serde_json::from_slice(&command.assert().success().get_output().stdout).unwrap()
}

/// QA P2-2: a dump or removal at the step that stands for `--warm-up T` lies a hair below T (its time is a sum of
/// steps) and was left out of the window. Here T is 0.4 Δt after such a time: it counts as at T.
fn at_a_step_time_a_hair_below_the_warm_up(out: &std::path::Path) {
    let hair = 0.4e-4;
    // Dumps: their times (the first field of a dump's first row; an empty dump has none and is not used).
    let mut names: Vec<_> = std::fs::read_dir(out.join("dumps")).unwrap().map(|e| e.unwrap().path()).collect();
    names.retain(|p| p.extension().is_some_and(|e| e == "csv"));
    names.sort();
    let times: Vec<f64> = names
        .iter()
        .filter_map(|p| {
            let text = std::fs::read_to_string(p).unwrap();
            text.lines().nth(1).map(|row| row.split(',').next().unwrap().parse().unwrap())
        })
        .collect();
    let k = times.len() / 2;
    let report = analyse_from(out, times[k] + hair);
    assert_eq!(report["dumps"].as_u64().unwrap() as usize, times.len() - k, "dumps from {}", times[k]);
    // Removals: the third one and every later one count.
    let transits = std::fs::read_to_string(out.join("transits.csv")).unwrap();
    let mut left: Vec<f64> = transits.lines().skip(1).map(|l| l.split(',').nth(4).unwrap().parse().unwrap()).collect();
    left.sort_by(f64::total_cmp);
    let from = left[2] + hair;
    let report = analyse_from(out, from);
    let end = report["window_s"][1].as_f64().unwrap();
    let outlet = &report["outlets"][0];
    let rate = outlet["particles_per_second"].as_f64().unwrap();
    let expected = (left.len() - 2) as f64 / (end - from);
    let counts = (outlet["removed_in_window"].as_u64().unwrap(), outlet["removed_total"].as_u64().unwrap());
    assert_eq!(counts, ((left.len() - 2) as u64, left.len() as u64));
    assert!((rate - expected).abs() < 1e-9 * expected, "{rate} against {expected}: {} removals", left.len() - 2);
}

/// The particle samples `(x, y)` of the dumps in `out` between `from` and `to` s (within half of the scene's step).
fn dump_samples(out: &std::path::Path, from: f64, to: f64) -> Vec<(f64, f64)> {
    let mut samples = Vec::new();
    for entry in std::fs::read_dir(out.join("dumps")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "csv") {
            continue;
        }
        for row in std::fs::read_to_string(&path).unwrap().lines().skip(1) {
            let fields: Vec<f64> = row.split(',').map(|f| f.parse().unwrap_or(f64::NAN)).collect();
            if fields[0] >= from - 0.5e-4 && fields[0] <= to + 0.5e-4 {
                samples.push((fields[4], fields[5]));
            }
        }
    }
    samples
}

/// QA P2-4: the profiles spanned the first outlet only; a top outlet given as two halves lost the particles beside
/// the first half without a word. The section now spans the outlets on one line, and samples beside it are counted
/// and warned about.
#[test]
fn the_profiles_span_a_top_outlet_given_in_two_halves() {
    let split = |left_y: &str| {
        scene().replace("end_time_s: 2.0", "end_time_s: 1.0").replace(
            r#"outlets: [(name: "top", from_m: (0.25, 1.0), to_m: (-0.25, 1.0))]"#,
            &format!(
                r#"outlets: [(name: "right", from_m: (0.25, 1.0), to_m: (0.0, 1.0)),
                             (name: "left", from_m: (0.0, {left_y}), to_m: (-0.25, {left_y}))]"#
            ),
        )
    };
    let analyse = |text: &str| {
        let dir = tempfile::tempdir().unwrap();
        let out = run(dir.path(), text);
        let assert = Command::cargo_bin("gc2d-rs")
            .unwrap()
            .args(["analyze", out.to_str().unwrap(), "--kind", "feedpipe", "--bins", "5"])
            .assert()
            .success();
        let report: serde_json::Value = serde_json::from_slice(&assert.get_output().stdout).unwrap();
        let stderr = String::from_utf8_lossy(&assert.get_output().stderr).to_string();
        let window = [report["window_s"][0].as_f64().unwrap(), report["window_s"][1].as_f64().unwrap()];
        let samples = dump_samples(&out, window[0], window[1]);
        (report, stderr, samples, dir)
    };
    let binned = |report: &serde_json::Value| -> u64 {
        report["profile"].as_array().unwrap().iter().map(|b| b["samples"].as_u64().unwrap()).sum()
    };

    // On one line: the whole 0.5 m section, every sample binned.
    let (report, stderr, samples, _dir) = analyse(&split("1.0"));
    assert!(!samples.is_empty());
    assert_eq!(report["section_m"], serde_json::json!([[0.25, 1.0], [-0.25, 1.0]]));
    assert_eq!((binned(&report), report["samples_outside_section"].as_u64()), (samples.len() as u64, Some(0)));
    assert!(!stderr.contains("beside the section"), "{stderr}");

    // The left half 1 mm higher is another line: the section is the right half, x from 0.25 to 0, and the samples at
    // x ≤ 0 are counted beside it, with a warning.
    let (report, stderr, samples, _dir) = analyse(&split("1.001"));
    let beside = samples.iter().filter(|(x, _)| !(*x > 0.0 && *x <= 0.25)).count();
    assert!(beside > 0, "the feed spreads over both halves");
    assert_eq!(report["samples_outside_section"].as_u64(), Some(beside as u64));
    assert_eq!(binned(&report) as usize + beside, samples.len());
    let warning = format!("{beside} of the {} particle samples in the window lie beside the section", samples.len());
    assert!(stderr.contains(&warning) && stderr.contains("(0.25, 1) to (0, 1) m"), "{stderr}");
}
