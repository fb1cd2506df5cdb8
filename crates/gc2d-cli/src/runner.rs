//! The run loop: steps a World to its end time, writing time-series rows, recording frames and checkpoints on their
//! cadences, showing progress, and stopping cleanly on Ctrl-C (or SIGTERM, SIGHUP) or on an error.

use crate::chatter::{AlternationWindow, ChatterSummary, ChatterWatch};
use crate::outputs::{RunStatus, TimeSeriesWriter};
use gc2d_engine::World;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Something that receives the World on a cadence of simulated time (recordings, checkpoints, pictures). `Send`
/// because the run loop executes on a worker of the run's thread pool.
pub trait FrameSink: Send {
    /// Simulated time between two calls, s.
    fn interval(&self) -> f64;
    /// Takes the World as it is now; an error stops the run with that message.
    fn take(&mut self, world: &World) -> Result<(), String>;
    /// Sees the World after every step (what happened on that step only: contact events); nothing by default.
    fn after_step(&mut self, _world: &World) -> Result<(), String> {
        Ok(())
    }
    /// True for a sink that writes the checkpoints a run resumes from: before it takes the World, the run loop has
    /// every sink [`flush`](Self::flush) what it buffered, so that a run killed right after a checkpoint leaves the
    /// rows up to it on disk (a resumed run continues its files from the checkpoint's time, and never writes earlier
    /// rows again); false by default.
    fn is_checkpoint(&self) -> bool {
        false
    }
    /// Hands the rows buffered so far to the operating system; nothing by default.
    fn flush(&mut self) -> Result<(), String> {
        Ok(())
    }
    /// Hears of the run's new largest force-alternation window (the chatter watch's, when a window of steps closes
    /// above all before it); nothing by default.
    fn largest_alternation(&mut self, _window: AlternationWindow) {}
    /// Ends the run's part of the output: hands what is still buffered to the operating system, so that the files are
    /// whole when the run reports (a mill run's summary reads `events.csv` right after); [`flush`](Self::flush) by
    /// default.
    fn finish(&mut self) -> Result<(), String> {
        self.flush()
    }
}

/// The place on a cadence of `interval` (s) of the last tick the World has reached: ⌊(t + Δt/2)/interval⌋, so that a
/// file written on the tick k·interval is named k in every process of a run, a resumed one included.
pub fn cadence_index(world: &World, interval: f64) -> u64 {
    ((world.time() + 0.5 * world.time_step()) / interval).floor().max(0.0) as u64
}

/// The place on a cadence of `interval` (s) of the first tick a run part starting at `time` takes: the first multiple
/// of the interval at or after `time`, a tick within `slack` (half a step) before it included.
pub fn first_tick(interval: f64, time: f64, slack: f64) -> u64 {
    ((time - slack) / interval).ceil().max(0.0) as u64
}

/// Ticks at whole multiples of an interval of simulated time (not counted from the start), so that a resumed run
/// writes its rows, frames and checkpoints at the times the uninterrupted run would have.
struct Ticks {
    interval: f64,
    next: u64,
}

impl Ticks {
    /// The ticks from `time` on; a tick within half a step (`slack`) before `time` is still due.
    fn from(interval: f64, time: f64, slack: f64) -> Self {
        Self { interval, next: first_tick(interval, time, slack) }
    }

    /// True when the next tick has been reached at `time`, with half a step of slack so that a tick at exactly
    /// k·interval is not missed by round-off.
    fn due(&self, time: f64, slack: f64) -> bool {
        time + slack >= self.next as f64 * self.interval
    }

    /// Moves past every tick reached at `time`.
    fn advance(&mut self, time: f64, slack: f64) {
        while self.due(time, slack) {
            self.next += 1;
        }
    }
}

/// Calls a sink whenever its next tick has been reached.
struct ScheduledSink<'a> {
    sink: &'a mut dyn FrameSink,
    ticks: Ticks,
}

impl ScheduledSink<'_> {
    /// True when the sink writes checkpoints and its next tick has been reached.
    fn checkpoint_due(&self, world: &World) -> bool {
        self.sink.is_checkpoint() && self.ticks.due(world.time(), 0.5 * world.time_step())
    }

    fn poll(&mut self, world: &World) -> Result<(), String> {
        let slack = 0.5 * world.time_step();
        if self.ticks.due(world.time(), slack) {
            self.sink.take(world)?;
            self.ticks.advance(world.time(), slack);
        }
        Ok(())
    }
}

/// How a run loop ended, and what the chatter watch saw.
#[derive(Debug, Clone, PartialEq)]
pub struct RunOutcome {
    /// How the run ended.
    pub status: RunStatus,
    /// The force-alternation windows of the whole run: this process's (warned once on stderr when they exceeded the
    /// threshold) and the earlier processes' largest.
    pub chatter: ChatterSummary,
    /// The bodies the engine's error named when the run failed in a step (by id), for the caller to name them as
    /// the scene does; empty otherwise.
    pub failed_bodies: Vec<u32>,
}

/// Steps `world` until `end_time`, appending a row to `series` every `series_interval` of simulated time and
/// feeding each sink on its cadence, and watches for chatter (`earlier_chatter`: the largest window of the processes
/// before this one, for a resumed run). Returns how the run ended; the outputs are flushed in every case.
#[allow(clippy::too_many_arguments)]
pub fn run_to(
    world: &mut World,
    end_time: f64,
    series: &mut TimeSeriesWriter,
    series_interval: f64,
    sinks: &mut [&mut dyn FrameSink],
    stop: &AtomicBool,
    show_progress: bool,
    earlier_chatter: Option<AlternationWindow>,
) -> RunOutcome {
    let progress = Progress::new(world, end_time, show_progress);
    let mut chatter = ChatterWatch::continuing(earlier_chatter);
    let (start, slack) = (world.time(), 0.5 * world.time_step());
    let mut rows = Ticks::from(series_interval, start, slack);
    let mut scheduled: Vec<ScheduledSink> = sinks
        .iter_mut()
        .map(|sink| {
            let ticks = Ticks::from(sink.interval(), start, slack);
            ScheduledSink { sink: &mut **sink, ticks }
        })
        .collect();
    let mut failed_bodies = Vec::new();
    let mut last_row_time = None;
    let status = loop {
        if rows.due(world.time(), slack) {
            if let Err(e) = series.append(world) {
                break RunStatus::Failed(format!("could not write the time series: {e}"));
            }
            last_row_time = Some(world.time());
            rows.advance(world.time(), slack);
        }
        // A checkpoint marks a state the other files must already hold on disk: the time series does (each row is
        // flushed as written), the sinks' buffered rows (events.csv, transits.csv) are flushed first.
        if scheduled.iter().any(|c| c.checkpoint_due(world))
            && let Some(message) = scheduled.iter_mut().find_map(|c| c.sink.flush().err())
        {
            break RunStatus::Failed(message);
        }
        if let Some(message) = scheduled.iter_mut().find_map(|c| c.poll(world).err()) {
            break RunStatus::Failed(message);
        }
        if world.time() + 0.5 * world.time_step() >= end_time {
            break RunStatus::Completed;
        }
        if stop.load(Ordering::Relaxed) {
            break RunStatus::Interrupted;
        }
        if let Err(e) = world.step() {
            failed_bodies = e.bodies();
            break RunStatus::Failed(e.to_string());
        }
        if let Some(message) = scheduled.iter_mut().find_map(|c| c.sink.after_step(world).err()) {
            break RunStatus::Failed(message);
        }
        if let Some(warning) = chatter.observe(world) {
            progress.warn(&warning);
        }
        if let Some(window) = chatter.new_largest() {
            scheduled.iter_mut().for_each(|c| c.sink.largest_alternation(window));
        }
        progress.update(world);
    };
    // The last row: the final state of a run that ended between two rows (an end time off the rows' cadence, a stop
    // or a failure between two rows), so that the series ends where summary.json and final.ckpt do (a resumed run
    // drops such a row again, `TimeSeriesWriter::continue_at`). A run that ended on a step with its row (a stop that
    // came while that step's outputs were written) has its last row already; a failure before it (a full disk) stays
    // the reported cause.
    let status = match status {
        _ if last_row_time == Some(world.time()) => status,
        _ if series.append(world).is_ok() => status,
        RunStatus::Completed | RunStatus::Interrupted => {
            RunStatus::Failed("could not write the last row of the time series".into())
        }
        failed => failed,
    };
    // Every sink ends its files, whatever the others do; the first that cannot fails a run that had not failed.
    let unfinished: Vec<String> = scheduled.iter_mut().filter_map(|c| c.sink.finish().err()).collect();
    let status = match (status, unfinished.into_iter().next()) {
        (RunStatus::Completed | RunStatus::Interrupted, Some(message)) => RunStatus::Failed(message),
        (status, _) => status,
    };
    progress.finish(&status);
    RunOutcome { status, chatter: chatter.summary(), failed_bodies }
}

/// The progress bar: simulated time, steps/s, contacts and ETA; hidden when stderr is not a terminal.
struct Progress {
    bar: ProgressBar,
    start_time: f64,
    started: Instant,
    start_steps: u64,
}

/// The progress bar of a stretch of simulation `length` units long (a run's microseconds, a settling's chunks), on
/// stderr when `visible`: the one look of every simulation bar of the program.
pub fn simulation_bar(length: u64, visible: bool) -> ProgressBar {
    let target = if visible { ProgressDrawTarget::stderr() } else { ProgressDrawTarget::hidden() };
    let bar = ProgressBar::with_draw_target(Some(length), target);
    bar.set_style(
        ProgressStyle::with_template("{bar:32.cyan/blue} {percent:>3}%  {msg}  ETA {eta}")
            .expect("the template is a valid indicatif template")
            .progress_chars("=> "),
    );
    bar.enable_steady_tick(Duration::from_millis(500));
    bar
}

impl Progress {
    /// Steps between two updates of the bar (it redraws at most a few times a second anyway).
    const EVERY: u64 = 256;

    fn new(world: &World, end_time: f64, visible: bool) -> Self {
        let total_us = ((end_time - world.time()).max(0.0) * 1e6).round() as u64;
        let bar = simulation_bar(total_us, visible);
        Self { bar, start_time: world.time(), started: Instant::now(), start_steps: world.steps() }
    }

    fn update(&self, world: &World) {
        if world.steps() % Self::EVERY != 0 || self.bar.is_hidden() {
            return;
        }
        let elapsed = self.started.elapsed().as_secs_f64().max(1e-9);
        let steps_per_s = (world.steps() - self.start_steps) as f64 / elapsed;
        self.bar.set_position(((world.time() - self.start_time) * 1e6).round() as u64);
        self.bar.set_message(format!(
            "t = {:.4} s  {:.0} steps/s  {} particles  {} contacts",
            world.time(),
            steps_per_s,
            world.bodies().particles().count(),
            world.stats().contacts
        ));
    }

    /// Prints a warning above the bar, or on stderr when the bar is hidden.
    fn warn(&self, message: &str) {
        if self.bar.is_hidden() {
            crate::console::err(message);
        } else {
            self.bar.println(message);
        }
    }

    fn finish(&self, status: &RunStatus) {
        match status {
            RunStatus::Completed => self.bar.finish_with_message("done"),
            _ => self.bar.abandon(),
        }
        // indicatif leaves the cursor after the bar's line, padded to the width it believes the terminal has, for the
        // terminal's wrap to end it; where that width is not the terminal's (a terminal recorded by `script`, a
        // resized window) the next message was appended to the bar. A line break of our own ends it in any case (a
        // carriage return and line feed after a wrap pending at the last column start the next line, no blank one).
        if !self.bar.is_hidden() {
            crate::console::err("");
        }
    }
}
