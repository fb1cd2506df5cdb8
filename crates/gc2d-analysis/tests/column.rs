//! A column of equal squares on a floor: floor pressure, pressure integral, coordination and force directions.

mod common;

use approx::assert_relative_eq;
use common::*;
use gc2d_analysis::*;
use gc2d_geometry::DVec2;

const N: usize = 10;
const D: f64 = 0.002;

#[test]
fn floor_pressure_under_a_column_is_its_weight_over_its_width() {
    let snapshot = column_on_floor(N, D, 0.05);
    let weight = snapshot.total_mass() * G;
    let forces = wall_forces(&snapshot, WallSelection::facing(Facing::Up));
    assert_eq!(forces.len(), 1);
    assert_relative_eq!(forces[0].normal_force, weight, max_relative = 1e-12);
    // A window of width 2b = D centred on the column: p = W / D.
    let options = ProfileOptions { half_width: 0.5 * D, step: 0.25 * D, moving_average: 1 };
    let profile = pressure_profile(&forces, &options, Some((-2.0 * D, 2.0 * D)));
    let centre = profile.positions.iter().position(|x| x.abs() < 1e-12).expect("a window centred on x = 0");
    assert_relative_eq!(profile.pressure[centre], weight / D, max_relative = 1e-12);
    assert_eq!(profile.pressure[0], 0.0, "no force two widths away");
    // (2.36): the mean over the whole floor face of length 0.1 m.
    let length = face_length(&snapshot, WallSelection::facing(Facing::Up));
    assert_relative_eq!(length, 0.1, max_relative = 1e-12);
    assert_relative_eq!(mean_pressure(&forces, length), weight / 0.1, max_relative = 1e-12);
    // The floor's side faces and bottom do not face up, and no wall faces sideways here.
    assert!(wall_forces(&snapshot, WallSelection::facing(Facing::Right)).is_empty());
    assert!(wall_forces(&snapshot, WallSelection { facing: Facing::Up, wall: Some(7) }).is_empty());
    assert_eq!(wall_forces(&snapshot, WallSelection { facing: Facing::Up, wall: Some(0) }).len(), 1);
}

#[test]
fn coordination_is_two_inside_and_one_on_top() {
    let snapshot = column_on_floor(N, D, 0.05);
    let k = coordination(&snapshot);
    assert_eq!(k.per_particle[N - 1], 1, "top square touches only the one below");
    assert!(k.per_particle[..N - 1].iter().all(|&c| c == 2), "{:?}", k.per_particle);
    assert_eq!(k.histogram, vec![0, 1, N - 1]);
    assert_eq!(k.rattlers, 0);
    assert_relative_eq!(k.mean, (2.0 * (N - 1) as f64 + 1.0) / N as f64, max_relative = 1e-12);

    let mut with_rattler = snapshot.clone();
    with_rattler.particles.push(common::square_particle(99, DVec2::new(0.02, 0.001), D, DENSITY));
    let k = coordination(&with_rattler);
    assert_eq!(k.histogram, vec![1, 1, N - 1]);
    assert_eq!(k.rattlers, 1);
}

#[test]
fn force_directions_are_all_vertical_and_symmetric() {
    let snapshot = column_on_floor(N, D, 0.05);
    let histogram = force_direction_histogram(&snapshot, 36);
    assert_eq!(histogram.forces, 2 * N);
    for (centre, fraction) in histogram.centers_degrees.iter().zip(&histogram.fraction) {
        let expected = if (centre - 90.0).abs() < 1e-9 || (centre - 270.0).abs() < 1e-9 { 0.5 } else { 0.0 };
        assert_relative_eq!(*fraction, expected, epsilon = 1e-12);
    }
    // P(α) = P(α + π) for any bin count that splits the circle evenly.
    let h = force_direction_histogram(&snapshot, 12);
    for k in 0..6 {
        assert_relative_eq!(h.fraction[k], h.fraction[k + 6], epsilon = 1e-12);
    }
}

#[test]
fn force_magnitudes_of_the_column_are_linear_in_height() {
    let snapshot = column_on_floor(N, D, 0.05);
    let histogram = force_magnitude_histogram(&snapshot, 0.1);
    // Forces are W·N, W·(N−1), …, W·1: mean W (N+1)/2.
    let weight = DENSITY * D * D * G;
    assert_relative_eq!(histogram.mean_force, weight * (N as f64 + 1.0) / 2.0, max_relative = 1e-12);
    let total: f64 = histogram.density.iter().map(|p| p * histogram.bin_width).sum();
    assert_relative_eq!(total, 1.0, max_relative = 1e-12);
    assert_eq!(histogram.contacts, N);
}

#[test]
fn pressure_integral_equals_the_total_floor_force_of_a_row() {
    // A row of squares of different masses on a floor, plus side-wall contacts that the floor selection must ignore.
    let d = 0.003;
    let mut snapshot = Snapshot { time: 0.0, gravity: G, ..Default::default() };
    snapshot.walls.push(wall(0, rectangle(DVec2::new(0.0, -d), DVec2::new(0.3, 0.0))));
    snapshot.walls.push(wall(1, rectangle(DVec2::new(-d, 0.0), DVec2::new(0.0, 0.1))));
    let mut weight = 0.0;
    for i in 0..60 {
        let x = 0.004 + i as f64 * 0.0047;
        let side = d * (1.0 + 0.3 * ((i * 7 % 11) as f64 / 11.0));
        let particle = common::square_particle(i + 2, DVec2::new(x, 0.5 * side), side, DENSITY);
        weight += particle.mass * G;
        snapshot.contacts.push(contact(
            BodyRef::Wall(0),
            BodyRef::Particle(snapshot.particles.len()),
            DVec2::new(0.0, -particle.mass * G),
            DVec2::new(x, 0.0),
        ));
        snapshot.particles.push(particle);
    }
    snapshot.contacts.push(contact(
        BodyRef::Particle(0),
        BodyRef::Wall(1),
        DVec2::new(0.5, 0.0),
        DVec2::new(0.0, 0.001),
    ));
    let forces = wall_forces(&snapshot, WallSelection::facing(Facing::Up));
    assert_eq!(forces.len(), 60);
    let options = ProfileOptions { half_width: 0.01, step: 0.0005, moving_average: 5 };
    let profile = pressure_profile(&forces, &options, None);
    assert_relative_eq!(profile.total_normal_force, weight, max_relative = 1e-12);
    // Rectangle rule on a window sum: exact up to one sample per window, step/(2b) = 2.5 %.
    assert_relative_eq!(profile.integral(), weight, max_relative = options.step / (2.0 * options.half_width));
    // The side wall's force is on a face with outward normal +x and is seen only by that selection (E7: along y).
    let side = wall_forces(&snapshot, WallSelection::facing(Facing::Right));
    assert_eq!(side.len(), 1);
    assert_relative_eq!(side[0].normal_force, 0.5, max_relative = 1e-12);
    assert_relative_eq!(side[0].along, 0.001, max_relative = 1e-12);
    // The smoothed profile keeps the integral (a moving average of a profile that is zero at both ends).
    let smoothed: f64 = profile.smoothed.iter().sum::<f64>() * profile.step;
    assert_relative_eq!(smoothed, profile.integral(), max_relative = 1e-9);
    // Scaled form: x into [0, 1] over the row, p/(ρgh).
    let scaled = profile.scaled(0.0, 0.3, 2.0);
    assert_eq!(scaled.len(), profile.positions.len());
    assert_relative_eq!(scaled[10].1, profile.pressure[10] / 2.0, max_relative = 1e-12);
}
