//! The time window `[t1, t2]` of gc2d's time laws and its clamp (reference (B.1) and (B.3)).

use serde::{Deserialize, Serialize};

/// A closed time interval `[start, end]` in seconds during which a time law is active.
///
/// gc2d evaluates its time laws (vibration, heating, gravity ramps, drag springs) at the time clamped to the window,
/// so the law stands still before `start` and freezes after `end` (eqs. B.1, B.3). Either end may be infinite
/// (gc2d's `∞` defaults). Nothing here panics or returns NaN for a reversed or non-finite window: a window with
/// `start > end` clamps every time to `end` and is never active.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TimeWindow {
    /// t1, s.
    pub start: f64,
    /// t2, s.
    pub end: f64,
}

impl TimeWindow {
    /// The window `[start, end]`.
    pub const fn new(start: f64, end: f64) -> Self {
        Self { start, end }
    }

    /// The time clamped into the window, eqs. (B.1)/(B.3): `start` before it, `end` after it, `t` inside.
    #[inline]
    pub fn clamp(&self, t: f64) -> f64 {
        t.max(self.start).min(self.end)
    }

    /// True while the law is moving, `start ≤ t < end`. Rates (velocities, ds/dt) are zero outside, including at
    /// `t = end`, from which on the law stands still.
    #[inline]
    pub fn is_active(&self, t: f64) -> bool {
        self.start <= t && t < self.end
    }

    /// Time spent inside the window up to `t`: `clamp(t) − start`, never negative. A non-finite result (an
    /// unbounded `start`) counts as zero, so laws that accumulate (rotation angle, drag distance) stand still.
    #[inline]
    pub fn elapsed(&self, t: f64) -> f64 {
        let elapsed = self.clamp(t) - self.start;
        if elapsed.is_finite() { elapsed.max(0.0) } else { 0.0 }
    }

    /// Fraction of the window that has passed at `t`, in `[0, 1]`: 0 up to `start`, 1 from `end` on. A window of
    /// zero or negative length jumps from 0 to 1 at `start`; an unbounded window never progresses.
    #[inline]
    pub fn progress(&self, t: f64) -> f64 {
        if t >= self.end {
            1.0
        } else if t > self.start {
            let fraction = (t - self.start) / (self.end - self.start);
            if fraction.is_finite() { fraction.clamp(0.0, 1.0) } else { 0.0 }
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamp_follows_b1() {
        let window = TimeWindow::new(1.0, 3.0);
        assert_eq!(window.clamp(0.5), 1.0);
        assert_eq!(window.clamp(2.25), 2.25);
        assert_eq!(window.clamp(7.0), 3.0);
        assert_eq!(window.elapsed(0.5), 0.0);
        assert_eq!(window.elapsed(2.25), 1.25);
        assert_eq!(window.elapsed(7.0), 2.0);
        assert_eq!(window.progress(2.5), 0.75);
        assert!(window.is_active(1.0) && window.is_active(2.999) && !window.is_active(3.0) && !window.is_active(0.9));
    }

    #[test]
    fn degenerate_windows_give_finite_answers() {
        let reversed = TimeWindow::new(3.0, 1.0);
        assert_eq!(reversed.clamp(2.0), 1.0);
        assert!(!reversed.is_active(2.0));
        assert_eq!(reversed.elapsed(5.0), 0.0);
        assert_eq!((reversed.progress(0.5), reversed.progress(2.0)), (0.0, 1.0));
        let never = TimeWindow::new(f64::INFINITY, f64::INFINITY);
        assert_eq!(never.elapsed(10.0), 0.0);
        assert_eq!(never.progress(10.0), 0.0);
        let unbounded_start = TimeWindow::new(f64::NEG_INFINITY, 1.0);
        assert_eq!(unbounded_start.elapsed(0.0), 0.0);
        assert_eq!(unbounded_start.progress(0.0), 0.0);
        assert_eq!(TimeWindow::new(0.0, f64::INFINITY).progress(1e9), 0.0);
        let instant = TimeWindow::new(2.0, 2.0);
        assert_eq!((instant.progress(1.9), instant.progress(2.0)), (0.0, 1.0));
        assert_eq!(TimeWindow::new(0.0, 1.0).progress(f64::NAN), 0.0);
    }
}
