//! Wall-clock time per stage of [`World::step`](crate::World::step), for finding what limits a run on many threads
//! (`gc2d-rs bench --stages`, docs/performance.md). Off unless asked for: a World without it pays one branch per
//! stage.

use std::time::{Duration, Instant};

/// The stages of a step, in the order the step runs them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// Integrator's predictor and the moving walls' prescribed poses (parallel over the bodies).
    Predict,
    /// World vertices and bounding boxes of every body (parallel over the bodies). On several threads, without
    /// moving walls or heating, each range of bodies is also predicted in the same pass, so this stage then holds the
    /// time of the predictor too.
    Vertices,
    /// Sort-and-sweep update of the pair list and the ended pairs' booking (sequential).
    Broadphase,
    /// Overlap, contact law and the chunks' sums for every pair (parallel over chunks of pairs); on one thread also
    /// the contact forces added to the bodies.
    Narrowphase,
    /// Contact forces added to the bodies in pair order (parallel over ranges of bodies; on one thread in the
    /// narrowphase instead), the chunks' sums booked, contact events (sequential). On several threads, where gravity
    /// is the only body force and no events are written, each range also adds its weights and is corrected in the
    /// same pass (and sums its chunks of the closing pass), so this stage then holds the time of the two next ones too.
    Accumulation,
    /// Gravity, drag springs and fluid drag.
    BodyForces,
    /// Integrator's corrector (parallel over the bodies); where no particle is removed or added after it, each range
    /// of bodies also sums its chunks of the closing pass here.
    Correct,
    /// Pistons, gravity changes, outlets, the domain, sources and inlets.
    Boundaries,
    /// The ledger's kinetic and potential energies (summed here where the corrector's pass did not sum them), the
    /// finiteness, overlap, travel and energy checks.
    LedgerAndChecks,
}

impl Stage {
    /// Every stage, in step order.
    pub const ALL: [Stage; 9] = [
        Stage::Predict,
        Stage::Vertices,
        Stage::Broadphase,
        Stage::Narrowphase,
        Stage::Accumulation,
        Stage::BodyForces,
        Stage::Correct,
        Stage::Boundaries,
        Stage::LedgerAndChecks,
    ];

    /// Short name, for table heads and CSV columns.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Predict => "predict",
            Stage::Vertices => "vertices",
            Stage::Broadphase => "broadphase",
            Stage::Narrowphase => "narrowphase",
            Stage::Accumulation => "accumulation",
            Stage::BodyForces => "body_forces",
            Stage::Correct => "correct",
            Stage::Boundaries => "boundaries",
            Stage::LedgerAndChecks => "ledger_checks",
        }
    }
}

/// Wall-clock time spent in each stage over the steps since the clock was started or reset.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StageTimes {
    /// Time per stage, indexed like [`Stage::ALL`].
    spent: [Duration; Stage::ALL.len()],
    /// Steps measured.
    pub steps: u64,
}

impl StageTimes {
    /// Time spent in `stage`, s.
    pub fn seconds(&self, stage: Stage) -> f64 {
        self.spent[stage as usize].as_secs_f64()
    }

    /// Time spent in all stages together, s.
    pub fn total_seconds(&self) -> f64 {
        self.spent.iter().sum::<Duration>().as_secs_f64()
    }
}

/// The running clock a World keeps while stage timing is on.
#[derive(Debug, Clone)]
pub(crate) struct StageClock {
    times: StageTimes,
    lap_started: Instant,
}

impl StageClock {
    /// A clock with nothing measured yet.
    pub(crate) fn new() -> Self {
        Self { times: StageTimes::default(), lap_started: Instant::now() }
    }

    /// Starts timing a step's first stage.
    pub(crate) fn start_step(&mut self) {
        self.lap_started = Instant::now();
    }

    /// Books the time since the previous lap (or the step's start) to `stage`.
    pub(crate) fn lap(&mut self, stage: Stage) {
        let now = Instant::now();
        self.times.spent[stage as usize] += now - self.lap_started;
        self.lap_started = now;
    }

    /// Counts a finished step.
    pub(crate) fn end_step(&mut self) {
        self.times.steps += 1;
    }

    /// What has been measured.
    pub(crate) fn into_times(self) -> StageTimes {
        self.times
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn laps_are_booked_to_their_stage_and_add_up() {
        let mut clock = StageClock::new();
        clock.start_step();
        std::thread::sleep(Duration::from_millis(2));
        clock.lap(Stage::Narrowphase);
        clock.lap(Stage::Correct);
        clock.end_step();
        let times = clock.into_times();
        assert_eq!(times.steps, 1);
        assert!(times.seconds(Stage::Narrowphase) >= 0.002);
        assert!(times.seconds(Stage::Correct) < times.seconds(Stage::Narrowphase));
        assert_eq!(times.seconds(Stage::Predict), 0.0);
        let sum: f64 = Stage::ALL.iter().map(|&s| times.seconds(s)).sum();
        assert!((times.total_seconds() - sum).abs() < 1e-9);
    }

    #[test]
    fn stages_index_their_own_slot() {
        for (i, stage) in Stage::ALL.iter().enumerate() {
            assert_eq!(*stage as usize, i);
        }
    }

    #[test]
    fn stage_names_are_distinct() {
        let mut names: Vec<&str> = Stage::ALL.iter().map(|s| s.name()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), Stage::ALL.len());
    }
}
