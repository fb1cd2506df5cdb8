//! `gc2d-rs sweep` on a tiny scene: the points' run directories and scenes, --jobs, skipping finished points,
//! resuming interrupted ones bitwise, the collected table (CSV and Parquet), the Slurm script and task selection, and
//! located errors for bad sweep files.

mod common;

use assert_cmd::Command;
use predicates::prelude::PredicateBooleanExt;
use predicates::str::contains;
use std::path::{Path, PathBuf};

fn gc2d() -> Command {
    Command::cargo_bin("gc2d-rs").unwrap()
}

/// A folder with tiny_pile.ron and a sweep file `sweep.ron` with `body` inside `Sweep(scene: "tiny_pile.ron", …)`.
fn sweep_folder(body: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/tiny_pile.ron");
    std::fs::copy(scene, dir.path().join("tiny_pile.ron")).unwrap();
    let text =
        format!("// A sweep for the tests.\nSweep(\n    scene: \"tiny_pile.ron\",\n    out: \"out\",\n{body})\n");
    std::fs::write(dir.path().join("sweep.ron"), text).unwrap();
    dir
}

/// 2 × 2 points: two friction coefficients and two end times (0.02 and 0.03 s), the scene's seed, checkpoints every
/// 0.01 s.
const TWO_BY_TWO: &str = r#"    parameters: [
        (path: "materials[0].mu", values: List([0.3, 0.6])),
        (path: "run.end_time_s", name: "end", values: Grid(start: 0.02, stop: 0.03, step: 0.01)),
    ],
    run: (checkpoint_every_s: 0.01),
    plots: [(x: "end", y: ["energy.kinetic_j"])],
"#;

const POINTS: [&str; 4] =
    ["mu=0.3_end=0.02_seed=3", "mu=0.3_end=0.03_seed=3", "mu=0.6_end=0.02_seed=3", "mu=0.6_end=0.03_seed=3"];

fn sweep(dir: &Path) -> Command {
    let mut command = gc2d();
    command.current_dir(dir).args(["sweep", "sweep.ron", "--quiet"]);
    command
}

fn read(path: impl AsRef<Path>) -> Vec<u8> {
    std::fs::read(path.as_ref()).unwrap_or_else(|e| panic!("{}: {e}", path.as_ref().display()))
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_slice(&read(dir.join("summary.json"))).unwrap()
}

/// The CSV as a header and rows of fields (no field of these tables is quoted).
fn csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = String::from_utf8(read(path)).unwrap();
    let mut lines = text.lines().map(|l| l.split(',').map(str::to_owned).collect::<Vec<_>>());
    let header = lines.next().unwrap();
    (header, lines.collect())
}

#[test]
fn a_two_by_two_sweep_runs_skips_and_collects() {
    let dir = sweep_folder(TWO_BY_TWO);
    sweep(dir.path())
        .args(["--jobs", "2", "--threads", "1"])
        .assert()
        .success()
        .stderr(contains("4 points: 4 run, 0 resumed, 0 already done"));
    let out = dir.path().join("out");
    for (k, name) in POINTS.iter().enumerate() {
        let run = out.join(name);
        // The scene as used: the base scene with the point's values, read back by the scene loader.
        let scene = gc2d_scene::Scene::from_path(run.join("scene.ron")).unwrap();
        assert_eq!(scene.materials[0].mu, [0.3, 0.6][k / 2]);
        assert_eq!(scene.run.end_time_s, [0.02, 0.03][k % 2]);
        assert_eq!(scene.run.seed, 3);
        assert_eq!(scene.name, "tiny_pile");
        let summary = summary(&run);
        assert_eq!(summary["outcome"]["status"], "completed");
        assert!((summary["time_s"].as_f64().unwrap() - scene.run.end_time_s).abs() < 2e-6);
    }

    // A second run finds every point finished and leaves the run directories alone.
    let before: Vec<Vec<u8>> = POINTS.iter().map(|p| read(out.join(p).join("summary.json"))).collect();
    sweep(dir.path()).assert().success().stderr(contains("4 points: 0 run, 0 resumed, 4 already done"));
    let after: Vec<Vec<u8>> = POINTS.iter().map(|p| read(out.join(p).join("summary.json"))).collect();
    assert!(before == after, "a finished point was run again");

    // The table: the point, the parameters, the seed and the outcome, then the summary's numbers.
    let (header, rows) = csv(&out.join("sweep.csv"));
    assert_eq!(header[..5], ["point", "mu", "end", "seed", "outcome"]);
    for column in ["energy.kinetic_j", "particles", "steps", "time_s", "chatter.warned"] {
        assert!(header.iter().any(|h| h == column), "no column {column} in {header:?}");
    }
    assert!(!header.iter().any(|h| h == "program_version" || h == "scene"), "text fields are not numbers");
    assert_eq!(rows.len(), 4);
    let kinetic = header.iter().position(|h| h == "energy.kinetic_j").unwrap();
    let steps = header.iter().position(|h| h == "steps").unwrap();
    for (row, name) in rows.iter().zip(POINTS) {
        assert_eq!(row[0], name);
        assert_eq!(row[3], "3");
        assert_eq!(row[4], "completed");
        let summary = summary(&out.join(name));
        let value: f64 = row[kinetic].parse().unwrap();
        assert_eq!(value.to_bits(), summary["energy"]["kinetic_j"].as_f64().unwrap().to_bits());
        assert_eq!(row[steps], summary["steps"].to_string());
    }
    assert_eq!(rows[1][1..3], ["0.3".to_owned(), "0.03".to_owned()]);

    // The Parquet file holds the same table.
    let file = std::fs::File::open(out.join("sweep.parquet")).unwrap();
    let reader = parquet::file::reader::SerializedFileReader::new(file).unwrap();
    let parquet_rows: Vec<parquet::record::Row> =
        parquet::file::reader::FileReader::get_row_iter(&reader, None).unwrap().map(Result::unwrap).collect();
    assert_eq!(parquet_rows.len(), 4);
    for (row, csv_row) in parquet_rows.iter().zip(&rows) {
        let fields: Vec<(&String, &parquet::record::Field)> = row.get_column_iter().collect();
        assert_eq!(fields.len(), header.len());
        assert_eq!(fields[0].1, &parquet::record::Field::Str(csv_row[0].clone()));
        assert_eq!(fields[1].1, &parquet::record::Field::Double(csv_row[1].parse().unwrap()));
        assert_eq!(fields[3].1, &parquet::record::Field::ULong(3));
        assert_eq!(fields[kinetic].0, "energy.kinetic_j");
        assert_eq!(fields[kinetic].1, &parquet::record::Field::Double(csv_row[kinetic].parse().unwrap()));
    }
    // One figure per output named in `plots`.
    let figure = String::from_utf8(read(out.join("plots/energy_kinetic_j_vs_end.svg"))).unwrap();
    assert!(figure.contains("<svg") && figure.contains("mu=0.3") && figure.contains("mu=0.6"));

    // --collect alone writes the same table again.
    std::fs::remove_file(out.join("sweep.csv")).unwrap();
    sweep(dir.path()).arg("--collect").assert().success().stderr(contains("Collected 4 points (4 completed"));
    assert_eq!(csv(&out.join("sweep.csv")).1, rows);
}

#[test]
fn an_interrupted_point_is_resumed_to_the_uninterrupted_result() {
    let dir = sweep_folder(TWO_BY_TWO);
    sweep(dir.path()).args(["--jobs", "2", "--threads", "1"]).assert().success();
    let out = dir.path().join("out");
    let point = out.join(POINTS[3]);
    let reference_state = read(point.join("final.ckpt"));
    let reference_series = read(point.join("timeseries.csv"));

    // What a run killed without warning at 0.025 s leaves: its scene, periodic checkpoints at 0.01 and 0.02 s, a time
    // series, and no summary or final checkpoint.
    let scene_copy = read(point.join("scene.ron"));
    std::fs::remove_dir_all(&point).unwrap();
    std::fs::create_dir_all(&point).unwrap();
    std::fs::write(point.join("scene.ron"), scene_copy).unwrap();
    gc2d()
        .arg("run")
        .arg(point.join("scene.ron"))
        .args(["--quiet", "--until", "0.025", "--checkpoint-every", "0.01", "--out"])
        .arg(&point)
        .assert()
        .success();
    std::fs::remove_file(point.join("summary.json")).unwrap();
    std::fs::remove_file(point.join("final.ckpt")).unwrap();

    sweep(dir.path()).assert().success().stderr(contains("4 points: 0 run, 1 resumed, 3 already done"));
    assert!(read(point.join("final.ckpt")) == reference_state, "the resumed point's final state differs");
    assert!(read(point.join("timeseries.csv")) == reference_series, "the resumed point's time series differs");
}

#[test]
fn a_stopped_sweep_stops_its_runs_with_a_checkpoint_and_resumes_them() {
    // One point long enough to be stopped while it runs (0.5 s of simulated time).
    let dir = sweep_folder(
        r#"    parameters: [(path: "run.end_time_s", name: "end", values: List([0.5]))],
"#,
    );
    let reference = tempfile::tempdir().unwrap();
    gc2d()
        .current_dir(dir.path())
        .args(["sweep", "sweep.ron", "--quiet", "--out"])
        .arg(reference.path())
        .assert()
        .success();

    let point = dir.path().join("out/end=0.5_seed=3");
    let child = std::process::Command::new(assert_cmd::cargo::cargo_bin("gc2d-rs"))
        .current_dir(dir.path())
        .args(["sweep", "sweep.ron", "--quiet"])
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // Stop it (as Ctrl-C or a batch system would) once its run has written a few rows.
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    while std::fs::read_to_string(point.join("timeseries.csv")).map_or(0, |t| t.lines().count()) < 5 {
        assert!(std::time::Instant::now() < deadline, "the point's run wrote no rows");
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    // SAFETY: kill(2) on our own child with SIGTERM.
    unsafe {
        libc::kill(child.id() as libc::pid_t, libc::SIGTERM);
    }
    let output = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(130), "{stderr}");
    assert!(stderr.contains("interrupted: end=0.5_seed=3"), "{stderr}");
    assert_eq!(summary(&point)["outcome"]["status"], "interrupted");

    sweep(dir.path()).assert().success().stderr(contains("1 point: 0 run, 1 resumed, 0 already done"));
    let reference_point = reference.path().join("end=0.5_seed=3");
    assert!(read(point.join("final.ckpt")) == read(reference_point.join("final.ckpt")), "the resumed state differs");
}

#[test]
fn seeds_multiply_the_points_and_slurm_tasks_take_chunks() {
    let dir = sweep_folder(
        r#"    parameters: [(path: "materials[0].gamma", values: List([0.5, 0.75, 1.0]))],
    seeds: List([7, 9]),
"#,
    );
    sweep(dir.path())
        .args(["--slurm", "--points-per-task", "4", "--time", "0:10:00", "--checkpoint-every", "0.01"])
        .assert()
        .success()
        .stderr(contains("6 points in 2 array tasks").and(contains("--out out --collect`")));
    let script = String::from_utf8(read(dir.path().join("out/slurm/sweep.sbatch"))).unwrap();
    // The gathering command names the output folder, which `--out` may have moved from the sweep file's.
    let gather = script.lines().find(|line| line.contains("--collect")).unwrap();
    assert!(
        gather.contains(&format!("--out '{}'", std::path::absolute(dir.path().join("out")).unwrap().display())),
        "{gather}"
    );
    for line in ["#SBATCH --array=0-1", "#SBATCH --time=0:10:00", "#SBATCH --requeue", "#SBATCH --signal=B:TERM@120"] {
        assert!(script.contains(line), "no `{line}` in\n{script}");
    }
    assert!(script.contains("--task \"$SLURM_ARRAY_TASK_ID\" --points-per-task 4"), "{script}");
    assert!(script.contains("--checkpoint-every 0.01"), "{script}");
    assert!(script.contains("scontrol requeue"), "{script}");
    // A signal no earlier than the task's start (--time 1:00 is one minute in Slurm) requeued the task endlessly, and
    // a task without a limit is never told to checkpoint.
    for (time, signal, message) in [
        ("1:00", "7200", "--signal-before 7200 s with --time 1:00 (60 s)"),
        ("0:10:00", "0", "--signal-before 0 s"),
        ("0", "120", "--time 0: give each task a time limit"),
    ] {
        sweep(dir.path())
            .args(["--slurm", "--time", time, "--signal-before", signal])
            .assert()
            .code(2)
            .stderr(contains(message));
    }

    // Task 1 holds the last two points: gamma = 1.0 with seeds 7 and 9.
    sweep(dir.path())
        .args(["--task", "1", "--points-per-task", "4"])
        .assert()
        .success()
        .stderr(contains("2 points: 2 run"));
    let made: Vec<PathBuf> = std::fs::read_dir(dir.path().join("out"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("summary.json").exists())
        .collect();
    let mut names: Vec<String> = made.iter().map(|p| p.file_name().unwrap().to_string_lossy().into_owned()).collect();
    names.sort();
    assert_eq!(names, ["gamma=1.0_seed=7", "gamma=1.0_seed=9"]);
    assert_eq!(gc2d_scene::Scene::from_path(made[0].join("scene.ron")).unwrap().materials[0].gamma, 1.0);
    // Collecting before the other tasks have run names the points without results in one warning.
    sweep(dir.path()).arg("--collect").assert().success().stderr(contains(
        "warning: 4 of 6 points have no summary.json yet (not run, or still running): gamma=0.5_seed=7, \
         gamma=0.5_seed=9, gamma=0.75_seed=7, gamma=0.75_seed=9\n",
    ));
    sweep(dir.path())
        .args(["--task", "2", "--points-per-task", "4"])
        .assert()
        .code(2)
        .stderr(contains("the sweep has 2 tasks of up to 4 points (0 to 1)"));
}

/// The error `gc2d-rs sweep` gives for a sweep with `body`, with the exit code 2; the lines miette wraps joined again
/// (every run of spaces and frame characters `│` read as one space).
fn sweep_error(body: &str) -> String {
    let dir = sweep_folder(body);
    let output = sweep(dir.path()).assert().code(2).get_output().clone();
    assert!(!dir.path().join("out").exists(), "nothing may run or be written for an invalid sweep");
    let text = String::from_utf8(output.stderr).unwrap();
    text.split(|c: char| c.is_whitespace() || c == '│').filter(|w| !w.is_empty()).collect::<Vec<_>>().join(" ")
}

/// A misspelled path names its parameter after the typo: the plot of the right name is reported too, but after the
/// path's error and without suggesting the typo (QA docs 23: only the plot's error came, with "did you mean `muu`?").
#[test]
fn a_misspelled_path_is_reported_before_the_plot_it_breaks_which_does_not_suggest_the_typo() {
    let error = sweep_error(
        "    parameters: [(path: \"materials[0].muu\", values: List([0.3, 0.6]))],\n    plots: [(x: \"mu\", y: [\"time_s\"])],\n",
    );
    let path = error.find(
        "`parameters[0].path`: `materials[0].muu` is not a field of the scene: unknown field `muu`, did you mean `mu`?",
    );
    let plot = error.find("`plots[0].x`: `mu` is not a parameter of this sweep (the parameters are muu)");
    assert!(path.is_some() && plot.is_some() && path < plot, "{error}");
    assert!(!error.contains("did you mean `muu`"), "{error}");
}

#[test]
fn a_misspelled_path_is_located_in_the_sweep_file_with_the_nearest_field() {
    let error = sweep_error(
        r#"    parameters: [
        (path: "run.end_time_s", values: List([0.01])),
        (path: "materials[0].muu", values: List([0.3, 0.6])),
    ],
"#,
    );
    assert!(error.contains("sweep.ron:7:"), "{error}");
    assert!(error.contains("`parameters[1].path`"), "{error}");
    assert!(
        error.contains("`materials[0].muu` is not a field of the scene: unknown field `muu`, did you mean `mu`?"),
        "{error}"
    );
    let error = sweep_error("    parameters: [(path: \"run.sed\", values: List([1]))],\n");
    assert!(error.contains("did you mean `seed`?"), "{error}");
}

#[test]
fn paths_outside_the_scene_say_where_they_stop() {
    let error = sweep_error("    parameters: [(path: \"mill.rotor.rpm\", values: List([1700]))],\n");
    assert!(error.contains("sweep.ron:5:"), "{error}");
    assert!(error.contains("`mill.rotor.rpm`: the scene does not write `mill`"), "{error}");
    let error = sweep_error("    parameters: [(path: \"materials[2].mu\", values: List([0.1]))],\n");
    assert!(error.contains("`materials` has 1 element, so no [2]"), "{error}");
}

#[test]
fn a_point_whose_scene_is_invalid_is_named_with_the_scene_error() {
    let error = sweep_error("    parameters: [(path: \"materials[0].mu\", values: List([0.5, -1.0, -2.0]))],\n");
    assert!(
        error.contains("the scene of point `mu=-1.0_seed=3` (materials[0].mu = -1.0, run.seed = 3) is invalid"),
        "{error}"
    );
    assert!(error.contains("materials[0].mu"), "{error}");
    assert!(error.contains("2 of 3 points fail; the others: `mu=-2.0_seed=3`"), "{error}");
    // Located in the point's scene, not in a scene.ron that was never written.
    assert!(error.contains("point mu=-1.0_seed=3:") && !error.contains("scene.ron:"), "{error}");
}

/// A scene's VTK field is named relative to the scene file; the points' scenes live in their run directories, where
/// that name found nothing, so no sweep of a scene with a loaded field could start.
#[test]
fn a_sweep_of_a_scene_with_a_vtk_field_finds_the_field() {
    let dir = tempfile::tempdir().unwrap();
    common::scene_with_a_vtk_field(dir.path());
    let sweep_file = "Sweep(\n    scene: \"scenes/air.ron\",\n    out: \"out\",\n    parameters: [(path: \
        \"fluid.density_kg_m3\", values: List([1.2, 2.4]))],\n)\n";
    std::fs::write(dir.path().join("sweep.ron"), sweep_file).unwrap();
    sweep(dir.path()).assert().success();
    for point in ["density_kg_m3=1.2_seed=0", "density_kg_m3=2.4_seed=0"] {
        assert_eq!(summary(&dir.path().join("out").join(point))["outcome"]["status"], "completed", "{point}");
    }
    // A file name a parameter gives is read from the base scene's folder, as the scene's own names are.
    std::fs::copy(dir.path().join("scenes/fields/u.vtk"), dir.path().join("scenes/fields/v.vtk")).unwrap();
    let files = "Sweep(\n    scene: \"scenes/air.ron\",\n    out: \"files\",\n    parameters: [(path: \
        \"fluid.field.file\", name: \"field\", values: List([\"fields/u.vtk\", \"fields/v.vtk\"]))],\n)\n";
    std::fs::write(dir.path().join("sweep.ron"), files).unwrap();
    sweep(dir.path()).assert().success();
    let runs: Vec<PathBuf> = std::fs::read_dir(dir.path().join("files"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .collect();
    assert_eq!(runs.len(), 2);
    for run in runs {
        assert_eq!(summary(&run)["outcome"]["status"], "completed", "{}", run.display());
    }
}

#[test]
fn bad_sweep_files_are_located() {
    let error = sweep_error("    parameter: [],\n");
    assert!(error.contains("unknown field `parameter`, did you mean `parameters`?"), "{error}");
    assert!(error.contains("sweep.ron:5:"), "{error}");
    let error =
        sweep_error("    parameters: [(path: \"run.end_time_s\", values: Grid(start: 0.1, stop: 0.0, step: 0.1))],\n");
    assert!(error.contains("`parameters[0].values`: stop (0) is below start (0.1)"), "{error}");
    let error = sweep_error(
        "    parameters: [(path: \"materials[0].mu\", values: List([0.5])), (path: \"run.end_time_s\", name: \"mu\", values: List([0.1]))],\n",
    );
    assert!(error.contains("a second parameter (or the seed) is named `mu`"), "{error}");
    // Named like a column every run fills: the table had two columns of that name, and pyarrow refused its Parquet
    // file (a time-step study, `run.time_step_s`, did so by default).
    for (parameter, column) in [
        ("path: \"run.time_step_s\"", "time_step_s"),
        ("path: \"run.end_time_s\", name: \"point\"", "point"),
        ("path: \"run.end_time_s\", name: \"energy.kinetic_j\"", "energy"),
        ("path: \"run.end_time_s\", name: \"mill.hits\"", "mill"),
    ] {
        let error = sweep_error(&format!("    parameters: [({parameter}, values: List([1e-6]))],\n"));
        assert!(error.contains(&format!("is the name of the table's column `{column}`")), "{error}");
    }
    // One path set by two parameters: every run used the later value while the table showed both.
    let error = sweep_error(
        "    parameters: [(path: \"materials[0].mu\", values: List([0.3])), (path: \"materials[0].mu\", name: \"mu2\", values: List([0.6]))],\n",
    );
    assert!(error.contains("`parameters[1].path`: another parameter sets `materials[0].mu` already"), "{error}");
    // One value written two ways: the same run twice, as two points of the table.
    let error = sweep_error("    parameters: [(path: \"materials[0].mu\", values: List([0.3, 0.5, 3e-1]))],\n");
    assert!(error.contains("the value `3e-1` is `0.3` again, written another way"), "{error}");
    let error = sweep_error("    seeds: Count(0),\n");
    assert!(error.contains("`seeds`: at least one seed is needed"), "{error}");
    let error = sweep_error("    parameters: [(path: \"run.seed\", values: List([1]))],\n");
    assert!(error.contains("the seed is set by `seeds`"), "{error}");
    let error = sweep_error(
        "    parameters: [(path: \"materials[0].mu\", values: List([0.5]))],\n    plots: [(x: \"m\", y: [\"time_s\"])],\n",
    );
    assert!(error.contains("`m` is not a parameter of this sweep, did you mean `mu`?"), "{error}");
    // Values that are no numbers on x were found only after every run (exit 2, no figures).
    let error = sweep_error(
        "    parameters: [(path: \"run.corrector\", values: List([VelocityDependent, PositionDependent]))],\n    plots: [(x: \"corrector\", y: [\"time_s\"])],\n",
    );
    assert!(
        error.contains("`corrector` has the value `VelocityDependent`, which is not a number to put on an axis"),
        "{error}"
    );
    let error = sweep_error("    seeds: Count(2),\n    plots: [(x: \"seed\", y: [\"time_s\"])],\n");
    assert!(error.contains("this sweep has no parameters, only seeds, so there is nothing to plot against"), "{error}");
    let error = sweep_error("    analysis: (kind: Mill),\n");
    assert!(error.contains("`analysis.kind`: this analysis needs a scene with a `mill`"), "{error}");
    let error = sweep_error("    analysis: (kind: Feedpipe),\n");
    assert!(error.contains("this analysis needs a scene with `outlets`"), "{error}");
    let error = sweep_error("    analysis: (kind: Heap),\n");
    assert!(error.contains("Heap"), "{error}");
    let error = sweep_error("    analysis: (warm_up_s: -0.1),\n");
    assert!(error.contains("`analysis.warm_up_s`: must be a time ≥ 0 in s, got -0.1"), "{error}");
}

/// The analysis's warnings reach the sweep's user: a point whose grains were still falling gave a "pile" of one grain
/// in the table, and its warning was dropped.
#[test]
fn a_points_analysis_warnings_are_shown() {
    let dir = sweep_folder(
        "    parameters: [(path: \"run.end_time_s\", values: List([0.01]))],\n    analysis: (kind: Pile),\n",
    );
    sweep(dir.path()).assert().success().stderr(contains("warning: end_time_s=0.01_seed=3: only 1 of the"));
}

#[test]
fn a_pile_ensemble_is_analysed_as_a_pile_before_it_is_collected() {
    let dir = sweep_folder("    seeds: Count(2),\n    analysis: (kind: Pile),\n");
    sweep(dir.path()).args(["--jobs", "2", "--threads", "1"]).assert().success();
    let out = dir.path().join("out");
    let (header, rows) = csv(&out.join("sweep.csv"));
    assert_eq!(rows.iter().map(|r| r[0].as_str()).collect::<Vec<_>>(), ["seed=3", "seed=4"]);
    // `analyze --kind pile` ran in each run directory, and its report's numbers are columns prefixed `analysis.`.
    let column = |name: &str| header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no {name}: {header:?}"));
    let (height, particles) = (column("analysis.pile.height"), column("analysis.particles"));
    for row in &rows {
        let report: serde_json::Value =
            serde_json::from_slice(&read(out.join(&row[0]).join("analysis/analysis.json"))).unwrap();
        assert_eq!(report["scene"], "pile");
        let value: f64 = row[height].parse().unwrap();
        assert_eq!(value.to_bits(), report["pile"]["height"].as_f64().unwrap().to_bits());
        assert!(value > 0.0);
        assert_eq!(row[particles], report["particles"].to_string());
    }
    assert_ne!(rows[0][height], rows[1][height], "two seeds pour two different piles");

    // The ensemble's mean and spread over the seeds: one row, as the thesis reports its pile ensemble.
    let (means_header, means) = csv(&out.join("sweep_means.csv"));
    assert_eq!(means_header[0], "seeds");
    assert_eq!(means.len(), 1);
    assert_eq!(means[0][0], "2");
    let heights: Vec<f64> = rows.iter().map(|r| r[height].parse().unwrap()).collect();
    let at = |name: &str| means_header.iter().position(|h| h == name).unwrap();
    let mean: f64 = means[0][at("analysis.pile.height.mean")].parse().unwrap();
    let sd: f64 = means[0][at("analysis.pile.height.sd")].parse().unwrap();
    assert!((mean - 0.5 * (heights[0] + heights[1])).abs() <= 1e-15 * mean);
    assert!((sd - (heights[0] - heights[1]).abs() / 2f64.sqrt()).abs() <= 1e-12 * sd);
}

#[test]
fn a_mill_sweep_is_analysed_before_it_is_collected() {
    // scenes/mill.ron cut to 20 balls and 2 ms at two rotor speeds, a time-series row every 0.1 ms.
    let dir = tempfile::tempdir().unwrap();
    let mill = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/mill.ron");
    std::fs::copy(mill, dir.path().join("mill.ron")).unwrap();
    let text = r#"Sweep(
    scene: "mill.ron",
    out: "out",
    parameters: [
        (path: "mill.rotor.rpm", values: Grid(start: 1500, stop: 1700, step: 200)),
        (path: "mill.balls.count", values: List([20])),
        (path: "run.end_time_s", name: "end", values: List([0.002])),
        (path: "run.frames_per_second", name: "fps", values: List([10000])),
    ],
    analysis: (warm_up_s: 0.0005),
)
"#;
    std::fs::write(dir.path().join("sweep.ron"), text).unwrap();
    sweep(dir.path()).assert().success();
    let out = dir.path().join("out");
    let (header, rows) = csv(&out.join("sweep.csv"));
    assert_eq!(header[..7], ["point", "rpm", "count", "end", "fps", "seed", "outcome"]);
    assert_eq!(rows[0][0], "rpm=1500_count=20_end=0.002_fps=10000_seed=1");
    // The mill analysis ran in each run directory, and its numbers are columns.
    let balls = header.iter().position(|h| h == "mill.balls").expect("a mill.balls column");
    for row in &rows {
        let analysis = out.join(&row[0]).join("analysis/mill.json");
        let report: serde_json::Value = serde_json::from_slice(&read(&analysis)).unwrap();
        assert_eq!(report["balls"], 20);
        assert_eq!(row[balls], "20");
    }
    assert!(header.iter().any(|h| h.starts_with("mill.power.")), "{header:?}");

    // The warm-up changed in the sweep file: the reports are made again (the old ones were kept, and the table mixed
    // two averaging windows without a word).
    std::fs::write(dir.path().join("sweep.ron"), text.replace("warm_up_s: 0.0005", "warm_up_s: 0.001")).unwrap();
    sweep(dir.path()).assert().success().stderr(contains(
        "analysed again, its report was made with other settings (mill analysis, warm-up 0.0005 s; now mill \
         analysis, warm-up 0.001 s)",
    ));
    for row in &rows {
        let report: serde_json::Value =
            serde_json::from_slice(&read(out.join(&row[0]).join("analysis/mill.json"))).unwrap();
        assert_eq!(report["warm_up"]["start_s"], 0.001);
    }
    let (header, _) = csv(&out.join("sweep.csv"));
    assert!(!header.iter().any(|h| h.contains("sweep-analysis") || h.starts_with("kind")), "{header:?}");
}

/// A figure whose y is not a column of the collected table (an analysis that reported nothing, or a misspelt name) is
/// skipped with a warning; the sweep succeeds and draws its other figures (it exited 2 after every run, and the
/// figures after the missing one were not drawn).
#[test]
fn a_figure_of_a_missing_column_is_skipped_with_a_warning() {
    let dir = sweep_folder(
        "    parameters: [(path: \"run.end_time_s\", name: \"end\", values: List([0.004, 0.005]))],\n    plots: [(x: \"end\", y: [\"analysis.pile.mean_degrees\", \"steps\"])],\n",
    );
    sweep(dir.path())
        .assert()
        .success()
        .stderr(contains("warning: the figure of `analysis.pile.mean_degrees` against `end` is not drawn"));
    assert!(dir.path().join("out/plots/steps_vs_end.svg").is_file());
}

/// A mill sweep whose analysis would fail on every point after its run is refused before the runs: a warm-up not
/// before a point's end, and runs told not to write the contact events the mill analysis reads (both ran every point,
/// then left the table without the mill's columns, and exited 0).
#[test]
fn a_mill_sweep_refuses_an_analysis_that_would_fail_after_the_runs() {
    let refusal = |rest: &str| {
        let dir = tempfile::tempdir().unwrap();
        let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/scenes/mill_ci.ron");
        std::fs::copy(scene, dir.path().join("mill_ci.ron")).unwrap();
        let text = format!(
            "Sweep(\n    scene: \"mill_ci.ron\",\n    out: \"out\",\n    parameters: [(path: \"run.end_time_s\", name: \
             \"end\", values: List([0.04, 0.02]))],\n{rest})\n"
        );
        std::fs::write(dir.path().join("sweep.ron"), text).unwrap();
        let output = sweep(dir.path()).assert().code(2).get_output().clone();
        assert!(!dir.path().join("out").exists(), "nothing may run for an invalid sweep");
        String::from_utf8(output.stderr).unwrap()
    };
    let error = refusal("    analysis: (warm_up_s: 0.03),\n");
    assert!(error.contains("analysis.warm_up_s") && error.contains("point `end=0.02_seed="), "{error}");
    let error = refusal("    run: (events: false),\n");
    assert!(error.contains("run.events") && error.contains("reads the contact events"), "{error}");
}

/// A point another gc2d-rs process is running (a second sweep on the same `out`, a run by hand) is left to it and
/// named as such; the sweep exits 130 (run it again to finish), not 1 (it reported such points as failed).
#[test]
fn a_point_another_process_runs_is_left_to_it_not_failed() {
    let dir =
        sweep_folder("    parameters: [(path: \"run.end_time_s\", name: \"end\", values: List([0.004, 0.005]))],\n");
    let busy = dir.path().join("out/end=0.004_seed=3");
    std::fs::create_dir_all(&busy).unwrap();
    let lock = gc2d_cli::run_lock::lock_run_directory(&busy).unwrap();
    sweep(dir.path()).assert().code(130).stderr(
        contains("left to the other gc2d-rs process running them: end=0.004_seed=3").and(contains("failed").not()),
    );
    assert!(dir.path().join("out/end=0.005_seed=3/final.ckpt").is_file(), "the other point ran");
    drop(lock);
}

/// A malformed path is refused with the path as written and what is wrong in it: `materials[0]mu` said "`materials`
/// has 1 element, so no [0]mu]", and `materials[0].` spoke of a name "``" the sweep file never gave.
#[test]
fn a_malformed_path_is_refused_with_what_is_wrong_in_it() {
    for (path, what) in [
        ("materials[0]mu", "expected `.` or `[` after `]`, found `m`"),
        ("materials[0].", "empty field name after `.`"),
        ("run..end_time_s", "empty field name after `.`"),
        (".run.end_time_s", "empty field name at the start"),
        ("materials[0", "`[` without its closing `]`"),
        ("materials[].mu", "`[]`: an index is a number, counted from 0"),
        ("materials[x].mu", "`[x]`: an index is a number, counted from 0"),
        ("run.end time", "`end time`: a field name has only letters, digits and `_`"),
        ("", "the path is empty"),
    ] {
        let error = sweep_error(&format!("    parameters: [(path: \"{path}\", values: List([0.3]))],\n"));
        assert!(error.contains("sweep.ron:5:"), "{error}");
        assert!(error.contains(&format!("`parameters[0].path`: `{path}` is not a field path: {what}")), "{error}");
    }
    // The seed is no parameter: each point of a figure is already the mean over the seeds.
    let error = sweep_error(
        "    parameters: [(path: \"materials[0].mu\", values: List([0.5]))],\n    plots: [(x: \"seed\", y: [\"time_s\"])],\n",
    );
    assert!(
        error.contains("`seed` is not a parameter of this sweep: each point of a figure is the mean over the seeds"),
        "{error}"
    );
}

/// A scene without `materials` has the implicit material `default` (`gc2d-rs check` prints it), whose
/// `materials[0].mu` was refused as "`materials` has 0 elements, so no [0]". The sweep writes it out, and a point at
/// the default's own values runs exactly as the base scene does.
#[test]
fn the_implicit_default_material_of_a_scene_can_be_swept() {
    let dir = tempfile::tempdir().unwrap();
    let scene = "Scene(\n    run: (end_time_s: 0.01, seed: 3),\n    walls: [Wall(shape: Rectangle(width_m: 0.1, height_m: \
                 0.01), position_m: (0, -0.005))],\n    particles: [(shape: Regular(corners: 6, radius_m: 0.003), \
                 position_m: (0, 0.003), velocity_m_s: (0.1, -0.2))],\n)\n";
    std::fs::write(dir.path().join("bare.ron"), scene).unwrap();
    let sweep_file = "Sweep(\n    scene: \"bare.ron\",\n    out: \"out\",\n    parameters: [(path: \"materials[0].mu\", \
                      values: List([0.3, 0.6]))],\n)\n";
    std::fs::write(dir.path().join("sweep.ron"), sweep_file).unwrap();
    sweep(dir.path()).assert().success();
    for (point, mu) in [("mu=0.3_seed=3", 0.3), ("mu=0.6_seed=3", 0.6)] {
        let run = dir.path().join("out").join(point);
        assert_eq!(summary(&run)["outcome"]["status"], "completed", "{point}");
        let scene = gc2d_scene::Scene::from_path(run.join("scene.ron")).unwrap();
        assert_eq!(scene.materials.len(), 1, "{point}");
        assert_eq!((scene.materials[0].name.as_str(), scene.materials[0].mu), ("default", mu), "{point}");
    }
    // μ = 0.6 is the default material's own: that point ends in the base scene's final state, bit for bit.
    gc2d().current_dir(dir.path()).args(["run", "bare.ron", "--out", "base", "--quiet"]).assert().success();
    assert!(read(dir.path().join("base/final.ckpt")) == read(dir.path().join("out/mu=0.6_seed=3/final.ckpt")));
    // A sweep that leaves the materials alone writes the scene as before, without the material.
    let sweep_file = "Sweep(\n    scene: \"bare.ron\",\n    out: \"ends\",\n    parameters: [(path: \"run.end_time_s\", \
                      values: List([0.005]))],\n)\n";
    std::fs::write(dir.path().join("sweep.ron"), sweep_file).unwrap();
    sweep(dir.path()).assert().success();
    let text = String::from_utf8(read(dir.path().join("ends/end_time_s=0.005_seed=3/scene.ron"))).unwrap();
    assert!(text.contains("materials: []"), "{text}");
}

/// A parameter `name` too long for a directory name (255 bytes) was accepted and failed at the first point with
/// "File name too long (os error 36)"; it is refused before anything runs, at the name, or at the parameters where
/// only their names together are too long.
#[test]
fn a_point_directory_name_too_long_is_refused_before_any_run() {
    let long = "m".repeat(250);
    let error = sweep_error(&format!(
        "    parameters: [(path: \"materials[0].mu\", name: \"{long}\", values: List([0.3]))],\n"
    ));
    assert!(error.contains("`parameters[0].name`:"), "{error}");
    // miette breaks the long name across lines.
    let unbroken = error.replace(' ', "");
    assert!(
        unbroken.contains(&format!("thepointdirectory`{long}=0.3_seed=3`is261byteslong,morethanthe255")),
        "{error}"
    );
    let (a, b) = ("a".repeat(120), "b".repeat(120));
    let error = sweep_error(&format!(
        "    parameters: [(path: \"materials[0].mu\", name: \"{a}\", values: List([0.3])), (path: \"run.end_time_s\", \
         name: \"{b}\", values: List([0.01, 0.02]))],\n"
    ));
    assert!(error.contains("`parameters`:"), "{error}");
    let unbroken = error.replace(' ', "");
    assert!(unbroken.contains(&format!("thepointdirectory`{a}=0.3_{b}=0.01_seed=3`is257byteslong")), "{error}");
}
