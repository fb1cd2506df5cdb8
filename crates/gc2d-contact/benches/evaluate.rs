//! Cost of one contact evaluation: the full law (damping, friction, cohesion) against the elastic-only law.

use criterion::{Criterion, criterion_group, criterion_main};
use gc2d_contact::{
    BodyMotion, Cohesion, ContactGeometry, ContactLaw, ContactState, CundallStrack, DVec2, NormalDamping,
};
use std::hint::black_box;

fn sliding_contacts(law: &ContactLaw, steps: usize) -> f64 {
    let body_i = BodyMotion::free(0.02, 6.7e-9, DVec2::new(0.05, -0.001), 0.3);
    let body_j = BodyMotion::free(0.03, 1e-8, DVec2::new(-0.01, 0.0), -0.1);
    let mut state = ContactState::default();
    let mut sum = 0.0;
    for k in 0..steps {
        let geometry = ContactGeometry {
            area: 2e-9 * (1.0 + 0.1 * (k % 7) as f64),
            normal: DVec2::new(0.6, 0.8),
            chord_length: 2e-3,
            arm_i: DVec2::new(0.1e-3, -1e-3),
            arm_j: DVec2::new(-0.2e-3, 1e-3),
        };
        let out = law.evaluate(&geometry, &body_i, &body_j, &state, 1e-6);
        sum += out.force_on_i.x + out.energy.absorbed();
        state = out.state;
    }
    sum
}

fn evaluate(c: &mut Criterion) {
    let full = ContactLaw {
        damping: Some(NormalDamping { gamma: 0.5 }),
        friction: Some(CundallStrack { mu: 0.6 }),
        cohesion: Some(Cohesion { k_coh: 1e3 }),
        ..ContactLaw::elastic(1e7)
    };
    let elastic = ContactLaw::elastic(1e7);
    c.bench_function("evaluate full law x1000", |b| b.iter(|| sliding_contacts(black_box(&full), 1000)));
    c.bench_function("evaluate elastic law x1000", |b| b.iter(|| sliding_contacts(black_box(&elastic), 1000)));
}

criterion_group!(benches, evaluate);
criterion_main!(benches);
