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

/// The shape-generic queries allocate nothing either: every pair family, overlapping and apart, both orders.
#[test]
fn shape_generic_queries_allocate_nothing() {
    use gc2d_geometry::{ShapeView, area_contact, penetration};
    let origin = DVec2::new(0.07, 0.05);
    let r = 1.75e-3;
    let polygons: Vec<Vec<DVec2>> = [3, 7, 20, MAX_VERTICES].iter().map(|&n| regular(n, r, origin, 0.37)).collect();
    let mut walls = vec![
        ShapeView::Capsule {
            a: origin + DVec2::new(-2.0 * r, 1.5 * r),
            b: origin + DVec2::new(2.0 * r, 1.9 * r),
            radius: 0.5 * r,
        },
        ShapeView::Capsule {
            a: origin + DVec2::new(0.0, 1.2 * r),
            b: origin + DVec2::new(0.0, 1.2 * r),
            radius: 0.5 * r,
        },
        ShapeView::InnerCircle { center: origin + DVec2::new(0.3 * r, 0.0), radius: 1.5 * r },
        ShapeView::InnerCircle { center: origin, radius: 10.0 * r },
    ];
    walls.extend(polygons.iter().map(|p| ShapeView::Polygon(p)));
    let mut particles: Vec<ShapeView> = polygons.iter().map(|p| ShapeView::Polygon(p)).collect();
    for offset in [0.0, 0.5, 1.5, 1.9, 2.5] {
        particles.push(ShapeView::Disk { center: origin + DVec2::new(offset * r, 0.2 * offset * r), radius: r });
        particles.push(ShapeView::Disk { center: origin + DVec2::new(0.0, offset * r), radius: 0.3 * r });
    }
    walls.extend(particles.iter().copied());
    let before = thread_allocations();
    let mut touching = 0;
    for i in &particles {
        for j in &walls {
            touching += usize::from(area_contact(*i, *j).is_some());
            touching += usize::from(penetration(*i, *j).is_some());
            touching += usize::from(area_contact(*j, *i).is_some());
            touching += usize::from(penetration(*j, *i).is_some());
        }
    }
    assert_eq!(thread_allocations() - before, 0);
    let total = 4 * particles.len() * walls.len();
    assert!(touching > total / 4 && touching < total, "{touching} of {total} evaluations touch");
}
