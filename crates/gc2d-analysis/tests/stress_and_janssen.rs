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

#[test]
fn free_k_fit_recovers_mu_j_and_k_from_a_noisy_profile() {
    // The same thesis silo; the fit is told neither k nor μ_j.
    let parameters = JanssenParameters { k: 0.64, rho: 0.78 * 5000.0, g: G, half_width: 0.05 };
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let noise = Normal::new(0.0, 0.03).unwrap();
    let depth: Vec<f64> = (1..=80).map(|i| i as f64 * 0.005).collect();
    let sigma: Vec<f64> =
        depth.iter().map(|&z| parameters.sigma_xx(z, 0.33) * (1.0 + noise.sample(&mut rng))).collect();
    let fit = fit_janssen_free_k(&depth, &sigma, parameters.rho, G, 0.05).expect("fit");
    assert_relative_eq!(fit.mu_j, 0.33, max_relative = 0.05);
    assert_relative_eq!(fit.k, 0.64, max_relative = 0.05);
    assert_relative_eq!(fit.saturation_depth, 0.05 / (fit.k * fit.mu_j), max_relative = 1e-9);
    assert!(fit.relative_rms_residual < 0.03, "{}", fit.relative_rms_residual);
    let exact: Vec<f64> = depth.iter().map(|&z| parameters.sigma_xx(z, 0.33)).collect();
    let fit = fit_janssen_free_k(&depth, &exact, parameters.rho, G, 0.05).expect("fit");
    assert_relative_eq!(fit.mu_j, 0.33, max_relative = 1e-6);
    assert_relative_eq!(fit.k, 0.64, max_relative = 1e-6);
}

#[test]
fn free_k_fit_reads_mu_j_off_the_plateau_where_k_varies_with_depth() {
    // k falls from 1.0 at the surface to 0.5 at depth, so the profile is not (3.4) with any one k; the free-k fit's
    // asymptote still gives μ_j = ρ g r / plateau once the column reaches the plateau (here five saturation depths).
    let (rho, r, mu_j) = (4000.0, 0.02, 0.33);
    let depth: Vec<f64> = (1..=120).map(|i| i as f64 * 0.005).collect();
    let mut sigma_zz = 0.0;
    let dz = 1e-5;
    let mut z = 0.0;
    let mut sigma_xx = Vec::new();
    for &target in &depth {
        let k = |z: f64| 0.5 + 0.5 * (-z / 0.05).exp();
        while z < target - 0.5 * dz {
            sigma_zz += dz * (rho * G - mu_j * k(z) * sigma_zz / r);
            z += dz;
        }
        sigma_xx.push(k(z) * sigma_zz);
    }
    let fit = fit_janssen_free_k(&depth, &sigma_xx, rho, G, r).expect("fit");
    assert_relative_eq!(fit.mu_j, mu_j, max_relative = 0.05);
}

#[test]
fn free_k_fit_refuses_a_profile_that_does_not_saturate() {
    let depth = [0.05, 0.1, 0.15, 0.2];
    let hydrostatic: Vec<f64> = depth.iter().map(|z| 3900.0 * G * z).collect();
    let fit = fit_janssen_free_k(&depth, &hydrostatic, 3900.0, G, 0.05);
    assert!(matches!(fit, Err(AnalysisError::NotEnoughData(ref m)) if m.contains("does not saturate")), "{fit:?}");
    assert!(matches!(
        fit_janssen_free_k(&[0.1, 0.2], &[1.0, 2.0], 3900.0, G, 0.05),
        Err(AnalysisError::NotEnoughData(_))
    ));
    assert!(matches!(
        fit_janssen_free_k(&[0.1, 0.2, 0.3], &[1.0, 2.0, 2.5], 3900.0, G, -0.05),
        Err(AnalysisError::InvalidParameter(_))
    ));
}
