//! `gc2d-rs`: run, check and import gc2d-rs scenes.
//!
//! Exit codes: 0 success, 1 the run failed (blow-up, I/O), 2 the input is invalid, 130 interrupted by Ctrl-C.

use clap::{Parser, Subcommand};
use gc2d_cli::outputs::{RunStatus, Summary, TimeSeriesWriter};
use gc2d_cli::runner::{FrameSink, run_to};
use gc2d_engine::World;
use gc2d_scene::Scene;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

#[derive(Parser)]
#[command(name = "gc2d-rs", version, about = "Soft-particle DEM for 2D convex polygons, a re-creation of gc2d")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene and write its summary and time series to an output directory.
    Run(RunArgs),
    /// Validate a scene and print what it contains and its time-step bound, without running it.
    Check {
        /// The scene file (.ron).
        scene: PathBuf,
    },
    /// Convert a legacy gc2d input file (.gsi) into a RON scene; prints its `$` comments and every warning.
    ImportGsi {
        /// The gc2d input file (.gsi).
        gsi: PathBuf,
        /// The scene file to write [default: the input with the extension .ron].
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// How PART_SIZE is read: as the ellipse's semi-axes, its full axes, or decided per file (auto).
        #[arg(long, value_enum, default_value_t)]
        part_size: gc2d_cli::import::PartSizeOption,
    },
}

#[derive(clap::Args)]
struct RunArgs {
    /// The scene file (.ron).
    scene: PathBuf,
    /// Output directory [default: out/<scene name>].
    #[arg(long)]
    out: Option<PathBuf>,
    /// Worker threads [default: all cores]. Results are identical for any count.
    #[arg(long)]
    threads: Option<usize>,
    /// Stop at this simulated time (s) instead of the scene's end time.
    #[arg(long)]
    until: Option<f64>,
    /// Hide the progress bar (it is also hidden when stderr is not a terminal).
    #[arg(long)]
    quiet: bool,
    /// Write a restartable checkpoint every this many simulated seconds (into <out>/checkpoints/).
    #[arg(long)]
    checkpoint_every: Option<f64>,
    /// Continue from a checkpoint written by an earlier run of the same scene.
    #[arg(long)]
    resume: Option<PathBuf>,
}

/// A failure and the exit code it maps to.
struct Failure {
    code: u8,
    report: String,
}

impl Failure {
    fn input(report: impl Into<String>) -> Self {
        Self { code: 2, report: report.into() }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run(args) => run(args),
        Command::Check { scene } => check(&scene),
        Command::ImportGsi { gsi, output, part_size } => {
            gc2d_cli::import::import_gsi(&gsi, output.as_deref(), part_size)
                .map(|_| 0)
                .map_err(|e| Failure { code: e.code, report: e.report })
        }
    };
    match result {
        Ok(code) => ExitCode::from(code),
        Err(failure) => {
            eprintln!("{}", failure.report);
            ExitCode::from(failure.code)
        }
    }
}

/// Renders a scene diagnostic with its source snippet.
fn render(error: gc2d_scene::SceneError) -> String {
    format!("{:?}", miette::Report::new(error))
}

fn load(path: &Path) -> Result<Scene, Failure> {
    Scene::from_path(path).map_err(|e| Failure::input(render(e)))
}

fn check(path: &Path) -> Result<u8, Failure> {
    let scene = load(path)?;
    let summary = scene.summary().map_err(|e| Failure::input(render(e)))?;
    println!("{summary}");
    Ok(0)
}

fn run(args: RunArgs) -> Result<u8, Failure> {
    let scene = load(&args.scene)?;
    if let Some(threads) = args.threads {
        if threads == 0 {
            return Err(Failure::input("--threads must be at least 1"));
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build_global()
            .map_err(|e| Failure::input(format!("could not start {threads} threads: {e}")))?;
    }
    let end_time = args.until.unwrap_or(scene.run.end_time_s);
    if !(end_time.is_finite() && end_time >= 0.0) {
        return Err(Failure::input(format!("--until must be a non-negative time in seconds, got {end_time}")));
    }
    let mut world = match &args.resume {
        Some(checkpoint) => World::load_checkpoint_file(checkpoint)
            .map_err(|e| Failure::input(format!("cannot resume from {}: {e}", checkpoint.display())))?,
        None => scene.build().map_err(|e| Failure::input(render(e)))?,
    };
    let out = args.out.clone().unwrap_or_else(|| default_out_dir(&args.scene));
    std::fs::create_dir_all(&out)
        .map_err(|e| Failure::input(format!("cannot create the output directory {}: {e}", out.display())))?;
    let series_path = out.join("timeseries.csv");
    let mut series = if args.resume.is_some() && series_path.exists() {
        TimeSeriesWriter::append_to(&series_path)
    } else {
        TimeSeriesWriter::create(&series_path)
    }
    .map_err(|e| Failure::input(format!("cannot write {}: {e}", series_path.display())))?;

    let stop = Arc::new(AtomicBool::new(false));
    let handler_flag = Arc::clone(&stop);
    // Without a handler Ctrl-C still ends the run, only less tidily; a failure to install one is not fatal.
    let _ = ctrlc::set_handler(move || handler_flag.store(true, Ordering::Relaxed));

    let checkpoint_interval = args.checkpoint_every.or(scene.run.checkpoint_interval_s);
    let mut checkpoints = checkpoint_interval.map(|interval| Checkpoints { dir: out.join("checkpoints"), interval });
    let mut sinks: Vec<&mut dyn FrameSink> = Vec::new();
    if let Some(c) = checkpoints.as_mut() {
        sinks.push(c);
    }
    let series_interval = 1.0 / scene.run.frames_per_second;
    let started = Instant::now();
    let status = run_to(&mut world, end_time, &mut series, series_interval, &mut sinks, &stop, !args.quiet);
    let wall_time = started.elapsed().as_secs_f64();
    let final_checkpoint = out.join("final.ckpt");
    let status = match (status, world.save_checkpoint_file(&final_checkpoint)) {
        (RunStatus::Completed, Err(e)) => RunStatus::Failed(format!("could not write the final checkpoint: {e}")),
        (status, _) => status,
    };
    Summary::of(&world, &args.scene, status.clone(), wall_time)
        .write(&out.join("summary.json"))
        .map_err(|e| Failure { code: 1, report: format!("could not write the summary: {e}") })?;
    report_outcome(&status, &world, &out, wall_time)
}

/// Prints the one-paragraph outcome and maps it to the exit code.
fn report_outcome(status: &RunStatus, world: &World, out: &Path, wall_time: f64) -> Result<u8, Failure> {
    let particles = world.bodies().particles().count();
    match status {
        RunStatus::Completed => {
            eprintln!(
                "Finished at t = {:.6} s after {} steps in {:.2} s: {} particles, {} contacts. Results in {}.",
                world.time(),
                world.steps(),
                wall_time,
                particles,
                world.stats().contacts,
                out.display()
            );
            Ok(0)
        }
        RunStatus::Interrupted => {
            eprintln!(
                "Interrupted at t = {:.6} s (step {}). The outputs in {} are complete up to this point; continue \
                 with --resume {}.",
                world.time(),
                world.steps(),
                out.display(),
                out.join("final.ckpt").display()
            );
            Ok(130)
        }
        RunStatus::Failed(message) => Err(Failure {
            code: 1,
            report: format!(
                "The run stopped at t = {:.6} s (step {}): {message}. The outputs in {} are complete up to this \
                 point.",
                world.time(),
                world.steps(),
                out.display()
            ),
        }),
    }
}

/// `out/<scene file name without extension>`.
fn default_out_dir(scene: &Path) -> PathBuf {
    let stem = scene.file_stem().map_or_else(|| "run".into(), |s| s.to_string_lossy().into_owned());
    PathBuf::from("out").join(stem)
}

/// Writes `<dir>/checkpoint-<step>.ckpt` on its cadence.
struct Checkpoints {
    dir: PathBuf,
    interval: f64,
}

impl FrameSink for Checkpoints {
    fn interval(&self) -> f64 {
        self.interval
    }

    fn take(&mut self, world: &World) -> Result<(), String> {
        std::fs::create_dir_all(&self.dir).map_err(|e| format!("cannot create {}: {e}", self.dir.display()))?;
        let path = self.dir.join(format!("checkpoint-{:010}.ckpt", world.steps()));
        world.save_checkpoint_file(&path).map_err(|e| format!("cannot write {}: {e}", path.display()))
    }
}
