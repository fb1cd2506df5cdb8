//! `gc2d-rs bench` (issue 18 item 6): the table and CSV of every pile, size and thread count, the cache of settled
//! piles (a cached state measures exactly as the freshly settled one did), every thread count measured from the same
//! settled state and ending in the same state, a cache line's round trip beside every many-thread row, and refusals
//! of bad arguments.

use assert_cmd::Command;
use std::path::Path;

/// One row of the bench CSV.
#[derive(Debug, PartialEq)]
struct Row {
    pile: String,
    particles: usize,
    threads: usize,
    steps: u64,
    particle_steps_per_s: f64,
    wall_s: f64,
    contacts_per_particle: f64,
    heap_bytes_per_particle: f64,
    /// A cache line's round trip between two threads before the timed steps, ns; `None` on one thread.
    line_trip_ns: Option<f64>,
    /// Seconds in each stage of the step over the timed steps; empty where the stages were not timed.
    stage_s: Vec<f64>,
}

/// The stages `--stages` times, in the order of the CSV's columns.
const STAGES: [&str; 9] = [
    "predict",
    "vertices",
    "broadphase",
    "narrowphase",
    "accumulation",
    "body_forces",
    "correct",
    "boundaries",
    "ledger_checks",
];

/// Runs a small bench (two piles of 60 grains, settled 2 ms, 1 and 2 threads) with its cache in `cache` and the
/// further arguments `extra`; returns stdout, stderr and the CSV's rows.
fn small_bench(cache: &Path, csv: &Path, extra: &[&str]) -> (String, String, Vec<Row>) {
    let output = Command::cargo_bin("gc2d-rs")
        .unwrap()
        .args(["bench", "--pile", "dense7,disks", "--size", "60", "--threads", "1,2"])
        .args(if extra.contains(&"--steps") { &[][..] } else { &["--particle-steps", "3000"][..] })
        .args(extra)
        .args(["--settle-time", "0.002", "--quiet", "--cache"])
        .arg(cache)
        .arg("--csv")
        .arg(csv)
        .output()
        .unwrap();
    let (stdout, stderr) = (String::from_utf8(output.stdout).unwrap(), String::from_utf8(output.stderr).unwrap());
    assert!(output.status.success(), "{stdout}\n{stderr}");
    let text = std::fs::read_to_string(csv).unwrap();
    let mut lines = text.lines();
    let stage_columns: String = STAGES.iter().map(|s| format!(",stage_{s}_s")).collect();
    assert_eq!(
        lines.next(),
        Some(
            format!(
                "pile,particles,threads,steps,wall_s,cpu_s,particle_steps_per_s,contacts_per_particle,\
                 heap_bytes_per_particle,cache_line_round_trip_ns{stage_columns}"
            )
            .as_str()
        )
    );
    let rows = lines
        .map(|line| {
            let f: Vec<&str> = line.split(',').collect();
            Row {
                pile: f[0].to_string(),
                particles: f[1].parse().unwrap(),
                threads: f[2].parse().unwrap(),
                steps: f[3].parse().unwrap(),
                wall_s: f[4].parse().unwrap(),
                particle_steps_per_s: f[6].parse().unwrap(),
                contacts_per_particle: f[7].parse().unwrap(),
                heap_bytes_per_particle: f[8].parse().unwrap(),
                line_trip_ns: (!f[9].is_empty()).then(|| f[9].parse().unwrap()),
                stage_s: f[10..].iter().filter(|cell| !cell.is_empty()).map(|cell| cell.parse().unwrap()).collect(),
            }
        })
        .collect();
    (stdout, stderr, rows)
}

#[test]
fn bench_measures_every_pile_and_thread_count_and_a_cached_pile_measures_as_the_fresh_one() {
    let dir = tempfile::tempdir().unwrap();
    let cache = dir.path().join("cache");
    let (stdout, stderr, fresh) = small_bench(&cache, &dir.path().join("fresh.csv"), &[]);
    assert!(stdout.contains("dense7 (settled 0.002 s)") && stdout.contains("disks (settled 0.002 s)"), "{stdout}");
    assert_eq!(stdout.lines().filter(|l| l.starts_with("|      60 |")).count(), 4, "{stdout}");
    assert!(stderr.contains("dense7 60: built and settled 0.002 s (1000 steps)"), "{stderr}");
    let order: Vec<(&str, usize)> = fresh.iter().map(|r| (r.pile.as_str(), r.threads)).collect();
    assert_eq!(order, [("dense7", 1), ("dense7", 2), ("disks", 1), ("disks", 2)]);
    for row in &fresh {
        assert_eq!((row.particles, row.steps), (60, 50), "3000 particle-steps of 60 grains: {row:?}");
        assert!(row.particle_steps_per_s > 0.0 && row.heap_bytes_per_particle > 100.0, "{row:?}");
        assert!(row.stage_s.is_empty(), "stages are timed only with --stages: {row:?}");
        let trip = row.line_trip_ns;
        assert_eq!(trip.is_some(), row.threads > 1, "the trip is measured for more than one thread: {row:?}");
        assert!(trip.is_none_or(|ns| ns.is_finite() && ns > 0.0), "{row:?}");
    }
    assert!(!stdout.contains("per step in each stage"), "{stdout}");
    // Every thread count starts from the settled state and ends in the same one, bit for bit.
    for pile in ["dense7", "disks"] {
        let verdict = format!("{pile} 60, the state after the timed steps: bitwise identical on 1, 2 threads");
        assert!(stderr.contains(&verdict), "{stderr}");
    }
    for pair in fresh.chunks(2) {
        assert_eq!(pair[0].contacts_per_particle.to_bits(), pair[1].contacts_per_particle.to_bits(), "{pair:?}");
    }
    // After 2 ms the 1 µm gaps of the deposition have closed: the grains rest on the floor and on each other.
    assert!(fresh[0].contacts_per_particle > 0.3, "{:?}", fresh[0]);
    assert!(cache.join("dense7-60-settled-0.002s-v1.ckpt").is_file());

    let (_, stderr, cached) = small_bench(&cache, &dir.path().join("cached.csv"), &[]);
    assert!(stderr.contains("dense7 60: settled state from"), "{stderr}");
    assert!(!stderr.contains("built and settled"), "{stderr}");
    for (fresh, cached) in fresh.iter().zip(&cached) {
        assert_eq!(
            fresh.contacts_per_particle.to_bits(),
            cached.contacts_per_particle.to_bits(),
            "{fresh:?} {cached:?}"
        );
    }

    // A valid checkpoint of another pile under this one's name (here the disks') was measured under the dense7
    // label; it is now settled again.
    let dense = cache.join("dense7-60-settled-0.002s-v1.ckpt");
    std::fs::copy(cache.join("disks-60-settled-0.002s-v1.ckpt"), &dense).unwrap();
    let (_, stderr, again) = small_bench(&cache, &dir.path().join("again.csv"), &[]);
    assert!(stderr.contains("its seed is 10000, not the dense7 pile's 2000; settling again"), "{stderr}");
    assert_eq!(again[0].contacts_per_particle.to_bits(), fresh[0].contacts_per_particle.to_bits());
}

#[test]
fn bench_stages_split_the_step_time_among_the_stages() {
    let dir = tempfile::tempdir().unwrap();
    let (stdout, _, rows) = small_bench(&dir.path().join("cache"), &dir.path().join("stages.csv"), &["--stages"]);
    assert!(stdout.contains("dense7 60, µs per step in each stage:"), "{stdout}");
    let head = format!("| grains | threads | {} | all stages |", STAGES.join(" | "));
    assert_eq!(stdout.lines().filter(|l| *l == head).count(), 2, "{stdout}");
    for row in &rows {
        assert_eq!(row.stage_s.len(), STAGES.len(), "{row:?}");
        assert!(row.stage_s.iter().all(|&s| s >= 0.0), "{row:?}");
        // The narrowphase of a pile at rest on its floor always takes time; the stages' sum is the timed steps'
        // time less the loop's bookkeeping between steps.
        assert!(row.stage_s[3] > 0.0, "{row:?}");
        let sum: f64 = row.stage_s.iter().sum();
        assert!(sum <= row.wall_s && sum > 0.5 * row.wall_s, "stages {sum} s of {} s: {row:?}", row.wall_s);
    }
}

#[test]
fn bench_refuses_unknown_piles_and_zero_counts() {
    let refusal = |args: &[&str]| {
        let output = Command::cargo_bin("gc2d-rs").unwrap().arg("bench").args(args).output().unwrap();
        assert_eq!(output.status.code(), Some(2), "{args:?}");
        String::from_utf8(output.stderr).unwrap()
    };
    let unknown = refusal(&["--pile", "sand"]);
    assert!(
        unknown.contains("no standard pile is called `sand`; the piles are dense7, squares, layer, disks"),
        "{unknown}"
    );
    assert!(refusal(&["--threads", "1,0"]).contains("at least 1, got 0"));
    assert!(refusal(&["--settle-time=-1"]).contains("--settle-time must be a time in seconds"));
    assert!(refusal(&["--steps", "0"]).contains("--particle-steps and --steps must be at least 1"));
    // A size beyond a scene's million particles aborted on a failed allocation of 64 GB, or panicked.
    for size in ["1000000000", "18446744073709551615"] {
        assert!(refusal(&["--size", size]).contains("a standard pile has at most 1000000 particles"), "{size}");
    }
    // A table that cannot be written is refused before the measurements, not after them.
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().to_str().unwrap();
    assert!(refusal(&["--csv", folder]).contains("this is a folder; give a file name"));
    assert!(refusal(&["--csv", &format!("{folder}/x.csv/")]).contains("this is a folder; give a file name"));
    let nowhere = dir.path().join("no/such/folder/bench.csv");
    assert!(refusal(&["--csv", nowhere.to_str().unwrap()]).contains("does not exist"));
    // A regular file where the table's folder should be was called a folder that does not exist.
    std::fs::write(dir.path().join("afile"), "").unwrap();
    for csv in ["afile/x.csv", "afile/deeper/x.csv"] {
        let error = refusal(&["--csv", dir.path().join(csv).to_str().unwrap()]);
        assert!(error.contains(&format!("{folder}/afile is a file, not a folder")), "{error}");
    }
    // A pile, size or thread count given twice was measured twice, and the verdict read "bitwise identical on 1, 1
    // threads".
    assert!(refusal(&["--pile", "dense7,disks,dense7"]).contains("--pile: dense7 is given twice"));
    assert!(refusal(&["--size", "60,70,60"]).contains("--size: 60 is given twice"));
    assert!(refusal(&["--threads", "1,1"]).contains("--threads: 1 is given twice"));
    // `--steps` silently won over a `--particle-steps` given with it.
    let both = refusal(&["--steps", "30", "--particle-steps", "20000"]);
    assert!(both.contains("'--steps <STEPS>' cannot be used with '--particle-steps <PARTICLE_STEPS>'"), "{both}");
    // A folder where no file can be made (even by root).
    if cfg!(target_os = "linux") {
        assert!(refusal(&["--csv", "/proc/bench.csv"]).contains("cannot write it"));
    }
}

/// `--steps` times every size for the same number of steps, whatever the particle-step budget, even below the
/// budget's floor of 20 steps.
#[test]
fn bench_steps_fix_the_timed_steps_for_every_size() {
    let dir = tempfile::tempdir().unwrap();
    let (_, _, rows) = small_bench(&dir.path().join("cache"), &dir.path().join("steps.csv"), &["--steps", "7"]);
    assert_eq!(rows.len(), 4);
    assert!(rows.iter().all(|row| row.steps == 7), "{rows:?}");
}

/// A layer wide enough for the broadphase's y axis in bands (docs/model.md, "The y axis in bands of x") says how many
/// bands it has, fresh and from the cache; a dense pile, which has one y axis, says nothing.
#[test]
fn bench_names_the_bands_of_a_wide_layer() {
    let dir = tempfile::tempdir().unwrap();
    let run = |pile: &str, size: &str| {
        let output = Command::cargo_bin("gc2d-rs")
            .unwrap()
            .args(["bench", "--pile", pile, "--size", size, "--threads", "1", "--steps", "2"])
            .args(["--settle-time", "0.0001", "--quiet", "--cache"])
            .arg(dir.path())
            .output()
            .unwrap();
        assert!(output.status.success(), "{output:?}");
        String::from_utf8(output.stderr).unwrap()
    };
    let fresh = run("layer", "4000");
    assert!(fresh.contains("layer 4000: built and settled") && fresh.contains("; y axis in 15 bands"), "{fresh}");
    let cached = run("layer", "4000");
    assert!(cached.contains("layer 4000: settled state from") && cached.contains("; y axis in 15 bands"), "{cached}");
    let dense = run("dense7", "60");
    assert!(dense.contains("dense7 60: built and settled") && !dense.contains("bands"), "{dense}");
}
