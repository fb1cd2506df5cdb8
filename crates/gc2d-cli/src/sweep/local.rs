//! Running points: each as its own `gc2d-rs run` process (this binary), up to `jobs` at once, with one progress bar
//! for the whole set. Finished points are skipped and interrupted ones resumed from their run directory; a stop
//! (Ctrl-C, SIGTERM, SIGHUP) is passed on to the running children as SIGTERM, so that each writes its final
//! checkpoint, and no further point starts.

use super::scenes::PointScene;
use super::state::{State, state, write_scene};
use crate::failure::CommandFailure;
use crate::outputs::SCENE_COPY;
use crate::run_lock::is_locked;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::collections::VecDeque;
use std::fs::OpenOptions;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// How often the children are polled.
const POLL: Duration = Duration::from_millis(50);

/// How the points run.
#[derive(Debug, Clone)]
pub struct RunSettings {
    /// Points run at once.
    pub jobs: usize,
    /// Worker threads of each run.
    pub threads: usize,
    /// `--checkpoint-every` of each run, s.
    pub checkpoint_every_s: Option<f64>,
    /// `--events` (true) or `--no-events` (false) for every run; `None`: `run`'s default (events for a mill scene).
    pub events: Option<bool>,
    /// The sweep file (named in each `scene.ron`).
    pub sweep_file: PathBuf,
    /// Hide the progress bar.
    pub quiet: bool,
}

/// What became of the points.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Tally {
    /// Points run from the start to their end.
    pub ran: usize,
    /// Points continued from a checkpoint to their end.
    pub resumed: usize,
    /// Points already finished.
    pub skipped: usize,
    /// Points whose run failed (their names).
    pub failed: Vec<String>,
    /// Points stopped before their end (their names).
    pub interrupted: Vec<String>,
    /// Points not started because the sweep was stopped.
    pub not_started: usize,
    /// Points another gc2d-rs process was running (another sweep on the same `out`, a run by hand), left to it (their
    /// names).
    pub busy: Vec<String>,
}

/// A point being run.
struct Running<'a> {
    child: Child,
    point: &'a PointScene,
    resumed: bool,
}

/// Runs (or resumes) every point of `points` that is not finished; `stop` is set by the signal handler.
pub fn run_points(points: &[PointScene], settings: &RunSettings, stop: &AtomicBool) -> Result<Tally, CommandFailure> {
    let mut tally = Tally::default();
    let mut queue = VecDeque::new();
    for point in points {
        match state(point)? {
            State::Finished(outcome) => {
                tally.skipped += 1;
                if outcome == "failed" {
                    tally.failed.push(point.name.clone());
                }
            }
            other => queue.push_back((point, other == State::Resume)),
        }
    }
    let bar = progress_bar(queue.len() as u64, tally.skipped, settings.quiet);
    let exe = std::env::current_exe()
        .map_err(|e| CommandFailure::failed(format!("cannot find the gc2d-rs program to run the points with: {e}")))?;
    let mut running: Vec<Running> = Vec::new();
    let mut forwarded = false;
    loop {
        let stopping = stop.load(Ordering::Relaxed);
        if stopping && !forwarded {
            running.iter().for_each(|r| terminate(&r.child));
            forwarded = true;
        }
        while !stopping && running.len() < settings.jobs.max(1) {
            let Some((point, resume)) = queue.pop_front() else { break };
            if is_locked(&point.dir) {
                tally.busy.push(point.name.clone());
                bar.inc(1);
                continue;
            }
            running.push(Running { child: spawn(&exe, point, resume, settings)?, point, resumed: resume });
        }
        let mut k = 0;
        while k < running.len() {
            let status = running[k].child.try_wait().map_err(|e| {
                CommandFailure::failed(format!("cannot watch the run of {}: {e}", running[k].point.name))
            })?;
            let Some(status) = status else {
                k += 1;
                continue;
            };
            let done = running.swap_remove(k);
            let name = done.point.name.clone();
            match status.code() {
                Some(0) if done.resumed => tally.resumed += 1,
                Some(0) => tally.ran += 1,
                Some(130) | None => tally.interrupted.push(name),
                // Refused because another process took the directory between the test above and the start.
                Some(_) if is_locked(&done.point.dir) => tally.busy.push(name),
                Some(_) => tally.failed.push(name),
            }
            bar.inc(1);
            bar.set_message(message(&tally, running.len()));
        }
        if running.is_empty() && (queue.is_empty() || stopping) {
            break;
        }
        std::thread::sleep(POLL);
    }
    tally.not_started = queue.len();
    bar.finish_and_clear();
    Ok(tally)
}

/// Starts `gc2d-rs run` on a point (writing its `scene.ron` first when it starts from the beginning); its output
/// goes to `run.log` in the run directory.
fn spawn(exe: &Path, point: &PointScene, resume: bool, settings: &RunSettings) -> Result<Child, CommandFailure> {
    if !resume {
        write_scene(point, &settings.sweep_file)?;
    }
    let log_path = point.dir.join("run.log");
    let log = OpenOptions::new()
        .create(true)
        .append(true)
        .open(&log_path)
        .map_err(|e| CommandFailure::failed(format!("cannot write {}: {e}", log_path.display())))?;
    let log_err =
        log.try_clone().map_err(|e| CommandFailure::failed(format!("cannot write {}: {e}", log_path.display())))?;
    let mut command = Command::new(exe);
    command
        .arg("run")
        .arg(point.dir.join(SCENE_COPY))
        .arg("--out")
        .arg(&point.dir)
        .arg("--threads")
        .arg(settings.threads.max(1).to_string())
        .arg("--quiet");
    if resume {
        command.arg("--resume").arg(&point.dir);
    }
    match settings.events {
        Some(true) => {
            command.arg("--events");
        }
        Some(false) => {
            command.arg("--no-events");
        }
        None => {}
    }
    if let Some(every) = settings.checkpoint_every_s {
        command.arg("--checkpoint-every").arg(every.to_string());
    }
    command
        .stdin(Stdio::null())
        .stdout(log)
        .stderr(log_err)
        .spawn()
        .map_err(|e| CommandFailure::failed(format!("cannot start the run of {}: {e}", point.name)))
}

/// Asks a child to stop as a batch system does (SIGTERM): it writes its final checkpoint and summary.
fn terminate(child: &Child) {
    #[cfg(unix)]
    if let Ok(pid) = libc::pid_t::try_from(child.id()) {
        // SAFETY: kill(2) with a child's own pid and a standard signal has no memory effects; a child that has
        // already exited makes it fail harmlessly (ESRCH, or the zombie ignores it).
        unsafe {
            libc::kill(pid, libc::SIGTERM);
        }
    }
    #[cfg(not(unix))]
    let _ = child;
}

/// The bar over the points to run, with the count of skipped ones in its prefix.
fn progress_bar(length: u64, skipped: usize, quiet: bool) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(length), ProgressDrawTarget::stderr());
    let style =
        ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} points, {elapsed} elapsed, ETA {eta} {msg}")
            .map(|s| s.progress_chars("=> "))
            .unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style);
    bar.set_prefix(format!("sweep ({skipped} already done)"));
    bar.enable_steady_tick(Duration::from_millis(500));
    bar
}

fn message(tally: &Tally, running: usize) -> String {
    let mut parts = vec![format!("{running} running")];
    if !tally.failed.is_empty() {
        parts.push(format!("{} failed", tally.failed.len()));
    }
    parts.join(", ")
}
