//! The closest-feature walk against independent references: parry2d-f64 and a brute-force segment minimum on
//! random convex pairs, and cold starts along a slowly moving pair (reference §10.3 level 0).

use gc2d_geometry::{ConvexPolygon, DVec2, Feature, FeaturePair, Pose, Separation, closest_features, cross};
use parry2d_f64::math::Pose as ParryPose;
use parry2d_f64::query;
use parry2d_f64::shape::ConvexPolygon as ParryPolygon;
use proptest::prelude::*;
use std::f64::consts::TAU;

/// A polygon with one vertex per gap on the ellipse with semi-axes `semi_x`, `semi_y`; the gaps are relative
/// angular spacings (reference §1.2, RAND-style shapes). `None` when the outline is rejected as degenerate.
fn ellipse_polygon(semi_x: f64, semi_y: f64, gaps: &[f64]) -> Option<ConvexPolygon> {
    let total: f64 = gaps.iter().sum();
    let mut phi: f64 = 0.0;
    let points: Vec<DVec2> = gaps
        .iter()
        .map(|gap| {
            let p = DVec2::new(semi_x * phi.cos(), semi_y * phi.sin());
            phi += gap / total * TAU;
            p
        })
        .collect();
    ConvexPolygon::new(&points).ok().map(|(polygon, _)| polygon)
}

fn world(polygon: &ConvexPolygon, pose: Pose) -> Vec<DVec2> {
    let mut out = vec![DVec2::ZERO; polygon.len()];
    pose.transform_into(polygon.vertices(), &mut out);
    out
}

fn point_segment_distance(p: DVec2, q0: DVec2, q1: DVec2) -> f64 {
    let d = q1 - q0;
    if d == DVec2::ZERO {
        return (p - q0).length();
    }
    let t = ((p - q0).dot(d) / d.length_squared()).clamp(0.0, 1.0);
    (q0 + d * t - p).length()
}

fn segments_intersect(p0: DVec2, p1: DVec2, q0: DVec2, q1: DVec2) -> bool {
    let side = |o: DVec2, d: DVec2, x: DVec2| cross(d, x - o).signum();
    side(p0, p1 - p0, q0) != side(p0, p1 - p0, q1) && side(q0, q1 - q0, p0) != side(q0, q1 - q0, p1)
}

fn segment_distance(p0: DVec2, p1: DVec2, q0: DVec2, q1: DVec2) -> f64 {
    if segments_intersect(p0, p1, q0, q1) {
        return 0.0;
    }
    point_segment_distance(p0, q0, q1)
        .min(point_segment_distance(p1, q0, q1))
        .min(point_segment_distance(q0, p0, p1))
        .min(point_segment_distance(q1, p0, p1))
}

fn edges(poly: &[DVec2]) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
    (0..poly.len()).map(|i| (poly[i], poly[(i + 1) % poly.len()]))
}

/// Largest signed distance of `p` outside the edge lines of `poly` (≤ 0: inside or on).
fn outside_by(poly: &[DVec2], p: DVec2) -> f64 {
    edges(poly).map(|(v0, v1)| cross(p - v0, v1 - v0) / (v1 - v0).length()).fold(f64::NEG_INFINITY, f64::max)
}

fn boundary_distance(poly: &[DVec2], p: DVec2) -> f64 {
    edges(poly).map(|(v0, v1)| point_segment_distance(p, v0, v1)).fold(f64::INFINITY, f64::min)
}

/// Brute-force distance: 0 when the polygons overlap, else the minimum over all edge pairs.
fn reference_distance(a: &[DVec2], b: &[DVec2]) -> f64 {
    if outside_by(b, a[0]) <= 0.0 || outside_by(a, b[0]) <= 0.0 {
        return 0.0;
    }
    edges(a)
        .flat_map(|(p0, p1)| edges(b).map(move |(q0, q1)| segment_distance(p0, p1, q0, q1)))
        .fold(f64::INFINITY, f64::min)
}

fn parry_polygon(vertices: &[DVec2]) -> ParryPolygon {
    ParryPolygon::from_convex_polyline_unmodified(vertices.to_vec()).expect("valid convex polygon")
}

fn feature_segment(poly: &[DVec2], feature: Feature) -> (DVec2, DVec2) {
    match feature {
        Feature::Vertex(_) => (poly[feature.index()], poly[feature.index()]),
        Feature::Edge(_) => (poly[feature.index()], poly[(feature.index() + 1) % poly.len()]),
    }
}

/// Asserts everything a result promises, with `scale` the size of the polygons for absolute tolerances.
fn assert_consistent(a: &[DVec2], b: &[DVec2], r: &Separation, scale: f64) {
    let tolerance = 1e-12 * scale;
    assert!(r.distance >= 0.0 && r.distance.is_finite());
    assert!(((r.point_a - r.point_b).length() - r.distance).abs() <= tolerance);
    let (a0, a1) = feature_segment(a, r.features.a);
    let (b0, b1) = feature_segment(b, r.features.b);
    if r.penetrating {
        assert_eq!(r.distance, 0.0);
        assert!(outside_by(a, r.point_a) <= tolerance && outside_by(b, r.point_a) <= tolerance);
        match (r.features.a, r.features.b) {
            (Feature::Edge(_), Feature::Edge(_)) => {
                assert!(point_segment_distance(r.point_a, a0, a1) <= tolerance);
                assert!(point_segment_distance(r.point_a, b0, b1) <= tolerance);
            }
            (Feature::Vertex(i), _) => assert_eq!(r.point_a, a[usize::from(i)]),
            (_, Feature::Vertex(j)) => assert_eq!(r.point_a, b[usize::from(j)]),
        }
    } else {
        assert!(boundary_distance(a, r.point_a) <= tolerance);
        assert!(boundary_distance(b, r.point_b) <= tolerance);
        assert!(point_segment_distance(r.point_a, a0, a1) <= tolerance);
        assert!(point_segment_distance(r.point_b, b0, b1) <= tolerance);
        assert!((segment_distance(a0, a1, b0, b1) - r.distance).abs() <= tolerance);
    }
}

fn shape() -> impl Strategy<Value = (f64, f64, Vec<f64>)> {
    (0.3f64..2.0, 0.2f64..1.0, prop::collection::vec(0.3f64..1.3, 3..=20))
        .prop_map(|(semi_x, aspect, gaps)| (semi_x, semi_x * aspect, gaps))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10_000))]

    #[test]
    fn distance_matches_parry_and_brute_force(
        (ax, ay, a_gaps) in shape(),
        (bx, by, b_gaps) in shape(),
        a_pose in (-10.0f64..10.0, -10.0f64..10.0, -4.0f64..4.0),
        b_angle in -4.0f64..4.0,
        direction in 0.0f64..TAU,
        reach in 0.2f64..1.6,
        warm in (0usize..64, 0usize..64, 0u8..4),
    ) {
        let (Some(pa), Some(pb)) = (ellipse_polygon(ax, ay, &a_gaps), ellipse_polygon(bx, by, &b_gaps)) else {
            return Err(TestCaseError::reject("degenerate outline"));
        };
        let centre_a = DVec2::new(a_pose.0, a_pose.1);
        let offset = DVec2::from_angle(direction) * (pa.bounding_radius() + pb.bounding_radius()) * reach;
        let a = world(&pa, Pose::new(centre_a, a_pose.2));
        let b = world(&pb, Pose::new(centre_a + offset, b_angle));
        let scale = pa.bounding_radius() + pb.bounding_radius();
        // No f64 computation resolves a distance finer than the round-off of the coordinates it starts from.
        let round_off = 4.0 * f64::EPSILON * a.iter().chain(&b).map(|p| p.abs().max_element()).fold(0.0, f64::max);

        let reference = reference_distance(&a, &b);
        let identity = ParryPose::identity();
        let parry = query::distance(&identity, &parry_polygon(&a), &identity, &parry_polygon(&b)).unwrap().distance;
        let parry_overlap =
            query::intersection_test(&identity, &parry_polygon(&a), &identity, &parry_polygon(&b)).unwrap();

        let (i, j) = (warm.0 % a.len(), warm.1 % b.len());
        let warm_pair = FeaturePair {
            a: if warm.2 & 1 == 0 { Feature::vertex(i) } else { Feature::edge(i) },
            b: if warm.2 & 2 == 0 { Feature::vertex(j) } else { Feature::edge(j) },
        };
        for r in [closest_features(&a, &b, None), closest_features(&a, &b, Some(warm_pair))] {
            assert_consistent(&a, &b, &r, scale);
            if reference == 0.0 {
                prop_assert_eq!(r.distance, 0.0);
                prop_assert!(r.penetrating);
                prop_assert!(parry_overlap.intersecting);
            } else {
                prop_assert!(!r.penetrating);
                let error = (r.distance - reference).abs();
                prop_assert!(error <= 1e-12 * reference + round_off, "{} vs {}", r.distance, reference);
                // parry's GJK stops once its bounds are within sqrt(10 ε) ≈ 4.7e-8 relative (gjk.rs, `_eps_rel`), so
                // it is the exact reference only to that; the brute force above is the 1e-12 one.
                let error = (r.distance - parry).abs();
                prop_assert!(error <= 1e-7 * reference + round_off, "{} vs parry {}", r.distance, parry);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// Rectangles turned by the same angle, side by side: their facing edges are parallel (footnote 10).
    #[test]
    fn parallel_facing_edges_give_the_gap(
        angle in -4.0f64..4.0,
        gap in -0.5f64..0.5,
        slide in -1.5f64..1.5,
        warm in (0usize..4, 0usize..4),
    ) {
        let (rectangle, _) = ConvexPolygon::new(&[
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, 0.6),
            DVec2::new(0.0, 0.6),
        ])
        .unwrap();
        let axis = DVec2::from_angle(angle);
        let a = world(&rectangle, Pose::new(DVec2::new(3.0, 1.0), angle));
        let b = world(&rectangle, Pose::new(DVec2::new(3.0, 1.0) + axis.rotate(DVec2::new(1.0 + gap, slide)), angle));
        let reference = reference_distance(&a, &b);
        let warm_pair = FeaturePair { a: Feature::edge(warm.0), b: Feature::edge(warm.1) };
        for r in [closest_features(&a, &b, None), closest_features(&a, &b, Some(warm_pair))] {
            assert_consistent(&a, &b, &r, 2.0);
            prop_assert!((r.distance - reference).abs() <= 1e-12 * 2.0, "{} vs {}", r.distance, reference);
            prop_assert_eq!(r.penetrating, reference == 0.0);
            if gap > 1e-9 && slide.abs() < 0.6 - 1e-9 {
                prop_assert!((r.distance - gap).abs() <= 1e-12);
            }
        }
    }
}

/// Deterministic pseudo-random gaps so the motion test always sees the same shapes.
fn gaps(n: usize, seed: u64) -> Vec<f64> {
    let mut state = seed;
    (0..n)
        .map(|_| {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            0.4 + (state >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect()
}

/// Counts of one motion run.
#[derive(Default)]
struct MotionStats {
    steps: usize,
    penetrating: usize,
    more_than_one_pass: usize,
    more_than_two_passes: usize,
    same_features: usize,
}

/// Moves `b` around `a` for `steps` steps (about 1e-4 of the size per step): approaching, overlapping, sliding
/// past and separating, while both turn. Every warm-started result must match a cold start.
fn follow(pa: &ConvexPolygon, pb: &ConvexPolygon, steps: usize, stats: &mut MotionStats) {
    let reach = pa.bounding_radius() + pb.bounding_radius();
    let mut warm: Option<FeaturePair> = None;
    for k in 0..steps {
        let s = k as f64 / steps as f64;
        let centre_distance = reach * (0.9 + 0.25 * (2.0 * TAU * s).cos());
        let direction = DVec2::from_angle(0.7 * (TAU * s).sin());
        let a = world(pa, Pose::new(DVec2::new(1.0, -2.0), -0.3 * TAU * s));
        let b = world(pb, Pose::new(DVec2::new(1.0, -2.0) + direction * centre_distance, 0.5 * TAU * s));
        let warm_result = closest_features(&a, &b, warm);
        let cold = closest_features(&a, &b, None);
        assert_consistent(&a, &b, &warm_result, reach);
        assert!((warm_result.distance - cold.distance).abs() <= 1e-12 * reach, "step {k}: {warm_result:?} {cold:?}");
        assert_eq!(warm_result.penetrating, cold.penetrating, "step {k}");
        if warm.is_some() {
            stats.steps += 1;
            stats.penetrating += warm_result.penetrating as usize;
            stats.more_than_one_pass += (warm_result.passes > 1) as usize;
            stats.more_than_two_passes += (warm_result.passes > 2) as usize;
            stats.same_features += (warm_result.features == cold.features) as usize;
        }
        warm = Some(warm_result.features);
    }
}

#[test]
fn warm_start_follows_a_moving_pair_like_a_cold_start() {
    let shapes = [
        (ellipse_polygon(1.0, 0.8, &gaps(7, 1)).unwrap(), ellipse_polygon(0.9, 0.7, &gaps(7, 2)).unwrap()),
        (ellipse_polygon(1.0, 0.5, &gaps(3, 3)).unwrap(), ellipse_polygon(1.2, 1.0, &gaps(20, 4)).unwrap()),
        (ellipse_polygon(1.0, 1.0, &gaps(12, 5)).unwrap(), ellipse_polygon(1.5, 0.4, &gaps(5, 6)).unwrap()),
    ];
    let mut stats = MotionStats::default();
    for (pa, pb) in &shapes {
        follow(pa, pb, 40_000, &mut stats);
    }
    let fraction = |count: usize| count as f64 / stats.steps as f64;
    println!(
        "warm-started steps: {}, overlapping {:.1} %, >1 pass {:.3} %, >2 passes {:.3} %, features as cold {:.2} %",
        stats.steps,
        100.0 * fraction(stats.penetrating),
        100.0 * fraction(stats.more_than_one_pass),
        100.0 * fraction(stats.more_than_two_passes),
        100.0 * fraction(stats.same_features),
    );
    assert!(
        fraction(stats.penetrating) > 0.2 && fraction(stats.penetrating) < 0.8,
        "the path must both touch and part"
    );
    assert!(fraction(stats.more_than_one_pass) < 0.1);
    assert!(fraction(stats.more_than_two_passes) < 0.05);
    // Generic positions have unique closest features, and overlaps report the unique crossing where a leaves b.
    assert!(fraction(stats.same_features) > 0.99);
}

/// Millimetre grains at decimetre coordinates, 10 nm apart or 10 nm into each other (the stiff-contact scale of
/// the architecture notes): the gap is resolved to round-off of the coordinates, and the overlap is detected.
#[test]
fn nanometre_gaps_and_overlaps_at_grain_scale() {
    let grain = ellipse_polygon(1.75e-3, 1.5e-3, &gaps(7, 9)).unwrap();
    let a = world(&grain, Pose::new(DVec2::new(0.07, 0.05), 0.3));
    for (k, angle) in [0.0, 1.0, 2.0, 3.0, 4.0, 5.0].into_iter().enumerate() {
        let direction = DVec2::from_angle(angle);
        let far = world(&grain, Pose::new(DVec2::new(0.07, 0.05) + direction * 5e-3, 0.1 * k as f64));
        let apart = closest_features(&a, &far, None);
        assert!(!apart.penetrating && apart.distance > 0.0);
        // Slide b along the line of closest points until the gap is ±10 nm.
        let normal = (apart.point_b - apart.point_a) / apart.distance;
        for target in [1e-8, -1e-8] {
            let shift = normal * (target - apart.distance);
            let b: Vec<DVec2> = far.iter().map(|&p| p + shift).collect();
            let cold = closest_features(&a, &b, None);
            let warm = closest_features(&a, &b, Some(apart.features));
            for r in [cold, warm] {
                assert_consistent(&a, &b, &r, 4e-3);
                if target > 0.0 {
                    assert!(!r.penetrating);
                    assert!((r.distance - target).abs() < 1e-16 * 0.1 * 4.0, "{} vs {target}", r.distance);
                } else {
                    assert!(r.penetrating && r.distance == 0.0);
                }
            }
        }
    }
}
