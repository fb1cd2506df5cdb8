//! Cost of the Gear integrator per body and step: predict + correct of 10,000 bodies (translation and rotation).
//! Criterion reports the time per step and, through the element throughput, bodies per second.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use gc2d_engine::integrator::{Gear6, GearC0, GearState, TimeStep};
use glam::DVec2;
use std::hint::black_box;

const BODIES: usize = 10_000;

fn predict_and_correct(c: &mut Criterion) {
    let time_step = TimeStep::new(2e-6).expect("valid time step");
    let gear = Gear6::new(time_step, GearC0::default());
    let mut states: Vec<GearState> = (0..BODIES)
        .map(|i| {
            let x = i as f64 * 1e-3;
            GearState::from_physical(DVec2::new(x, 0.5), DVec2::new(0.1, -0.2), DVec2::ZERO, x, 3.0, 0.0, &time_step)
        })
        .collect();
    let linear_acceleration: Vec<DVec2> = (0..BODIES).map(|i| DVec2::new(0.0, -9.81 + (i % 7) as f64)).collect();
    let angular_acceleration: Vec<f64> = (0..BODIES).map(|i| (i % 5) as f64 - 2.0).collect();

    let mut group = c.benchmark_group("gear6");
    group.throughput(Throughput::Elements(BODIES as u64));
    group.bench_function("predict_correct_10k", |b| {
        b.iter(|| {
            gear.predict(black_box(&mut states));
            gear.correct(black_box(&mut states), black_box(&linear_acceleration), black_box(&angular_acceleration));
        })
    });
    group.bench_function("predict_10k", |b| b.iter(|| gear.predict(black_box(&mut states))));
    group.finish();
}

criterion_group!(benches, predict_and_correct);
criterion_main!(benches);
