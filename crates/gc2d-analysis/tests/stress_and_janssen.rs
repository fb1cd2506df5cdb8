//! Stress tensor (2.52) on loaded columns, principal axes, and the Janssen fit (3.4).

mod common;

use approx::assert_relative_eq;
use common::*;
use gc2d_analysis::*;
use gc2d_geometry::DVec2;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// `nx` columns of `ny` squares of side `d` between a floor and a piston, each column pressed with `load_per_column`
/// (no gravity): every contact carries the load, the force points are the midpoints of the touching edges.
fn loaded_block(nx: usize, ny: usize, d: f64, load_per_column: f64) -> Snapshot {
    let mut snapshot = block_of_squares(nx, ny, d, 0.0);
    snapshot.gravity = 0.0;
    let top = ny as f64 * d;
    snapshot.walls.push(wall(0, rectangle(DVec2::new(0.0, -d), DVec2::new(nx as f64 * d, 0.0))));
    snapshot.walls.push(wall(1, rectangle(DVec2::new(0.0, top), DVec2::new(nx as f64 * d, top + d))));
    let index = |i: usize, j: usize| j * nx + i;
    let up = DVec2::new(0.0, load_per_column);
    for i in 0..nx {
        let x = d * (i as f64 + 0.5);
        snapshot.contacts.push(contact(BodyRef::Particle(index(i, 0)), BodyRef::Wall(0), up, DVec2::new(x, 0.0)));
        for j in 1..ny {
            let point = DVec2::new(x, d * j as f64);
            snapshot.contacts.push(contact(
                BodyRef::Particle(index(i, j)),
                BodyRef::Particle(index(i, j - 1)),
                up,
                point,
            ));
        }
        snapshot.contacts.push(contact(BodyRef::Particle(index(i, ny - 1)), BodyRef::Wall(1), -up, DVec2::new(x, top)));
    }
    snapshot
}

#[test]
fn single_file_column_stress_is_load_over_width_with_vertical_axis() {
    let (d, load) = (0.002, 3.0);
    let column = loaded_block(1, 12, d, load);
    let rect = Rect::new(DVec2::new(-0.001, 0.0), DVec2::new(0.003, 12.0 * d));
    let stress = local_stress(&column, rect, &StressOptions::default()).expect("stress");
    // The force points are collinear: the force-point hull is degenerate and the particle hull d × H is used.
    assert_eq!(stress.volume_used, StressVolume::ParticleHull);
    assert_relative_eq!(stress.volume, d * 12.0 * d, max_relative = 1e-12);
    assert_eq!(stress.particles, 12);
    assert_relative_eq!(stress.sigma.yy, load / d, max_relative = 1e-9);
    assert_relative_eq!(stress.sigma.xx, 0.0, epsilon = 1e-9);
    assert_relative_eq!(stress.sigma.xy, 0.0, epsilon = 1e-9);
    assert_relative_eq!(stress.principal.major, load / d, max_relative = 1e-9);
    assert_relative_eq!(stress.principal.psi_degrees, 0.0, epsilon = 1e-9);
}

#[test]
fn wide_block_stress_with_both_volume_choices() {
    let (nx, ny, d, load) = (10, 10, 0.002, 2.0);
    let block = loaded_block(nx, ny, d, load);
    let rect = Rect::new(DVec2::ZERO, DVec2::new(nx as f64 * d, ny as f64 * d));
    let applied = nx as f64 * load / (nx as f64 * d);
    let particle_hull =
        local_stress(&block, rect, &StressOptions { volume: StressVolume::ParticleHull }).expect("stress");
    assert_relative_eq!(particle_hull.sigma.yy, applied, max_relative = 1e-9);
    assert_relative_eq!(particle_hull.principal.psi_degrees, 0.0, epsilon = 1e-9);
    // The thesis's V: the force points span (nx − 1) d by ny d, so σ_zz comes out nx/(nx − 1) larger.
    let force_hull = local_stress(&block, rect, &StressOptions::default()).expect("stress");
    assert_eq!(force_hull.volume_used, StressVolume::ForcePointHull);
    assert_relative_eq!(force_hull.volume, (nx - 1) as f64 * d * ny as f64 * d, max_relative = 1e-9);
    assert_relative_eq!(force_hull.sigma.yy, applied * nx as f64 / (nx - 1) as f64, max_relative = 1e-9);
    // A test area over the middle rows: internal forces on its boundary give the same stress.
    let inner = Rect::new(DVec2::new(0.0, 3.0 * d), DVec2::new(nx as f64 * d, 7.0 * d));
    let inner_stress = local_stress(&block, inner, &StressOptions { volume: StressVolume::ParticleHull }).unwrap();
    assert_eq!(inner_stress.particles, 4 * nx);
    assert_relative_eq!(inner_stress.sigma.yy, applied, max_relative = 1e-9);
    // A grid of 2 × 2 cells over the block sees the same uniform stress in every cell.
    let grid = Grid::with_cell_size(rect, 5.0 * d);
    let cells = stress_grid(&block, &grid, &StressOptions { volume: StressVolume::ParticleHull });
    assert_eq!(cells.len(), 4);
    for cell in cells {
        assert_relative_eq!(cell.sigma.yy, applied, max_relative = 1e-9);
    }
}

#[test]
fn principal_axis_angle_of_a_rotated_tensor() {
    for psi in [-60.0f64, -10.0, 0.0, 25.0, 45.0, 80.0] {
        let (major, minor) = (5.0, 2.0);
        let u = DVec2::new(-psi.to_radians().sin(), psi.to_radians().cos());
        let v = DVec2::new(u.y, -u.x);
        let sigma = StressTensor {
            xx: major * u.x * u.x + minor * v.x * v.x,
            xy: major * u.x * u.y + minor * v.x * v.y,
            yy: major * u.y * u.y + minor * v.y * v.y,
        };
        let p = sigma.principal();
        assert_relative_eq!(p.major, major, max_relative = 1e-12);
        assert_relative_eq!(p.minor, minor, max_relative = 1e-12);
        assert_relative_eq!(p.psi_degrees, psi, epsilon = 1e-9);
    }
    let isotropic = StressTensor { xx: 1.0, xy: 0.0, yy: 1.0 }.principal();
    assert_eq!(isotropic.psi_degrees, 0.0);
}

#[test]
fn janssen_fit_recovers_mu_j_from_a_noisy_profile() {
    // The thesis's silo (§7.1): r = 5 cm, ρ = 0.78 · 5000 kg/m², k = 0.64, μ_j = 0.33, depths to 0.4 m.
    let parameters = JanssenParameters { k: 0.64, rho: 0.78 * 5000.0, g: G, half_width: 0.05 };
    let mu_j = 0.33;
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let noise = Normal::new(0.0, 0.03).unwrap();
    let depth: Vec<f64> = (1..=80).map(|i| i as f64 * 0.005).collect();
    let sigma: Vec<f64> =
        depth.iter().map(|&z| parameters.sigma_xx(z, mu_j) * (1.0 + noise.sample(&mut rng))).collect();
    let fit = fit_janssen(&depth, &sigma, parameters).expect("fit");
    assert_relative_eq!(fit.mu_j, mu_j, max_relative = 0.02);
    assert_relative_eq!(fit.saturation_depth, 0.05 / (0.64 * fit.mu_j), max_relative = 1e-12);
    assert_relative_eq!(fit.asymptotic_pressure, 3900.0 * G * 0.05 / fit.mu_j, max_relative = 1e-12);
    assert!(fit.relative_rms_residual < 0.03, "{}", fit.relative_rms_residual);
    // Without noise the fit is exact.
    let exact: Vec<f64> = depth.iter().map(|&z| parameters.sigma_xx(z, mu_j)).collect();
    let fit = fit_janssen(&depth, &exact, parameters).expect("fit");
    assert_relative_eq!(fit.mu_j, mu_j, max_relative = 1e-6);
    assert!(fit.relative_rms_residual < 1e-6);
}

#[test]
fn janssen_fit_refuses_bad_input() {
    let parameters = JanssenParameters { k: 0.64, rho: 3900.0, g: G, half_width: 0.05 };
    assert!(matches!(fit_janssen(&[0.1], &[10.0], parameters), Err(AnalysisError::NotEnoughData(_))));
    let bad = JanssenParameters { k: f64::NAN, ..parameters };
    assert!(matches!(fit_janssen(&[0.1, 0.2], &[1.0, 2.0], bad), Err(AnalysisError::InvalidParameter(_))));
    let fit = fit_janssen(&[0.1, 0.2, f64::NAN], &[f64::INFINITY, 50.0, 1.0], parameters);
    assert!(matches!(fit, Err(AnalysisError::NotEnoughData(_))));
}
