//! Analytic fields, ramps and snapshot series.

use gc2d_fluid::vtk::Cells;
use gc2d_fluid::{
    FieldSamples, FieldSnapshot, FluidField, Interpolation, Outside, Poiseuille, PoiseuilleError, RampShape,
    SampledField, SeriesError, SnapshotSeries, TimeInterpolation, TimeRamp,
};
use gc2d_geometry::DVec2;

#[test]
fn poiseuille_profile_across_a_tilted_channel() {
    // Axis through (1, 2) at 30° to x, half-width 0.1 m, 3 m/s on the axis; the direction need not be unit.
    let e = DVec2::new(30f64.to_radians().cos(), 30f64.to_radians().sin());
    let channel = Poiseuille::new(DVec2::new(1.0, 2.0), 5.0 * e, 0.1, 3.0).unwrap();
    let field = FluidField::Poiseuille(channel);
    let across = e.perp();
    let at = |along: f64, d: f64| field.velocity(DVec2::new(1.0, 2.0) + along * e + d * across, 0.0).unwrap();
    for (d, factor) in [(0.0, 1.0), (0.05, 0.75), (-0.05, 0.75), (0.08, 0.36), (0.1, 0.0), (-0.1, 0.0)] {
        let u = at(7.0, d);
        assert!((u - 3.0 * factor * e).length() < 1e-12, "d = {d}: {u}");
    }
    assert_eq!(at(0.0, 0.1000001), DVec2::ZERO, "zero outside the channel");
    // The mean over the width is 2/3 of the centre speed (midpoint rule, 2000 strips).
    let mean: f64 = (0..2000).map(|k| at(0.0, -0.1 + 0.2 * (k as f64 + 0.5) / 2000.0).dot(e)).sum::<f64>() / 2000.0;
    assert!((mean - 2.0).abs() < 1e-6, "{mean}");
    assert_eq!(Poiseuille::new(DVec2::ZERO, DVec2::ZERO, 0.1, 1.0), Err(PoiseuilleError::Direction(0.0, 0.0)));
    assert_eq!(Poiseuille::new(DVec2::ZERO, DVec2::Y, -0.1, 1.0), Err(PoiseuilleError::HalfWidth(-0.1)));
}

#[test]
fn ramps_linear_smooth_and_step() {
    let linear = TimeRamp { start_s: 0.5, end_s: 1.5, shape: RampShape::Linear };
    let smooth = TimeRamp { shape: RampShape::Smooth, ..linear };
    for (t, l, s) in
        [(0.0, 0.0, 0.0), (0.5, 0.0, 0.0), (0.75, 0.25, 0.15625), (1.0, 0.5, 0.5), (1.5, 1.0, 1.0), (9.0, 1.0, 1.0)]
    {
        assert_eq!((linear.factor(t), smooth.factor(t)), (l, s), "t = {t}");
    }
    // The smooth ramp starts and ends flat: its slope at the ends is O(h).
    let h = 1e-6;
    assert!(smooth.factor(0.5 + h) < 1e-11 && 1.0 - smooth.factor(1.5 - h) < 1e-11);
    let step = TimeRamp { start_s: 2.0, end_s: 2.0, shape: RampShape::Linear };
    assert_eq!((step.factor(1.999), step.factor(2.0)), (0.0, 1.0));
    let field = FluidField::Ramped { field: Box::new(FluidField::Uniform(DVec2::new(0.0, 4.0))), ramp: linear };
    assert_eq!(field.velocity(DVec2::new(3.0, -1.0), 1.25).unwrap(), DVec2::new(0.0, 3.0));
}

/// A loaded snapshot whose velocity is `a + b·x` at every node of a 3 × 3 lattice on [0, 1]².
fn snapshot(time_s: f64, a: DVec2, b: DVec2) -> FieldSnapshot {
    let positions: Vec<[f64; 3]> = (0..9).map(|k| [(k % 3) as f64 * 0.5, (k / 3) as f64 * 0.5, 0.0]).collect();
    let samples = FieldSamples {
        source: format!("U_{time_s}.vtk"),
        velocities: positions.iter().map(|p| a + b * p[0]).collect(),
        mesh_points: positions.clone(),
        positions,
        cells: Cells::default(),
    };
    FieldSnapshot { time_s, field: SampledField::new(&samples, Interpolation::Bilinear, Outside::Error).unwrap() }
}

#[test]
fn a_series_interpolates_linearly_between_its_snapshots_times() {
    let snapshots = vec![
        snapshot(0.1, DVec2::new(1.0, 0.0), DVec2::ZERO),
        snapshot(0.3, DVec2::new(3.0, 2.0), DVec2::new(0.0, 1.0)),
        snapshot(0.4, DVec2::new(-1.0, 0.0), DVec2::ZERO),
    ];
    let series = FluidField::Series(SnapshotSeries::new(snapshots.clone(), TimeInterpolation::Linear).unwrap());
    let x = DVec2::new(0.5, 0.25);
    let u = |t: f64| series.velocity(x, t).unwrap();
    assert_eq!(u(0.0), DVec2::new(1.0, 0.0), "before the first: the first");
    assert_eq!(u(0.1), DVec2::new(1.0, 0.0));
    // At 0.15, a quarter of the way from the first (1, 0) to the second (3, 2 + 0.5).
    assert!((u(0.15) - DVec2::new(1.5, 0.625)).length() < 1e-15);
    assert_eq!(u(0.3), DVec2::new(3.0, 2.5));
    assert!((u(0.35) - DVec2::new(1.0, 1.25)).length() < 1e-15);
    assert_eq!(u(7.0), DVec2::new(-1.0, 0.0), "after the last: the last");
    // The thesis's piecewise-constant hold.
    let hold = SnapshotSeries::new(snapshots.clone(), TimeInterpolation::Hold).unwrap();
    assert_eq!(hold.velocity(x, 0.29).unwrap(), DVec2::new(1.0, 0.0));
    assert_eq!(hold.velocity(x, 0.3).unwrap(), DVec2::new(3.0, 2.5));
    // Off the mesh, either snapshot's error.
    assert!(series.velocity(DVec2::new(2.0, 0.0), 0.2).unwrap_err().to_string().contains("U_0.1.vtk"));
    let unordered = vec![snapshots[1].clone(), snapshots[0].clone()];
    let e = SnapshotSeries::new(unordered, TimeInterpolation::Linear).unwrap_err();
    assert!(
        matches!(e, SeriesError::Times { .. }) && e.to_string().contains("U_0.1.vtk at 0.1 s follows 0.3 s"),
        "{e}"
    );
    assert_eq!(SnapshotSeries::new(Vec::new(), TimeInterpolation::Linear).unwrap_err(), SeriesError::Empty);
}
