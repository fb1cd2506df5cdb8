//! Timing of `World::step` for the throughput examples (`bench_pile`, `bench_disk_pile`): one measurement on a
//! rayon pool of a given size, wall-clock and CPU time, and its row in the Markdown table docs/performance.md quotes.

#![allow(dead_code)] // each example uses its own subset

use gc2d_engine::World;
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
}

impl Measurement {
    /// Particle-steps per wall-clock second.
    pub fn particle_steps_per_second(&self) -> f64 {
        self.particles as f64 * self.steps as f64 / self.seconds
    }

    /// Prints the run as a row of the table of [`print_header`].
    pub fn print(&self) {
        let per_step = |x: u64| x as f64 / self.steps as f64 / self.particles as f64;
        println!(
            "| {:>7} | {:>7} | {:>6} | {:>8.3} | {:>8.3} | {:>10.2} | {:>10.2} | {:>6.1} | {:>8.1} | {:>8.2} | {:>8.2} | {:>7} | {:>7} |",
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
        );
    }
}

/// Prints the head of the table of [`Measurement::print`]; `particle` names them ("grain", "disk").
pub fn print_header(particle: &str) {
    println!(
        "| {particle}s | threads | steps | wall s | CPU s | M p-steps/s | M contacts/s | wall ns/p-step | CPU ns/p-step \
         | box pairs/{particle} | contacts/{particle} | heap B/{particle} | of it bodies |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
}

/// A rayon pool of `threads` threads.
pub fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("thread pool")
}

/// CPU time used by all threads of this process so far, s (the sum of `/proc/self/task/*/schedstat`), or `None`
/// where that is not available. On a shared machine it is the better measure of the work a run needs.
fn process_cpu_seconds() -> Option<f64> {
    let mut nanoseconds = 0u64;
    for task in std::fs::read_dir("/proc/self/task").ok()? {
        let stat = std::fs::read_to_string(task.ok()?.path().join("schedstat")).ok()?;
        nanoseconds += stat.split_whitespace().next()?.parse::<u64>().ok()?;
    }
    Some(nanoseconds as f64 * 1e-9)
}

/// Steps `world` `steps` times on a pool of `threads` threads, after `WARM_STEPS` untimed ones, and times it.
pub fn measure(world: &mut World, threads: usize, steps: u64) -> Measurement {
    let particles = world.bodies().particles().count();
    pool(threads).install(|| {
        for _ in 0..WARM_STEPS {
            world.step().expect("no blow-up");
        }
        let (mut contacts, mut box_pairs) = (0, 0);
        let cpu_before = process_cpu_seconds();
        let started = Instant::now();
        for _ in 0..steps {
            world.step().expect("no blow-up");
            contacts += world.stats().contacts as u64;
            box_pairs += world.stats().box_pairs as u64;
        }
        let seconds = started.elapsed().as_secs_f64();
        let cpu_seconds = process_cpu_seconds().zip(cpu_before).map_or(f64::NAN, |(after, before)| after - before);
        let (heap_bytes, body_heap_bytes) = (world.heap_bytes(), world.bodies().heap_bytes());
        Measurement {
            particles,
            threads,
            steps,
            seconds,
            cpu_seconds,
            contacts,
            box_pairs,
            heap_bytes,
            body_heap_bytes,
        }
    })
}

/// The system's load average, as `/proc/loadavg` gives it.
pub fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg").map_or_else(|_| "unknown".into(), |s| s.trim().to_string())
}
