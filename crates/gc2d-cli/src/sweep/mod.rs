//! `gc2d-rs sweep SWEEP.ron`: parameter sweeps and ensembles (docs/sweeps.md). A sweep file names a base scene and
//! parameters (paths into the scene with a grid or a list of values) and seeds; every point of their full grid gets
//! a run directory with its scene, is run as a `gc2d-rs run` process (several at once with `--jobs`), skipped when
//! finished and resumed when interrupted, and the results are collected into one table (CSV and Parquet) with SVG
//! plots. `--slurm` writes a job-array script instead, whose tasks run `--task I`.

mod apply;
mod collect;
mod file;
mod local;
mod parquet_file;
mod plots;
mod scenes;
mod seed_means;
mod slurm;
mod spec;
mod state;

use crate::console;
use crate::failure::CommandFailure;
use local::{RunSettings, Tally, run_points};
use scenes::PointScene;
use slurm::{ScriptPaths, SlurmOptions};
use spec::Sweep;
pub(crate) use state::outcome;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// The collected table's file names in the sweep's output directory.
pub const TABLE_CSV: &str = "sweep.csv";
/// The collected table as Parquet.
pub const TABLE_PARQUET: &str = "sweep.parquet";
/// The means and spreads over the seeds of each combination of parameter values.
pub const MEANS_CSV: &str = "sweep_means.csv";

/// The arguments of `gc2d-rs sweep`.
#[derive(Debug, Clone, clap::Args)]
#[allow(
    rustdoc::invalid_html_tags,
    rustdoc::broken_intra_doc_links,
    reason = "the field docs are clap's help text, where `<out>` is a placeholder and `[default: …]` is not a link"
)]
pub struct SweepArgs {
    /// The sweep file (.ron, docs/sweeps.md).
    pub sweep: PathBuf,
    /// Output directory [default: the sweep file's `out`, else out/<sweep file name>].
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Points run at once, each as its own process.
    #[arg(long, default_value_t = 1)]
    pub jobs: usize,
    /// Worker threads of each run [default: the cores divided by --jobs; 1 for --slurm].
    #[arg(long)]
    pub threads: Option<usize>,
    /// Write a restartable checkpoint of each run every this many simulated seconds [default: the sweep file's
    /// run.checkpoint_every_s, else the scene's].
    #[arg(long)]
    pub checkpoint_every: Option<f64>,
    /// Only gather the results of the run directories into the table and plots.
    #[arg(long, conflicts_with_all = ["slurm", "task"])]
    pub collect: bool,
    /// Write a Slurm job-array script (<out>/slurm/sweep.sbatch) instead of running.
    #[arg(long, conflicts_with = "task")]
    pub slurm: bool,
    /// Points per Slurm array task (with --slurm and --task).
    #[arg(long, default_value_t = 1)]
    pub points_per_task: usize,
    /// Time limit of each Slurm array task (Slurm's format: minutes, HH:MM:SS or D-HH:MM:SS).
    #[arg(long, default_value = "1:00:00")]
    pub time: String,
    /// Seconds before a task's time limit at which Slurm signals it to checkpoint and requeue.
    #[arg(long, default_value_t = 120)]
    pub signal_before: u32,
    /// Run only the points of this Slurm array task ($SLURM_ARRAY_TASK_ID), without collecting.
    #[arg(long)]
    pub task: Option<usize>,
    /// Hide the progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// Runs `gc2d-rs sweep`; returns the exit code.
pub fn sweep(args: &SweepArgs) -> Result<u8, CommandFailure> {
    for (flag, value) in
        [("--jobs", Some(args.jobs)), ("--threads", args.threads), ("--points-per-task", Some(args.points_per_task))]
    {
        if value == Some(0) {
            return Err(CommandFailure::input(format!("{flag} must be at least 1")));
        }
    }
    crate::refuse_too_many_threads("--threads", args.threads.unwrap_or(0)).map_err(CommandFailure::input)?;
    if let Some(every) = args.checkpoint_every
        && !(every.is_finite() && every > 0.0)
    {
        return Err(CommandFailure::input(format!(
            "--checkpoint-every must be a positive time in seconds, got {every}"
        )));
    }
    let bytes = std::fs::read(&args.sweep)
        .map_err(|e| CommandFailure::input(format!("cannot read the sweep file {}: {e}", args.sweep.display())))?;
    let text = String::from_utf8(bytes)
        .map_err(|_| CommandFailure::input(format!("{} is not UTF-8 text", args.sweep.display())))?;
    let parsed = file::parse(&text, &args.sweep.display().to_string())?;
    let sweep = Sweep::new(&args.sweep, parsed, args.out.clone())?;
    let points = scenes::point_scenes(&sweep)?;
    for point in &points {
        state::state(point)?;
    }
    let checkpoint_every_s = args.checkpoint_every.or(sweep.file.run.checkpoint_every_s);
    if args.slurm {
        return write_slurm(args, &sweep, points.len(), checkpoint_every_s);
    }
    if args.collect {
        return collect_results(&sweep, &points);
    }
    let selected: &[PointScene] = match args.task {
        Some(task) => &points[slurm::task_points(task, points.len(), args.points_per_task)?],
        None => &points,
    };
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let settings = RunSettings {
        jobs: args.jobs,
        threads: args.threads.unwrap_or((cores / args.jobs).max(1)),
        checkpoint_every_s,
        events: sweep.file.run.events,
        sweep_file: sweep.path.clone(),
        quiet: args.quiet,
    };
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    // Ctrl-C, SIGTERM and SIGHUP stop the sweep; the runs are told with SIGTERM. Without a handler a signal still
    // ends the sweep, only without passing it on; a failure to install one is not fatal.
    let _ = ctrlc::set_handler(move || flag.store(true, Ordering::Relaxed));
    let tally = run_points(selected, &settings, &stop)?;
    report(&tally, selected.len(), &sweep.out);
    if !tally.interrupted.is_empty() || tally.not_started > 0 || !tally.busy.is_empty() {
        return Ok(130);
    }
    let code = if tally.failed.is_empty() { 0 } else { 1 };
    if args.task.is_some() {
        return Ok(code);
    }
    collect_results(&sweep, &points).map(|collected| collected.max(code))
}

/// Says what became of the points.
fn report(tally: &Tally, total: usize, out: &Path) {
    let mut line = format!(
        "{total} point{}: {} run, {} resumed, {} already done",
        if total == 1 { "" } else { "s" },
        tally.ran,
        tally.resumed,
        tally.skipped
    );
    if !tally.failed.is_empty() {
        line.push_str(&format!("; failed (see run.log and summary.json in each): {}", tally.failed.join(", ")));
    }
    if !tally.busy.is_empty() {
        line.push_str(&format!(
            "; left to the other gc2d-rs process running them: {}; run the sweep again once it has ended",
            tally.busy.join(", ")
        ));
    }
    if !tally.interrupted.is_empty() || tally.not_started > 0 {
        line.push_str(&format!(
            "; interrupted: {} (their checkpoints are kept), not started: {}; run the sweep again to continue",
            if tally.interrupted.is_empty() { "none".to_owned() } else { tally.interrupted.join(", ") },
            tally.not_started
        ));
    }
    console::err(&format!("{line}. Run directories in {}.", out.display()));
}

/// `--collect`: the table (CSV and Parquet) and the plots.
fn collect_results(sweep: &Sweep, points: &[PointScene]) -> Result<u8, CommandFailure> {
    let (table, warnings) = collect::collect(sweep, points);
    for warning in &warnings {
        console::err(&format!("warning: {warning}"));
    }
    std::fs::create_dir_all(&sweep.out)
        .map_err(|e| CommandFailure::failed(format!("cannot create {}: {e}", sweep.out.display())))?;
    let csv = sweep.out.join(TABLE_CSV);
    collect::write_csv(&table, &csv)?;
    let parquet = sweep.out.join(TABLE_PARQUET);
    parquet_file::write_parquet(&table, &parquet)?;
    let means = sweep.out.join(MEANS_CSV);
    seed_means::write_means_csv(&table, &seed_means::seed_groups(&table), &means)?;
    let drawn = plots::draw_plots(&table, &sweep.file.plots, &sweep.out.join("plots"))?;
    for skipped in &drawn.skipped {
        console::err(&format!("warning: {skipped}"));
    }
    let figures = drawn.files;
    let finished = table.rows.iter().filter(|r| r.outcome.as_deref() == Some("completed")).count();
    console::err(&format!(
        "Collected {} points ({finished} completed, {} columns) into {} and {}, the means over the seeds into {}{}.",
        table.rows.len(),
        table.numbers.len() + table.parameters.len() + 3,
        csv.display(),
        parquet.display(),
        means.display(),
        if figures.is_empty() {
            String::new()
        } else {
            format!(
                "; {} {} in {}",
                figures.len(),
                if figures.len() == 1 { "figure" } else { "figures" },
                sweep.out.join("plots").display()
            )
        }
    ));
    Ok(0)
}

/// `--slurm`: writes the job-array script and says how to submit it.
fn write_slurm(
    args: &SweepArgs,
    sweep: &Sweep,
    points: usize,
    checkpoint_every_s: Option<f64>,
) -> Result<u8, CommandFailure> {
    let absolute = |path: &Path| {
        std::path::absolute(path).map_err(|e| CommandFailure::failed(format!("cannot resolve {}: {e}", path.display())))
    };
    let exe = std::env::current_exe()
        .map_err(|e| CommandFailure::failed(format!("cannot find the gc2d-rs program for the script: {e}")))?;
    let paths = ScriptPaths { exe, sweep: absolute(&sweep.path)?, out: absolute(&sweep.out)? };
    let options = SlurmOptions {
        points_per_task: args.points_per_task,
        time: args.time.clone(),
        signal_s: args.signal_before,
        threads: args.threads.unwrap_or(1),
        checkpoint_every_s,
    };
    let script = slurm::write_script(&paths, points, &options)?;
    console::err(&format!(
        "Wrote {} ({points} points in {} array tasks). Submit it with `sbatch {}`; afterwards gather the results with \
         `gc2d-rs sweep {} --out {} --collect`.",
        script.display(),
        slurm::task_count(points, args.points_per_task),
        script.display(),
        sweep.path.display(),
        sweep.out.display()
    ));
    Ok(0)
}
