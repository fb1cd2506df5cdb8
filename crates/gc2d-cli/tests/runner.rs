//! The run loop on a small World built in code: rows on their cadence, clean stops, failures reported.

use gc2d_cli::events::EventsWriter;
use gc2d_cli::object_names::ObjectNames;
use gc2d_cli::outputs::{RunStatus, Summary, TimeSeriesWriter};
use gc2d_cli::runner::{FrameSink, run_to};
use gc2d_cli::sinks::Checkpoints;
use gc2d_contact::ContactLaw;
use gc2d_engine::schedules::GravitySchedule;
use gc2d_engine::{ContactEventKind, InteractionTable, MassModel, WallMotion, World, WorldConfig};
use gc2d_geometry::{DVec2, Pose, rectangle, regular_polygon};
use std::sync::atomic::AtomicBool;

fn small_world() -> World {
    let config = WorldConfig {
        time_step: 1e-5,
        integrator: Default::default(),
        interactions: InteractionTable::uniform(ContactLaw::elastic(1e7)),
        mass_model: MassModel::PerUnitThickness,
        gravity: GravitySchedule::constant(9.81),
        heating: None,
        safety: Default::default(),
        domain: None,
        seed: 1,
    };
    let mut world = World::new(config).unwrap();
    world.add_wall(
        rectangle(0.2, 0.01).unwrap(),
        Pose::new(DVec2::new(0.0, -0.005), 0.0),
        DVec2::ZERO,
        WallMotion::Static,
    );
    let grain = regular_polygon(7, 0.005).unwrap();
    for k in 0..5 {
        world
            .add_particle(&grain, Pose::new(DVec2::new(0.012 * k as f64, 0.02), 0.0), 5000.0, DVec2::ZERO, 0.0)
            .unwrap();
    }
    world
}

/// Counts how often it was called and at which times.
struct Ticks {
    interval: f64,
    times: Vec<f64>,
}

impl FrameSink for Ticks {
    fn interval(&self) -> f64 {
        self.interval
    }
    fn take(&mut self, world: &World) -> Result<(), String> {
        self.times.push(world.time());
        Ok(())
    }
}

#[test]
fn rows_and_frames_follow_their_cadence() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("timeseries.csv");
    let mut world = small_world();
    let mut series = TimeSeriesWriter::create(&path).unwrap();
    let mut ticks = Ticks { interval: 0.01, times: Vec::new() };
    let outcome = run_to(&mut world, 0.05, &mut series, 0.005, &mut [&mut ticks], &AtomicBool::new(false), false, None);
    assert_eq!(outcome.status, RunStatus::Completed);
    assert!((world.time() - 0.05).abs() < 1e-9);
    let text = std::fs::read_to_string(&path).unwrap();
    // Header plus rows at 0, 0.005, ..., 0.05.
    assert_eq!(text.lines().count(), 1 + 11);
    assert_eq!(ticks.times.len(), 6);
    for (k, t) in ticks.times.iter().enumerate() {
        assert!((t - 0.01 * k as f64).abs() < 1e-9, "frame {k} at {t}");
    }
}

#[test]
fn a_stop_request_ends_the_run_cleanly_with_a_last_row() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("timeseries.csv");
    let mut world = small_world();
    let mut series = TimeSeriesWriter::create(&path).unwrap();
    let outcome = run_to(&mut world, 1.0, &mut series, 0.1, &mut [], &AtomicBool::new(true), false, None);
    assert_eq!(outcome.status, RunStatus::Interrupted);
    assert_eq!(world.steps(), 0);
    assert_eq!(outcome.chatter.largest_window, None, "no step, no window");
    let summary = Summary::of(&world, std::path::Path::new("in-code"), outcome.status, outcome.chatter, 0.0);
    summary.write(&dir.path().join("summary.json")).unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("summary.json")).unwrap()).unwrap();
    assert_eq!(json["outcome"]["status"], "interrupted");
    assert_eq!(json["particles"], 5);
    // The fields a sweep's parameters may not be named like.
    let fields: Vec<&str> = json.as_object().unwrap().keys().map(String::as_str).collect();
    let mut listed = gc2d_cli::outputs::SUMMARY_FIELDS.to_vec();
    listed.sort_unstable();
    assert_eq!(fields, listed);
    // Header and the row of t = 0, which is also the state the run stopped at: written once (QA R7).
    assert_eq!(std::fs::read_to_string(&path).unwrap().lines().count(), 2);
}

/// A sink that fails on its second call.
struct Failing(u32);

impl FrameSink for Failing {
    fn interval(&self) -> f64 {
        0.001
    }
    fn take(&mut self, _: &World) -> Result<(), String> {
        self.0 += 1;
        if self.0 > 1 { Err("disk full".into()) } else { Ok(()) }
    }
}

#[test]
fn a_failing_sink_stops_the_run_with_its_message() {
    let dir = tempfile::tempdir().unwrap();
    let mut world = small_world();
    let mut series = TimeSeriesWriter::create(&dir.path().join("t.csv")).unwrap();
    let outcome =
        run_to(&mut world, 1.0, &mut series, 0.1, &mut [&mut Failing(0)], &AtomicBool::new(false), false, None);
    assert_eq!(outcome.status, RunStatus::Failed("disk full".into()));
    assert!(world.time() < 0.01);
}

/// Counts the contact episodes that ended, and on its ticks (polled after the checkpoints, on their cadence) records
/// every time `events.csv` on disk held fewer rows than had ended: what a run killed right then would have left.
struct EventsOnDisk {
    path: std::path::PathBuf,
    interval: f64,
    ended: usize,
    checked: Vec<(f64, usize)>,
    short: Vec<(f64, usize, usize)>,
}

impl FrameSink for EventsOnDisk {
    fn interval(&self) -> f64 {
        self.interval
    }
    fn take(&mut self, world: &World) -> Result<(), String> {
        let rows = std::fs::read_to_string(&self.path).unwrap().lines().count() - 1;
        self.checked.push((world.time(), self.ended));
        if rows != self.ended {
            self.short.push((world.time(), rows, self.ended));
        }
        Ok(())
    }
    fn after_step(&mut self, world: &World) -> Result<(), String> {
        self.ended += world.contact_events().iter().filter(|e| e.kind == ContactEventKind::End).count();
        Ok(())
    }
}

/// QA R14: `events.csv` was flushed on its own cadence only, so that a run killed right after a periodic checkpoint
/// had episodes that ended before it still in its buffer, and a resume from that checkpoint never wrote them. Every
/// checkpoint now finds the rows up to it on disk.
#[test]
fn a_checkpoint_finds_the_events_up_to_it_on_disk() {
    let dir = tempfile::tempdir().unwrap();
    let mut world = small_world();
    world.record_contact_events();
    let mut series = TimeSeriesWriter::create(&dir.path().join("timeseries.csv")).unwrap();
    let path = dir.path().join("events.csv");
    // Flushed on its own cadence only at t = 0: every later row reaches the disk before a checkpoint or at the end.
    let mut events = EventsWriter::create(&path, vec!["m".into()], ObjectNames::default(), 1.0).unwrap();
    let mut checkpoints = Checkpoints { dir: dir.path().join("checkpoints"), interval: 0.01 };
    let mut watch =
        EventsOnDisk { path: path.clone(), interval: 0.01, ended: 0, checked: Vec::new(), short: Vec::new() };
    let sinks: &mut [&mut dyn FrameSink] = &mut [&mut events, &mut checkpoints, &mut watch];
    let outcome = run_to(&mut world, 0.1, &mut series, 0.005, sinks, &AtomicBool::new(false), false, None);
    assert_eq!(outcome.status, RunStatus::Completed);
    assert_eq!(std::fs::read_dir(dir.path().join("checkpoints")).unwrap().count(), 11, "t = 0, 0.01, …, 0.1");
    assert!(watch.checked.iter().filter(|(_, ended)| *ended > 0).count() >= 3, "too few episodes: {:?}", watch.checked);
    assert!(watch.short.is_empty(), "events.csv behind its checkpoints (t, rows, ended): {:?}", watch.short);
}

/// Asks the run to stop (as Ctrl-C does) when it takes its `at`-th tick, so that the stop lands on a step that also
/// has a time-series row.
struct StopOnTick<'a> {
    interval: f64,
    at: usize,
    taken: usize,
    stop: &'a AtomicBool,
}

impl FrameSink for StopOnTick<'_> {
    fn interval(&self) -> f64 {
        self.interval
    }
    fn take(&mut self, _: &World) -> Result<(), String> {
        self.taken += 1;
        if self.taken == self.at {
            self.stop.store(true, std::sync::atomic::Ordering::Relaxed);
        }
        Ok(())
    }
}

/// QA R7: a stop that came while the outputs of a row's step were written (a checkpoint's step) had the run write that
/// row again as its "last row at the final state", and a resume kept both copies. The stopped run's series now ends
/// with the row once, and continued it is the unsplit run's series byte for byte; a series an earlier version left
/// with the row twice is repaired by the resume.
#[test]
fn a_stop_on_a_rows_step_writes_its_row_once() {
    let dir = tempfile::tempdir().unwrap();
    let whole = dir.path().join("whole.csv");
    let mut series = TimeSeriesWriter::create(&whole).unwrap();
    let never = AtomicBool::new(false);
    let outcome = run_to(&mut small_world(), 0.04, &mut series, 0.005, &mut [], &never, false, None);
    assert_eq!(outcome.status, RunStatus::Completed);

    let split = dir.path().join("split.csv");
    let mut world = small_world();
    let mut series = TimeSeriesWriter::create(&split).unwrap();
    let stop = AtomicBool::new(false);
    let mut stopper = StopOnTick { interval: 0.01, at: 3, taken: 0, stop: &stop };
    let outcome = run_to(&mut world, 0.04, &mut series, 0.005, &mut [&mut stopper], &stop, false, None);
    assert_eq!(outcome.status, RunStatus::Interrupted);
    assert!((world.time() - 0.02).abs() < 1e-9, "stopped at {}", world.time());
    let stopped = std::fs::read_to_string(&split).unwrap();
    let times: Vec<&str> = stopped.lines().skip(1).map(|line| line.split(',').next().unwrap()).collect();
    assert_eq!(times.len(), 5, "rows at 0, 0.005, …, 0.02, once each: {times:?}");
    assert!(times.windows(2).all(|pair| pair[0] != pair[1]), "a row written twice: {times:?}");

    // The same World goes on (a resume from the stop's final.ckpt, without the checkpoint's unknown force history).
    let (time, slack) = (world.time(), 0.5 * world.time_step());
    let mut series = TimeSeriesWriter::continue_at(&split, time, slack, 0.005).unwrap();
    run_to(&mut world, 0.04, &mut series, 0.005, &mut [], &never, false, None);
    assert!(std::fs::read_to_string(&split).unwrap() == std::fs::read_to_string(&whole).unwrap());

    // What an earlier version left: the stop's row twice. The resume keeps it once.
    let last = stopped.lines().last().unwrap();
    std::fs::write(&split, format!("{stopped}{last}\n")).unwrap();
    drop(TimeSeriesWriter::continue_at(&split, time, slack, 0.005).unwrap());
    assert_eq!(std::fs::read_to_string(&split).unwrap(), stopped);
}
