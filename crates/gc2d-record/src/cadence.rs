//! When a frame is due: frames sample simulated time at a fixed rate, never every step.

use crate::RecordError;

/// Decides which steps produce a frame. Frame k belongs to the tick t_k = k / rate (k = 0, 1, …) and is taken at the
/// first observed time that reaches t_k. A tick counts as reached half a time step early, so round-off in the
/// summed simulated time (t = n·Δt) never pushes a frame to the step after its tick. When one step jumps over several
/// ticks, one frame is taken and the skipped ticks are dropped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cadence {
    rate: f64,
    next_tick: u64,
}

impl Cadence {
    /// Frames per simulated second unless the caller chooses otherwise: smooth playback in Foxglove at real speed
    /// for the usual runs of seconds to minutes.
    pub const DEFAULT_FRAMES_PER_SECOND: f64 = 30.0;

    /// A cadence of `frames_per_second` frames per simulated second, starting with the tick at t = 0.
    pub fn new(frames_per_second: f64) -> Result<Self, RecordError> {
        if !(frames_per_second > 0.0 && frames_per_second.is_finite()) {
            return Err(RecordError::InvalidOption(format!(
                "frames per simulated second must be a positive number, got {frames_per_second}"
            )));
        }
        Ok(Self { rate: frames_per_second, next_tick: 0 })
    }

    /// Frames per simulated second.
    pub fn frames_per_second(&self) -> f64 {
        self.rate
    }

    /// The index of the next tick.
    pub fn next_tick(&self) -> u64 {
        self.next_tick
    }

    /// Simulated time of tick `tick`, s.
    pub fn tick_time(&self, tick: u64) -> f64 {
        tick as f64 / self.rate
    }

    /// True when a World at `time`, stepping by `time_step`, has reached the next tick.
    pub fn is_due(&self, time: f64, time_step: f64) -> bool {
        time >= self.tick_time(self.next_tick) - 0.5 * time_step.max(0.0)
    }

    /// Records that a frame was taken at `time`: the next tick is the first one after `time` (plus half a step).
    pub fn mark_taken(&mut self, time: f64, time_step: f64) {
        let reached = ((time + 0.5 * time_step.max(0.0)) * self.rate).floor();
        let reached = if reached.is_finite() && reached >= 0.0 { reached as u64 } else { self.next_tick };
        self.next_tick = reached.max(self.next_tick) + 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Steps a clock by `dt` from 0 to `t_end` and returns the step indices that took a frame.
    fn frame_steps(rate: f64, dt: f64, t_end: f64) -> Vec<u64> {
        let mut cadence = Cadence::new(rate).unwrap();
        let mut frames = Vec::new();
        let mut step = 0u64;
        loop {
            let t = step as f64 * dt;
            if t > t_end + 0.5 * dt {
                break;
            }
            if cadence.is_due(t, dt) {
                cadence.mark_taken(t, dt);
                frames.push(step);
            }
            step += 1;
        }
        frames
    }

    #[test]
    fn one_frame_per_tick_at_the_first_step_reaching_it() {
        // 30 frames/s with Δt = 1e-4 s: ticks at k/30 s; tick k falls on step round(k/30/1e-4) or the one after.
        let steps = frame_steps(30.0, 1e-4, 1.0);
        assert_eq!(steps.len(), 31, "ticks 0, 1/30, …, 30/30");
        for (k, &s) in steps.iter().enumerate() {
            let tick = k as f64 / 30.0;
            let t = s as f64 * 1e-4;
            assert!(t >= tick - 0.5e-4 && t < tick + 0.5e-4, "frame {k} at t = {t}, tick {tick}");
        }
    }

    #[test]
    fn ticks_on_exact_step_times_are_not_lost_to_round_off() {
        // 1/10 s is a whole number of steps of 1e-3 s, but 100 · 1e-3 summed in floating point is not exactly 0.1.
        let steps = frame_steps(10.0, 1e-3, 1.0);
        assert_eq!(steps, (0..=10).map(|k| k * 100).collect::<Vec<_>>());
    }

    #[test]
    fn steps_longer_than_the_interval_take_one_frame_each_and_drop_skipped_ticks() {
        // Δt = 0.1 s at 30 frames/s: every step passes 3 ticks; each step takes exactly one frame.
        let steps = frame_steps(30.0, 0.1, 1.0);
        assert_eq!(steps, (0..=10).collect::<Vec<_>>());
    }

    #[test]
    fn refuses_rates_that_are_not_positive_numbers() {
        for rate in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(Cadence::new(rate).is_err(), "{rate}");
        }
    }
}
