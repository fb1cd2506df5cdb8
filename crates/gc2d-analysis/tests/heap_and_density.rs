//! Angle of repose on synthetic heaps, and packing density with the convex-hull correction.

mod common;

use approx::assert_relative_eq;
use common::*;
use gc2d_analysis::*;
use gc2d_geometry::DVec2;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// `count` squares of side `d` at uniformly random positions under a symmetric triangle of base `base` and flank
/// angle `angle_degrees` with its foot at the origin (each square's top at or below the flank line). The squares may
/// overlap: the fit reads only centroids and the envelope only outlines. A lattice would be a poor test, since its
/// staircase surface snaps to rational slopes (26.8° comes out as the lattice's 26.57°).
fn random_heap(base: f64, angle_degrees: f64, d: f64, count: usize, seed: u64) -> Snapshot {
    let tan = angle_degrees.to_radians().tan();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut particles = Vec::with_capacity(count);
    while particles.len() < count {
        let c = DVec2::new(rng.random_range(0.0..base), rng.random_range(0.0..0.5 * base * tan));
        if c.y >= 0.5 * d && c.y + 0.5 * d <= tan * c.x.min(base - c.x) {
            particles.push(square_particle(particles.len() as u32, c, d, DENSITY));
        }
    }
    Snapshot { time: 0.0, gravity: G, particles, walls: Vec::new(), contacts: Vec::new() }
}

#[test]
fn fit_method_recovers_the_flank_angle_of_a_rough_heap() {
    let (base, d) = (0.2, 0.0005);
    for (angle, seed) in [(26.8, 1), (33.0, 2), (20.0, 3)] {
        let tan = f64::to_radians(angle).tan();
        let count = (0.25 * base * base * tan / (d * d)) as usize;
        let heap = random_heap(base, angle, d, count, seed);
        let repose = angle_of_repose(&heap, &FlankOptions::default()).expect("a heap");
        let left = repose.left.as_ref().expect("left flank");
        let right = repose.right.as_ref().expect("right flank");
        assert!((left.angle_degrees - angle).abs() < 0.5, "left {} vs {angle}", left.angle_degrees);
        assert!((right.angle_degrees - angle).abs() < 0.5, "right {} vs {angle}", right.angle_degrees);
        assert!(left.points.len() >= 50, "{} bins", left.points.len());
        assert!((repose.mean_degrees.unwrap() - angle).abs() < 0.5);
        // The feet are thin wedges that random points seldom reach: the width is short by a few particles.
        assert!(repose.shape.width <= base && repose.shape.width > base - 10.0 * d, "{}", repose.shape.width);
        assert_relative_eq!(repose.shape.apex_x, 0.5 * base, epsilon = 10.0 * d);
        assert_relative_eq!(repose.shape.height, 0.5 * base * tan, epsilon = 4.0 * d);
        // The area method sees the same outline; its envelope has particle-scale dents, so it is only close.
        assert!((repose.area_whole_degrees.unwrap() - angle).abs() < 1.5, "{:?}", repose.area_whole_degrees);
    }
}

#[test]
fn area_method_is_exact_for_a_triangular_outline() {
    // Two right-triangle particles make an isosceles heap of base 0.4 m and height 0.1 m: tan φ = 0.5.
    let h = 0.1;
    let left = vec![DVec2::new(0.0, 0.0), DVec2::new(0.2, 0.0), DVec2::new(0.2, h)];
    let right = vec![DVec2::new(0.2, 0.0), DVec2::new(0.4, 0.0), DVec2::new(0.2, h)];
    let particle = |id: u32, vertices: Vec<DVec2>| {
        let centroid = vertices.iter().copied().sum::<DVec2>() / 3.0;
        ParticleOutline { id, centroid, vertices, area: 0.01, mass: 50.0, is_disk: false }
    };
    let heap = Snapshot { gravity: G, particles: vec![particle(0, left), particle(1, right)], ..Default::default() };
    let repose = angle_of_repose(&heap, &FlankOptions { bin_width: 0.01, ..Default::default() }).unwrap();
    let expected = 0.5f64.atan().to_degrees();
    assert_relative_eq!(repose.area_left_degrees.unwrap(), expected, epsilon = 0.05);
    assert_relative_eq!(repose.area_right_degrees.unwrap(), expected, epsilon = 0.05);
    assert_relative_eq!(repose.area_whole_degrees.unwrap(), expected, epsilon = 0.05);
    assert_relative_eq!(repose.shape.apex_x, 0.2, epsilon = 1e-3);
    assert_relative_eq!(repose.shape.height, h, max_relative = 1e-12);
}

#[test]
fn full_rectangle_of_squares_has_density_one_inside() {
    let d = 0.002;
    let block = block_of_squares(50, 40, d, 0.0);
    // An off-lattice test area cuts squares on all four sides: exact clipping still sums to its area.
    let rect = Rect::new(DVec2::new(0.0123, 0.0171), DVec2::new(0.0567, 0.0489));
    let density = local_density(&block, rect);
    assert_relative_eq!(density.simple, 1.0, max_relative = 1e-9);
    assert_relative_eq!(density.corrected, 1.0, max_relative = 1e-9);
    assert_relative_eq!(density.hull_area, rect.area(), max_relative = 1e-9);
    let total = bulk_packing_fraction(&block);
    assert_relative_eq!(total, 1.0, max_relative = 1e-9);
}

#[test]
fn hull_correction_removes_the_dilution_at_a_free_surface() {
    let d = 0.002;
    let block = block_of_squares(50, 40, d, 0.0);
    // Reaches 0.0137 m above the top (y = 0.08) and 0.005 m past the left side: 2.44 counts the empty part.
    let rect = Rect::new(DVec2::new(-0.005, 0.0611), DVec2::new(0.0301, 0.0937));
    let density = local_density(&block, rect);
    let filled = (0.0301 - 0.0) * (0.08 - 0.0611);
    assert_relative_eq!(density.particle_area, filled, max_relative = 1e-9);
    assert_relative_eq!(density.simple, filled / rect.area(), max_relative = 1e-9);
    assert_relative_eq!(density.corrected, 1.0, max_relative = 1e-9);
    assert_relative_eq!(density.hull_area, filled, max_relative = 1e-9);
}

#[test]
fn spaced_squares_give_the_lattice_packing_fraction() {
    // Squares of side 2 mm on a 2.5 mm lattice: ρ_rel = 0.64 in a test area of whole lattice cells.
    let (d, s) = (0.002, 0.0025);
    let particles: Vec<ParticleOutline> = (0..20)
        .flat_map(|j| (0..20).map(move |i| (i, j)))
        .map(|(i, j)| square_particle(0, DVec2::new(s * (i as f64 + 0.5), s * (j as f64 + 0.5)), d, DENSITY))
        .collect();
    let lattice = Snapshot { particles, ..Default::default() };
    let rect = Rect::new(DVec2::new(5.0 * s, 5.0 * s), DVec2::new(15.0 * s, 13.0 * s));
    let density = local_density(&lattice, rect);
    assert_relative_eq!(density.simple, 0.64, max_relative = 1e-9);
    assert_eq!(density.particles, 80);
    // The grid of 2×2 lattice cells sees the same everywhere inside.
    let grid = Grid::with_cell_size(Rect::new(DVec2::ZERO, DVec2::splat(20.0 * s)), 2.0 * s);
    assert_eq!((grid.nx, grid.ny), (10, 10));
    for cell in density_grid(&lattice, &grid) {
        assert_relative_eq!(cell.simple, 0.64, max_relative = 1e-9);
    }
}

#[test]
fn convex_hull_of_a_square_with_interior_and_collinear_points() {
    let mut points = square(DVec2::new(1.0, 2.0), 2.0);
    points.extend([DVec2::new(1.0, 2.0), DVec2::new(1.0, 1.0), DVec2::new(0.5, 2.5), DVec2::new(f64::NAN, 0.0)]);
    let hull = convex_hull(&points);
    assert_eq!(hull.len(), 4);
    assert_relative_eq!(polygon_area(&hull), 4.0, max_relative = 1e-12);
    assert_eq!(hull_area(&[DVec2::ZERO, DVec2::X, DVec2::new(2.0, 0.0)]), 0.0);
    assert_eq!(hull_area(&[]), 0.0);
}
