//! The step's closing pass over the bodies: the ledger's kinetic and potential energies, the finiteness check and the
//! travel check, summed over fixed chunks of bodies.
//!
//! Each chunk of [`BODIES_PER_CHUNK`] bodies sums its own bodies in id order; the step then adds the chunks' sums in
//! chunk order. The grouping depends only on the number of bodies, never on the thread count, so the ledger stays
//! bitwise the same for any number of threads and across a checkpoint split. The chunks are summed in a pass of their
//! own (in parallel) or, where nothing changes the bodies after the corrector, by each range of bodies right after
//! its correction (the ranges start at whole chunks, [`crate::force_ranges::BodyRanges`]).

use crate::bodies::{Bodies, BodyKind, KinematicsColumns};
use crate::safety;
use gc2d_geometry::{DVec2, Pose};

/// Bodies per chunk of the closing pass. Fixed, so that the energies are grouped the same way for any thread count.
/// 32, so that the ranges of bodies, which start at whole chunks so that each range can sum its own chunks after its
/// correction, are no more than 31 bodies longer than an equal share: with 512 the 10,000-grain piles made ranges of
/// 1,024 bodies on 16 threads and left six threads without one. A chunk's sums take 48 bytes: 1.5 bytes a body.
pub(crate) const BODIES_PER_CHUNK: usize = 32;

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

/// The columns the closing pass reads, one slice each over the same bodies.
#[derive(Clone, Copy)]
pub(crate) struct ClosingColumns<'a> {
    pub pose: &'a [Pose],
    pub velocity: &'a [DVec2],
    pub angular_velocity: &'a [f64],
    pub kind: &'a [BodyKind],
    pub alive: &'a [bool],
    pub reach: &'a [f64],
    pub mass: &'a [f64],
    pub inverse_inertia: &'a [f64],
    pub inscribed_radius: &'a [f64],
}

impl<'a> ClosingColumns<'a> {
    /// The columns of all of `bodies`.
    pub fn of_bodies(b: &'a Bodies) -> Self {
        Self {
            pose: &b.pose,
            velocity: &b.velocity,
            angular_velocity: &b.angular_velocity,
            kind: &b.kind,
            alive: &b.alive,
            reach: &b.reach,
            mass: &b.mass,
            inverse_inertia: &b.inverse_inertia,
            inscribed_radius: &b.inscribed_radius,
        }
    }

    /// The columns of the bodies of `rows` (which start at body `first`), their masses, inertias and inscribed radii
    /// taken from the columns `mass`, `inverse_inertia` and `inscribed_radius` over all bodies.
    pub fn of_rows(
        rows: &'a KinematicsColumns<'_>,
        first: usize,
        mass: &'a [f64],
        inverse_inertia: &'a [f64],
        inscribed_radius: &'a [f64],
    ) -> Self {
        let bodies = first..first + rows.len();
        Self {
            pose: &*rows.pose,
            velocity: &*rows.velocity,
            angular_velocity: &*rows.angular_velocity,
            kind: rows.kind,
            alive: rows.alive,
            reach: rows.reach,
            mass: &mass[bodies.clone()],
            inverse_inertia: &inverse_inertia[bodies.clone()],
            inscribed_radius: &inscribed_radius[bodies],
        }
    }
}

impl ClosingPass {
    /// Fills `sums` with the sums of the chunks of `columns`, whose bodies start at body `first` (the first body of a
    /// chunk): `sums[k]` those of its bodies `k * BODIES_PER_CHUNK..`, in id order.
    pub fn sum_chunks(&self, columns: &ClosingColumns, first: usize, sums: &mut [BodySums]) {
        debug_assert_eq!(first % BODIES_PER_CHUNK, 0, "chunks start at multiples of BODIES_PER_CHUNK");
        debug_assert_eq!(sums.len(), columns.pose.len().div_ceil(BODIES_PER_CHUNK));
        for (k, chunk_sums) in sums.iter_mut().enumerate() {
            *chunk_sums = self.chunk(columns, k * BODIES_PER_CHUNK, first);
        }
    }

    /// The sums of the bodies `start..start + BODIES_PER_CHUNK` of `columns` (or to its last body), in id order;
    /// `first` is the id of the first body of `columns`.
    pub fn chunk(&self, c: &ClosingColumns, start: usize, first: usize) -> BodySums {
        let mut sums = BodySums::default();
        for i in start..(start + BODIES_PER_CHUNK).min(c.pose.len()) {
            if !c.alive[i] {
                continue;
            }
            let (pose, velocity, angular_velocity) = (&c.pose[i], c.velocity[i], c.angular_velocity[i]);
            sums.not_finite |= !(pose.position.is_finite()
                & pose.angle.is_finite()
                & velocity.is_finite()
                & angular_velocity.is_finite());
            if c.kind[i] == BodyKind::Particle {
                sums.translational += 0.5 * c.mass[i] * velocity.length_squared();
                sums.rotational += 0.5 * angular_velocity.powi(2) / c.inverse_inertia[i];
                sums.potential += c.mass[i] * self.gravity * pose.position.y;
                if sums.first_excessive_travel.is_none()
                    && safety::travel_in_step(velocity, angular_velocity, c.reach[i] * pose.scale, self.dt)
                        > self.max_travel_fraction * (c.inscribed_radius[i] * pose.scale)
                {
                    sums.first_excessive_travel = Some(first + i);
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
