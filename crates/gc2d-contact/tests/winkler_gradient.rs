//! The Winkler formulation is the exact gradient of its potential against a flat face (issue 19, item 2;
//! docs/model.md, "Rocking of flat contacts").
//!
//! For a polygon i pressed into a wall whose face is the line y = 0 (the wall below it), the local overlap depth at
//! x is δ(x) = −y_low(x), the depth of i's lower outline, and ∫δ² dx = 2∫∫(−y) dA over the overlap: the potential
//! U = (E/2l)·∫δ² dx is (E/l)·A·d̄, with d̄ the depth of the overlap centroid below the face. Its central
//! differences under translations and rotations of i, l held fixed, must match the law's force and torque: E·A/l
//! along the normal, acting at the overlap centroid projected on the chord.

use gc2d_contact::{
    AreaFormulation, BodyMotion, ContactConstants, ContactGeometry, ContactLaw, ContactState, NormalElastic,
};
use gc2d_geometry::{ConvexPolygon, DVec2, contact_geometry_with_centroid, rectangle, regular_polygon};

const E: f64 = 1e7;
/// The characteristic length, held fixed as the law freezes it at the first contact step, m.
const LENGTH: f64 = 4e-3;

/// A polygon's outline about its centroid, placed at `position` turned by `angle`.
fn placed(polygon: &ConvexPolygon, position: DVec2, angle: f64) -> Vec<DVec2> {
    let (centred, _) = ConvexPolygon::new(polygon.vertices()).unwrap();
    let rotation = DVec2::from_angle(angle);
    centred.vertices().iter().map(|&p| position + rotation.rotate(p)).collect()
}

/// A wall 1 m wide and 0.1 m thick whose top face is y = 0.
fn wall() -> Vec<DVec2> {
    [(-0.5, -0.1), (0.5, -0.1), (0.5, 0.0), (-0.5, 0.0)].map(|(x, y)| DVec2::new(x, y)).to_vec()
}

/// U = (E/l)·A·d̄ of the polygon at (`position`, `angle`), J per unit thickness.
fn potential(polygon: &ConvexPolygon, position: DVec2, angle: f64) -> f64 {
    contact_geometry_with_centroid(&placed(polygon, position, angle), &wall())
        .map_or(0.0, |g| E / LENGTH * g.area * -g.centroid.unwrap().y)
}

/// 72 contacts of a 7-gon, a square and a triangle at 24 orientations each (corners, faces, tilted faces): worst
/// relative error 1.5e-7, the central differences' own.
#[test]
fn winkler_force_and_torque_against_a_flat_face_are_the_gradient_of_its_potential() {
    let law = ContactLaw {
        elastic: NormalElastic { formulation: AreaFormulation::Winkler, ..NormalElastic::thesis(E) },
        ..ContactLaw::elastic(E)
    };
    let shapes =
        [regular_polygon(7, 5e-3).unwrap(), rectangle(10e-3, 10e-3).unwrap(), regular_polygon(3, 4e-3).unwrap()];
    let constants = ContactConstants { length: LENGTH, normal_mass: 0.1, tangential_mass: 0.05 };
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    for shape in &shapes {
        for k in 0..24 {
            let angle = 0.261 * k as f64;
            // Press the polygon 30 µm into the face: corners, faces and tilted faces by turn.
            let lowest = placed(shape, DVec2::ZERO, angle).iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
            let position = DVec2::new(1e-3, -lowest - 3e-5);
            let vertices = placed(shape, position, angle);
            let g = contact_geometry_with_centroid(&vertices, &wall()).expect("the polygon overlaps the wall");
            let centroid = g.centroid.unwrap();
            let geometry = ContactGeometry {
                area: g.area,
                normal: g.normal,
                chord_length: g.chord_length,
                arm_i: g.point - position,
                arm_j: g.point,
                centroid_offset: (centroid - g.point).dot(g.normal.perp()),
                rocking: true,
            };
            let state = ContactState {
                constants: Some(constants),
                previous_area: g.area,
                previous_chord: g.chord_length,
                ..ContactState::default()
            };
            let body = BodyMotion::free(0.1, 1e-6, DVec2::ZERO, 0.0);
            let response = law.evaluate(&geometry, &body, &BodyMotion::wall(DVec2::ZERO), &state, 1e-6);

            let h = 1e-9;
            let d_x = (potential(shape, position + DVec2::new(h, 0.0), angle)
                - potential(shape, position - DVec2::new(h, 0.0), angle))
                / (2.0 * h);
            let d_y = (potential(shape, position + DVec2::new(0.0, h), angle)
                - potential(shape, position - DVec2::new(0.0, h), angle))
                / (2.0 * h);
            let d_theta = (potential(shape, position, angle + 1e-7) - potential(shape, position, angle - 1e-7)) / 2e-7;
            let force_scale = E * g.area / LENGTH;
            let errors = [
                (response.force_on_i.x + d_x).abs() / force_scale,
                (response.force_on_i.y + d_y).abs() / force_scale,
                (response.torque_on_i + d_theta).abs() / (force_scale * g.chord_length),
            ];
            assert!(errors.iter().all(|e| *e < 1e-4), "angle {angle}: relative errors {errors:?}");
            worst = errors.into_iter().fold(worst, f64::max);
            checked += 1;
        }
    }
    println!("{checked} contacts, worst relative error {worst:.2e}");
}

/// The dashpots: a flat plate spinning on a wall at constant overlap meets the couple γ·√(E·m⊥)/l · c³/12 · ω
/// against its spin, on both bodies with opposite signs, and the ledger books c·ω²·Δt of it as normal damping.
#[test]
fn winkler_dashpots_resist_rocking_with_a_couple_and_book_its_dissipation() {
    let (gamma, chord, spin, dt) = (0.5, 2e-3, 3.0, 1e-6);
    let law = ContactLaw {
        elastic: NormalElastic { formulation: AreaFormulation::Winkler, ..NormalElastic::thesis(E) },
        damping: Some(gc2d_contact::NormalDamping { gamma }),
        ..ContactLaw::elastic(E)
    };
    let area = chord * 1e-6;
    let geometry = ContactGeometry {
        area,
        normal: DVec2::Y,
        chord_length: chord,
        arm_i: DVec2::new(0.0, -1e-3),
        arm_j: DVec2::ZERO,
        centroid_offset: 0.0,
        rocking: true,
    };
    let constants = ContactConstants { length: 1e-3, normal_mass: 0.02, tangential_mass: 0.005 };
    let state = ContactState {
        constants: Some(constants),
        previous_area: area,
        previous_chord: chord,
        ..ContactState::default()
    };
    let plate = BodyMotion::free(0.02, 1e-8, DVec2::ZERO, spin);
    let response = law.evaluate(&geometry, &plate, &BodyMotion::wall(DVec2::ZERO), &state, dt);
    let coefficient = gamma * (E * 0.02f64).sqrt() / 1e-3 * chord.powi(3) / 12.0;
    let from_force = geometry.arm_i.perp_dot(response.force_on_i);
    assert!((response.torque_on_i - from_force + coefficient * spin).abs() < 1e-12 * coefficient * spin);
    let from_force_j = -geometry.arm_j.perp_dot(response.force_on_i);
    assert!((response.torque_on_j - from_force_j - coefficient * spin).abs() < 1e-12 * coefficient * spin);
    let dissipation = coefficient * spin * spin * dt;
    assert!((response.energy.normal_damping - dissipation).abs() < 1e-12 * dissipation);
}
