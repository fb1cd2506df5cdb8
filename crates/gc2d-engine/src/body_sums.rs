//! The step's closing pass over the bodies: the ledger's kinetic and potential energies, the finiteness check and the
//! travel check, in parallel over fixed chunks of bodies.
//!
//! Each chunk of [`BODIES_PER_CHUNK`] bodies sums its own bodies in id order; the step then adds the chunks' sums in
//! chunk order. The grouping depends only on the number of bodies, never on the thread count, so the ledger stays
//! bitwise the same for any number of threads and across a checkpoint split.

use crate::bodies::{Bodies, BodyKind};
use crate::safety;

/// Bodies per chunk of the closing pass. Fixed, so that the energies are grouped the same way for any thread count.
/// 512, the fewest bodies a World steps in parallel ([`crate::parallel::PARALLEL_MIN_BODIES`]), so that every such World
/// gives the second thread a share: with 1,024 a World of fewer bodies summed them on the calling thread alone, and its
/// other thread, idle through the end of the step, had to be woken again in the next step's predictor (the 800 squares
/// and the 1,000-grain layer 3–4 % faster on two threads, docs/performance.md "The predictor and corrector of small
/// Worlds in two").
pub(crate) const BODIES_PER_CHUNK: usize = 512;

/// What one chunk of bodies adds to the step's sums.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct BodySums {
    /// Σ ½ m v² of the particles, J.
    pub translational: f64,
    /// Σ ½ I ω² of the particles, J.
    pub rotational: f64,
    /// Σ m g y of the particles, J.
    pub potential: f64,
    /// Some living body's pose or velocity is not finite.
    pub not_finite: bool,
    /// The first particle (by id) that moved further in the step than the travel limit allows.
    pub first_excessive_travel: Option<usize>,
}

/// The limits and fields the closing pass needs besides the bodies.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ClosingPass {
    /// |g| at the end of the step, m/s².
    pub gravity: f64,
    /// Δt, s.
    pub dt: f64,
    /// The largest travel in one step, as a fraction of the particle's inscribed radius.
    pub max_travel_fraction: f64,
}

impl ClosingPass {
    /// The sums of the bodies `first..first + BODIES_PER_CHUNK` (or to the last body), in id order.
    pub fn chunk(&self, b: &Bodies, first: usize) -> BodySums {
        let mut sums = BodySums::default();
        for i in first..(first + BODIES_PER_CHUNK).min(b.len()) {
            if !b.alive[i] {
                continue;
            }
            let (pose, velocity) = (&b.pose[i], b.velocity[i]);
            sums.not_finite |= !(pose.position.is_finite()
                & pose.angle.is_finite()
                & velocity.is_finite()
                & b.angular_velocity[i].is_finite());
            if b.kind[i] == BodyKind::Particle {
                sums.translational += 0.5 * b.mass[i] * velocity.length_squared();
                sums.rotational += 0.5 * b.angular_velocity[i].powi(2) / b.inverse_inertia[i];
                sums.potential += b.mass[i] * self.gravity * pose.position.y;
                if sums.first_excessive_travel.is_none()
                    && safety::step_travel(b, i, self.dt)
                        > self.max_travel_fraction * (b.inscribed_radius[i] * pose.scale)
                {
                    sums.first_excessive_travel = Some(i);
                }
            }
        }
        sums
    }
}

impl BodySums {
    /// Adds the sums of the next chunk.
    pub fn add(&mut self, chunk: &BodySums) {
        self.translational += chunk.translational;
        self.rotational += chunk.rotational;
        self.potential += chunk.potential;
        self.not_finite |= chunk.not_finite;
        self.first_excessive_travel = self.first_excessive_travel.or(chunk.first_excessive_travel);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_chunk_with_a_violation_names_the_body() {
        let mut whole = BodySums::default();
        let later = BodySums { first_excessive_travel: Some(5000), ..BodySums::default() };
        let earlier = BodySums { first_excessive_travel: Some(10), not_finite: true, ..BodySums::default() };
        whole.add(&BodySums { translational: 1.0, ..BodySums::default() });
        whole.add(&earlier);
        whole.add(&later);
        assert_eq!(whole.first_excessive_travel, Some(10));
        assert!(whole.not_finite);
        assert_eq!(whole.translational, 1.0);
    }
}
