//! Cost of one contact evaluation: the full area law (damping, friction, cohesion) against the elastic-only law, and
//! the full penetration law (Hertz, e(v) damping, Mindlin friction, rolling resistance) against elastic Hertz.

use criterion::{Criterion, criterion_group, criterion_main};
use gc2d_contact::penetration::effective_modulus;
use gc2d_contact::{
    BodyMotion, Cohesion, ContactGeometry, ContactLaw, ContactState, CundallStrack, DVec2, ImpactLaw, NormalDamping,
    NormalSpring, PairProperties, PenetrationDamping, PenetrationGeometry, PenetrationLaw, PenetrationState,
    RollingResistance, TangentialSpring, TangentialStiffness,
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
            centroid_offset: 0.0,
            rocking: true,
        };
        let out = law.evaluate(&geometry, &body_i, &body_j, &state, 1e-6);
        sum += out.force_on_i.x + out.energy.absorbed();
        state = out.state;
    }
    sum
}

fn penetration_contacts(law: &PenetrationLaw, steps: usize) -> f64 {
    let body_i = BodyMotion::free(4e-3, 4e-8, DVec2::new(0.05, -0.3), 0.3);
    let body_j = BodyMotion::free(4e-3, 4e-8, DVec2::new(-0.01, 0.0), -0.1);
    let properties = PairProperties::disks(5e-3, &body_i, 5e-3, &body_j);
    let normal = DVec2::new(0.6, 0.8);
    let mut state = PenetrationState::default();
    let mut sum = 0.0;
    for k in 0..steps {
        let depth = 1e-6 * (1.0 + 0.1 * (k % 7) as f64);
        let geometry = PenetrationGeometry {
            depth,
            normal,
            arm_i: -(5e-3 - 0.5 * depth) * normal,
            arm_j: (5e-3 - 0.5 * depth) * normal,
        };
        let out = law.evaluate(&geometry, &properties, &body_i, &body_j, &state, 1e-8);
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
    let hertz = NormalSpring::Hertz { effective_modulus_pa: effective_modulus(2.1e11, 0.3, 2.1e11, 0.3) };
    let full = PenetrationLaw {
        normal: hertz,
        damping: Some(PenetrationDamping::VelocityDependent(ImpactLaw::SteelReichardt)),
        tangential: Some(TangentialSpring {
            mu: 0.3,
            stiffness: TangentialStiffness::Mindlin { effective_shear_modulus_pa: 4e10 },
            damping_ratio: 0.2,
        }),
        rolling: Some(RollingResistance { mu_r: 0.01, stiffness_ratio: 0.5, damping_ratio: 0.2 }),
        tensile_clamp: false,
    };
    let elastic = PenetrationLaw::elastic(hertz);
    c.bench_function("evaluate full penetration law x1000", |b| {
        b.iter(|| penetration_contacts(black_box(&full), 1000))
    });
    c.bench_function("evaluate elastic Hertz law x1000", |b| {
        b.iter(|| penetration_contacts(black_box(&elastic), 1000))
    });
}

criterion_group!(benches, evaluate);
criterion_main!(benches);
