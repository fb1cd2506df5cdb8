//! When a World's step hands its stages to the rayon pool, one rule for every stage.

/// Worlds with fewer bodies than this step on the calling thread: below it, handing work to the thread pool costs
/// more than it saves. Results are bitwise the same either way (every parallel task writes only its own data).
pub(crate) const PARALLEL_MIN_BODIES: usize = 512;

/// Whether a World of `bodies` bodies hands its stages to the thread pool: from [`PARALLEL_MIN_BODIES`] bodies on,
/// and only in a pool of more than one thread (in a pool of one, handing out tasks costs time and gains none).
pub(crate) fn steps_in_parallel(bodies: usize) -> bool {
    bodies >= PARALLEL_MIN_BODIES && rayon::current_num_threads() > 1
}
