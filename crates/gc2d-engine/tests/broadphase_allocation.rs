//! A warm broadphase update allocates nothing (preamble: the hot paths must not allocate).
//!
//! The counting allocator (`gc2d-alloc-count`) is installed in this test binary only; the count is per thread, so the
//! test harness's own threads cannot disturb it. The updates run on a worker of a two-thread pool, as a World's steps
//! do (`World::run_until`): the lattice is large enough that its two axes are sorted on two threads, and a `join`
//! from a thread outside the pool would hand its task over through the pool's queue, which grows as it goes.

use gc2d_alloc_count::{CountingAllocator, thread_allocations};
use gc2d_engine::BodyKind;
use gc2d_engine::broadphase::SortAndSweep;
use gc2d_geometry::{Aabb, DVec2};

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

/// A 30 × 30 lattice of unit boxes breathing in and out: pairs form and break every few steps.
fn lattice(step: u32) -> Vec<Aabb> {
    let spacing = 1.0 + 0.05 * f64::from(step % 8);
    (0..900)
        .map(|i| {
            let center = DVec2::new(f64::from(i % 30), f64::from(i / 30)) * spacing;
            Aabb { min: center - DVec2::splat(0.5), max: center + DVec2::splat(0.5) }
        })
        .collect()
}

#[test]
fn warm_updates_do_not_allocate() {
    let frames: Vec<Vec<Aabb>> = (0..8).map(lattice).collect();
    let mut sweep = SortAndSweep::<[f64; 4]>::new();
    for (id, aabb) in frames[0].iter().enumerate() {
        sweep.insert(id as u32, *aabb, BodyKind::Particle).unwrap();
    }
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
    let (allocations, pairs_seen) = pool.install(|| {
        for frame in frames.iter().cycle().take(16) {
            sweep.update(frame);
        }
        let before = thread_allocations();
        let mut pairs_seen = 0;
        for frame in frames.iter().cycle().take(64) {
            sweep.update(frame);
            pairs_seen += sweep.pairs().len() + sweep.ended_pairs().len();
        }
        (thread_allocations() - before, pairs_seen)
    });
    assert_eq!(allocations, 0);
    assert!(pairs_seen > 0);
}
