//! Broadphase cost on a dense packing of 10,000 boxes (reference §10.5: track it, no hard target).
//!
//! The packing is a jittered, polydisperse 100 × 100 lattice in which neighbouring boxes overlap, so about two pairs
//! per body exist. Each box circles its site; the step length per update is a fixed fraction of the box size. A DEM
//! step moves a particle by about 1e-4 to 1e-3 of its size (Δt = 2e-6 s at up to 0.5 m/s for d ≈ 3 mm), so 1e-3 is
//! the realistic case and 1e-2 a fast one. Throughput is counted in bodies: criterion's time per element is the cost
//! per body per update.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use gc2d_engine::BodyKind;
use gc2d_engine::broadphase::SortAndSweep;
use gc2d_geometry::{Aabb, DVec2};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::TAU;
use std::hint::black_box;

const SIDE: u32 = 100;
const BODIES: u32 = SIDE * SIDE;
const FRAMES: u32 = 32;

/// The engine's per-pair record is about this large (old area, spring, features).
type Payload = [f64; 4];

/// One box of the packing: its lattice site (jittered), half size and phase on its circle.
struct Site {
    center: DVec2,
    half: f64,
    phase: f64,
}

fn packing() -> Vec<Site> {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    (0..BODIES)
        .map(|i| {
            let lattice = DVec2::new(f64::from(i % SIDE), f64::from(i / SIDE));
            let jitter = DVec2::new(rng.random_range(-0.3..0.3), rng.random_range(-0.3..0.3));
            Site { center: lattice + jitter, half: rng.random_range(0.45..0.6), phase: rng.random_range(0.0..TAU) }
        })
        .collect()
}

/// The boxes of `frame` when every box moves `step` (in box sizes) per update along its circle.
fn frame(sites: &[Site], step: f64, frame: u32) -> Vec<Aabb> {
    let radius = step / (TAU / f64::from(FRAMES));
    let t = TAU * f64::from(frame) / f64::from(FRAMES);
    sites
        .iter()
        .map(|site| {
            let center = site.center + radius * DVec2::from_angle(t + site.phase);
            Aabb { min: center - DVec2::splat(site.half), max: center + DVec2::splat(site.half) }
        })
        .collect()
}

fn filled(boxes: &[Aabb]) -> SortAndSweep<Payload> {
    let mut sweep = SortAndSweep::new();
    for (id, aabb) in boxes.iter().enumerate() {
        sweep.insert(id as u32, *aabb, BodyKind::Particle).expect("ids are below the limit");
    }
    sweep.update(boxes);
    sweep
}

fn update(c: &mut Criterion) {
    let sites = packing();
    let mut group = c.benchmark_group("broadphase_update_10000");
    group.throughput(Throughput::Elements(u64::from(BODIES)));
    for step in [1e-3, 1e-2] {
        let frames: Vec<Vec<Aabb>> = (0..FRAMES).map(|f| frame(&sites, step, f)).collect();
        let mut sweep = filled(&frames[0]);
        for boxes in &frames {
            sweep.update(boxes);
        }
        let mut next = 0;
        group.bench_with_input(BenchmarkId::new("step_per_size", step), &frames, |b, frames| {
            b.iter(|| {
                sweep.update(black_box(&frames[next]));
                next = (next + 1) % frames.len();
            })
        });
        let stats = sweep.stats();
        println!(
            "step {step}: {} pairs; last update {} swaps, {} pairs added, {} removed",
            sweep.pairs().len(),
            stats.swaps,
            stats.pairs_added,
            stats.pairs_removed
        );
    }
    group.finish();
}

fn build(c: &mut Criterion) {
    let boxes = frame(&packing(), 0.0, 0);
    let mut group = c.benchmark_group("broadphase_build_10000");
    group.throughput(Throughput::Elements(u64::from(BODIES)));
    group.sample_size(10);
    group.bench_function("insert_all_and_first_update", |b| b.iter(|| filled(black_box(&boxes)).pairs().len()));
    group.finish();
}

criterion_group!(benches, update, build);
criterion_main!(benches);
