//! The shape-generic pair queries on shallow contacts (1e-3 of the radius deep) at the thesis's grain size
//! (1.75 mm) and 0.07 m from the origin: every pair family of the ball mill and the feed pipe, area law and
//! penetration law, to set beside `contact_geometry` of two polygons (benches/overlap.rs).

use criterion::{Criterion, criterion_group, criterion_main};
use gc2d_geometry::{DVec2, ShapeView, area_contact, penetration};
use std::f64::consts::TAU;
use std::hint::black_box;

const RADIUS: f64 = 1.75e-3;
const ORIGIN: DVec2 = DVec2::new(0.07, 0.05);

fn regular(n: usize, center: DVec2, phase: f64) -> Vec<DVec2> {
    (0..n).map(|k| center + RADIUS * DVec2::from_angle(phase + TAU * k as f64 / n as f64)).collect()
}

/// Body i (made by `make` at a shift along +x) moved towards j until it penetrates 1e-3·RADIUS.
fn pressed<'a>(make: &dyn Fn(f64) -> ShapeView<'a>, j: ShapeView<'a>) -> ShapeView<'a> {
    let (mut deep, mut apart) = (-3.0 * RADIUS, 3.0 * RADIUS);
    for _ in 0..200 {
        let middle = 0.5 * (deep + apart);
        if penetration(make(middle), j).map_or(0.0, |p| p.depth) > 1e-3 * RADIUS {
            deep = middle;
        } else {
            apart = middle;
        }
    }
    make(deep)
}

fn bench_pairs(c: &mut Criterion) {
    let heptagon = regular(7, ORIGIN, 0.37);
    let disk_at =
        |x: f64| ShapeView::Disk { center: ORIGIN + DVec2::new(2.0 * RADIUS + x, 0.3 * RADIUS), radius: RADIUS };
    let blade = ShapeView::Capsule {
        a: ORIGIN + DVec2::new(-2.0 * RADIUS, 2.0 * RADIUS),
        b: ORIGIN + DVec2::new(4.0 * RADIUS, 2.5 * RADIUS),
        radius: 0.5 * RADIUS,
    };
    let chamber = ShapeView::InnerCircle { center: ORIGIN - DVec2::new(0.05, 0.0), radius: 0.05 + 1.0 * RADIUS };
    let heptagon_view = ShapeView::Polygon(&heptagon);
    let cases = [
        (
            "disk-disk",
            pressed(&disk_at, ShapeView::Disk { center: ORIGIN, radius: RADIUS }),
            ShapeView::Disk { center: ORIGIN, radius: RADIUS },
        ),
        ("disk-7gon", pressed(&disk_at, heptagon_view), heptagon_view),
        (
            "disk-capsule",
            pressed(
                &|x| ShapeView::Disk {
                    center: ORIGIN + DVec2::new(RADIUS, 2.2 * RADIUS - 0.5 * (x + 3.0 * RADIUS)),
                    radius: RADIUS,
                },
                blade,
            ),
            blade,
        ),
        (
            "disk-inner circle",
            pressed(&|x| ShapeView::Disk { center: ORIGIN - DVec2::new(x, 0.0), radius: RADIUS }, chamber),
            chamber,
        ),
    ];
    for (name, i, j) in cases {
        assert!(area_contact(i, j).is_some(), "{name} must touch");
        c.bench_function(&format!("area_contact {name}"), |bench| {
            bench.iter(|| area_contact(black_box(i), black_box(j)))
        });
        c.bench_function(&format!("penetration {name}"), |bench| {
            bench.iter(|| penetration(black_box(i), black_box(j)))
        });
    }
    // A 7-gon against a blade and in a chamber, moved by `pressed_polygon`.
    for (name, direction, j) in [("7gon-capsule", DVec2::NEG_Y, blade), ("7gon-inner circle", DVec2::NEG_X, chamber)] {
        let points = pressed_polygon(&heptagon, direction, j);
        let i = ShapeView::Polygon(&points);
        assert!(area_contact(i, j).is_some(), "{name} must touch");
        c.bench_function(&format!("area_contact {name}"), |bench| {
            bench.iter(|| area_contact(black_box(i), black_box(j)))
        });
        c.bench_function(&format!("penetration {name}"), |bench| {
            bench.iter(|| penetration(black_box(i), black_box(j)))
        });
    }
}

/// `points` shifted by s·`direction`, with s found by bisection so that the penetration into j is 1e-3·RADIUS
/// (s = −3R deep, s = +3R apart, from a start where j reaches over the polygon's centre).
fn pressed_polygon(points: &[DVec2], direction: DVec2, j: ShapeView) -> Vec<DVec2> {
    let at = |s: f64| points.iter().map(|&p| p + direction * (s + 1.5 * RADIUS)).collect::<Vec<_>>();
    let depth = |s: f64| penetration(ShapeView::Polygon(&at(s)), j).map_or(0.0, |p| p.depth);
    let (mut deep, mut apart) = (-3.0 * RADIUS, 3.0 * RADIUS);
    for _ in 0..200 {
        let middle = 0.5 * (deep + apart);
        if depth(middle) > 1e-3 * RADIUS {
            deep = middle;
        } else {
            apart = middle;
        }
    }
    at(deep)
}

criterion_group!(benches, bench_pairs);
criterion_main!(benches);
