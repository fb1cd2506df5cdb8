//! Overlap area and contact chord against independent references, and the force-law exponents of §2.6 / §10.3.

use approx::assert_relative_eq;
use gc2d_geometry::{
    ContactKind, ConvexPolygon, DVec2, OverlapGeometry, OverlapPolygon, Pose, contact_geometry,
    contact_geometry_with_centroid, cross, overlap_polygon,
};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use std::f64::consts::PI;

fn regular(n: usize, radius: f64, center: DVec2, phase: f64) -> Vec<DVec2> {
    (0..n)
        .map(|i| {
            let phi = phase + 2.0 * PI * i as f64 / n as f64;
            center + radius * DVec2::new(phi.cos(), phi.sin())
        })
        .collect()
}

/// Shoelace area relative to the first vertex.
fn area_of(points: &[DVec2]) -> f64 {
    let Some(&origin) = points.first() else { return 0.0 };
    0.5 * points.windows(2).map(|w| cross(w[0] - origin, w[1] - origin)).sum::<f64>()
}

/// Reference intersection, written independently of the crate: Sutherland–Hodgman clipping of `b` by `a`
/// (the crate clips `a` by `b`), with `Vec`s and open half-planes.
fn reference_area(a: &[DVec2], b: &[DVec2]) -> f64 {
    let mut poly = b.to_vec();
    for i in 0..a.len() {
        let (o, e) = (a[i], a[(i + 1) % a.len()] - a[i]);
        let side = |p: DVec2| cross(e, p - o);
        let mut next = Vec::with_capacity(poly.len() + 1);
        for k in 0..poly.len() {
            let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                next.push(p);
            }
            if (sp > 0.0 && sq < 0.0) || (sp < 0.0 && sq > 0.0) {
                next.push(p + (q - p) * (sp / (sp - sq)));
            }
        }
        poly = next;
        if poly.len() < 3 {
            return 0.0;
        }
    }
    area_of(&poly).max(0.0)
}

fn parry_area(a: &[DVec2], b: &[DVec2]) -> f64 {
    let mut points = Vec::new();
    parry2d_f64::transformation::convex_polygons_intersection_points(a, b, &mut points);
    area_of(&points).abs()
}

/// Distance from `p` to the closed outline of `polygon`.
fn distance_to_outline(p: DVec2, polygon: &[DVec2]) -> f64 {
    (0..polygon.len())
        .map(|i| {
            let (s, e) = (polygon[i], polygon[(i + 1) % polygon.len()]);
            let t = ((p - s).dot(e - s) / (e - s).length_squared()).clamp(0.0, 1.0);
            (s + t * (e - s) - p).length()
        })
        .fold(f64::INFINITY, f64::min)
}

/// A random convex polygon: 3–20 vertices at sorted random angles on an ellipse (gc2d's RAND1 shapes, §1.2),
/// validated, then placed by a random pose near (0.07, −0.03) m.
fn convex_polygon(size: f64) -> impl Strategy<Value = Vec<DVec2>> {
    (prop::collection::vec(0.0..1.0f64, 3..=20), 0.4..1.0f64, 0.0..2.0 * PI, (-1.5..1.5f64, -1.5..1.5f64))
        .prop_filter_map("degenerate outline", move |(fractions, aspect, angle, (x, y))| {
            let mut angles: Vec<f64> = fractions.iter().map(|f| 2.0 * PI * f).collect();
            angles.sort_by(f64::total_cmp);
            let outline: Vec<DVec2> =
                angles.iter().map(|phi| size * DVec2::new(phi.cos(), aspect * phi.sin())).collect();
            let (body, _) = ConvexPolygon::new(&outline).ok()?;
            if body.inscribed_radius() < 0.05 * size {
                return None;
            }
            let pose = Pose::new(size * DVec2::new(x, y) + DVec2::new(0.07, -0.03), angle);
            Some(body.vertices().iter().map(|&v| pose.apply(v)).collect())
        })
}

/// The properties every result must have, against the reference area. Returns the contact for further checks.
fn check_contact(a: &[DVec2], b: &[DVec2], size: f64) -> Result<Option<OverlapGeometry>, TestCaseError> {
    let reference = reference_area(a, b);
    let contact = contact_geometry(a, b);
    let mut polygon = OverlapPolygon::new();
    overlap_polygon(a, b, &mut polygon);
    let Some(c) = contact else {
        prop_assert!(reference <= 1e-13 * size * size, "missed overlap of area {reference}");
        prop_assert!(polygon.vertices().is_empty());
        return Ok(None);
    };
    prop_assert!((c.area - reference).abs() <= 1e-9 * reference + 1e-13 * size * size, "{} vs {reference}", c.area);
    prop_assert_eq!(polygon.area(), c.area);
    prop_assert!((area_of(polygon.vertices()) - c.area).abs() <= 1e-12 * c.area);
    prop_assert!((c.normal.length() - 1.0).abs() < 1e-12);
    prop_assert!(c.normal.dot(c.c2 - c.c1).abs() <= 1e-12 * c.chord_length.max(size));
    // Coordinates near 0.1 m carry ~1e-17 m of rounding each.
    prop_assert!((c.chord_length - (c.c2 - c.c1).length()).abs() <= 1e-12 * size);
    prop_assert!((c.point - 0.5 * (c.c1 + c.c2)).length() <= 1e-12 * size);
    let tolerance = 1e-10 * size;
    if c.kind == ContactKind::Contained {
        for end in [c.c1, c.c2] {
            prop_assert!(distance_to_outline(end, polygon.vertices()) <= tolerance);
        }
    } else {
        for end in [c.c1, c.c2] {
            prop_assert!(distance_to_outline(end, a) <= tolerance, "chord end off a's outline");
            prop_assert!(distance_to_outline(end, b) <= tolerance, "chord end off b's outline");
        }
    }
    Ok(Some(c))
}

/// A convex polygon with small integer coordinates: the convex hull of random lattice points. Lattice outlines
/// produce the degenerate cases by the hundred (collinear edges, vertices on edges, shared corners, containment),
/// and every coordinate, side test and crossing is exact or nearly so.
fn lattice_polygon() -> impl Strategy<Value = Vec<DVec2>> {
    prop::collection::vec((0..6i32, 0..6i32), 3..=8).prop_filter_map("degenerate hull", |points| {
        let points: Vec<DVec2> = points.iter().map(|&(x, y)| DVec2::new(x as f64, y as f64)).collect();
        let hull = convex_hull(points);
        ConvexPolygon::new(&hull).ok().map(|_| hull)
    })
}

/// Counter-clockwise convex hull without collinear vertices (Andrew's monotone chain).
fn convex_hull(mut points: Vec<DVec2>) -> Vec<DVec2> {
    points.sort_by(|p, q| p.x.total_cmp(&q.x).then(p.y.total_cmp(&q.y)));
    points.dedup();
    let mut hull: Vec<DVec2> = Vec::new();
    for pass in [points.clone(), points.into_iter().rev().collect()] {
        let floor = hull.len();
        for p in pass {
            while hull.len() >= floor + 2
                && cross(hull[hull.len() - 1] - hull[hull.len() - 2], p - hull[hull.len() - 1]) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// 4000 cases from a fixed seed keep the suite deterministic; PROPTEST_CASES and PROPTEST_RNG_SEED search further.
fn config(seed: u64) -> ProptestConfig {
    let mut config = ProptestConfig::default();
    if std::env::var_os("PROPTEST_CASES").is_none() {
        config.cases = 4000;
    }
    if std::env::var_os("PROPTEST_RNG_SEED").is_none() {
        config.rng_seed = RngSeed::Fixed(seed);
    }
    config
}

proptest! {
    #![proptest_config(config(0x6c2d_0001))]

    /// Area, chord and normal of random convex pairs, overlapping or not, at grain size (1.75 mm) and 0.07 m from
    /// the origin; areas against the test's own clipper and against parry2d.
    #[test]
    fn random_pairs_agree_with_the_reference(a in convex_polygon(1.75e-3), b in convex_polygon(1.75e-3)) {
        let size = 1.75e-3;
        let Some(c) = check_contact(&a, &b, size)? else { return Ok(()) };
        let parry = parry_area(&a, &b);
        prop_assert!((c.area - parry).abs() <= 1e-9 * parry + 1e-13 * size * size, "{} vs parry {parry}", c.area);
        if c.kind == ContactKind::Crossing {
            // Swapping the bodies walks the same chord the other way and flips the normal.
            let d = contact_geometry(&b, &a).unwrap();
            prop_assert_eq!(d.kind, ContactKind::Crossing);
            prop_assert!((d.area - c.area).abs() <= 1e-9 * c.area);
            prop_assert!((d.c1 - c.c2).length() <= 1e-12 * size && (d.c2 - c.c1).length() <= 1e-12 * size);
            prop_assert!((d.normal + c.normal).length() <= 1e-9);
        }
    }

    /// `contact_geometry_with_centroid` adds the overlap's area centroid, against the centroid of parry2d's
    /// intersection polygon, and leaves every other field bitwise as `contact_geometry` gives it.
    #[test]
    fn the_overlap_centroid_agrees_with_parry(a in convex_polygon(1.75e-3), b in convex_polygon(1.75e-3)) {
        let Some(plain) = contact_geometry(&a, &b) else { return Ok(()) };
        let with = contact_geometry_with_centroid(&a, &b).unwrap();
        prop_assert_eq!(OverlapGeometry { centroid: None, ..with }, plain);
        let mut points = Vec::new();
        parry2d_f64::transformation::convex_polygons_intersection_points(&a, &b, &mut points);
        let origin = points[0];
        let (mut twice_area, mut weighted) = (0.0, DVec2::ZERO);
        for w in points[1..].windows(2) {
            let (p, q) = (w[0] - origin, w[1] - origin);
            twice_area += cross(p, q);
            weighted += (p + q) * cross(p, q);
        }
        // parry's polygon may run clockwise; the centroid is the same either way.
        let reference = origin + weighted / (3.0 * twice_area);
        prop_assert!(
            (with.centroid.unwrap() - reference).length() <= 1e-6 * plain.area.sqrt() + 1e-12 * 1.75e-3,
            "{:?} vs parry {reference}", with.centroid
        );
    }

    /// The normal is the direction of −∂A/∂x_a and the chord length its magnitude (the overlap shrinks fastest
    /// when a moves along the normal), checked by central differences where the overlap's shape does not change
    /// within the step.
    #[test]
    fn the_chord_is_minus_the_area_gradient(a in convex_polygon(1.0), b in convex_polygon(1.0)) {
        let Some(c) = contact_geometry(&a, &b).filter(|c| c.kind == ContactKind::Crossing) else { return Ok(()) };
        let step = 1e-6;
        let area_at = |shift: DVec2| {
            let moved: Vec<DVec2> = a.iter().map(|&p| p + shift).collect();
            contact_geometry(&moved, &b).map_or(0.0, |m| m.area)
        };
        let forward = DVec2::new(area_at(DVec2::X * step) - c.area, area_at(DVec2::Y * step) - c.area) / step;
        let backward = DVec2::new(c.area - area_at(-DVec2::X * step), c.area - area_at(-DVec2::Y * step)) / step;
        // A kink within the step (a vertex crossing an edge) shows as disagreeing one-sided differences: skip those.
        if (forward - backward).length() > 1e-4 * c.chord_length {
            return Ok(());
        }
        let gradient = 0.5 * (forward + backward);
        prop_assert!((gradient + c.chord_length * c.normal).length() <= 1e-6 * c.chord_length.max(1e-3),
            "gradient {gradient} vs -L n = {}", -c.chord_length * c.normal);
    }

    /// Lattice polygons: ties everywhere, same properties (chord ends on both outlines, areas, no NaN). Where the
    /// outlines touch along a segment, a rounded crossing point can leave a sliver of area ~1e-16·|x|² on one side
    /// of the swap; the floor of `check_contact` (1e-13·size²) admits it.
    #[test]
    fn lattice_pairs_resolve_every_tie(a in lattice_polygon(), b in lattice_polygon()) {
        let size = 5.0;
        let forward = check_contact(&a, &b, size)?.map_or(0.0, |c| c.area);
        let backward = check_contact(&b, &a, size)?.map_or(0.0, |c| c.area);
        prop_assert!((forward - backward).abs() <= 1e-12 * forward + 1e-13 * size * size);
    }

    /// Pairs of 21–64-gons exercise the larger stack buffers.
    #[test]
    fn many_sided_pairs_agree_with_the_reference(
        n in 21usize..=64, m in 21usize..=64, phase in 0.0..PI, offset in (-2.2..2.2f64, -2.2..2.2f64)
    ) {
        let a = regular(n, 1.0, DVec2::ZERO, phase);
        let b = regular(m, 1.1, DVec2::new(offset.0, offset.1), 0.0);
        check_contact(&a, &b, 1.0)?;
    }
}

/// Least-squares slope of ln A against ln h.
fn log_log_slope(samples: &[(f64, f64)]) -> f64 {
    let points: Vec<(f64, f64)> = samples.iter().map(|&(h, area)| (h.ln(), area.ln())).collect();
    let count = points.len() as f64;
    let (mean_x, mean_y) = points.iter().fold((0.0, 0.0), |(sx, sy), (x, y)| (sx + x / count, sy + y / count));
    let covariance: f64 = points.iter().map(|(x, y)| (x - mean_x) * (y - mean_y)).sum();
    let variance: f64 = points.iter().map(|(x, _)| (x - mean_x).powi(2)).sum();
    covariance / variance
}

/// `count` penetrations spaced evenly in ln h over [low, high].
fn penetrations(low: f64, high: f64, count: usize) -> impl Iterator<Item = f64> {
    (0..count).map(move |i| low * (high / low).powf(i as f64 / (count - 1) as f64))
}

/// Turns a scene by `angle` about the origin and moves it to (0.07, 0.05) m, where world coordinates live.
fn place(points: &[DVec2], angle: f64) -> Vec<DVec2> {
    let rotation = DVec2::from_angle(angle);
    points.iter().map(|&p| rotation.rotate(p) + DVec2::new(0.07, 0.05)).collect()
}

#[test]
fn edge_to_edge_area_grows_linearly_with_penetration() {
    // A square of side L pressed by h into a wider square, the pair turned by 0.3 rad: A = L h, F ∝ h (§2.6).
    let side = 2e-3;
    let samples: Vec<(f64, f64)> = penetrations(1e-6 * side, 1e-1 * side, 16)
        .map(|h| {
            let a = [(0.0, -h), (side, -h), (side, side - h), (0.0, side - h)].map(|(x, y)| DVec2::new(x, y));
            let b = [(-side, -2.0 * side), (2.0 * side, -2.0 * side), (2.0 * side, 0.0), (-side, 0.0)]
                .map(|(x, y)| DVec2::new(x, y));
            let c = contact_geometry(&place(&a, 0.3), &place(&b, 0.3)).unwrap();
            assert_eq!(c.kind, ContactKind::Crossing);
            assert_relative_eq!(c.area, side * h, max_relative = 1e-6);
            assert_relative_eq!(c.chord_length, side, max_relative = 1e-9);
            assert_relative_eq!(c.normal, DVec2::from_angle(0.3).rotate(DVec2::Y), epsilon = 1e-9);
            (h, c.area)
        })
        .collect();
    let slope = log_log_slope(&samples);
    assert!((slope - 1.0).abs() < 0.05, "slope {slope}");
}

#[test]
fn tip_to_tip_area_grows_with_the_square_of_penetration() {
    // Two squares turned 45°, 90° corners meeting tip to tip: the overlap is a square of diagonal h, A = h²/2.
    let half_diagonal = 1e-3;
    let diamond = |center_y: f64| regular(4, half_diagonal, DVec2::new(0.0, center_y), 0.0);
    let samples: Vec<(f64, f64)> = penetrations(1e-6 * half_diagonal, 1e-1 * half_diagonal, 16)
        .map(|h| {
            let a = diamond(half_diagonal - h / 2.0);
            let b = diamond(-half_diagonal + h / 2.0);
            let c = contact_geometry(&place(&a, 0.0), &place(&b, 0.0)).unwrap();
            assert_eq!(c.kind, ContactKind::Crossing);
            assert_relative_eq!(c.area, h * h / 2.0, max_relative = 1e-6);
            assert_relative_eq!(c.chord_length, h, max_relative = 1e-6);
            assert_relative_eq!(c.normal, DVec2::Y, epsilon = 1e-9);
            (h, c.area)
        })
        .collect();
    let slope = log_log_slope(&samples);
    assert!((slope - 2.0).abs() < 0.05, "slope {slope}");
}

#[test]
fn disk_like_area_grows_with_penetration_to_the_three_halves() {
    // Two regular 64-gons of radius R pushed together by h from first touch, flat edges facing or corners facing.
    // Far below the edge sagitta (~1e-3 R) the facing edges (or corners) set the exponent; for 2e-2 R ≤ h ≤ 2e-1 R
    // the chord spans several edges and the polygons overlap like disks: A ∝ h^{3/2} (Hertz, §2.3). The fitted
    // slope is 1.473 (disks of radius R: 1.494); it sits below 3/2 because a 64-gon is slightly smaller than its
    // circumscribed disk, which shifts h by ~1e-3 R.
    let radius = 1.75e-3;
    let n = 64;
    for (phase, touching_distance) in [(PI / n as f64, 2.0 * radius * (PI / n as f64).cos()), (0.0, 2.0 * radius)] {
        let samples: Vec<(f64, f64)> = penetrations(2e-2 * radius, 2e-1 * radius, 16)
            .map(|h| {
                let a = regular(n, radius, DVec2::ZERO, phase);
                let b = regular(n, radius, DVec2::new(touching_distance - h, 0.0), phase);
                let c = contact_geometry(&place(&a, 0.0), &place(&b, 0.0)).unwrap();
                assert_eq!(c.kind, ContactKind::Crossing);
                assert_relative_eq!(c.normal, -DVec2::X, epsilon = 1e-9);
                let disk_chord = 2.0 * (radius * h - h * h / 4.0).sqrt();
                assert!((c.chord_length / disk_chord - 1.0).abs() < 0.1, "chord {} vs {disk_chord}", c.chord_length);
                (h, c.area)
            })
            .collect();
        let slope = log_log_slope(&samples);
        assert!((slope - 1.5).abs() < 0.05, "slope {slope}");
    }
}
