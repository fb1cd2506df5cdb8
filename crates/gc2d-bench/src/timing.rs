//! Timing of `World::step`: one measurement on a rayon pool of a given size, wall-clock and CPU time, and its row in
//! the Markdown table docs/performance.md quotes.

use crate::line_trip::cache_line_round_trip_ns;
use gc2d_engine::{Stage, StageTimes, World, WorldError};
use std::time::Instant;

/// Untimed steps before each measurement (fills the caches, lets the thread pool spin up).
pub const WARM_STEPS: u64 = 20;

/// One timed run.
pub struct Measurement {
    /// Particles in the World.
    pub particles: usize,
    /// Threads of the rayon pool.
    pub threads: usize,
    /// Timed steps.
    pub steps: u64,
    /// Wall-clock time of the timed steps, s.
    pub seconds: f64,
    /// CPU time of all threads during the timed steps, s (NaN where it cannot be read).
    pub cpu_seconds: f64,
    /// Touching pairs summed over the timed steps.
    pub contacts: u64,
    /// Pairs of touching boxes summed over the timed steps.
    pub box_pairs: u64,
    /// `World::heap_bytes` after the run.
    pub heap_bytes: usize,
    /// The body columns' part of it.
    pub body_heap_bytes: usize,
    /// Wall-clock time per stage of the timed steps, where the measurement was asked to time them.
    pub stages: Option<StageTimes>,
    /// A cache line's round trip between two threads just before the timed steps, ns ([`cache_line_round_trip_ns`]);
    /// measured only for more than one thread, whose speed-up it bounds.
    pub line_trip_ns: Option<f64>,
}

impl Measurement {
    /// Particle-steps per wall-clock second.
    pub fn particle_steps_per_second(&self) -> f64 {
        self.particles as f64 * self.steps as f64 / self.seconds
    }

    /// Contacts (touching pairs, walls included) per particle, averaged over the timed steps.
    pub fn contacts_per_particle(&self) -> f64 {
        self.contacts as f64 / self.steps as f64 / self.particles as f64
    }

    /// The run as a row of the Markdown table of [`table_header`].
    pub fn row(&self) -> String {
        let per_step = |x: u64| x as f64 / self.steps as f64 / self.particles as f64;
        format!(
            "| {:>7} | {:>7} | {:>6} | {:>8.3} | {:>8.3} | {:>10.2} | {:>10.2} | {:>6.1} | {:>8.1} | {:>8.2} | {:>8.2} | {:>7} | {:>7} | {:>6} |",
            self.particles,
            self.threads,
            self.steps,
            self.seconds,
            self.cpu_seconds,
            self.particle_steps_per_second() / 1e6,
            self.contacts as f64 / self.seconds / 1e6,
            1e9 / self.particle_steps_per_second(),
            1e9 * self.cpu_seconds / (self.particles as f64 * self.steps as f64),
            per_step(self.box_pairs),
            per_step(self.contacts),
            self.heap_bytes / self.particles,
            self.body_heap_bytes / self.particles,
            self.line_trip_ns.map_or_else(|| "–".into(), |ns| format!("{ns:.0}")),
        )
    }

    /// The stage times as a row of the Markdown table of [`stage_table_header`], µs per step; `None` where the
    /// stages were not timed.
    pub fn stage_row(&self) -> Option<String> {
        let stages = self.stages.as_ref()?;
        let per_step = |seconds: f64| 1e6 * seconds / stages.steps as f64;
        let cells: Vec<String> =
            Stage::ALL.iter().map(|&stage| format!("{:>8.1}", per_step(stages.seconds(stage)))).collect();
        Some(format!(
            "| {:>7} | {:>7} | {} | {:>8.1} |",
            self.particles,
            self.threads,
            cells.join(" | "),
            per_step(stages.total_seconds())
        ))
    }
}

/// The head of the Markdown table of [`Measurement::row`] (two lines); `particle` names them ("grain", "disk").
pub fn table_header(particle: &str) -> String {
    format!(
        "| {particle}s | threads | steps | wall s | CPU s | M p-steps/s | M contacts/s | wall ns/p-step | CPU ns/p-step \
         | box pairs/{particle} | contacts/{particle} | heap B/{particle} | of it bodies | line trip ns |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    )
}

/// The head of the Markdown table of [`Measurement::stage_row`] (two lines): microseconds per step in each stage.
pub fn stage_table_header(particle: &str) -> String {
    let names: Vec<&str> = Stage::ALL.iter().map(|s| s.name()).collect();
    format!(
        "| {particle}s | threads | {} | all stages |\n|---|---|{}---|",
        names.join(" | "),
        "---|".repeat(names.len())
    )
}

/// A rayon pool of `threads` threads.
pub fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("thread pool")
}

/// CPU time used by all threads of this process so far, s, those that have ended included (the threads of an
/// earlier measurement's pool end during the next one), or `None` where the clock cannot be read. On a shared machine
/// it is the better measure of the work a run needs.
fn process_cpu_seconds() -> Option<f64> {
    let mut time = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: clock_gettime writes one timespec through the valid pointer it is given and keeps no reference to it.
    let status = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut time) };
    (status == 0).then_some(time.tv_sec as f64 + time.tv_nsec as f64 * 1e-9)
}

/// Steps `world` `steps` times on a pool of `threads` threads, after `WARM_STEPS` untimed ones, and times it, each
/// stage too where `time_stages` asks for it ([`World::start_stage_clock`]); on more than one thread it first measures
/// a cache line's round trip between two threads. The error of a step that fails (a blow-up).
pub fn measure(world: &mut World, threads: usize, steps: u64, time_stages: bool) -> Result<Measurement, WorldError> {
    let particles = world.bodies().particles().count();
    // Before the pool exists: its idle workers would compete with the two threads for the cores.
    let line_trip_ns = (threads > 1).then(cache_line_round_trip_ns);
    pool(threads).install(|| {
        for _ in 0..WARM_STEPS {
            world.step()?;
        }
        if time_stages {
            world.start_stage_clock();
        }
        let (mut contacts, mut box_pairs) = (0, 0);
        let cpu_before = process_cpu_seconds();
        let started = Instant::now();
        for _ in 0..steps {
            world.step()?;
            contacts += world.stats().contacts as u64;
            box_pairs += world.stats().box_pairs as u64;
        }
        let seconds = started.elapsed().as_secs_f64();
        let cpu_seconds = process_cpu_seconds().zip(cpu_before).map_or(f64::NAN, |(after, before)| after - before);
        let (heap_bytes, body_heap_bytes) = (world.heap_bytes(), world.bodies().heap_bytes());
        Ok(Measurement {
            particles,
            threads,
            steps,
            seconds,
            cpu_seconds,
            contacts,
            box_pairs,
            heap_bytes,
            body_heap_bytes,
            stages: world.stop_stage_clock(),
            line_trip_ns,
        })
    })
}

/// The system's load average, as `/proc/loadavg` gives it.
pub fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg").map_or_else(|_| "unknown".into(), |s| s.trim().to_string())
}
