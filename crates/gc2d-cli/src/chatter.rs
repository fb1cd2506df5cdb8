//! Watches the engine's force-alternation diagnostic during a run and warns once when the contact forces chatter
//! (alternate from step to step): the sign that Δt is too large for the contact damping (docs/model.md, "Automatic
//! Δt"; docs/validation.md, "Damping limit of flat contacts").
//!
//! A run split by a resume reports the unsplit run's windows but one: the window the resume falls in, which neither
//! process judges. The earlier process stopped before its end, and the resumed one cannot measure its first step (a
//! checkpoint holds the contact forces of one step, the diagnostic needs two: `World::force_alternation` is NaN on the
//! step after loading), so that window's sums could not be the unsplit run's even if its first part were carried
//! over. The largest window of a split run is therefore the unsplit run's, except where the unsplit run's largest is
//! that one window (docs/validation.md, "Chatter warning").

use gc2d_engine::{ForceAlternation, World};
use serde::Serialize;

/// Steps over which the diagnostic is summed: long enough that impacts (a step or two each) do not count, short
/// enough to catch chatter that lasts a few milliseconds. The windows are the run's steps (k − 1)·`WINDOW_STEPS` + 1
/// to k·`WINDOW_STEPS`, counted from step 0 whichever process takes them, so that a resumed run's windows are the
/// unsplit run's; a window is judged only when the process that closes it measured all of its steps, which the one a
/// resume falls in never is (module doc).
pub const WINDOW_STEPS: u64 = 1000;

/// Force alternation over a window (change over scale, each summed over the window's steps) above which the run is
/// warned about. Chattering runs measured 0.07–1, smooth ones below 0.01 (docs/validation.md, "Chatter warning").
pub const WARNING_THRESHOLD: f64 = 0.05;

/// Fewest steps of a window on which some contact counted (a pair with a force now and two steps ago) for the window
/// to be judged: chatter is sustained, so it counts on at least every other step of a window (a contact that lifts
/// off every other step counts on half of them), while a window that holds only a few steps of one brief contact,
/// such as a single bounce of dilute pellets, sees nothing but the curvature of its onset (0.03–0.05 per step of a
/// Hertz onset) and says nothing about chatter (docs/validation.md, "Chatter warning").
pub const MIN_CONTACT_STEPS: u64 = WINDOW_STEPS / 4;

/// The running window and what it has seen.
#[derive(Debug, Default)]
pub struct ChatterWatch {
    change: f64,
    scale: f64,
    /// Steps of the window this watch measured (a finite diagnostic).
    measured: u64,
    /// Steps of the window on which some contact counted.
    contact_steps: u64,
    largest: Option<AlternationWindow>,
    largest_is_new: bool,
    warned: bool,
}

/// The force alternation of one window of steps.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AlternationWindow {
    /// Σ change / Σ scale over the window's steps.
    pub alternation: f64,
    /// Simulated time at the end of the window, s.
    pub time_s: f64,
}

/// What `summary.json` reports about chatter.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ChatterSummary {
    /// The window with the largest force alternation among those judged (at least `min_contact_steps` steps with a
    /// counted contact), if one was run.
    pub largest_window: Option<AlternationWindow>,
    /// Steps per window.
    pub window_steps: u64,
    /// Fewest steps with a counted contact for a window to be judged.
    pub min_contact_steps: u64,
    /// The warning threshold.
    pub warning_threshold: f64,
    /// True when some window of the run (of this process or, for a resumed run, of the processes before it) exceeded
    /// the threshold.
    pub warned: bool,
}

impl ChatterWatch {
    /// A watch that continues a run whose earlier processes saw `earlier` as their largest window (up to the
    /// checkpoint the run resumes from): the summary then describes the whole run. The warning on stderr is still
    /// given by this process when one of its own windows exceeds the threshold.
    pub fn continuing(earlier: Option<AlternationWindow>) -> Self {
        Self { largest: earlier, ..Self::default() }
    }

    /// The run's largest window if it changed since the last call (a window closed with a larger alternation).
    pub fn new_largest(&mut self) -> Option<AlternationWindow> {
        std::mem::take(&mut self.largest_is_new).then_some(self.largest).flatten()
    }

    /// Takes the step the World has just taken; returns the warning the first time a window's alternation exceeds the
    /// threshold.
    pub fn observe(&mut self, world: &World) -> Option<String> {
        self.take_step(world.force_alternation(), world.steps(), world.time(), world.time_step())
    }

    /// [`observe`](Self::observe) with the step's diagnostic, the run's steps and the time at its end, and Δt given.
    fn take_step(&mut self, step: ForceAlternation, steps: u64, time: f64, time_step: f64) -> Option<String> {
        if step.change.is_finite() && step.scale.is_finite() {
            self.change += step.change;
            self.scale += step.scale;
            self.measured += 1;
            self.contact_steps += u64::from(step.scale > 0.0);
        }
        if steps % WINDOW_STEPS != 0 {
            return None;
        }
        // A window of which this watch missed a step (begun before a resume, or with the step after it) is not judged.
        let judged = self.measured == WINDOW_STEPS && self.contact_steps >= MIN_CONTACT_STEPS;
        let alternation = if self.scale > 0.0 { self.change / self.scale } else { 0.0 };
        let window = AlternationWindow { alternation, time_s: time };
        (self.change, self.scale, self.measured, self.contact_steps) = (0.0, 0.0, 0, 0);
        if !judged {
            return None;
        }
        if self.largest.is_none_or(|largest| window.alternation > largest.alternation) {
            self.largest = Some(window);
            self.largest_is_new = true;
        }
        if self.warned || window.alternation <= WARNING_THRESHOLD {
            return None;
        }
        self.warned = true;
        Some(format!(
            "warning: at t = {:.6} s the contact forces alternate by {:.0} % from step to step (over the last \
             {WINDOW_STEPS} steps). This is period-2 chatter: Δt = {:.3e} s is too large for the contact damping, and \
             forces, stresses and pressures sampled on a single step are off by about that much. Set a smaller \
             run.time_step_s (flat or elongated grains and strong damping need less than the automatic 0.15 of the \
             stable bound); see docs/model.md, \"Automatic Δt\".",
            time,
            100.0 * window.alternation,
            time_step
        ))
    }

    /// The summary of the run so far.
    pub fn summary(&self) -> ChatterSummary {
        ChatterSummary {
            largest_window: self.largest,
            window_steps: WINDOW_STEPS,
            min_contact_steps: MIN_CONTACT_STEPS,
            warning_threshold: WARNING_THRESHOLD,
            warned: self.largest.is_some_and(|largest| largest.alternation > WARNING_THRESHOLD),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Feeds `steps` steps of the diagnostic `step(k)` (k counts from 0) at Δt = 1 µs; returns the warnings.
    fn watch(watch: &mut ChatterWatch, steps: u64, step: impl Fn(u64) -> ForceAlternation) -> Vec<String> {
        watch_from(watch, 0, steps, step)
    }

    /// Feeds the run's steps `from + 1` to `to` of the diagnostic `step(k)` (k the step's number less one) at
    /// Δt = 1 µs, as a watch of a run resumed at step `from` does; returns the warnings.
    fn watch_from(watch: &mut ChatterWatch, from: u64, to: u64, step: impl Fn(u64) -> ForceAlternation) -> Vec<String> {
        (from..to).filter_map(|k| watch.take_step(step(k), k + 1, 1e-6 * (k + 1) as f64, 1e-6)).collect()
    }

    /// QA R8: the windows were counted from the step a resumed run started at, so that where a run was split changed
    /// its largest window. They are the run's steps k·1000 + 1 to (k + 1)·1000 now: a run resumed mid-window skips the
    /// rest of that window (whose step after the resume is not measured) and then judges the unsplit run's windows.
    #[test]
    fn a_resumed_watch_judges_the_unsplit_runs_windows_but_the_one_it_resumed_in() {
        // Smooth contacts whose alternation grows from window to window, so that every window has its own value.
        let step = |k: u64| ForceAlternation { change: 1e-6 * (k / 7) as f64, scale: 1.0 };
        let mut whole = ChatterWatch::default();
        watch(&mut whole, 5 * WINDOW_STEPS, step);
        let mut first = ChatterWatch::default();
        watch(&mut first, 2500, step);
        let earlier = first.summary().largest_window;
        assert_eq!(earlier.map(|window| window.time_s), Some(1e-6 * 2000.0), "the largest of steps 1–2000");
        let mut resumed = ChatterWatch::continuing(earlier);
        // The step after loading the checkpoint has no force history.
        let after_loading = |k: u64| if k == 2500 { ForceAlternation::not_measured() } else { step(k) };
        watch_from(&mut resumed, 2500, 5 * WINDOW_STEPS, after_loading);
        assert_eq!(resumed.summary(), whole.summary());
        // The window a resume falls in is judged by neither part: resumed at step 2500, the split run lacks the window
        // of steps 2001–3000; had that one been the largest, the split run would report the next largest.
        let mut resumed = ChatterWatch::continuing(earlier);
        watch_from(&mut resumed, 2500, 3 * WINDOW_STEPS, after_loading);
        assert_eq!(resumed.summary(), first.summary());
        // Resumed on a window's boundary, the next window lacks its first step.
        let mut resumed = ChatterWatch::continuing(earlier);
        watch_from(&mut resumed, 2000, 3 * WINDOW_STEPS, |k| {
            if k == 2000 { ForceAlternation::not_measured() } else { step(k) }
        });
        assert_eq!(resumed.summary().largest_window, earlier);
    }

    #[test]
    fn chatter_that_lifts_off_every_other_step_is_warned_about() {
        // A plate chattering F, 0, F, …: its pair counts on the steps with a force, at ratio 1.
        let mut w = ChatterWatch::default();
        let chatter = |k: u64| ForceAlternation {
            change: if k % 2 == 0 { 2.0 } else { 0.0 },
            scale: if k % 2 == 0 { 2.0 } else { 0.0 },
        };
        let warnings = watch(&mut w, WINDOW_STEPS, chatter);
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert!(warnings[0].contains("alternate by 100 %"), "{}", warnings[0]);
        assert!(w.summary().warned);
    }

    #[test]
    fn a_window_with_a_brief_contact_only_is_not_judged() {
        // Dilute pellets: one pair touching for the last 10 steps of the window, its Hertz onset alone at 0.05.
        let mut w = ChatterWatch::default();
        let onset = |k: u64| {
            let touching = k % WINDOW_STEPS >= WINDOW_STEPS - 10;
            ForceAlternation { change: if touching { 0.05 } else { 0.0 }, scale: if touching { 1.0 } else { 0.0 } }
        };
        assert!(watch(&mut w, 3 * WINDOW_STEPS, onset).is_empty());
        let summary = w.summary();
        assert_eq!((summary.largest_window, summary.warned), (None, false));
        // The same onset in a window whose other steps carry resting contacts is judged, and is smooth.
        let resting =
            |k: u64| if k >= WINDOW_STEPS - 10 { onset(k) } else { ForceAlternation { change: 1e-6, scale: 1.0 } };
        let mut w = ChatterWatch::default();
        assert!(watch(&mut w, WINDOW_STEPS, resting).is_empty());
        assert!(w.summary().largest_window.is_some_and(|window| window.alternation < 1e-3));
    }
}
