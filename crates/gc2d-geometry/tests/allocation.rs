//! The narrowphase queries allocate nothing (preamble: the hot paths must not allocate): `contact_geometry`,
//! `overlap_polygon` and `closest_features`, cold and warm, for every admissible vertex count and for touching,
//! overlapping, separated, contained and degenerate pairs.
//!
//! The counting allocator (`gc2d-alloc-count`) is installed in this test binary only; the count is per thread, so the
//! test harness's own threads cannot disturb it.

use gc2d_alloc_count::{CountingAllocator, thread_allocations};
use gc2d_geometry::{DVec2, MAX_VERTICES, OverlapPolygon, closest_features, contact_geometry, overlap_polygon};
use std::f64::consts::TAU;

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

/// A regular n-gon of circumradius `radius` around `center`, turned by `phase`.
fn regular(n: usize, radius: f64, center: DVec2, phase: f64) -> Vec<DVec2> {
    (0..n).map(|i| center + radius * DVec2::from_angle(phase + TAU * i as f64 / n as f64)).collect()
}

/// Pairs of every kind the narrowphase meets, at the thesis's particle size and 0.07 m from the origin.
fn pairs() -> Vec<(Vec<DVec2>, Vec<DVec2>)> {
    let origin = DVec2::new(0.07, 0.05);
    let r = 1.75e-3;
    let mut pairs = Vec::new();
    for n in [3, 7, 13, 20, MAX_VERTICES] {
        let a = regular(n, r, origin, 0.37);
        // Far apart, close, shallow, deep, contained and identical.
        for (offset, radius) in [(2.5 * r, r), (1.9 * r, r), (1.8 * r, r), (0.7 * r, r), (0.0, 0.3 * r), (0.0, r)] {
            let b = regular(n, radius, origin + DVec2::new(offset, 0.1 * offset), if radius == r { 0.37 } else { 1.1 });
            pairs.push((a.clone(), b));
        }
        // Collinear edges (a square resting on a square) and mixed vertex counts.
        pairs.push((
            regular(4, r, origin, 0.25 * TAU / 2.0),
            regular(4, r, origin + DVec2::new(0.0, 2f64.sqrt() * r), 0.25 * TAU / 2.0),
        ));
        pairs.push((a, regular(7, r, origin + DVec2::new(1.5 * r, 0.0), 0.2)));
    }
    pairs
}

#[test]
fn contact_queries_allocate_nothing() {
    let pairs = pairs();
    let mut out = OverlapPolygon::new();
    let before = thread_allocations();
    let mut touching = 0;
    for (a, b) in &pairs {
        let cold = closest_features(a, b, None);
        let warm = closest_features(a, b, Some(cold.features));
        touching += usize::from(contact_geometry(a, b).is_some());
        touching += usize::from(contact_geometry(b, a).is_some());
        overlap_polygon(a, b, &mut out);
        assert_eq!(cold.distance, warm.distance);
    }
    assert_eq!(thread_allocations() - before, 0);
    // The set must hold contacts and separated pairs alike: 4 of the 6 offsets overlap for each vertex count.
    assert!(touching >= 2 * 4 * 5, "only {touching} overlapping evaluations");
    assert!(touching < 2 * pairs.len());
}
