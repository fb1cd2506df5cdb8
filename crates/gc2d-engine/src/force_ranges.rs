//! The contact forces added to the bodies in parallel, one range of bodies per thread, each body's terms in pair
//! order (so the same sums, bit for bit, for any thread count: docs/model.md, "The forces are added by ranges of
//! bodies").
//!
//! The narrowphase marks, for each chunk of [`PAIRS_PER_CHUNK`] pairs, which of its touching pairs reach each range
//! ([`mark_touching_pair`]: one bit per pair and range); a range then reads exactly those pairs' records and no
//! other. A record read on another thread than the one that wrote it is a cache line passed between cores, which is
//! what limits more threads (docs/performance.md, "Two threads and the trip of a cache line"), so a range reads no
//! record it has no use for, not even to find out that it has none.

use crate::body_sums::BODIES_PER_CHUNK;
use crate::broadphase::PairEntry;
use crate::narrowphase::PairContact;
use crate::pair_sums::PAIRS_PER_CHUNK;
use glam::DVec2;

/// One bit per pair of a chunk: the chunk's pairs fit.
const _: () = assert!(PAIRS_PER_CHUNK <= u64::BITS as usize);

/// The bodies cut into ranges of equal length (the last one shorter), one per thread: the force accumulation's, and
/// the light passes' that go to each range's home thread ([`crate::home_threads`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct BodyRanges {
    /// Bodies per range.
    per_range: u32,
    /// ⌊2⁶⁴ / `per_range`⌋ + 1: a body's range is the high half of its id times this, exactly for every 32-bit id
    /// and range length from 2 (Lemire, Kaser and Kurz 2019, "Faster remainder by direct computation"), a
    /// multiplication instead of a division for each touching pair.
    reciprocal: u64,
    /// Ranges there can be: the threads. The last ones hold no body where the bodies fill fewer ranges.
    pub count: usize,
}

impl Default for BodyRanges {
    /// All bodies in one range.
    fn default() -> Self {
        Self::with_per_range(u32::MAX, 1)
    }
}

impl BodyRanges {
    /// `bodies` cut into `threads` ranges of whole chunks of the closing pass ([`BODIES_PER_CHUNK`]), so that each
    /// range can sum its own chunks after its correction; a World of fewer bodies than `BODIES_PER_CHUNK` times the
    /// threads leaves the last ranges empty.
    pub fn new(bodies: usize, threads: usize) -> Self {
        let per_range = bodies.div_ceil(threads).next_multiple_of(BODIES_PER_CHUNK).max(BODIES_PER_CHUNK);
        Self::with_per_range(u32::try_from(per_range).expect("body ids are u32"), threads)
    }

    /// `count` ranges of `per_range` bodies, at least 2.
    fn with_per_range(per_range: u32, count: usize) -> Self {
        debug_assert!(per_range >= 2, "⌊2⁶⁴ / 1⌋ + 1 overflows");
        Self { per_range, reciprocal: u64::MAX / u64::from(per_range) + 1, count }
    }

    /// Bodies per range.
    pub fn per_range(&self) -> usize {
        self.per_range as usize
    }

    /// The range that holds `body`.
    #[inline]
    fn of(&self, body: u32) -> usize {
        ((u128::from(self.reciprocal) * u128::from(body)) >> 64) as usize
    }
}

/// Marks the touching `pair`, at `position` in its chunk, in `masks` (the chunk's, one per range of `ranges`, zeroed
/// before its first pair): bit `position` of the masks of the ranges its two bodies lie in.
#[inline]
pub(crate) fn mark_touching_pair(
    masks: &mut [u64],
    ranges: &BodyRanges,
    position: usize,
    pair: &PairEntry<PairContact>,
) {
    masks[ranges.of(pair.a())] |= 1 << position;
    masks[ranges.of(pair.b())] |= 1 << position;
}

/// Sets `forces` and `torques`, the rows of the bodies of range `range`, to the sum of the contact forces and torques
/// the touching pairs exert on them, adding each body's terms in pair order: the same sums, bit for bit, as one pass
/// over the pairs in list order, whatever range a body falls in. `masks` are [`mark_touching_pair`]'s, chunk after
/// chunk.
pub(crate) fn add_contact_forces(
    pairs: &[PairEntry<PairContact>],
    masks: &[u64],
    ranges: &BodyRanges,
    range: usize,
    forces: &mut [DVec2],
    torques: &mut [f64],
) {
    forces.fill(DVec2::ZERO);
    torques.fill(0.0);
    let first = range * ranges.per_range();
    for (chunk, chunk_masks) in pairs.chunks(PAIRS_PER_CHUNK).zip(masks.chunks(ranges.count)) {
        let mut marked = chunk_masks[range];
        // Lowest bit first: the pairs in list order.
        while marked != 0 {
            add_pair_forces(&chunk[marked.trailing_zeros() as usize], first, forces, torques);
            marked &= marked - 1;
        }
    }
}

/// Adds the force and torques of the touching `pair` to those of its bodies that lie in the rows `forces` and
/// `torques` of bodies `first`, `first + 1`, ….
#[inline]
pub(crate) fn add_pair_forces(pair: &PairEntry<PairContact>, first: usize, forces: &mut [DVec2], torques: &mut [f64]) {
    let len = forces.len();
    // Below `first` the subtraction wraps to a huge index: one comparison tells whether the body is in the range.
    let local = |body: u32| Some((body as usize).wrapping_sub(first)).filter(|&i| i < len);
    let c = &pair.payload;
    if let Some(i) = local(pair.a()) {
        forces[i] += c.force_on_a;
        torques[i] += c.torque_on_a;
    }
    if let Some(j) = local(pair.b()) {
        forces[j] -= c.force_on_a;
        torques[j] += c.torque_on_b;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Adding each body's forces within ranges of bodies gives the same bits as one pass over the pairs in list
    /// order, for any split into ranges, whether the pairs are near neighbours in id order or far apart.
    #[test]
    fn forces_added_by_ranges_of_bodies_equal_one_pass_in_pair_order_bit_for_bit() {
        for near in [0.8, 0.98, 0.0] {
            forces_by_ranges_equal_one_pass(near);
        }
    }

    /// The test above on pairs that are near neighbours with probability `near`.
    fn forces_by_ranges_equal_one_pass(near: f64) {
        let bodies = 3000;
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut pairs: Vec<PairEntry<PairContact>> = (0..9000)
            .map(|k| {
                // Mostly near neighbours in id order, some far apart, like a pile numbered partly in space order.
                let a = (k / 3 + rng.random_range(0..40)).min(bodies - 2) as u32;
                let b = if rng.random_bool(near) {
                    a + rng.random_range(1..60).min(bodies as u32 - 1 - a)
                } else {
                    rng.random_range(a + 1..bodies as u32)
                };
                let contact = PairContact {
                    touching: rng.random_bool(0.7),
                    force_on_a: DVec2::new(rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)),
                    torque_on_a: rng.random_range(-1e-3..1e-3),
                    torque_on_b: rng.random_range(-1e-3..1e-3),
                    ..PairContact::default()
                };
                PairEntry::for_test(a, b, contact)
            })
            .collect();
        pairs.sort_by_key(|p| p.a());
        let mut expected_force = vec![DVec2::ZERO; bodies];
        let mut expected_torque = vec![0.0; bodies];
        // The single pass in list order, written out rather than through `add_pair_forces`, so that it checks it.
        for pair in pairs.iter().filter(|p| p.payload.touching) {
            let (a, b, c) = (pair.a() as usize, pair.b() as usize, &pair.payload);
            expected_force[a] += c.force_on_a;
            expected_force[b] -= c.force_on_a;
            expected_torque[a] += c.torque_on_a;
            expected_torque[b] += c.torque_on_b;
        }
        let by_threads = [1, 2, 7, 16].map(|threads| BodyRanges::new(bodies, threads));
        // Ranges shorter than a chunk of the closing pass, down to the reciprocal's least, as `new` makes none.
        let short =
            [(2, 1500), (3, 1000), (31, 97)].map(|(per_range, count)| BodyRanges::with_per_range(per_range, count));
        for ranges in by_threads.into_iter().chain(short) {
            let threads = ranges.count;
            let masks = marks(&pairs, &ranges);
            let mut force = vec![DVec2::splat(f64::NAN); bodies];
            let mut torque = vec![f64::NAN; bodies];
            let rows = force.chunks_mut(ranges.per_range()).zip(torque.chunks_mut(ranges.per_range()));
            for (range, (f, t)) in rows.enumerate() {
                add_contact_forces(&pairs, &masks, &ranges, range, f, t);
            }
            for i in 0..bodies {
                let what = format!("near {near}: {threads} ranges, body {i}");
                assert_eq!(force[i].x.to_bits(), expected_force[i].x.to_bits(), "{what}");
                assert_eq!(force[i].y.to_bits(), expected_force[i].y.to_bits(), "{what}");
                assert_eq!(torque[i].to_bits(), expected_torque[i].to_bits(), "{what}");
            }
        }
    }

    /// The masks of `pairs` for `ranges`, as the narrowphase marks them.
    fn marks(pairs: &[PairEntry<PairContact>], ranges: &BodyRanges) -> Vec<u64> {
        let mut masks = vec![u64::MAX; pairs.len().div_ceil(PAIRS_PER_CHUNK) * ranges.count];
        for (chunk, chunk_masks) in pairs.chunks(PAIRS_PER_CHUNK).zip(masks.chunks_mut(ranges.count)) {
            chunk_masks.fill(0);
            for (position, pair) in chunk.iter().enumerate().filter(|(_, pair)| pair.payload.touching) {
                mark_touching_pair(chunk_masks, ranges, position, pair);
            }
        }
        masks
    }

    /// The range of a body is its id divided by the range length, rounded down, for any 32-bit id and length of at
    /// least 2.
    #[test]
    fn the_range_of_a_body_is_the_quotient_of_its_id() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for per_range in [2, 3, 7, 11, 1000, 65_537, 1 << 31, u32::MAX - 1, u32::MAX] {
            let ranges = BodyRanges::with_per_range(per_range, 1);
            let edges = [0, 1, per_range - 1, per_range, per_range.saturating_add(1), u32::MAX - 1, u32::MAX];
            for body in edges.into_iter().chain((0..10_000).map(|_| rng.random::<u32>())) {
                assert_eq!(ranges.of(body), (body / per_range) as usize, "{body} / {per_range}");
            }
        }
    }

    /// The ranges start at whole chunks of the closing pass and share the bodies out to within a chunk.
    #[test]
    fn ranges_are_whole_chunks_of_the_closing_pass_and_nearly_equal() {
        for (bodies, threads) in [(512, 2), (804, 2), (10_003, 16), (12_803, 16), (100_000, 16), (40, 16), (1, 1)] {
            let ranges = BodyRanges::new(bodies, threads);
            let what = format!("{bodies} bodies on {threads} threads");
            assert_eq!(ranges.per_range() % BODIES_PER_CHUNK, 0, "{what}");
            assert!(ranges.per_range() * threads >= bodies, "{what}: every body in a range");
            assert!(ranges.per_range() < bodies.div_ceil(threads) + BODIES_PER_CHUNK, "{what}");
        }
    }

    /// A range's mask holds exactly the chunk's touching pairs with a body in the range.
    #[test]
    fn a_range_is_marked_for_exactly_the_touching_pairs_that_reach_it() {
        let touching = PairContact { touching: true, ..PairContact::default() };
        let chunk = [
            PairEntry::for_test(0, 5, touching),
            PairEntry::for_test(1, 25, PairContact::default()),
            PairEntry::for_test(12, 13, touching),
            PairEntry::for_test(3, 31, touching),
        ];
        let ranges = BodyRanges::with_per_range(11, 3);
        assert_eq!(marks(&chunk, &ranges), [0b1001, 0b0100, 0b1000]);
    }
}
