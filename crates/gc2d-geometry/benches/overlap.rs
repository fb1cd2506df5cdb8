//! Overlap area + contact chord of two touching polygons, the per-pair narrowphase cost of every step.
//!
//! Each case places two regular n-gons of radius 1.75 mm (the thesis's 7-gon piles) rotated against each other, at
//! 0.07 m from the origin, pressed together by a penetration of 1e-3 of their size, as in a typical DEM contact: found
//! from scratch, and found from the last step's crossing as the engine finds a contact that persists.

use criterion::{Criterion, criterion_group, criterion_main};
use gc2d_geometry::{DVec2, contact_geometry, contact_geometry_from_exit};
use std::f64::consts::PI;
use std::hint::black_box;

fn regular(n: usize, radius: f64, center: DVec2, phase: f64) -> Vec<DVec2> {
    (0..n)
        .map(|i| {
            let phi = phase + 2.0 * PI * i as f64 / n as f64;
            center + radius * DVec2::new(phi.cos(), phi.sin())
        })
        .collect()
}

/// Two n-gons side by side along x (b a little higher), moved together until their overlap is 1e-3 of the radius
/// deep: the touching shift is found by bisection on whether the overlap is empty.
fn touching_pair(n: usize) -> (Vec<DVec2>, Vec<DVec2>) {
    let radius = 1.75e-3;
    let origin = DVec2::new(0.07, 0.05);
    let a = regular(n, radius, origin, 0.37);
    let b_at = |shift: f64| regular(n, radius, origin + DVec2::new(shift, 0.3 * radius), 1.1);
    let (mut overlapping, mut apart) = (0.0, 3.0 * radius);
    for _ in 0..100 {
        let middle = 0.5 * (overlapping + apart);
        if contact_geometry(&a, &b_at(middle)).is_some() {
            overlapping = middle;
        } else {
            apart = middle;
        }
    }
    let b = b_at(apart - 1e-3 * radius);
    (a, b)
}

fn bench_overlap(c: &mut Criterion) {
    for n in [7, 20] {
        let (a, b) = touching_pair(n);
        let contact = contact_geometry(&a, &b).expect("the bench pair must overlap");
        assert!(contact.area > 0.0);
        c.bench_function(&format!("contact_geometry touching {n}-gons"), |bench| {
            bench.iter(|| contact_geometry(black_box(&a), black_box(&b)))
        });
        // A persisting contact: the same pair found from the edges where the outlines crossed last time.
        let mut exit = None;
        assert_eq!(contact_geometry_from_exit(&a, &b, false, &mut exit), Some(contact));
        c.bench_function(&format!("contact_geometry_from_exit touching {n}-gons"), |bench| {
            bench.iter(|| {
                let mut hint = exit;
                contact_geometry_from_exit(black_box(&a), black_box(&b), false, black_box(&mut hint))
            })
        });
    }
}

criterion_group!(benches, bench_overlap);
criterion_main!(benches);
