//! Closest-feature queries as the engine makes them: warm-started on a slowly moving pair (about 1e-4 of the size
//! per step), and cold.

use criterion::{Criterion, criterion_group, criterion_main};
use gc2d_geometry::{ConvexPolygon, DVec2, FeaturePair, Pose, closest_features};
use std::f64::consts::TAU;
use std::hint::black_box;

/// Frames in one period of the motion; the path is periodic, so cycling through the frames stays smooth. Few
/// enough that the frames stay in L2 cache even for 20-gons, as an engine step's world vertices would.
const FRAMES: usize = 1024;

/// A polygon with vertices on an ellipse at the given relative angular gaps.
fn ellipse_polygon(semi_x: f64, semi_y: f64, gaps: &[f64]) -> ConvexPolygon {
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
    ConvexPolygon::new(&points).expect("convex outline").0
}

fn uneven_gaps(n: usize) -> Vec<f64> {
    (0..n).map(|i| 1.0 + 0.35 * (i as f64 * 2.3).sin()).collect()
}

/// `a` at rest and the world vertices of `b` over one period, frame after frame in one buffer: `b` sways sideways
/// and turns in front of `a` at centre distance `reach` × (sum of bounding radii). Steps are about 1e-4 of the size
/// in position and 1e-4 rad in angle.
struct Motion {
    a: Vec<DVec2>,
    b_frames: Vec<DVec2>,
    n_b: usize,
}

impl Motion {
    fn new(a: &ConvexPolygon, b: &ConvexPolygon, reach: f64) -> Self {
        let centre_distance = reach * (a.bounding_radius() + b.bounding_radius());
        let mut world_a = vec![DVec2::ZERO; a.len()];
        Pose::new(DVec2::ZERO, 0.1).transform_into(a.vertices(), &mut world_a);
        let mut b_frames = vec![DVec2::ZERO; FRAMES * b.len()];
        for (k, world_b) in b_frames.chunks_exact_mut(b.len()).enumerate() {
            let s = (TAU * k as f64 / FRAMES as f64).sin();
            Pose::new(DVec2::from_angle(0.0075 * s) * centre_distance, 0.4 + 0.015 * s)
                .transform_into(b.vertices(), world_b);
        }
        Self { a: world_a, b_frames, n_b: b.len() }
    }

    fn frame(&self, k: usize) -> (&[DVec2], &[DVec2]) {
        (&self.a, &self.b_frames[k * self.n_b..(k + 1) * self.n_b])
    }
}

fn bench_warm(c: &mut Criterion, name: &str, motion: &Motion) {
    c.bench_function(name, |bencher| {
        let mut k = 0;
        let mut warm: Option<FeaturePair> = None;
        bencher.iter(|| {
            let (a, b) = motion.frame(k);
            let result = closest_features(black_box(a), black_box(b), warm);
            warm = Some(result.features);
            k = (k + 1) % FRAMES;
            result.distance
        })
    });
}

fn closest(c: &mut Criterion) {
    let heptagon_a = ellipse_polygon(1.0, 0.8, &uneven_gaps(7));
    let heptagon_b =
        ellipse_polygon(0.9, 0.75, &uneven_gaps(7)[2..].iter().chain(&[0.8, 1.2]).copied().collect::<Vec<_>>());
    let icosagon_a = ellipse_polygon(1.0, 0.85, &uneven_gaps(20));
    let icosagon_b =
        ellipse_polygon(0.95, 0.8, &uneven_gaps(20)[5..].iter().chain(&uneven_gaps(5)).copied().collect::<Vec<_>>());

    let separated_heptagons = Motion::new(&heptagon_a, &heptagon_b, 1.1);
    bench_warm(c, "closest/warm 7-gons separated", &separated_heptagons);
    bench_warm(c, "closest/warm 7-gons overlapping", &Motion::new(&heptagon_a, &heptagon_b, 0.85));
    bench_warm(c, "closest/warm 20-gons separated", &Motion::new(&icosagon_a, &icosagon_b, 1.1));
    c.bench_function("closest/cold 7-gons separated", |bencher| {
        let mut k = 0;
        bencher.iter(|| {
            let (a, b) = separated_heptagons.frame(k);
            k = (k + 1) % FRAMES;
            closest_features(black_box(a), black_box(b), None).distance
        })
    });
}

criterion_group!(benches, closest);
criterion_main!(benches);
