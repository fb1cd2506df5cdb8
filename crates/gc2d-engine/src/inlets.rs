//! Particle inlets (feedpipe.md §2.12): a segment of the boundary that feeds particles at a fixed rate, each at its
//! own random point along the segment, starting with a given velocity into the domain.
//!
//! Orientation: walking from `from` to `to`, the domain lies on the **left** (the inward normal is the segment's
//! direction turned 90° counter-clockwise), as along a boundary traced counter-clockwise. The k-th particle (k = 0,
//! 1, …) is due at `start + k/rate` exactly (no accumulated drift) and is inserted at the end of the step during which
//! it fell due: with Δt = 1 ms and 10 per second from t = 0, at steps 1, 101, 201, … (t = 0.001, 0.101, … s, as in
//! the thesis). An insertion that finds no free spot waits for the next step (counted as postponed); the particles
//! behind it keep their due times, so a backlog catches up as soon as the spot clears.

use crate::interactions::MaterialId;
use crate::shape::ParticleRecipe;
use gc2d_geometry::DVec2;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

/// ChaCha8 stream of the first inlet's positions and shapes; inlet i draws from stream `INLET_STREAM_BASE + i`, so
/// adding an inlet changes no other draw (the World's sources use stream 0, the scene build streams 1 and 2).
pub const INLET_STREAM_BASE: u64 = 1 << 32;

/// Relative slack of the due-step rule: a due time within this fraction of a step of a step boundary counts as on
/// the boundary, so that k/rate and n·Δt that are equal in exact arithmetic agree in f64.
const DUE_STEP_SLACK: f64 = 1e-9;

/// A particle inlet: a segment that feeds `rate` particles per second with start velocity `velocity`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Inlet {
    /// The name its counters go by (in time series and summaries).
    pub name: String,
    /// First end of the segment, m.
    pub from: DVec2,
    /// Second end of the segment, m; the domain is on the left walking from `from` to `to`.
    pub to: DVec2,
    /// Particles per second (the thesis's pps), s⁻¹.
    pub rate: f64,
    /// Time of the first particle, s; the k-th is due at `start + k/rate`.
    pub start: f64,
    /// No particle is due at or after this time, s (∞: the inlet never stops).
    pub stop: f64,
    /// Start velocity of every particle, m/s; its component along the inward normal must be positive.
    pub velocity: DVec2,
    /// Start angular velocity of every particle, rad/s (CCW).
    pub angular_velocity: f64,
    /// Shape of the fed particles.
    pub recipe: ParticleRecipe,
    /// Density of the fed particles (kg/m² or kg/m³ by the World's mass model).
    pub density: f64,
    /// Material of the fed particles.
    pub material: MaterialId,
}

impl Inlet {
    /// The unit inward normal (the segment's direction turned 90° CCW); zero for a zero-length segment.
    pub fn inward_normal(&self) -> DVec2 {
        (self.to - self.from).perp().normalize_or_zero()
    }

    /// The start velocity's component along the inward normal, m/s.
    pub fn normal_speed(&self) -> f64 {
        self.velocity.dot(self.inward_normal())
    }

    /// The nominal radius of the fed particles, m: a disk's radius, a polygon's larger semi-axis.
    pub fn nominal_radius(&self) -> f64 {
        match &self.recipe {
            ParticleRecipe::Disk(disk) => disk.radius,
            ParticleRecipe::Polygon(polygon) => polygon.semi_axes.x.max(polygon.semi_axes.y),
        }
    }

    /// The thesis's start-phase rule (feedpipe.md §2.12): true when a particle moves less than one nominal diameter
    /// before the next one appears, v_n < 2R·rate, so that consecutive particles may pile up at the inlet.
    pub fn may_pile_up(&self) -> bool {
        self.normal_speed() < 2.0 * self.nominal_radius() * self.rate
    }

    /// Due time of particle `k`, s.
    fn due_time(&self, k: u64) -> f64 {
        self.start.max(0.0) + k as f64 / self.rate
    }
}

/// What an inlet did since the start.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct InletCounters {
    /// Particles fed into the domain.
    pub injected: u64,
    /// Step-and-particle pairs on which a due particle found no free spot and waited for the next step.
    pub postponed: u64,
}

/// An inlet with its schedule, random stream and counters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InletState {
    inlet: Inlet,
    /// Index k of the next particle to insert.
    next: u64,
    rng: ChaCha8Rng,
    counters: InletCounters,
}

impl InletState {
    /// Inlet number `index` of a World seeded with `seed`, nothing inserted yet.
    pub(crate) fn new(inlet: Inlet, seed: u64, index: usize) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(INLET_STREAM_BASE + index as u64);
        Self { inlet, next: 0, rng, counters: InletCounters::default() }
    }

    /// The inlet.
    pub fn inlet(&self) -> &Inlet {
        &self.inlet
    }

    /// Its counters.
    pub fn counters(&self) -> InletCounters {
        self.counters
    }

    /// True when the next particle fell due at or before the end of step `step` (1-based: the step that ends at
    /// `step·dt`), i.e. its due time lies before the end of that step.
    pub(crate) fn next_is_due(&self, step: u64, dt: f64) -> bool {
        let due = self.inlet.due_time(self.next);
        due < self.inlet.stop && due / dt < step as f64 - DUE_STEP_SLACK
    }

    /// The inlet and its random stream, for drawing the next particle.
    pub(crate) fn parts(&mut self) -> (&Inlet, &mut ChaCha8Rng) {
        (&self.inlet, &mut self.rng)
    }

    /// Books the next particle as inserted.
    pub(crate) fn inserted(&mut self) {
        self.next += 1;
        self.counters.injected += 1;
    }

    /// Books the next particle as postponed to the next step.
    pub(crate) fn postponed(&mut self) {
        self.counters.postponed += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::DiskRecipe;
    use gc2d_geometry::Randomization;

    fn inlet(rate: f64) -> Inlet {
        Inlet {
            name: "feed".into(),
            from: DVec2::ZERO,
            to: DVec2::new(1.0, 0.0),
            rate,
            start: 0.0,
            stop: f64::INFINITY,
            velocity: DVec2::new(0.0, 1.0),
            angular_velocity: 0.0,
            recipe: ParticleRecipe::Disk(DiskRecipe {
                radius: 0.01,
                size_randomization: Randomization::Const,
                size_variation: 0.0,
            }),
            density: 1.0,
            material: MaterialId(0),
        }
    }

    #[test]
    fn ten_per_second_fall_due_on_steps_one_hundred_and_one_and_so_on() {
        let mut state = InletState::new(inlet(10.0), 0, 0);
        let mut due_steps = Vec::new();
        for step in 1..=1000 {
            while state.next_is_due(step, 1e-3) {
                state.inserted();
                due_steps.push(step);
            }
        }
        assert_eq!(due_steps, (0..10).map(|k| 1 + 100 * k).collect::<Vec<u64>>());
    }

    #[test]
    fn the_inward_normal_is_on_the_left_and_the_pile_up_rule_is_the_thesis_one() {
        let mut i = inlet(10.0);
        assert_eq!(i.inward_normal(), DVec2::new(0.0, 1.0));
        assert_eq!(i.normal_speed(), 1.0);
        assert!(!i.may_pile_up());
        i.velocity = DVec2::new(5.0, 0.19);
        assert!(i.may_pile_up(), "0.19 m/s < 2·0.01 m·10 /s");
        std::mem::swap(&mut i.from, &mut i.to);
        assert_eq!(i.inward_normal(), DVec2::new(0.0, -1.0));
    }
}
