//! What a run leaves in its output directory: `scene.ron` (the scene the run started from), `timeseries.csv` (one
//! row per output tick, flushed as written, so an interrupted run leaves a readable file) and `summary.json` (written
//! at the end, whatever the outcome).

use crate::chatter::ChatterSummary;
use gc2d_engine::World;
use gc2d_scene::Scene;
use serde::Serialize;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// The name of the scene copy in a run's output directory.
pub const SCENE_COPY: &str = "scene.ron";

/// The scene of the run in `run_dir` whose state is `world` (a checkpoint of the run, named `checkpoint` in messages):
/// its [`SCENE_COPY`], where that can be read, builds, and builds `world`'s World but for what a resumed run may
/// change ([`Scene::differences_from_checkpoint`]). Otherwise why not, naming the file: missing, unreadable, not
/// building, or the first difference (a `scene.ron` edited, or copied from another run). Analyses and exports name
/// bodies and materials by it, so a wrong one would name them wrongly.
pub fn run_scene(run_dir: &Path, world: &World, checkpoint: &str) -> Result<RunScene, String> {
    let path = run_dir.join(SCENE_COPY);
    let scene = match Scene::from_path(&path) {
        Ok(scene) => scene,
        Err(_) if !path.exists() => return Err(format!("{} has no {SCENE_COPY}", run_dir.display())),
        Err(e) => return Err(format!("{} cannot be read ({})", path.display(), e.message())),
    };
    match scene.compare_with_checkpoint(world) {
        Ok(comparison) if comparison.differences.is_empty() => {
            Ok(RunScene { scene, body_origins: comparison.body_origins })
        }
        Ok(comparison) => {
            Err(format!("{} is not the scene of {checkpoint} ({})", path.display(), comparison.differences[0]))
        }
        Err(e) => Err(format!("{} does not build ({})", path.display(), e.message())),
    }
}

/// A run's scene, checked against its checkpoint by [`run_scene`], with the scene entry each of its start bodies
/// comes from ([`Scene::body_origins`], built with the check).
pub struct RunScene {
    /// The run's `scene.ron`.
    pub scene: Scene,
    /// The origin of each body the scene builds, by body id.
    pub body_origins: Vec<String>,
}

/// Writes `scene` as the run uses it (after `--seed`) to `path`, every field spelled out: what a run directory was
/// made from stays with it, so an ensemble of runs can be checked to share one scene and a run can be repeated
/// after the scene file has changed. The files the scene reads (a fluid's VTK field) are named by absolute paths, so
/// that the copy finds them from the run directory (`export` builds it to name the bodies).
pub fn write_scene_copy(path: &Path, scene: &Scene) -> io::Result<()> {
    let mut scene = scene.clone();
    scene.anchor_file_names(&scene.folder())?;
    let text = scene.to_ron_string().map_err(io::Error::other)?;
    let header = format!(
        "// The scene this run started from, as gc2d-rs {} read it (with --seed applied); a field left out has its default (docs/scene-format.md).\n\
         // Where the run ended (--until, or resumed to a later end) is summary.json's time_s, not run.end_time_s.\n",
        env!("CARGO_PKG_VERSION")
    );
    std::fs::write(path, header + &text + "\n")
}

/// `path` made absolute (against the working directory, without resolving links) for the files that record where a
/// run's inputs came from (`summary.json`'s `scene`, `segments.csv`'s `resumed_from`): as typed they were relative to
/// the shell the run was started from and pointed nowhere from the run directory. As typed where that fails.
pub fn absolute_path_text(path: &Path) -> String {
    std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf()).display().to_string()
}

/// Column names of `timeseries.csv`, in order. Energies in J per unit thickness (per metre of depth), or in J with
/// sphere-equivalent masses; `force_alternation` is the engine's chatter diagnostic on the row's step
/// (`World::force_alternation`); the `rotor_` columns are the drive of the walls turning about pivots on the row's
/// step (`World::rotor_power`: torque, and power from torque and from the work on the particles), zero without;
/// `median_speed_m_s` is the median |v| of the particles (the mill thesis's stationarity measure); the
/// `rotor_work_` columns are those powers summed over every step since t = 0 (`World::rotor_work`), whose differences
/// give a window's exact mean powers.
pub const TIME_SERIES_COLUMNS: [&str; 22] = [
    "time_s",
    "particles",
    "contacts",
    "max_overlap_fraction",
    "kinetic_translational_j",
    "kinetic_rotational_j",
    "potential_j",
    "contact_stored_j",
    "drag_stored_j",
    "dissipated_normal_damping_j",
    "dissipated_tangential_damping_j",
    "dissipated_sliding_j",
    "work_in_j",
    "opening_residual_j",
    "balance_error_j",
    "force_alternation",
    "rotor_torque_n_m",
    "rotor_power_torque_w",
    "rotor_power_work_w",
    "median_speed_m_s",
    "rotor_work_torque_j",
    "rotor_work_j",
];

/// The columns `timeseries.csv` has after [`TIME_SERIES_COLUMNS`] for a World with inlets or outlets, in their
/// order: `inlet_<name>_injected` and `inlet_<name>_postponed` per inlet, `outlet_<name>_removed` per outlet (counts
/// since t = 0; the name is the scene's or the index), then `removed_by_domain`, so that on every row the fed
/// particles balance: Σ injected (+ sources' and initial particles) = `particles` + Σ removed + `removed_by_domain`.
/// None for a World without either.
pub fn boundary_columns(world: &World) -> Vec<String> {
    if world.inlets().is_empty() && world.outlets().is_empty() {
        return Vec::new();
    }
    let inlets = world.inlets().iter().map(|i| &i.inlet().name);
    let mut columns: Vec<String> =
        inlets.flat_map(|name| [format!("inlet_{name}_injected"), format!("inlet_{name}_postponed")]).collect();
    columns.extend(world.outlets().iter().map(|o| format!("outlet_{}_removed", o.outlet().name)));
    columns.push("removed_by_domain".to_owned());
    columns
}

/// Appends one row per call to `timeseries.csv`.
pub struct TimeSeriesWriter {
    file: BufWriter<File>,
    /// True until the header is written, with the first row (its [`boundary_columns`] depend on the World).
    header_pending: bool,
    /// Time of the row a continued series already ends with: the resumed run does not write it again (its
    /// `force_alternation` would be NaN there, the history not being saved in checkpoints).
    kept_last_row: Option<f64>,
}

impl TimeSeriesWriter {
    /// Creates `path` (truncating it); the header line is written with the first row.
    pub fn create(path: &Path) -> io::Result<Self> {
        let file = BufWriter::new(File::create(path)?);
        Ok(Self { file, header_pending: true, kept_last_row: None })
    }

    /// Continues an existing `path` for a run resumed at simulated time `resumed_at`: rows after `resumed_at`
    /// (written by the earlier run after its checkpoint, when it went on before it was stopped) and any line that is
    /// not a whole row (a run killed mid-write) are dropped, so that the resumed run's rows follow on without
    /// repeating a time. A row at `resumed_at` itself (within `slack`, half a time step) was written from the same
    /// state and is kept where it lies on the rows' cadence (`row_interval`); off it, it is the last row an
    /// interrupted run wrote where it stopped, which the unsplit run does not have, and is dropped. A row repeating
    /// the time of the row before it (an interrupted run of an earlier version wrote its last row twice when it
    /// stopped on a row's step) is dropped too.
    pub fn continue_at(path: &Path, resumed_at: f64, slack: f64, row_interval: f64) -> io::Result<Self> {
        let text = std::fs::read_to_string(path)?;
        let mut lines = text.lines();
        let header = lines.next().unwrap_or_default();
        let fixed = TIME_SERIES_COLUMNS.join(",");
        if header != fixed && !header.starts_with(&format!("{fixed},")) {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                "its first line is not this version's time-series header (another gc2d-rs version wrote it?); resume \
                 into a new --out directory",
            ));
        }
        // The time of a whole row (every column a number), `None` for anything else.
        let row_time = |line: &str| {
            let values: Option<Vec<f64>> = line.split(',').map(|field| field.parse().ok()).collect();
            values.filter(|v| v.len() == header.split(',').count()).map(|v| v[0])
        };
        let mut kept = String::with_capacity(text.len());
        let mut kept_last_row = None;
        let on_cadence = |time: f64| ((time / row_interval).round() * row_interval - time).abs() <= slack;
        for line in lines {
            if let Some(time) = row_time(line)
                && kept_last_row != Some(time)
                && time < resumed_at + slack
                && (time < resumed_at - slack || on_cadence(time))
            {
                kept.push_str(line);
                kept.push('\n');
                kept_last_row = Some(time);
            }
        }
        std::fs::write(path, format!("{header}\n{kept}"))?;
        let file = std::fs::OpenOptions::new().append(true).open(path)?;
        Ok(Self { file: BufWriter::new(file), header_pending: false, kept_last_row })
    }

    /// Writes the World's current row and flushes it to disk; a no-op for the row a continued series already has.
    pub fn append(&mut self, world: &World) -> io::Result<()> {
        if self.kept_last_row.take() == Some(world.time()) {
            return Ok(());
        }
        if self.header_pending {
            let mut header = TIME_SERIES_COLUMNS.join(",");
            boundary_columns(world).iter().for_each(|column| header = format!("{header},{column}"));
            writeln!(self.file, "{header}")?;
            self.header_pending = false;
        }
        let l = world.ledger();
        let s = world.stats();
        let particles = world.bodies().particles().count();
        let rotor = world.rotor_power();
        write!(
            self.file,
            "{},{},{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e}",
            world.time(),
            particles,
            s.contacts,
            s.max_overlap_fraction,
            l.kinetic_translational,
            l.kinetic_rotational,
            l.potential,
            l.contact_stored,
            l.drag_stored,
            l.dissipated_normal_damping,
            l.dissipated_tangential_damping,
            l.dissipated_sliding,
            l.work_in(),
            l.opening_residual,
            l.balance_error(),
            world.force_alternation().ratio(),
            rotor.torque,
            rotor.power_from_torque,
            rotor.power_from_work,
            gc2d_record::stats::median_speed(world),
            world.rotor_work().from_torque,
            world.rotor_work().from_work,
        )?;
        for inlet in world.inlets() {
            write!(self.file, ",{},{}", inlet.counters().injected, inlet.counters().postponed)?;
        }
        for outlet in world.outlets() {
            write!(self.file, ",{}", outlet.counters().removed)?;
        }
        if !(world.inlets().is_empty() && world.outlets().is_empty()) {
            write!(self.file, ",{}", s.removed)?;
        }
        writeln!(self.file)?;
        self.file.flush()
    }
}

/// How a run ended.
#[derive(Debug, Clone, Serialize, PartialEq)]
#[serde(rename_all = "snake_case", tag = "status", content = "message")]
pub enum RunStatus {
    /// Reached the end time.
    Completed,
    /// Stopped by Ctrl-C, SIGTERM or SIGHUP; outputs are complete up to the last step.
    Interrupted,
    /// Stopped by an error (blow-up, I/O); the message explains it.
    Failed(String),
}

impl RunStatus {
    /// The status as `summary.json` and `segments.csv` name it.
    pub fn name(&self) -> &'static str {
        match self {
            RunStatus::Completed => "completed",
            RunStatus::Interrupted => "interrupted",
            RunStatus::Failed(_) => "failed",
        }
    }
}

/// The top-level fields of `summary.json`, in order ([`Summary`]): a sweep's table takes its columns from them, so a
/// parameter may not be named like one.
pub const SUMMARY_FIELDS: [&str; 21] = [
    "program_version",
    "scene",
    "outcome",
    "time_s",
    "steps",
    "time_step_s",
    "stable_time_step_s",
    "wall_time_s",
    "wall_time_all_segments_s",
    "particles",
    "particles_inserted",
    "insertions_skipped",
    "particles_removed",
    "particles_injected",
    "injections_postponed",
    "particles_removed_at_outlets",
    "inlets",
    "outlets",
    "contacts",
    "energy",
    "chatter",
];

/// The content of `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// gc2d-rs version that made the run.
    pub program_version: &'static str,
    /// The scene file.
    pub scene: String,
    /// How the run ended.
    pub outcome: RunStatus,
    /// Simulated time at the end, s.
    pub time_s: f64,
    /// Steps taken (in this process, plus those before a resumed checkpoint).
    pub steps: u64,
    /// Δt, s.
    pub time_step_s: f64,
    /// The stable bound (π/10)·sqrt(m/E) of the particles at the end, s.
    pub stable_time_step_s: Option<f64>,
    /// Wall-clock time of this process's run, s.
    pub wall_time_s: f64,
    /// Wall-clock time of every process that worked on the run (this one and those it resumed from, as
    /// `segments.csv` lists them), s.
    pub wall_time_all_segments_s: f64,
    /// Particles in the World at the end.
    pub particles: usize,
    /// Particles inserted by sources.
    pub particles_inserted: u64,
    /// Insertions skipped because no free spot was found.
    pub insertions_skipped: u64,
    /// Particles removed for leaving the domain.
    pub particles_removed: u64,
    /// Particles fed by inlets.
    pub particles_injected: u64,
    /// Due inlet particles that waited a step for a free spot (one per particle and step).
    pub injections_postponed: u64,
    /// Particles removed by outlets.
    pub particles_removed_at_outlets: u64,
    /// Each inlet's counters, in scene order; empty without inlets.
    pub inlets: Vec<InletSummary>,
    /// Each outlet's counter, in scene order; empty without outlets.
    pub outlets: Vec<OutletSummary>,
    /// Touching pairs at the end.
    pub contacts: usize,
    /// Energy ledger at the end, J per unit thickness.
    pub energy: EnergySummary,
    /// The chatter watch of the whole run (a resumed run's included the earlier processes' windows up to the
    /// checkpoint it resumed from): the largest force alternation over a window of steps.
    pub chatter: ChatterSummary,
}

/// One inlet in `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct InletSummary {
    /// Its name (the scene's, or its index).
    pub name: String,
    /// Particles it fed.
    pub injected: u64,
    /// Due particles that waited a step for a free spot (one per particle and step).
    pub postponed: u64,
}

/// One outlet in `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct OutletSummary {
    /// Its name (the scene's, or its index).
    pub name: String,
    /// Particles it removed.
    pub removed: u64,
}

/// The ledger's columns in `summary.json`: every term of the balance, so that it can be checked from the file alone,
/// (kinetic + potential + contact_stored + drag_stored) − initial_total − (work_in − dissipated − opening_residual) =
/// balance_error.
#[derive(Debug, Clone, Serialize)]
pub struct EnergySummary {
    /// Kinetic energy (translational + rotational).
    pub kinetic_j: f64,
    /// Potential energy m g y.
    pub potential_j: f64,
    /// Energy stored in contacts.
    pub contact_stored_j: f64,
    /// Energy stored in drag springs.
    pub drag_stored_j: f64,
    /// The total (kinetic, potential, contacts, drag springs) at t = 0.
    pub initial_total_j: f64,
    /// Energy dissipated by damping and sliding since the start.
    pub dissipated_j: f64,
    /// Stored contact energy left when contacts opened since the start (docs/model.md, "Energy terms").
    pub opening_residual_j: f64,
    /// Work done from outside (walls, drag springs, the fluid, g changes, insertions − removals).
    pub work_in_j: f64,
    /// (E_now − E_0) − (W_in − D − residual): the bookkeeping error.
    pub balance_error_j: f64,
}

impl Summary {
    /// Gathers the summary of `world` after a run; `wall_time_all_segments_s` starts equal to `wall_time_s` (a run
    /// in one process).
    pub fn of(world: &World, scene: &Path, outcome: RunStatus, chatter: ChatterSummary, wall_time_s: f64) -> Self {
        let l = world.ledger();
        let s = world.stats();
        Self {
            program_version: env!("CARGO_PKG_VERSION"),
            scene: absolute_path_text(scene),
            outcome,
            time_s: world.time(),
            steps: world.steps(),
            time_step_s: world.time_step(),
            stable_time_step_s: world.stable_time_step(),
            wall_time_s,
            wall_time_all_segments_s: wall_time_s,
            particles: world.bodies().particles().count(),
            particles_inserted: s.inserted,
            insertions_skipped: s.insertions_skipped,
            particles_removed: s.removed,
            particles_injected: s.injected,
            injections_postponed: s.postponed,
            particles_removed_at_outlets: s.removed_at_outlets,
            inlets: world
                .inlets()
                .iter()
                .map(|i| InletSummary {
                    name: i.inlet().name.clone(),
                    injected: i.counters().injected,
                    postponed: i.counters().postponed,
                })
                .collect(),
            outlets: world
                .outlets()
                .iter()
                .map(|o| OutletSummary { name: o.outlet().name.clone(), removed: o.counters().removed })
                .collect(),
            contacts: s.contacts,
            energy: EnergySummary {
                kinetic_j: l.kinetic(),
                potential_j: l.potential,
                contact_stored_j: l.contact_stored,
                drag_stored_j: l.drag_stored,
                initial_total_j: l.initial_total,
                dissipated_j: l.dissipated(),
                opening_residual_j: l.opening_residual,
                work_in_j: l.work_in(),
                balance_error_j: l.balance_error(),
            },
            chatter,
        }
    }

    /// Writes the summary as pretty JSON to `path`, atomically: into `<path>.tmp`, flushed and synced, then renamed
    /// over `path`. A write that fails (a full disk) is reported and leaves no partial or empty `summary.json`: the
    /// temporary file is removed, and so is an older summary at `path` (a resumed run's), which no longer describes
    /// the run.
    pub fn write(&self, path: &Path) -> io::Result<()> {
        let temporary = crate::resume::temporary_path(path);
        let written = (|| {
            let json = serde_json::to_vec_pretty(self).map_err(io::Error::other)?;
            let mut file = File::create(&temporary)?;
            file.write_all(&json)?;
            file.write_all(b"\n")?;
            file.sync_all()?;
            std::fs::rename(&temporary, path)
        })();
        if written.is_err() {
            let _ = std::fs::remove_file(&temporary);
            let _ = std::fs::remove_file(path);
        }
        written
    }
}
