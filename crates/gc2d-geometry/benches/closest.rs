//! Closest-feature queries as the engine makes them: warm-started on a slowly moving pair (about 1e-4 of the size
//! per step), and cold.

use criterion::{Criterion, criterion_group, criterion_main};
use gc2d_geometry::{ConvexPolygon, DVec2, FeaturePair, Pose, closest_features};
use std::f64::consts::TAU;
use std::hint::black_box;

/// Frames in one period of the motion; the path is periodic, so cycling through the frames stays smooth.
const FRAMES: usize = 4096;

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

/// World vertices of `a` and `b` over one period, frame after frame in one buffer: `b` sways sideways and turns in
/// front of `a`, at centre distance `reach` × (sum of bounding radii). Steps are about 1e-4 of the size in position
/// and angle.
struct Motion {
    vertices: Vec<DVec2>,
    n_a: usize,
    n_b: usize,
}

impl Motion {
    fn new(a: &ConvexPolygon, b: &ConvexPolygon, reach: f64) -> Self {
        let centre_distance = reach * (a.bounding_radius() + b.bounding_radius());
        let (n_a, n_b) = (a.len(), b.len());
        let mut vertices = vec![DVec2::ZERO; FRAMES * (n_a + n_b)];
        for (k, frame) in vertices.chunks_exact_mut(n_a + n_b).enumerate() {
            let s = (TAU * k as f64 / FRAMES as f64).sin();
            let (world_a, world_b) = frame.split_at_mut(n_a);
            Pose::new(DVec2::ZERO, 0.1).transform_into(a.vertices(), world_a);
            Pose::new(DVec2::from_angle(0.03 * s) * centre_distance, 0.4 + 0.06 * s)
                .transform_into(b.vertices(), world_b);
        }
        Self { vertices, n_a, n_b }
    }

    fn frame(&self, k: usize) -> (&[DVec2], &[DVec2]) {
        let stride = self.n_a + self.n_b;
        self.vertices[k * stride..(k + 1) * stride].split_at(self.n_a)
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
