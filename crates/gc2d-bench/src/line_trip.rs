//! How long a cache line takes to travel from one thread to another and back, measured beside each many-thread
//! timing. On more than one thread every step hands cache lines between cores (a pair's bodies written by one thread
//! and read by another, the pair records the force accumulation reads), so what this trip costs bounds how far a pile
//! can scale. It is a property of where the cores sit: on the 2-vCPU development VM it is about 66 ns at some moments
//! and 300–470 ns at others (most likely as the host moves the vCPUs), and the 1,000-grain layer on two threads takes
//! 157–173 or 324–368 ns per particle-step with it (docs/performance.md, "Two threads and the trip of a cache line").

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// How long round trips run before the samples: a new thread often starts on its parent's core, where each trip
/// waits for the scheduler, until the system moves it to an idle one.
const WARM_UP: Duration = Duration::from_millis(10);

/// Round trips in one sample.
const TRIPS_PER_SAMPLE: u64 = 2_000;

/// Samples of which the median is reported: a single sample can catch the other thread descheduled.
const SAMPLES: usize = 5;

/// A sample stops after this long even if its trips are not done (on one core the other thread runs only when the
/// scheduler switches, milliseconds a trip), so that the measurement never holds up a benchmark for long.
const SAMPLE_TIME_LIMIT: Duration = Duration::from_millis(20);

/// Spins of a trip's wait beyond which the clock is read after it: far more than a trip between two cores takes
/// (tens of spins), far fewer than a scheduler's time slice.
const LONG_WAIT_SPINS: u32 = 10_000;

/// The value that tells the answering thread to stop; the trips count up from 1 and never reach it.
const STOP: u64 = u64::MAX;

/// The median time, ns, of a cache line's round trip between the calling thread and one other thread: the calling
/// thread writes an odd number to a shared atomic, the other answers with the next even one, and so on. The two
/// threads are not pinned, so the operating system picks the cores, as it does for a benchmark's thread pool. Takes
/// about 11 ms on two idle cores, and about a tenth of a second where the two threads must share a core (each trip
/// then waits for the scheduler, and the result says so: milliseconds).
pub fn cache_line_round_trip_ns() -> f64 {
    // Its own cache line, so that nothing else the threads touch travels with it.
    #[repr(align(128))]
    struct Line(AtomicU64);
    let line = Line(AtomicU64::new(0));
    let shared = &line.0;
    std::thread::scope(|scope| {
        scope.spawn(|| answer(shared));
        let mut trips = Trips { shared, sent: 1 };
        trips.run(u64::MAX, WARM_UP);
        let mut samples: Vec<f64> = (0..SAMPLES).map(|_| trips.run(TRIPS_PER_SAMPLE, SAMPLE_TIME_LIMIT)).collect();
        shared.store(STOP, Ordering::Release);
        samples.sort_by(f64::total_cmp);
        samples[SAMPLES / 2]
    })
}

/// The answering thread: turns each odd value it sees into the next even one, until [`STOP`].
fn answer(shared: &AtomicU64) {
    loop {
        let value = shared.load(Ordering::Acquire);
        if value == STOP {
            return;
        }
        if value % 2 == 1 {
            shared.store(value + 1, Ordering::Release);
        } else {
            std::hint::spin_loop();
        }
    }
}

/// The calling thread's side: the odd value it sends next.
struct Trips<'a> {
    shared: &'a AtomicU64,
    sent: u64,
}

impl Trips<'_> {
    /// Up to `count` round trips, stopping after `limit`; returns the mean time of one, ns. The clock is read every
    /// 16 trips, and after any trip that waited long (where the two threads share a core, each trip waits for the
    /// scheduler), so that reading it adds little to a normal trip and the limit holds on a shared core.
    fn run(&mut self, count: u64, limit: Duration) -> f64 {
        let started = Instant::now();
        let mut done = 0;
        let mut waited_long = false;
        while done < count && ((done % 16 != 0 && !waited_long) || started.elapsed() < limit) {
            self.shared.store(self.sent, Ordering::Release);
            let mut spins = 0u32;
            while self.shared.load(Ordering::Acquire) != self.sent + 1 {
                std::hint::spin_loop();
                spins = spins.saturating_add(1);
            }
            waited_long = spins > LONG_WAIT_SPINS;
            self.sent += 2;
            done += 1;
        }
        started.elapsed().as_nanos() as f64 / done.max(1) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_round_trip_takes_a_positive_finite_time() {
        let trip = cache_line_round_trip_ns();
        assert!(trip.is_finite() && trip > 0.0, "{trip} ns");
    }
}
