//! Field evaluations per second on the thesis's 21 × 21 mesh (feedpipe.md §4.2) and on 100k-node meshes: bilinear on a 317 × 316 lattice, Shepard (4 neighbours,
//! power 2) on the same nodes with the lattice's quads as the mesh's cells, and Shepard on a random cloud of
//! 100,000 points (domain: its hull). Each iteration evaluates 10,000 points spread over the mesh, in random
//! order, and once more sorted by y (neighbouring queries touch neighbouring memory, as particles that the engine
//! keeps in space order would).

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use gc2d_fluid::vtk::Cells;
use gc2d_fluid::{FieldSamples, Interpolation, Outside, SampledField};
use gc2d_geometry::DVec2;
use std::hint::black_box;

/// A small deterministic generator of numbers in [0, 1).
struct Mix(u64);

impl Mix {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn velocity(p: [f64; 3]) -> DVec2 {
    DVec2::new((3.0 * p[1]).sin(), p[0] * p[1])
}

/// An nx × ny lattice on [0, 2] × [0, 1] with its quads as cells.
fn lattice(nx: usize, ny: usize) -> FieldSamples {
    let positions: Vec<[f64; 3]> = (0..nx * ny)
        .map(|k| [2.0 * (k % nx) as f64 / (nx - 1) as f64, (k / nx) as f64 / (ny - 1) as f64, 0.0])
        .collect();
    let mut cells = Cells { offsets: vec![0], indices: Vec::new() };
    for j in 0..ny - 1 {
        for i in 0..nx - 1 {
            let a = i + nx * j;
            cells.indices.extend([a, a + 1, a + 1 + nx, a + nx]);
            cells.offsets.push(cells.indices.len());
        }
    }
    FieldSamples {
        source: "lattice".into(),
        velocities: positions.iter().map(|&p| velocity(p)).collect(),
        mesh_points: positions.clone(),
        positions,
        cells,
    }
}

fn cloud(mix: &mut Mix) -> FieldSamples {
    let positions: Vec<[f64; 3]> = (0..100_000).map(|_| [2.0 * mix.unit(), mix.unit(), 0.0]).collect();
    FieldSamples {
        source: "cloud".into(),
        velocities: positions.iter().map(|&p| velocity(p)).collect(),
        mesh_points: Vec::new(),
        positions,
        cells: Cells::default(),
    }
}

fn fields(c: &mut Criterion) {
    let mut mix = Mix(1);
    let queries: Vec<DVec2> =
        (0..10_000).map(|_| DVec2::new(0.01 + 1.98 * mix.unit(), 0.01 + 0.98 * mix.unit())).collect();
    let large = lattice(317, 316);
    let thesis = lattice(21, 21);
    let cloud = cloud(&mut mix);
    let cases = [
        ("bilinear 21x21 lattice", SampledField::new(&thesis, Interpolation::Bilinear, Outside::Zero).unwrap()),
        (
            "shepard 21x21 lattice nodes, quad cells",
            SampledField::new(&thesis, Interpolation::SHEPARD_THESIS, Outside::Zero).unwrap(),
        ),
        ("bilinear 100k lattice", SampledField::new(&large, Interpolation::Bilinear, Outside::Zero).unwrap()),
        (
            "shepard 100k lattice nodes, quad cells",
            SampledField::new(&large, Interpolation::SHEPARD_THESIS, Outside::Zero).unwrap(),
        ),
        ("shepard 100k random cloud", SampledField::new(&cloud, Interpolation::SHEPARD_THESIS, Outside::Zero).unwrap()),
    ];
    let mut sorted = queries.clone();
    sorted.sort_by(|a, b| a.y.total_cmp(&b.y));
    let mut group = c.benchmark_group("field");
    group.throughput(Throughput::Elements(queries.len() as u64));
    for (name, field) in &cases {
        for (order, points) in [("random order", &queries), ("sorted", &sorted)] {
            group.bench_function(format!("{name}, {order}"), |b| {
                b.iter(|| {
                    let mut sum = DVec2::ZERO;
                    for &q in points {
                        sum += field.velocity(black_box(q)).unwrap();
                    }
                    sum
                })
            });
        }
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(3));
    targets = fields
}
criterion_main!(benches);
