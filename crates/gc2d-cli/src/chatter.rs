//! Watches the engine's force-alternation diagnostic during a run and warns once when the contact forces chatter
//! (alternate from step to step): the sign that Δt is too large for the contact damping (docs/model.md, "Automatic
//! Δt"; docs/validation.md, "Damping limit of flat contacts").

use gc2d_engine::World;
use serde::Serialize;

/// Steps over which the diagnostic is summed: long enough that impacts (a step or two each) do not count, short
/// enough to catch chatter that lasts a few milliseconds.
pub const WINDOW_STEPS: u64 = 1000;

/// Force alternation over a window (change over scale, each summed over the window's steps) above which the run is
/// warned about. Chattering runs measured 0.07–1, smooth ones below 0.01 (docs/validation.md, "Chatter warning").
pub const WARNING_THRESHOLD: f64 = 0.05;

/// The running window and what it has seen.
#[derive(Debug, Default)]
pub struct ChatterWatch {
    change: f64,
    scale: f64,
    steps: u64,
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
    /// The window with the largest force alternation, if a whole window was run.
    pub largest_window: Option<AlternationWindow>,
    /// Steps per window.
    pub window_steps: u64,
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

    /// Takes this step's parts; returns the warning the first time a window's alternation exceeds the threshold.
    pub fn observe(&mut self, world: &World) -> Option<String> {
        let step = world.force_alternation();
        if !(step.change.is_finite() && step.scale.is_finite()) {
            return None;
        }
        self.change += step.change;
        self.scale += step.scale;
        self.steps += 1;
        if self.steps < WINDOW_STEPS {
            return None;
        }
        let alternation = if self.scale > 0.0 { self.change / self.scale } else { 0.0 };
        let window = AlternationWindow { alternation, time_s: world.time() };
        (self.change, self.scale, self.steps) = (0.0, 0.0, 0);
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
            world.time(),
            100.0 * window.alternation,
            world.time_step()
        ))
    }

    /// The summary of the run so far.
    pub fn summary(&self) -> ChatterSummary {
        ChatterSummary {
            largest_window: self.largest,
            window_steps: WINDOW_STEPS,
            warning_threshold: WARNING_THRESHOLD,
            warned: self.largest.is_some_and(|largest| largest.alternation > WARNING_THRESHOLD),
        }
    }
}
