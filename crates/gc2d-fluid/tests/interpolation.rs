//! Loaded fields: bilinear interpolation is exact for bilinear fields, Shepard's method reproduces constants and
//! node values and equals the formula of feedpipe.md §4.4, the z-layers merge, points off the mesh get what the
//! scene chose, and evaluating allocates nothing.

use gc2d_fluid::vtk::{Cells, DataLocation, VtkFile};
use gc2d_fluid::{FieldSamples, Interpolation, Outside, SampledError, SampledField};
use gc2d_geometry::DVec2;

#[global_allocator]
static GLOBAL: gc2d_alloc_count::CountingAllocator = gc2d_alloc_count::CountingAllocator;

/// A small deterministic generator of numbers in [0, 1).
struct Mix(u64);

impl Mix {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn file(name: &str) -> VtkFile {
    VtkFile::read(&std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name)).unwrap()
}

/// Samples without cells (the domain is then the nodes' convex hull).
fn samples(positions: Vec<[f64; 3]>, velocities: Vec<DVec2>) -> FieldSamples {
    FieldSamples {
        source: "test".into(),
        mesh_points: positions.clone(),
        positions,
        velocities,
        cells: Cells::default(),
    }
}

/// A random cloud of `n` points in [0, 2] × [0, 1].
fn cloud(n: usize, mix: &mut Mix) -> Vec<[f64; 3]> {
    (0..n).map(|_| [2.0 * mix.unit(), mix.unit(), 0.0]).collect()
}

#[test]
fn bilinear_reproduces_any_bilinear_field_on_an_uneven_two_layer_lattice() {
    let mut mix = Mix(7);
    for _ in 0..20 {
        let [a, b, c, d, e, f, g, h] = [0; 8].map(|_| 10.0 * mix.unit() - 5.0);
        let field = |x: f64, y: f64| DVec2::new(a + b * x + c * y + d * x * y, e + f * x + g * y + h * x * y);
        let mut xs: Vec<f64> = (0..9).map(|_| -1.0 + 3.0 * mix.unit()).collect();
        let mut ys: Vec<f64> = (0..6).map(|_| 2.0 * mix.unit()).collect();
        xs.sort_by(f64::total_cmp);
        ys.sort_by(f64::total_cmp);
        // Both z-layers, in a scrambled order.
        let mut positions = Vec::new();
        for z in [0.0, 0.05] {
            for &x in &xs {
                for &y in &ys {
                    positions.push([x, y, z]);
                }
            }
        }
        for i in (1..positions.len()).rev() {
            positions.swap(i, (mix.unit() * (i + 1) as f64) as usize);
        }
        let velocities = positions.iter().map(|p| field(p[0], p[1])).collect();
        let sampled =
            SampledField::new(&samples(positions, velocities), Interpolation::Bilinear, Outside::Error).unwrap();
        assert_eq!(sampled.node_count(), 54);
        for _ in 0..500 {
            let p = DVec2::new(xs[0] + (xs[8] - xs[0]) * mix.unit(), ys[0] + (ys[5] - ys[0]) * mix.unit());
            let (got, want) = (sampled.velocity(p).unwrap(), field(p.x, p.y));
            assert!((got - want).abs().max_element() <= 1e-12 * want.abs().max_element().max(1.0), "{p}: {got} {want}");
        }
    }
}

#[test]
fn bilinear_on_the_thesis_layout_file_is_exact_and_needs_a_lattice() {
    let vtk = file("feedpipe_unstructured.vtk");
    let points = vtk.velocity_samples("U", DataLocation::Points).unwrap();
    let field = SampledField::new(&points, Interpolation::Bilinear, Outside::Error).unwrap();
    assert_eq!(field.node_count(), 12, "24 points in two z-layers are 12 nodes");
    let mut mix = Mix(3);
    for _ in 0..200 {
        let p = DVec2::new(2.0 * mix.unit(), mix.unit());
        let want = DVec2::new(1.0 + 2.0 * p.x + 3.0 * p.y + 4.0 * p.x * p.y, -0.5 + p.x - p.y + 0.25 * p.x * p.y);
        assert!((field.velocity(p).unwrap() - want).abs().max_element() < 1e-12);
    }
    let sheared = file("structured_grid.vtk").velocity_samples("U", DataLocation::Points).unwrap();
    let e = SampledField::new(&sheared, Interpolation::Bilinear, Outside::Error).unwrap_err();
    assert!(matches!(e, SampledError::NotALattice { columns: 6, rows: 2, nodes: 6, .. }), "{e}");
    assert!(e.to_string().contains("structured_grid.vtk: bilinear interpolation needs"), "{e}");
}

/// Shepard's formula (3.69)–(3.71) by brute force over all nodes: the k nearest, w = h^−p / Σ h^−p.
fn shepard_brute(nodes: &[[f64; 3]], values: &[DVec2], p: DVec2, k: usize, power: f64) -> DVec2 {
    let mut order: Vec<(f64, usize)> =
        nodes.iter().enumerate().map(|(i, n)| ((DVec2::new(n[0], n[1]) - p).length(), i)).collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let near = &order[..k];
    let total: f64 = near.iter().map(|(h, _)| h.powf(-power)).sum();
    near.iter().map(|&(h, i)| values[i] * (h.powf(-power) / total)).sum()
}

#[test]
fn shepard_equals_its_formula_reproduces_constants_and_returns_node_values() {
    let mut mix = Mix(11);
    let nodes = cloud(400, &mut mix);
    let values: Vec<DVec2> = nodes.iter().map(|n| DVec2::new(n[0].sin(), n[0] * n[1] - 1.0)).collect();
    for (power, k) in [(2.0, 4), (1.0, 1), (3.5, 9)] {
        let interpolation = Interpolation::Shepard { power, neighbours: k };
        let field = SampledField::new(&samples(nodes.clone(), values.clone()), interpolation, Outside::Error).unwrap();
        let constant = vec![DVec2::new(0.3, -1.7); nodes.len()];
        let flat = SampledField::new(&samples(nodes.clone(), constant), interpolation, Outside::Error).unwrap();
        for _ in 0..300 {
            let p = DVec2::new(0.2 + 1.6 * mix.unit(), 0.1 + 0.8 * mix.unit());
            let want = shepard_brute(&nodes, &values, p, k, power);
            assert!((field.velocity(p).unwrap() - want).abs().max_element() < 1e-12, "{p}");
            assert_eq!(flat.velocity(p).unwrap(), DVec2::new(0.3, -1.7), "constants exactly, {p}");
        }
        for (n, v) in nodes.iter().zip(&values).take(50) {
            assert_eq!(field.velocity(DVec2::new(n[0], n[1])).unwrap(), *v, "a node's own value");
        }
    }
}

#[test]
fn the_two_z_layers_merge_so_four_neighbours_are_four_places() {
    // One 1 m × 1 m cell, corners with different velocities, both layers listed (8 points), the back layer's
    // velocities slightly different: each node takes the mean of its two.
    let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let mut positions = Vec::new();
    let mut velocities = Vec::new();
    for (layer, z) in [0.0, 0.1].into_iter().enumerate() {
        for (i, c) in corners.iter().enumerate() {
            positions.push([c[0], c[1], z]);
            velocities.push(DVec2::new(i as f64 + 0.5 * layer as f64, 0.0));
        }
    }
    let field =
        SampledField::new(&samples(positions, velocities), Interpolation::SHEPARD_THESIS, Outside::Error).unwrap();
    assert_eq!(field.node_count(), 4);
    // At a node: the mean of its two layers. At the centre: all four corners weigh alike.
    assert_eq!(field.velocity(DVec2::new(1.0, 0.0)).unwrap(), DVec2::new(1.25, 0.0));
    assert!((field.velocity(DVec2::new(0.5, 0.5)).unwrap().x - (0.25 + 1.25 + 2.25 + 3.25) / 4.0).abs() < 1e-15);
}

#[test]
fn outside_the_mesh_zero_nearest_or_error() {
    // Shepard on the real cavity export: its mesh is the square [0, 0.1]²; the lid's nodes move at 1 m/s.
    let samples = file("foam_cavity.vtk").velocity_samples("U", DataLocation::Points).unwrap();
    let lid_above = DVec2::new(0.05, 0.3);
    let inside = DVec2::new(0.05, 0.05);
    for interpolation in [Interpolation::SHEPARD_THESIS, Interpolation::Bilinear] {
        let make = |outside| SampledField::new(&samples, interpolation, outside).unwrap();
        assert_eq!(make(Outside::Zero).velocity(lid_above).unwrap(), DVec2::ZERO);
        assert_eq!(make(Outside::Nearest).velocity(lid_above).unwrap(), DVec2::new(1.0, 0.0));
        let e = make(Outside::Error).velocity(lid_above).unwrap_err();
        assert_eq!(e.position, lid_above);
        assert!(e.to_string().contains("foam_cavity.vtk was sampled at (0.05, 0.3) m, outside its mesh"), "{e}");
        for outside in [Outside::Zero, Outside::Nearest, Outside::Error] {
            assert_eq!(make(outside).velocity(inside).unwrap(), make(Outside::Zero).velocity(inside).unwrap());
        }
    }
    // Bilinear's nearest point lies on the lattice's edge: right of the cavity, on the wall at rest; above the lid
    // between its nodes, the lid's speed.
    let bilinear = SampledField::new(&samples, Interpolation::Bilinear, Outside::Nearest).unwrap();
    assert_eq!(bilinear.velocity(DVec2::new(0.2, 0.05)).unwrap(), DVec2::ZERO);
    assert_eq!(bilinear.velocity(DVec2::new(0.06, 0.5)).unwrap(), DVec2::new(1.0, 0.0));
}

#[test]
fn the_domain_follows_the_cells_not_the_hull() {
    // An L of three unit cells (one layer of quads): the notch (1..2, 1..2) is off the mesh although the nodes'
    // hull covers it.
    let points: Vec<[f64; 3]> = [[0., 0.], [1., 0.], [2., 0.], [0., 1.], [1., 1.], [2., 1.], [0., 2.], [1., 2.]]
        .map(|[x, y]| [x, y, 0.0])
        .to_vec();
    let cells = Cells { offsets: vec![0, 4, 8, 12], indices: vec![0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 7, 6] };
    let samples = FieldSamples {
        source: "L".into(),
        positions: points.clone(),
        velocities: vec![DVec2::X; 8],
        mesh_points: points,
        cells,
    };
    let field = SampledField::new(&samples, Interpolation::SHEPARD_THESIS, Outside::Zero).unwrap();
    assert_eq!(field.velocity(DVec2::new(1.5, 0.5)).unwrap(), DVec2::X);
    assert_eq!(field.velocity(DVec2::new(1.5, 1.5)).unwrap(), DVec2::ZERO);
}

#[test]
fn cell_data_interpolate_from_the_cell_centres() {
    let samples = file("feedpipe_unstructured.vtk").velocity_samples("U", DataLocation::Cells).unwrap();
    let field = SampledField::new(&samples, Interpolation::SHEPARD_THESIS, Outside::Error).unwrap();
    // At a cell centre, that cell's value; near a corner of the mesh (inside the cells, beyond the centres) too.
    assert_eq!(field.velocity(DVec2::new(0.75, 0.625)).unwrap(), samples.velocities[4]);
    assert!(field.velocity(DVec2::new(0.01, 0.01)).unwrap().is_finite());
}

#[test]
fn bad_shepard_settings_and_samples_are_refused() {
    let s = samples(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], vec![DVec2::X; 3]);
    for (power, neighbours) in [(0.0, 4), (f64::NAN, 4), (2.0, 0), (2.0, 65)] {
        let e = SampledField::new(&s, Interpolation::Shepard { power, neighbours }, Outside::Zero).unwrap_err();
        assert!(matches!(e, SampledError::Shepard { .. }), "{e}");
    }
    let mut bad = s.clone();
    bad.velocities[1].y = f64::INFINITY;
    assert_eq!(
        SampledField::new(&bad, Interpolation::SHEPARD_THESIS, Outside::Zero).unwrap_err().to_string(),
        "test: sample 1 has a non-finite position or velocity"
    );
    let empty = samples(Vec::new(), Vec::new());
    assert!(matches!(
        SampledField::new(&empty, Interpolation::Bilinear, Outside::Zero),
        Err(SampledError::Empty { .. })
    ));
}

#[test]
fn evaluation_allocates_nothing() {
    let mut mix = Mix(5);
    let nodes = cloud(2000, &mut mix);
    let values: Vec<DVec2> = nodes.iter().map(|n| DVec2::new(n[1], -n[0])).collect();
    let shepard = SampledField::new(&samples(nodes, values), Interpolation::SHEPARD_THESIS, Outside::Nearest).unwrap();
    let points = file("feedpipe_unstructured.vtk").velocity_samples("U", DataLocation::Points).unwrap();
    let bilinear = SampledField::new(&points, Interpolation::Bilinear, Outside::Nearest).unwrap();
    let queries: Vec<DVec2> = (0..1000).map(|_| DVec2::new(3.0 * mix.unit() - 0.5, 2.0 * mix.unit() - 0.5)).collect();
    let before = gc2d_alloc_count::thread_allocations();
    let mut sum = DVec2::ZERO;
    for &q in &queries {
        sum += shepard.velocity(q).unwrap() + bilinear.velocity(q).unwrap();
    }
    assert_eq!(gc2d_alloc_count::thread_allocations(), before);
    assert!(sum.is_finite());
}
