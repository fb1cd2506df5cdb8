//! Passes over the bodies in which each range of bodies ([`BodyRanges`]) has a home thread of the pool and goes to
//! it in every pass of every step, so that a body's rows stay in the caches of one core from the predictor through the
//! vertex transform and the force accumulation to the corrector.
//!
//! Handed out by rayon's splitting, the rows of a pass landed on whichever thread stole them, a different one in each
//! pass, so nearly every row of the light passes came from another core's cache; on 16 threads the predictor and the
//! corrector took four to five times a sixteenth of their one-thread time (docs/performance.md, "Sixteen cores: each
//! range of bodies on its own thread"). Rayon has no way to send a task to a given thread without allocating
//! (`rayon::broadcast` allocates its jobs on each call; the step allocates nothing), so the pass hands out one task per
//! range as usual, and each task takes the range of the thread it runs on where that one is still free, else the next
//! free one. Each range is taken exactly once whichever thread takes it, and a pass's rows do not depend on one
//! another, so the results are the same on any thread count.

use crate::force_ranges::BodyRanges;
use rayon::prelude::*;
use std::sync::{Mutex, PoisonError};

/// Most ranges of bodies a pool's passes cut the bodies into: one per thread up to this; in a larger pool thread k's
/// home is range k mod 64, which it shares with thread k − 64. The pieces of a pass wait in an array of this length on
/// the stack.
pub(crate) const MAX_RANGES: usize = 64;

impl BodyRanges {
    /// The ranges of `bodies` bodies in the current rayon pool: one per thread, at most [`MAX_RANGES`].
    pub(crate) fn of_pool(bodies: usize) -> Self {
        Self::new(bodies, rayon::current_num_threads().min(MAX_RANGES))
    }
}

/// Calls `work(range, piece)` for each of `pieces`, the rows of ranges 0, 1, … (at most [`MAX_RANGES`]), in parallel
/// in the current pool: piece `range` on the thread of the same index wherever that thread takes one of the pass's
/// tasks before another thread has taken its piece, else on the thread that comes first. Every piece is worked on
/// exactly once. Allocates nothing.
pub(crate) fn for_each_on_home_thread<P: Send>(pieces: impl IntoIterator<Item = P>, work: impl Fn(usize, P) + Sync) {
    let mut slots: [Mutex<Option<P>>; MAX_RANGES] = std::array::from_fn(|_| Mutex::new(None));
    let mut pieces = pieces.into_iter();
    let mut count = 0;
    for (slot, piece) in slots.iter_mut().zip(pieces.by_ref()) {
        *slot.get_mut().unwrap_or_else(PoisonError::into_inner) = Some(piece);
        count += 1;
    }
    assert!(pieces.next().is_none(), "more than {MAX_RANGES} pieces: BodyRanges::of_pool makes at most that many");
    let take = |range: usize| slots[range].lock().unwrap_or_else(PoisonError::into_inner).take();
    // As many tasks as pieces, and each takes one piece: its thread's own where still free, else the next free one
    // after it. There is always one: the tasks before it took one piece each.
    (0..count).into_par_iter().with_max_len(1).for_each(|_| {
        let home = rayon::current_thread_index().unwrap_or(0) % count;
        let free = (home..count).chain(0..home).find_map(|range| take(range).map(|piece| (range, piece)));
        if let Some((range, piece)) = free {
            work(range, piece);
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// Every piece is worked on exactly once, with its own index, for pools of 1 to 9 threads and 0 to
    /// [`MAX_RANGES`] pieces.
    #[test]
    fn every_piece_is_worked_on_once_with_its_index() {
        for threads in 1..=9 {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            for pieces in [0, 1, 2, threads, 2 * threads + 1, MAX_RANGES] {
                let mut rows = vec![0_usize; pieces * 3];
                let calls = AtomicUsize::new(0);
                pool.install(|| {
                    for_each_on_home_thread(rows.chunks_mut(3), |range, piece| {
                        calls.fetch_add(1, Ordering::Relaxed);
                        piece.iter_mut().for_each(|row| *row += range + 1);
                    })
                });
                assert_eq!(calls.load(Ordering::Relaxed), pieces, "{threads} threads, {pieces} pieces");
                let expected: Vec<usize> = (0..pieces).flat_map(|range| [range + 1; 3]).collect();
                assert_eq!(rows, expected, "{threads} threads, {pieces} pieces");
            }
        }
    }

    /// The ranges of the pool: one per thread, at most [`MAX_RANGES`].
    #[test]
    fn a_pool_has_one_range_per_thread_up_to_the_maximum() {
        for (threads, ranges) in [(1, 1), (3, 3), (MAX_RANGES, MAX_RANGES), (MAX_RANGES + 5, MAX_RANGES)] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            assert_eq!(pool.install(|| BodyRanges::of_pool(1000)).count, ranges);
        }
    }
}
