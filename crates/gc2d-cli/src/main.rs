//! `gc2d-rs`: run, check, draw and analyse gc2d-rs scenes.
//!
//! Exit codes: 0 success, 1 the run failed (blow-up, I/O), 2 the input is invalid, 130 interrupted by
//! Ctrl-C, SIGTERM or SIGHUP.
#![allow(
    rustdoc::invalid_html_tags,
    rustdoc::broken_intra_doc_links,
    reason = "the argument docs are clap's help text, where `<run>` is a placeholder and `[default: …]` is not a link"
)]

use clap::{Parser, Subcommand};
use gc2d_analysis::{MillOptions, mill_report};
use gc2d_cli::analysis::{AnalysisKind, AnalysisSettings, DEFAULT_BINS};
use gc2d_cli::console;
use gc2d_cli::dumps::StateDumps;
use gc2d_cli::events::EventsWriter;
use gc2d_cli::export::ExportFormat;
use gc2d_cli::failure::CommandFailure;
use gc2d_cli::live::LiveSink;
use gc2d_cli::object_names::ObjectNames;
use gc2d_cli::outputs::{RunStatus, SCENE_COPY, Summary, TimeSeriesWriter, write_scene_copy};
use gc2d_cli::resume::{ResumePoint, ResumedOutputs, load_resume_point};
use gc2d_cli::runner::{FrameSink, RunOutcome, run_to};
use gc2d_cli::segments::SegmentLog;
use gc2d_cli::sinks::{Checkpoints, PngFrames, Recording, save_checkpoint};
use gc2d_cli::transits::{TRANSITS_FILE, TransitsWriter};
use gc2d_engine::World;
use gc2d_record::{ColourBy, PngOptions, RecordOptions, Recorder, RunInfo, SceneFile, render_png};
use gc2d_scene::{ErrorKind, Scene, SceneError};
use gc2d_validation::{ConvergenceOptions, run_convergence};
use std::io::Read;
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
    /// Export a run's state at one of its checkpoints for pandas, polars, DuckDB and ParaView: one row per particle
    /// and per touching pair (Parquet, CSV) and the particles' outlines (VTK .vtu with a .pvd); docs/export.md.
    Export {
        /// The run directory (written by `gc2d-rs run`).
        run: PathBuf,
        /// The simulated time to export, s: the last checkpoint at or before it [default: the latest checkpoint].
        #[arg(long, allow_hyphen_values = true)]
        at: Option<f64>,
        /// The formats to write.
        #[arg(long, value_enum, value_delimiter = ',', default_values_t = [ExportFormat::Parquet, ExportFormat::Csv, ExportFormat::Vtk])]
        format: Vec<ExportFormat>,
        /// The folder to write into [default: <run>/export].
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Draw a PNG picture of a run's final state (or of any checkpoint), for people without Foxglove.
    Snapshot {
        /// A run directory (its final.ckpt is drawn) or a checkpoint file.
        run: PathBuf,
        /// The picture [default: <run dir>/snapshot.png; for a checkpoint file, <run dir>/snapshot-<its name>.png
        /// where it belongs to a run directory, else <its name>.png beside it].
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Picture width in pixels.
        #[arg(long, default_value_t = 1200)]
        width: u32,
        /// What the particle colours show.
        #[arg(long, value_enum, default_value_t = Colour::Speed)]
        colour_by: Colour,
        /// Draw the force network (lines from each centroid to its contact points, width ∝ force).
        #[arg(long)]
        forces: bool,
    },
    /// Analyse a finished run: pressure profiles, angle of repose, density, coordination, stress, Janssen fit.
    Analyze {
        /// The run directory (written by `gc2d-rs run`).
        run: PathBuf,
        /// What the run is: a pile, a silo, a ball mill, a feed pipe, or auto: a mill or a feed pipe by the run's
        /// scene.ron, else a pile or a silo by the wall forces.
        #[arg(long, value_enum, default_value_t = AnalysisKind::Auto)]
        kind: AnalysisKind,
        /// Half-width of the pressure window, m [default: about 15 contacts per window].
        #[arg(long)]
        window: Option<f64>,
        /// Cell size of the density and stress grids, m [default: about 150 particles per cell].
        #[arg(long)]
        grid: Option<f64>,
        /// Mill and feed pipe: the warm-up left out of the averages, s [default: the mill's automatic cut of the
        /// median-speed series by its stationarity test; the feed pipe's first removal at an outlet; docs/analysis.md].
        #[arg(long)]
        warm_up: Option<f64>,
        /// Feed pipe: bins across the pipe's section for the profiles [default: 12].
        #[arg(long)]
        bins: Option<usize>,
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
        /// Replace the scene file if it exists (without it, an existing file, perhaps edited since an earlier import,
        /// is left alone and the import refused).
        #[arg(long)]
        force: bool,
    },
    /// Run a parameter sweep or ensemble: a run per point, several at once, resumable; a table and plots of the
    /// results; or a Slurm job-array script (docs/sweeps.md).
    Sweep(gc2d_cli::sweep::SweepArgs),
    /// Measure gc2d-rs on this machine: the standard piles, settled once and cached, stepped on each thread count;
    /// particle-steps per second, contacts and memory per grain (docs/performance.md).
    Bench(gc2d_cli::bench::BenchArgs),
    /// Error against run time of the integrators on reference problems (docs/validation.md).
    Convergence {
        /// Output directory for the tables and figures.
        #[arg(long, default_value = "out/convergence")]
        out: PathBuf,
        /// A coarse sweep that takes seconds instead of the full study.
        #[arg(long)]
        quick: bool,
    },
}

/// Particle colourings for pictures and recordings.
#[derive(Clone, Copy, clap::ValueEnum)]
enum Colour {
    /// Speed of the centroid.
    Speed,
    /// Contact pressure: the sum of contact forces per perimeter.
    Pressure,
    /// Insertion order.
    Age,
    /// Area density.
    Material,
}

impl From<Colour> for ColourBy {
    fn from(c: Colour) -> Self {
        match c {
            Colour::Speed => ColourBy::Speed,
            Colour::Pressure => ColourBy::Pressure,
            Colour::Age => ColourBy::Age,
            Colour::Material => ColourBy::Material,
        }
    }
}

#[derive(clap::Args)]
struct RunArgs {
    /// The scene file (.ron).
    scene: PathBuf,
    /// Output directory [default: the run directory --resume continues (the directory given, or the one that holds
    /// the checkpoint given), else out/<scene file name without .ron>].
    #[arg(long)]
    out: Option<PathBuf>,
    /// Worker threads [default: all cores]. Results are identical for any count.
    #[arg(long)]
    threads: Option<usize>,
    /// Stop at this simulated time (s) instead of the scene's end time.
    #[arg(long, allow_hyphen_values = true)]
    until: Option<f64>,
    /// Hide the progress bar (it is also hidden when stderr is not a terminal).
    #[arg(long)]
    quiet: bool,
    /// Write a restartable checkpoint every this many simulated seconds (into <out>/checkpoints/).
    #[arg(long, allow_hyphen_values = true)]
    checkpoint_every: Option<f64>,
    /// Continue from a checkpoint written by an earlier run of the same scene, or from the newest checkpoint in a
    /// run directory (its final.ckpt or checkpoints/checkpoint-<step>.ckpt, whichever took more steps). A scene that
    /// differs from the run directory's scene.ron (or from that of a run already in --out) in more than its end time,
    /// output cadences, seed, name and view is refused: the checkpoint's state would go on, ignoring the change.
    #[arg(long)]
    resume: Option<PathBuf>,
    /// Let --resume go back to a checkpoint earlier than the run directory's newest state: the later checkpoints,
    /// final.ckpt and the rows, events, dumps and frames after the checkpoint are removed. Without it such a resume is
    /// refused, naming them.
    #[arg(long, requires = "resume")]
    go_back: bool,
    /// Use this random seed instead of the scene's run.seed: one member of an ensemble of runs that differ only in
    /// their random numbers (shapes, sources). Not with --resume: a resumed run goes on with the seed and the random
    /// state its checkpoint holds.
    #[arg(long, conflicts_with = "resume")]
    seed: Option<u64>,
    /// Record the run for Foxglove into this MCAP file (frames at the scene's frames_per_second).
    #[arg(long)]
    record: Option<PathBuf>,
    /// Serve the run live to the Foxglove app (Foxglove WebSocket) at ADDR, host:port [default: 127.0.0.1:8765];
    /// frames at the scene's frames_per_second, built only while a client is subscribed.
    #[arg(long, value_name = "ADDR", num_args = 0..=1, default_missing_value = gc2d_record::DEFAULT_LIVE_ADDRESS)]
    live: Option<String>,
    /// Write every finished contact episode to <out>/events.csv (impact speeds, largest overlap, dissipated energy,
    /// impulses, contact point; docs/model.md, "Contact events") [default for a scene with a mill].
    #[arg(long, conflicts_with = "no_events")]
    events: bool,
    /// Do not write events.csv (a mill scene writes it unless told so); not with --events.
    #[arg(long)]
    no_events: bool,
    /// Write the state of every particle (position, angle, velocities, forces, contacts) every this many simulated
    /// seconds into <out>/dumps/particles_<k>.csv; 0 writes none [default: a mill scene and a scene with a fluid at
    /// its frames_per_second, other scenes none].
    #[arg(long, allow_hyphen_values = true)]
    dump_every: Option<f64>,
    /// The formats of the dumps: csv (what `analyze` reads), parquet (the export's particle table) and vtk (.vtu per
    /// dump with dumps/particles.pvd for ParaView); docs/export.md [default: csv].
    #[arg(long, value_enum, value_delimiter = ',')]
    dump_format: Option<Vec<ExportFormat>>,
    /// Also draw a PNG picture every this many simulated seconds (into <out>/frames/); 0 draws none (a resumed part
    /// then lets the earlier parts' pictures end at the checkpoint).
    #[arg(long, allow_hyphen_values = true)]
    png_every: Option<f64>,
    /// What the particle colours show in recordings and pictures.
    #[arg(long, value_enum, default_value_t = Colour::Speed)]
    colour_by: Colour,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run(args) => run(args),
        Command::Check { scene } => check(&scene),
        Command::Export { run, at, format, out } => export(&run, at, &format, out),
        Command::Snapshot { run, output, width, colour_by, forces } => snapshot(&run, output, width, colour_by, forces),
        Command::Analyze { run, kind, window, grid, warm_up, bins } => analyze(&run, kind, window, grid, warm_up, bins),
        Command::Convergence { out, quick } => convergence(out, quick),
        Command::Sweep(args) => gc2d_cli::sweep::sweep(&args),
        Command::Bench(args) => gc2d_cli::bench::bench(&args),
        Command::ImportGsi { gsi, output, part_size, force } => {
            gc2d_cli::import::import_gsi(&gsi, output.as_deref(), part_size, force).map(|_| 0)
        }
    };
    match result {
        Ok(code) => ExitCode::from(code),
        Err(failure) => {
            if !failure.report.is_empty() {
                console::err(&failure.report);
            }
            ExitCode::from(failure.code)
        }
    }
}

/// True when both paths name one existing file.
fn same_file(a: &Path, b: &Path) -> bool {
    matches!((a.canonicalize(), b.canonicalize()), (Ok(a), Ok(b)) if a == b)
}

/// Renders a scene diagnostic with its source snippet.
fn render(error: gc2d_scene::SceneError) -> String {
    format!("{:?}", miette::Report::new(error))
}

/// Loads and validates a scene, printing its warnings (an inlet too slow for its rate) to stderr.
fn load(path: &Path) -> Result<Scene, CommandFailure> {
    let scene = Scene::from_path(path).map_err(|e| CommandFailure::input(render(e)))?;
    for warning in scene.warnings() {
        console::err(&format!("warning: {warning}"));
    }
    Ok(scene)
}

fn check(path: &Path) -> Result<u8, CommandFailure> {
    let scene = load(path)?;
    let summary = scene.summary().map_err(|e| CommandFailure::input(render(e)))?;
    refuse_a_run_shorter_than_its_step(&scene, summary.time_step_s, None, || summary.limiting_entry.clone())?;
    refuse_more_steps_than_the_clock_counts(&scene, summary.time_step_s, 0.0, None)?;
    refuse_more_frames_than_steps(&scene, summary.time_step_s)?;
    console::out(&summary.to_string()).map_err(|e| CommandFailure::stdout(&e))?;
    Ok(0)
}

fn run(args: RunArgs) -> Result<u8, CommandFailure> {
    let mut scene = load(&args.scene)?;
    if let Some(seed) = args.seed {
        scene.run.seed = seed;
    }
    if args.threads == Some(0) {
        return Err(CommandFailure::input("--threads must be at least 1"));
    }
    gc2d_cli::refuse_too_many_threads("--threads", args.threads.unwrap_or(0)).map_err(CommandFailure::input)?;
    // A recording cannot be continued (an MCAP file ends with its index): writing a resumed run into the file of the
    // run before would overwrite the frames recorded before the stop.
    if let (Some(_), Some(record)) = (&args.resume, &args.record)
        && std::fs::metadata(record).is_ok_and(|file| file.len() > 0)
    {
        return Err(CommandFailure::input(format!(
            "--record {}: the file exists and holds the frames recorded before; a resumed run would overwrite them. \
             Record the resumed part into a new file (say {}); the Foxglove app opens several recordings of one \
             run together",
            record.display(),
            record.with_extension("resumed.mcap").display()
        )));
    }
    for (flag, interval, none) in
        [("--dump-every", args.dump_every, "dumps"), ("--png-every", args.png_every, "pictures")]
    {
        if let Some(interval) = interval
            && !(interval.is_finite() && interval >= 0.0)
        {
            return Err(CommandFailure::input(format!(
                "{flag} must be a time in seconds (0: no {none}), got {interval}"
            )));
        }
    }
    if let Some(interval) = args.checkpoint_every
        && !(interval.is_finite() && interval > 0.0)
    {
        return Err(CommandFailure::input(format!(
            "--checkpoint-every must be a positive time in seconds, got {interval}"
        )));
    }
    // The whole run loop executes on a worker of this pool: the engine's parallel sections then start from inside
    // the pool instead of handing every section over from the main thread and sleeping until it is done (which cost
    // about 15 % of a 1,900-grain silo's step on one thread).
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()
        .map_err(|e| CommandFailure::input(format!("could not start the worker threads: {e}")))?;
    let end_time = args.until.unwrap_or(scene.run.end_time_s);
    if !(end_time.is_finite() && end_time >= 0.0) {
        return Err(CommandFailure::input(format!("--until must be a non-negative time in seconds, got {end_time}")));
    }
    // The run directory a resume continues: the one its scene is checked against and, without --out, written to.
    let resumed_dir = args.resume.as_deref().and_then(gc2d_cli::resume::run_directory_of);
    let (mut world, resumed_from) = match &args.resume {
        Some(from) => {
            // The checkpoint's run directory and the one written to (--out, where it holds a run already): a run
            // continued into another run's directory mixed the two runs' rows in its time series.
            let other_out = args.out.as_ref().filter(|out| Some(*out) != resumed_dir.as_ref());
            let continued = resumed_dir.iter().chain(other_out);
            if let Some(mismatch) =
                continued.filter_map(|run_dir| gc2d_cli::resume::another_scene(&scene, &args.scene, run_dir)).next()
            {
                return Err(CommandFailure::input(mismatch));
            }
            let point = load_resume_point(from).map_err(CommandFailure::input)?;
            gc2d_cli::resume::another_checkpoint(&scene, &args.scene, &point).map_err(CommandFailure::input)?;
            let ResumePoint { path, world, .. } = point;
            if end_time < world.time() - 0.5 * world.time_step() {
                let end = match args.until {
                    Some(_) => format!("--until {end_time} s"),
                    None => format!("the scene's end time, {end_time} s,"),
                };
                return Err(CommandFailure::input(format!(
                    "{end} is before the time of {}, t = {:.6} s: a resumed run only goes on from there (to look \
                     at an earlier state, export or draw an earlier checkpoint)",
                    path.display(),
                    world.time()
                )));
            }
            (world, Some(path))
        }
        None => {
            let world = scene.build().map_err(|e| CommandFailure::input(render(e)))?;
            refuse_a_run_shorter_than_its_step(&scene, world.time_step(), args.until, || {
                scene.summary().ok().and_then(|summary| summary.limiting_entry)
            })?;
            (world, None)
        }
    };
    refuse_cadences_below_the_step(&args, &scene, world.time_step())?;
    refuse_more_frames_than_steps(&scene, world.time_step())?;
    refuse_more_steps_than_the_clock_counts(&scene, world.time_step(), world.time(), args.until)?;
    let out = match (&args.out, &resumed_dir) {
        (Some(out), _) => out.clone(),
        (None, Some(run_dir)) => run_dir.clone(),
        (None, None) => default_out_dir(&args.scene),
    };
    // A directory another process still runs in is refused before anything is compared with it: the checkpoints it
    // writes meanwhile would read as later states to go back from (the lock itself is taken below, once the directory
    // exists).
    if gc2d_cli::run_lock::is_locked(&out) {
        gc2d_cli::run_lock::lock_run_directory(&out).map_err(CommandFailure::input)?;
    }
    // The states of the run in `out` further on than the checkpoint, which a resume going back removes.
    let later_checkpoints = match &resumed_from {
        Some(from) => gc2d_cli::resume::later_checkpoints(&out, from, world.steps()),
        None => Vec::new(),
    };
    if let Some(from) = &resumed_from {
        // A checkpoint kept outside a run directory goes on in the scene's default directory only where that holds
        // no run: going on there would cut back a run that has nothing to do with the checkpoint.
        if args.out.is_none() && resumed_dir.is_none() && gc2d_cli::earlier_run::holds_a_run(&out) {
            return Err(CommandFailure::input(format!(
                "{} lies outside a run directory, and {}, where a run of {} goes by default, holds a run already: \
                 give --out, a new directory to go on from the checkpoint there (or that one, to go back to the \
                 checkpoint's time in it where the checkpoint is one of its states)",
                from.display(),
                out.display(),
                args.scene.display()
            )));
        }
        if let Some(why) = gc2d_cli::resume::not_a_state_of_the_run_in(&out, from, &world) {
            return Err(CommandFailure::input(why));
        }
        gc2d_cli::resume::refuse_going_back(&out, &later_checkpoints, world.time(), args.go_back)
            .map_err(CommandFailure::input)?;
        console::err(&format!(
            "Resuming from {} at t = {:.6} s (step {}).",
            from.display(),
            world.time(),
            world.steps()
        ));
    }
    std::fs::create_dir_all(&out)
        .map_err(|e| CommandFailure::input(format!("cannot create the output directory {}: {e}", out.display())))?;
    let _lock = gc2d_cli::run_lock::lock_run_directory(&out).map_err(CommandFailure::input)?;
    gc2d_cli::resume::remove_temporary_files(&out);
    if args.resume.is_none() {
        gc2d_cli::earlier_run::refuse_files_of_no_run(&out).map_err(CommandFailure::input)?;
    }
    let frame_interval = 1.0 / scene.run.frames_per_second;
    // The outputs that can fail to start (an address in use, a recording into a missing folder) start before the run
    // directory is touched, so that a failure leaves it as it was.
    let live_options = RecordOptions { colour_by: args.colour_by.into(), ..RecordOptions::default() };
    let mut live = match &args.live {
        Some(address) => Some(LiveSink::start(address, live_options, frame_interval).map_err(CommandFailure::input)?),
        None => None,
    };
    if let Some(path) = &args.record {
        refuse_recording_over_other_files(path, &args.scene, &out)?;
    }
    let mut recording = match &args.record {
        Some(path) => Some(start_recording(path, &args, &scene, frame_interval)?),
        None => None,
    };
    // The outputs numbered on a cadence: a resumed part on another interval, or with other formats, than the earlier
    // part's is refused here, before the run directory is touched.
    let mut pictures = args.png_every.filter(|&interval| interval > 0.0).map(|interval| PngFrames {
        dir: out.join(gc2d_cli::sinks::FRAMES_DIR),
        interval,
        options: PngOptions {
            colour_by: args.colour_by.into(),
            view: gc2d_cli::sinks::picture_region(&scene),
            ..PngOptions::default()
        },
    });
    let mill = scene.mill.is_some();
    let dumps_by_default = mill || scene.fluid.is_some();
    let dump_interval = args.dump_every.unwrap_or(if dumps_by_default { frame_interval } else { 0.0 });
    if dump_interval == 0.0 && args.dump_format.is_some() {
        return Err(CommandFailure::input(format!(
            "--dump-format is given, but this run writes no dumps ({}): add --dump-every T",
            if args.dump_every.is_some() {
                "--dump-every 0"
            } else {
                "only mills and scenes with a fluid dump by default"
            }
        )));
    }
    let dump_formats = args.dump_format.clone().unwrap_or_else(|| vec![ExportFormat::Csv]);
    let mut dumps =
        (dump_interval > 0.0).then(|| StateDumps::new(&out, dump_interval, scene.material_names(), dump_formats));
    let records_events = args.events || (mill && !args.no_events);
    if args.resume.is_some() {
        let asked = ResumedOutputs {
            events: records_events,
            events_stopped: args.no_events,
            dumps: dumps.is_some(),
            dump_interval_given: args.dump_every.is_some(),
            pictures: pictures.is_some(),
            picture_interval_given: args.png_every.is_some(),
        };
        gc2d_cli::resume::refuse_silently_stopped_outputs(&out, &asked).map_err(CommandFailure::input)?;
        let folders =
            pictures.iter().map(|p| (p.folder(), p.cadence())).chain(dumps.iter().map(|d| (d.folder(), d.cadence())));
        for (folder, cadence) in folders {
            folder.refuse_other_cadence(&cadence).map_err(CommandFailure::input)?;
        }
    }
    if args.resume.is_none() {
        let removed = gc2d_cli::earlier_run::remove_earlier_run(&out).map_err(CommandFailure::input)?;
        if removed > 0 {
            console::err(&format!(
                "Replacing the earlier run in {}: removed the {removed} output files it left (its time series, \
                 summary, checkpoints and any dumps and frames); continue a run with --resume instead.",
                out.display()
            ));
        }
    }
    let copy = out.join(SCENE_COPY);
    // The copy records what a fresh run started from; a resumed run keeps it, and the user's own scene file is
    // never overwritten by it (a scene named scene.ron run into its own directory). A run resumed into a directory
    // without one (a checkpoint continued in a new folder) writes the scene it was checked against.
    if (args.resume.is_none() || !copy.exists()) && !same_file(&copy, &args.scene) {
        write_scene_copy(&copy, &scene)
            .map_err(|e| CommandFailure::input(format!("cannot write {}: {e}", copy.display())))?;
    }
    let resumed = args.resume.is_some();
    // The run directory of a checkpoint continued in a new one: what its pictures and chatter watch go on from.
    let origin_dir = resumed_dir.as_ref().filter(|dir| !same_file(dir, &out));
    gc2d_cli::resume::remove_later_checkpoints(&later_checkpoints).map_err(CommandFailure::input)?;
    if let Some(p) = &mut pictures {
        let origin_frames = origin_dir.map(|dir| dir.join(gc2d_cli::sinks::FRAMES_DIR));
        p.prepare(&world, resumed, origin_frames.as_deref()).map_err(CommandFailure::input)?;
        // Without a view of the scene's, its domain or the earlier part's pictures, the first picture sets the region.
        if p.options.view.is_none() {
            console::err(
                "warning: the scene has neither a `view` nor a `run.domain`: every picture shows the region the first \
                 one fits (the bodies at its time), so later bodies outside it are cut off; give the scene a `view` to \
                 choose the region",
            );
        }
    }
    if let Some(d) = &dumps {
        d.prepare(&world, resumed).map_err(CommandFailure::input)?;
    }
    let series_path = out.join("timeseries.csv");
    let mut series = if args.resume.is_some() && series_path.exists() {
        TimeSeriesWriter::continue_at(&series_path, world.time(), 0.5 * world.time_step(), frame_interval)
    } else {
        TimeSeriesWriter::create(&series_path)
    }
    .map_err(|e| CommandFailure::input(format!("cannot write {}: {e}", series_path.display())))?;

    let stop = Arc::new(AtomicBool::new(false));
    let handler_flag = Arc::clone(&stop);
    // Ctrl-C, SIGTERM and SIGHUP end the run tidily. Without a handler they still end it, only without a final
    // checkpoint and summary; a failure to install one is not fatal.
    let _ = ctrlc::set_handler(move || handler_flag.store(true, Ordering::Relaxed));

    let checkpoint_interval = args.checkpoint_every.or(scene.run.checkpoint_interval_s);
    let mut checkpoints = checkpoint_interval.map(|interval| Checkpoints { dir: out.join("checkpoints"), interval });
    let segments_path = out.join("segments.csv");
    // A checkpoint continued in a new directory carries on the chatter watch of the run it comes from.
    let origin_segments = origin_dir.map(|dir| dir.join("segments.csv"));
    let mut segments = SegmentLog::start(
        &segments_path,
        resumed_from.as_deref(),
        origin_segments.as_deref(),
        pool.current_num_threads(),
        &world,
        checkpoint_interval.unwrap_or(frame_interval),
    )
    .map_err(|e| CommandFailure::input(format!("cannot write {}: {e}", segments_path.display())))?;
    let earlier_chatter = segments.earlier_chatter();
    let mut events = if records_events {
        Some(start_events(&out, &scene, &mut world, args.resume.is_some(), frame_interval)?)
    } else {
        None
    };
    let mut transits = if scene.outlets.is_empty() {
        None
    } else {
        Some(start_transits(&out, &world, args.resume.is_some(), frame_interval)?)
    };
    let mut sinks: Vec<&mut dyn FrameSink> = vec![&mut segments];
    if let Some(e) = events.as_mut() {
        sinks.push(e);
    }
    if let Some(t) = transits.as_mut() {
        sinks.push(t);
    }
    if let Some(d) = dumps.as_mut() {
        sinks.push(d);
    }
    if let Some(c) = checkpoints.as_mut() {
        sinks.push(c);
    }
    if let Some(r) = recording.as_mut() {
        sinks.push(r);
    }
    if let Some(l) = live.as_mut() {
        sinks.push(l);
    }
    if let Some(p) = pictures.as_mut() {
        sinks.push(p);
    }
    let started = Instant::now();
    let RunOutcome { mut status, chatter, failed_bodies } = pool.install(|| {
        run_to(&mut world, end_time, &mut series, frame_interval, &mut sinks, &stop, !args.quiet, earlier_chatter)
    });
    if let RunStatus::Failed(message) = &mut status {
        message.push_str(&body_names(&scene, &world, &failed_bodies));
    }
    drop(sinks);
    if let Some(l) = live {
        l.stop();
    }
    let status = match (status, recording.and_then(|r| r.recorder).map(Recorder::finish)) {
        (RunStatus::Completed, Some(Err(e))) => RunStatus::Failed(format!("could not finish the recording: {e}")),
        (status, _) => status,
    };
    let wall_time = started.elapsed().as_secs_f64();
    // The end-of-run files that could not be written (a full disk): the outcome names them instead of calling the
    // outputs complete.
    let mut unwritten = Vec::new();
    let final_checkpoint = out.join("final.ckpt");
    let status = match (status, save_checkpoint(&world, &final_checkpoint)) {
        (RunStatus::Completed, Err(e)) => RunStatus::Failed(format!("could not write the final checkpoint: {e}")),
        (status, Err(e)) => {
            unwritten.push(format!("{} ({e})", final_checkpoint.display()));
            status
        }
        (status, Ok(())) => status,
    };
    let (segment_written, wall_time_all_segments_s) = segments.finish(&world, status.name());
    let status = match (status, segment_written) {
        (RunStatus::Completed, Err(e)) => {
            RunStatus::Failed(format!("could not write {}: {e}", segments_path.display()))
        }
        (status, Err(e)) => {
            unwritten.push(format!("{} ({e})", segments_path.display()));
            status
        }
        (status, Ok(())) => status,
    };
    let summary =
        Summary { wall_time_all_segments_s, ..Summary::of(&world, &args.scene, status.clone(), chatter, wall_time) };
    let summary_path = out.join("summary.json");
    if let Err(e) = summary.write(&summary_path) {
        unwritten.push(format!("{} ({e})", summary_path.display()));
    }
    if let Some(warning) = nothing_fed(&world) {
        console::err(&warning);
    }
    let code = report_outcome(&status, &world, &out, wall_time, &unwritten)?;
    // A run that took no step (`--until 0`, to look at the start) has nothing to average.
    if mill && status == RunStatus::Completed && world.steps() > 0 {
        print_mill_summary(&out, world.time(), world.time_step());
    }
    Ok(code)
}

/// The thesis's averaging window starts at 0.2 s and ends at 1 s (ballmill.md §7.8).
const THESIS_WINDOW_S: [f64; 2] = [0.2, 1.0];

/// Prints the mill's statistics in a few lines (gc2d-analysis's [`gc2d_analysis::mill_report`], the numbers
/// `gc2d-rs analyze --kind mill` writes) with the analysis's warnings, as `analyze` prints them: over the thesis's
/// window when the run reaches its end, else from the automatic warm-up cut. A run without the files it needs says so
/// instead.
fn print_mill_summary(out: &Path, end: f64, time_step: f64) {
    let warm_up_s = reaches_the_thesis_window(end, time_step).then_some(THESIS_WINDOW_S[0]);
    let analyze = format!("`gc2d-rs analyze {} --kind mill`", out.display());
    let (balls, warning) = gc2d_cli::analysis::mill_balls(out);
    if let Some(warning) = warning {
        console::err(&format!("warning: {warning}"));
    }
    match mill_report(out, &MillOptions { warm_up_s, balls }) {
        Ok(report) => {
            console::err(&report.summary());
            for warning in &report.warnings {
                console::err(&format!("warning: {warning}"));
            }
            console::err(&format!("Tables, maps and figures: {analyze}."));
        }
        Err(e) => console::err(&format!("No mill summary: {e}.")),
    }
}

/// Whether a run that ended at `end` has reached the end of the thesis's window. The simulated time is a sum of steps,
/// so a run to 1 s may end a hair before it (0.99999975 s with Δt = 7.5e-7 s): within half a step counts as reached.
fn reaches_the_thesis_window(end: f64, time_step: f64) -> bool {
    end + 0.5 * time_step >= THESIS_WINDOW_S[1]
}

/// Opens `events.csv` (continued on a resumed run that has one) and has the World record contact events.
fn start_events(
    out: &Path,
    scene: &Scene,
    world: &mut World,
    resumed: bool,
    flush_interval: f64,
) -> Result<EventsWriter, CommandFailure> {
    world.record_contact_events();
    let path = out.join("events.csv");
    let (materials, objects) = (scene.material_names(), ObjectNames::of_scene(scene));
    let writer = if resumed && path.exists() {
        EventsWriter::continue_at(&path, materials, objects, flush_interval, world.time(), 0.5 * world.time_step())
    } else {
        EventsWriter::create(&path, materials, objects, flush_interval)
    };
    writer.map_err(|e| CommandFailure::input(format!("cannot write {}: {e}", path.display())))
}

/// The scene's names of `bodies` (ids an engine error named), as a sentence to append to its message: `walls[0]`,
/// `blocks[1] #17`, `sources[0] #5` (the source's particle after 5 others); empty when there are none.
fn body_names(scene: &Scene, world: &World, bodies: &[u32]) -> String {
    if bodies.is_empty() {
        return String::new();
    }
    let names = ObjectNames::of_scene(scene);
    let named: Vec<String> =
        bodies.iter().map(|&id| format!("body {id} is `{}`", names.name(world, gc2d_engine::BodyId(id)))).collect();
    format!(" ({})", named.join(", "))
}

/// Opens `transits.csv` (continued on a resumed run that has one).
fn start_transits(
    out: &Path,
    world: &World,
    resumed: bool,
    flush_interval: f64,
) -> Result<TransitsWriter, CommandFailure> {
    let path = out.join(TRANSITS_FILE);
    let writer = if resumed && path.exists() {
        TransitsWriter::continue_at(&path, flush_interval, world.time(), 0.5 * world.time_step())
    } else {
        TransitsWriter::create(&path, flush_interval)
    };
    writer.map_err(|e| CommandFailure::input(format!("cannot write {}: {e}", path.display())))
}

/// Opens the MCAP recording with the scene file attached and the run's metadata.
/// The first bytes of an MCAP file (its magic, with the major version).
const MCAP_MAGIC: &[u8] = b"\x89MCAP0";

/// Refuses a `--record` path that would overwrite the scene being run, one of the run's own outputs in `out`, or an
/// existing regular file that is not a recording (a device such as a pipe is left to the user): a slip of the user's that would destroy the file, or make the run fail at
/// its end when the output is written over the recording. An earlier recording is replaced, as a fresh run replaces
/// its outputs.
fn refuse_recording_over_other_files(path: &Path, scene_path: &Path, out: &Path) -> Result<(), CommandFailure> {
    let refuse = |what: &str| {
        Err(CommandFailure::input(format!(
            "--record {}: that is {what}, which the recording would overwrite; record to a file of its own, say {}",
            path.display(),
            out.join("run.mcap").display()
        )))
    };
    if same_file(path, scene_path) {
        return refuse("the scene file being run");
    }
    let in_out = path.parent().is_some_and(|folder| {
        let folder = if folder.as_os_str().is_empty() { Path::new(".") } else { folder };
        same_file(folder, out)
    });
    let output_names =
        ["final.ckpt", "summary.json", "segments.csv", "timeseries.csv", "events.csv", TRANSITS_FILE, SCENE_COPY];
    if in_out && path.file_name().and_then(|name| name.to_str()).is_some_and(|name| output_names.contains(&name)) {
        return refuse("one of the run's own outputs");
    }
    let mut start = Vec::new();
    let read = std::fs::File::open(path).and_then(|file| file.take(MCAP_MAGIC.len() as u64).read_to_end(&mut start));
    let regular = std::fs::metadata(path).is_ok_and(|file| file.is_file());
    if regular && read.is_ok_and(|length| length > 0) && !start.starts_with(MCAP_MAGIC) {
        return refuse("an existing file that is not a recording");
    }
    Ok(())
}

/// Creates the folders above an output file that do not exist yet, as `--out` creates a run directory.
fn create_parent_folder(file: &Path) -> Result<(), CommandFailure> {
    match file.parent().filter(|parent| !parent.as_os_str().is_empty()) {
        Some(parent) => std::fs::create_dir_all(parent)
            .map_err(|e| CommandFailure::input(format!("cannot create the folder {}: {e}", parent.display()))),
        None => Ok(()),
    }
}

fn start_recording(path: &Path, args: &RunArgs, scene: &Scene, interval: f64) -> Result<Recording, CommandFailure> {
    let info = RunInfo {
        program_version: env!("CARGO_PKG_VERSION").into(),
        seed: scene.run.seed,
        command_line: std::env::args().collect(),
        // The attachment is named by the scene's file name: the path as typed is relative to the shell it was typed
        // in, and the metadata's command line keeps it anyway.
        scene: std::fs::read(&args.scene).ok().map(|data| SceneFile {
            name: args
                .scene
                .file_name()
                .map_or_else(|| args.scene.display().to_string(), |name| name.to_string_lossy().into_owned()),
            media_type: "text/plain".into(),
            data,
        }),
    };
    let options = RecordOptions {
        frames_per_second: scene.run.frames_per_second,
        colour_by: args.colour_by.into(),
        ..RecordOptions::default()
    };
    create_parent_folder(path)?;
    let recorder = Recorder::create(path, options, &info)
        .map_err(|e| CommandFailure::input(format!("cannot record to {}: {e}", path.display())))?;
    Ok(Recording { recorder: Some(recorder), interval })
}

/// Refuses an automatic time step longer than the run (the scene's end time, or `--until`), which would end the run
/// before its first step: usually a density, a modulus or the end time in the wrong unit. An end time of 0 (build
/// and write the start) and a time step the scene gives (its author's choice) are not refused. `limiting` names the
/// scene entry whose particle sets the bound; it is asked for only when the step is refused.
fn refuse_a_run_shorter_than_its_step(
    scene: &Scene,
    time_step: f64,
    until: Option<f64>,
    limiting: impl FnOnce() -> Option<String>,
) -> Result<(), CommandFailure> {
    let end_time = until.unwrap_or(scene.run.end_time_s);
    if scene.run.time_step_s.is_some() || end_time <= 0.0 || time_step <= end_time {
        return Ok(());
    }
    let run = match until {
        Some(until) => format!("--until {until:.3e} s"),
        None => format!("end time {end_time:.3e} s"),
    };
    let mut error = SceneError::new(
        ErrorKind::TimeStep,
        if until.is_some() { "" } else { "run.end_time_s" },
        format!("the automatic time step {time_step:.3e} s is longer than the run ({run}): it would end before its first step"),
    )
    .with_label("shorter than one step")
    .with_help(
        "check the units of the end time and of the materials' densities and Young's moduli (the particles are far \
         heavier or softer than the run expects), or give `run.time_step_s`",
    );
    if let Some(path) = limiting() {
        error = error.with_related(
            SceneError::new(ErrorKind::TimeStep, path, "the particle that sets the time-step bound comes from here")
                .with_label("sets the bound"),
        );
    }
    Err(CommandFailure::input(render(error.located(scene.source.as_ref()))))
}

/// Most steps a run may have: 2⁵³. The clock advances by t + Δt, which stops advancing once t is 2⁵³ steps long (the
/// run would never end), and no run of that length could finish: at a billion steps per second it takes 104 days.
const MAX_STEPS: f64 = 9_007_199_254_740_992.0;

/// Refuses a run from `start` to its end (the scene's end time, or `--until`) of more than [`MAX_STEPS`] steps of
/// `time_step`: usually an end time in the wrong unit (1e30 s printed as 18446744073709551615 steps).
fn refuse_more_steps_than_the_clock_counts(
    scene: &Scene,
    time_step: f64,
    start: f64,
    until: Option<f64>,
) -> Result<(), CommandFailure> {
    let end_time = until.unwrap_or(scene.run.end_time_s);
    let steps = (end_time - start) / time_step;
    if steps <= MAX_STEPS {
        return Ok(());
    }
    let message = format!(
        "the run to {end_time:.3e} s takes {steps:.3e} steps of {time_step:.3e} s, more than the 2^53 ({MAX_STEPS:.3e}) a \
         run may have: its clock would stop advancing, and even at a billion steps per second it would take more than \
         100 days"
    );
    match until {
        Some(_) => Err(CommandFailure::input(format!("--until: {message}"))),
        None => Err(CommandFailure::input(render(
            SceneError::new(ErrorKind::Value, "run.end_time_s", message)
                .with_label("too long")
                .with_help("check the unit of the end time (seconds of simulated time)")
                .located(scene.source.as_ref()),
        ))),
    }
}

/// Refuses a cadence of output files shorter than the time step `dt`: it would write a file at every step (a unit
/// typo such as `--checkpoint-every 1e-9` wrote 31,251 checkpoints for a 0.05 s run and filled the disk).
fn refuse_cadences_below_the_step(args: &RunArgs, scene: &Scene, dt: f64) -> Result<(), CommandFailure> {
    let cadences = [
        ("--checkpoint-every", args.checkpoint_every),
        (
            "run.checkpoint_interval_s",
            args.checkpoint_every.is_none().then_some(scene.run.checkpoint_interval_s).flatten(),
        ),
        ("--dump-every", args.dump_every.filter(|&interval| interval > 0.0)),
        ("--png-every", args.png_every.filter(|&interval| interval > 0.0)),
    ];
    match cadences.into_iter().find_map(|(name, interval)| interval.filter(|&t| t < dt).map(|t| (name, t))) {
        Some((name, interval)) => Err(CommandFailure::input(format!(
            "{name} {} s is shorter than the time step, {dt:.3e} s: it would write a file at every step; give at \
             least the time step (the unit is seconds of simulated time)",
            gc2d_scene::significant_digits(interval, 15)
        ))),
        None => Ok(()),
    }
}

/// Refuses a frame rate (`run.frames_per_second`) above 1/`dt`: it records a time-series row and a frame at every
/// step, and 1e11 (a unit slip) made a run of seconds take hours. The default rate is left alone: with a step longer
/// than its 10 ms (an experiment with `allow_unsafe_time_step`) a row at every step is what it means.
fn refuse_more_frames_than_steps(scene: &Scene, dt: f64) -> Result<(), CommandFailure> {
    let fps = scene.run.frames_per_second;
    if 1.0 / fps < dt && fps != gc2d_scene::Run::default().frames_per_second {
        return Err(CommandFailure::input(render(
            SceneError::new(
                ErrorKind::Value,
                "run.frames_per_second",
                format!(
                    "{fps:e} frames per second is more than one per time step of {dt:.3e} s (at most {:.3e}): it would \
                     record a row and a frame at every step",
                    1.0 / dt
                ),
            )
            .with_label("more frames than steps")
            .with_help("frames per second of simulated time; the default is 100")
            .located(scene.source.as_ref()),
        )));
    }
    Ok(())
}

/// `snapshot`: draws a checkpoint (a run directory's final.ckpt, or the given file).
fn snapshot(
    run: &Path,
    output: Option<PathBuf>,
    width: u32,
    colour_by: Colour,
    forces: bool,
) -> Result<u8, CommandFailure> {
    if !(1..=gc2d_record::MAX_PIXELS).contains(&width) {
        return Err(CommandFailure::input(format!(
            "--width {width}: a picture is 1 to {} pixels wide",
            gc2d_record::MAX_PIXELS
        )));
    }
    if let Some(output) = output.as_ref().filter(|o| !o.extension().is_some_and(|e| e.eq_ignore_ascii_case("png"))) {
        return Err(CommandFailure::input(format!(
            "-o {}: a snapshot is a PNG picture, and its file name must end in .png",
            output.display()
        )));
    }
    // A run directory's newest state: final.ckpt, or the newest periodic checkpoint of a run killed without one.
    let ResumePoint { path: checkpoint, world, later_than_final } =
        gc2d_cli::resume::load_newest_state(run, "draw").map_err(CommandFailure::input)?;
    let output = output.unwrap_or_else(|| {
        if run.is_dir() {
            return run.join("snapshot.png");
        }
        // Each checkpoint its own picture, so that drawing several keeps every one.
        let stem = checkpoint.file_stem().unwrap_or_default().to_string_lossy();
        match gc2d_cli::resume::run_directory_of(&checkpoint) {
            Some(run_dir) => run_dir.join(format!("snapshot-{stem}.png")),
            None => checkpoint.with_file_name(format!("{stem}.png")),
        }
    });
    // A run directory's scene may name the region its pictures show (`view`), as the frames of `--png-every` do.
    let scene = if run.is_dir() { Scene::from_path(run.join(SCENE_COPY)).ok() } else { None };
    let view = scene.as_ref().and_then(|s| s.view);
    // (A damaged final.ckpt, passed over with a warning, has no time to compare with.)
    if later_than_final {
        console::err(&format!(
            "note: drawing {}, the run's newest state, later than its final.ckpt",
            checkpoint.display()
        ));
    }
    // A checkpoint of another run (copied in) was drawn without a word, as if it were this run's.
    if let Some(comparison) = scene.as_ref().and_then(|scene| scene.compare_with_checkpoint(&world).ok())
        && let Some(difference) = comparison.differences.first()
    {
        console::err(&format!(
            "warning: {} is not a state of the run's {SCENE_COPY} ({difference}): is it another run's?",
            checkpoint.display()
        ));
    }
    let options = PngOptions {
        width,
        view: view.map(|area| area.aabb()),
        colour_by: colour_by.into(),
        force_network: forces,
        ..PngOptions::default()
    };
    create_parent_folder(&output)?;
    render_png(&world, &output, &options)
        .map_err(|e| CommandFailure::input(format!("cannot draw {}: {e}", output.display())))?;
    console::err(&format!(
        "Wrote {} (t = {:.6} s, {} particles).",
        output.display(),
        world.time(),
        world.bodies().particles().count()
    ));
    Ok(0)
}

/// `analyze`: runs the analysis of a finished run and says where the tables and figures are.
fn analyze(
    run: &Path,
    kind: AnalysisKind,
    window: Option<f64>,
    grid: Option<f64>,
    warm_up: Option<f64>,
    bins: Option<usize>,
) -> Result<u8, CommandFailure> {
    let kind = match gc2d_cli::analysis::resolved_kind(run, kind) {
        resolved if resolved != kind => {
            console::err(&format!(
                "Analysing {} as a {} run, as its scene.ron says (--kind chooses another analysis).",
                run.display(),
                resolved.name()
            ));
            resolved
        }
        kind => kind,
    };
    let given = [
        ("--window", window.is_some()),
        ("--grid", grid.is_some()),
        ("--warm-up", warm_up.is_some()),
        ("--bins", bins.is_some()),
    ];
    refuse_options_of_other_kinds(kind, given)?;
    if run.is_file() {
        return Err(CommandFailure::input(format!(
            "{} is a file: give the run directory `gc2d-rs run` wrote (out/<scene> by default)",
            run.display()
        )));
    }
    let bins = bins.unwrap_or(DEFAULT_BINS);
    let settings = AnalysisSettings { window_half_width_m: window, grid_cell_m: grid, warm_up_s: warm_up, bins };
    // A run in progress has no final state yet; it is not one stopped without warning, and not to be resumed.
    if gc2d_cli::run_lock::is_locked(run) {
        return Err(CommandFailure::input(format!(
            "cannot analyse {}: a gc2d-rs run is still writing it; analyse it once the run has finished",
            run.display()
        )));
    }
    let analysis = gc2d_cli::analysis::analyze(run, kind, &settings)
        .map_err(|e| CommandFailure::input(format!("cannot analyse {}: {e}{}", run.display(), checkpoint_hint(run))))?;
    console::out(&analysis.json).map_err(|e| CommandFailure::stdout(&e))?;
    for warning in &analysis.warnings {
        console::err(&format!("warning: {warning}"));
    }
    console::err(&format!("Tables and figures in {}.", run.join("analysis").display()));
    Ok(0)
}

/// What a failed analysis of `run` adds where its final state is missing or damaged and periodic checkpoints are
/// there (the analyses read `final.ckpt`): how `--resume` writes it. Empty otherwise; looked at only on failure, so
/// that a good analysis does not load `final.ckpt` twice.
fn checkpoint_hint(run: &Path) -> String {
    let final_checkpoint = run.join("final.ckpt");
    if !run.join("checkpoints").is_dir() {
        String::new()
    } else if !final_checkpoint.exists() {
        // A run killed without warning has periodic checkpoints and no final.ckpt.
        format!(
            " (the run has no final.ckpt, only periodic checkpoints: it was stopped without warning; continue it with \
             `gc2d-rs run SCENE --resume {}` to write one)",
            run.display()
        )
    } else if final_checkpoint.is_file() && World::load_checkpoint_file(&final_checkpoint).is_err() {
        format!(
            " (the run's periodic checkpoints are intact: `gc2d-rs run SCENE --resume {}` goes on from the newest \
             of them to the run's end time and writes final.ckpt again)",
            run.display()
        )
    } else {
        String::new()
    }
}

/// Refuses an `analyze` option the analysis of `kind` does not read (it was ignored without a word); `given` lists
/// each option's flag and whether it was given.
fn refuse_options_of_other_kinds(kind: AnalysisKind, given: [(&str, bool); 4]) -> Result<(), CommandFailure> {
    use AnalysisKind::{Auto, Feedpipe, Mill, Pile, Silo};
    let readers = |flag: &str| match flag {
        "--window" | "--grid" => (&[Auto, Pile, Silo][..], "the pile and silo analyses (--kind auto, pile or silo)"),
        "--warm-up" => (&[Mill, Feedpipe][..], "the mill and feed-pipe analyses (--kind mill or feedpipe)"),
        _ => (&[Feedpipe][..], "the feed-pipe analysis (--kind feedpipe)"),
    };
    match given.iter().find(|(flag, given)| *given && !readers(flag).0.contains(&kind)) {
        Some((flag, _)) => Err(CommandFailure::input(format!(
            "{flag} is read only by {}, not by --kind {}",
            readers(flag).1,
            kind.name()
        ))),
        None => Ok(()),
    }
}

/// `export`: a run's state at a checkpoint as tables and VTK.
fn export(run: &Path, at: Option<f64>, formats: &[ExportFormat], out: Option<PathBuf>) -> Result<u8, CommandFailure> {
    if let Some(at) = at.filter(|at| !at.is_finite()) {
        return Err(CommandFailure::input(format!("--at must be a finite time in seconds, got {at}")));
    }
    let out = out.unwrap_or_else(|| run.join("export"));
    let done = gc2d_cli::export::export(run, at, formats, &out).map_err(CommandFailure::input)?;
    for warning in &done.warnings {
        console::err(&format!("warning: {warning}"));
    }
    console::err(&format!(
        "Exported t = {} s from {}: {} particles, {} contacts into {}.",
        console::rounded(done.time_s),
        done.checkpoint.display(),
        done.particles,
        done.contacts,
        out.display()
    ));
    Ok(0)
}

/// `convergence`: the work-precision study of the integrators.
fn convergence(out: PathBuf, quick: bool) -> Result<u8, CommandFailure> {
    let report = run_convergence(&ConvergenceOptions { out_dir: out.clone(), quick })
        .map_err(|e| CommandFailure { code: 1, report: format!("the convergence study failed: {e}") })?;
    console::err(&format!("{} problems; tables and figures in {}.", report.problems.len(), out.display()));
    Ok(0)
}

/// A warning where the run's sources and inlets tried to insert particles and found room for none: a source line or
/// an inlet segment inside a wall ran to "completed" having fed nothing, with only the counters in summary.json to
/// show it.
fn nothing_fed(world: &World) -> Option<String> {
    let stats = world.stats();
    let tried = stats.insertions_skipped + stats.postponed;
    (stats.inserted + stats.injected == 0 && tried > 0).then(|| {
        format!(
            "warning: no particle was inserted: the sources found no free spot {} times and the inlets {} times (is a \
             source's line or an inlet's segment inside a wall or a packed bed?)",
            stats.insertions_skipped, stats.postponed
        )
    })
}

/// Prints the one-paragraph outcome and maps it to the exit code. `unwritten` lists the end-of-run files that could
/// not be written (each with its error): the outputs are then not complete, and the run fails whatever its status.
fn report_outcome(
    status: &RunStatus,
    world: &World,
    out: &Path,
    wall_time: f64,
    unwritten: &[String],
) -> Result<u8, CommandFailure> {
    let particles = world.bodies().particles().count();
    let folder = folder_in_words(out);
    if !unwritten.is_empty() {
        let (time, steps) = (world.time(), world.steps());
        let ended = match status {
            RunStatus::Completed => format!("reached t = {time:.6} s (step {steps})"),
            RunStatus::Interrupted => format!("was interrupted at t = {time:.6} s (step {steps})"),
            RunStatus::Failed(message) => format!("stopped at t = {time:.6} s (step {steps}): {message}"),
        };
        return Err(CommandFailure {
            code: 1,
            report: format!(
                "The run {ended}, but these files could not be written: {}. The other outputs in {folder} end where \
                 they could be written; once there is room, run again or continue from its newest checkpoint with \
                 `--resume {}`.",
                unwritten.join("; "),
                out.display()
            ),
        });
    }
    match status {
        RunStatus::Completed => {
            console::err(&format!(
                "Finished at t = {:.6} s after {} steps in {:.2} s: {} particles, {} contacts. Results in {folder}.",
                world.time(),
                world.steps(),
                wall_time,
                particles,
                world.stats().contacts,
            ));
            Ok(0)
        }
        RunStatus::Interrupted => {
            console::err(&format!(
                "Interrupted at t = {:.6} s (step {}). The outputs in {folder} are complete up to this point; \
                 continue with `--resume {}`.",
                world.time(),
                world.steps(),
                out.display()
            ));
            Ok(130)
        }
        RunStatus::Failed(message) => Err(CommandFailure {
            code: 1,
            report: format!(
                "The run stopped at t = {:.6} s (step {}): {message}. The outputs in {folder} are complete up to \
                 this point.",
                world.time(),
                world.steps(),
            ),
        }),
    }
}

/// The output folder as a sentence names it: "the current folder" for `.`, which at the end of a sentence read
/// "Results in ..", else its path.
fn folder_in_words(out: &Path) -> String {
    if out == Path::new(".") { "the current folder".to_owned() } else { out.display().to_string() }
}

/// `out/<scene file name without extension>`.
fn default_out_dir(scene: &Path) -> PathBuf {
    let stem = scene.file_stem().map_or_else(|| "run".into(), |s| s.to_string_lossy().into_owned());
    PathBuf::from("out").join(stem)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_to_one_second_reaches_the_thesis_window_whatever_the_round_off() {
        // QA P2-5: the summed time of a 1 s run with Δt = 7.5e-7 s ends below 1 s, and its summary took the automatic
        // warm-up cut instead of the thesis's 0.2 s to the end.
        assert!(reaches_the_thesis_window(0.9999997499923179, 7.5e-7));
        assert!(reaches_the_thesis_window(0.9999999999628257, 5e-7));
        assert!(reaches_the_thesis_window(1.0000000000266958, 2e-7));
        assert!(!reaches_the_thesis_window(0.9999, 7.5e-7), "a run stopped short of 1 s");
    }

    #[test]
    fn the_bins_help_names_the_default_the_analysis_uses() {
        // `--bins` is an Option, so that `analyze` can tell whether it was given, and its help writes the default.
        let command = <Cli as clap::CommandFactory>::command();
        let analyze = command.find_subcommand("analyze").unwrap();
        let bins = analyze.get_arguments().find(|arg| arg.get_id() == "bins").unwrap();
        let help = bins.get_help().unwrap().to_string();
        assert!(help.contains(&format!("[default: {DEFAULT_BINS}]")), "{help}");
    }
}
