//! The conservative overlap-area law is the exact gradient of its potential W(A) = E·A²/(2l²) (issue 19, item 1):
//! its force on i is −W′(A)·∂A/∂x_i and its torques are −W′(A)·∂A/∂θ_i and −W′(A)·∂A/∂θ_j, checked against
//! central differences of the exact overlap area of two convex polygons under small translations and rotations of
//! either body about its centroid. The rotational derivative is a function of the chord ends alone,
//! ∂A/∂θ_i = −½(|c2 − x_i|² − |c1 − x_i|²) = −(s − x_i)·(c2 − c1) with s the chord midpoint, which is why the force
//! acting at the midpoint gives the exact torque (docs/model.md, "Energy of the area law").

use gc2d_contact::{BodyMotion, ContactGeometry, ContactLaw, ContactState, NormalElastic};
use gc2d_geometry::{ContactKind, ConvexPolygon, DVec2, contact_geometry, rectangle, regular_polygon};

const E: f64 = 1e7;

/// A polygon's outline about its centroid, placed at `position` turned by `angle`.
fn placed(local: &[DVec2], position: DVec2, angle: f64) -> Vec<DVec2> {
    let rotation = DVec2::from_angle(angle);
    local.iter().map(|&p| position + rotation.rotate(p)).collect()
}

/// The outline relative to its centroid.
fn centred(polygon: &ConvexPolygon) -> Vec<DVec2> {
    let (centred, _) = ConvexPolygon::new(polygon.vertices()).unwrap();
    centred.vertices().to_vec()
}

/// A pose: centroid and angle.
#[derive(Clone, Copy)]
struct Pose2 {
    x: DVec2,
    angle: f64,
}

fn area(a: &[DVec2], pa: Pose2, b: &[DVec2], pb: Pose2) -> f64 {
    contact_geometry(&placed(a, pa.x, pa.angle), &placed(b, pb.x, pb.angle)).map_or(0.0, |g| g.area)
}

#[test]
fn conservative_force_and_torques_are_the_exact_gradient_of_the_potential() {
    let shapes = [
        centred(&regular_polygon(7, 5e-3).unwrap()),
        centred(&regular_polygon(3, 4e-3).unwrap()),
        centred(&rectangle(12e-3, 3e-3).unwrap()),
        centred(&regular_polygon(4, 6e-3).unwrap()),
    ];
    let law = ContactLaw { elastic: NormalElastic::conservative(E), ..ContactLaw::elastic(E) };
    let mut checked = 0;
    let mut worst: f64 = 0.0;
    for (ka, a) in shapes.iter().enumerate() {
        for (kb, b) in shapes.iter().enumerate() {
            for step in 0..17 {
                let t = step as f64;
                let pa = Pose2 { x: DVec2::new(0.0, 0.0), angle: 0.37 * t + 0.1 * ka as f64 };
                let direction = DVec2::from_angle(0.71 * t + 0.3 * kb as f64);
                let pb0 = Pose2 { x: 2e-2 * direction, angle: -0.53 * t };
                // Bring b towards a until the overlap is about 1 % of the smaller area, by bisection on the distance.
                let target = 0.01 * area(a, pa, a, pa).min(area(b, pb0, b, pb0));
                let (mut near, mut far) = (0.0, 2e-2);
                for _ in 0..60 {
                    let mid = 0.5 * (near + far);
                    if area(a, pa, b, Pose2 { x: mid * direction, ..pb0 }) > target {
                        near = mid;
                    } else {
                        far = mid;
                    }
                }
                let pb = Pose2 { x: near * direction, ..pb0 };
                let (va, vb) = (placed(a, pa.x, pa.angle), placed(b, pb.x, pb.angle));
                let Some(g) = contact_geometry(&va, &vb) else { continue };
                if g.kind != ContactKind::Crossing {
                    continue;
                }
                let geometry = ContactGeometry {
                    area: g.area,
                    normal: g.normal,
                    chord_length: g.chord_length,
                    arm_i: g.point - pa.x,
                    arm_j: g.point - pb.x,
                    centroid_offset: 0.0,
                    rocking: true,
                };
                let body = BodyMotion::free(0.3, 4e-6, DVec2::ZERO, 0.0);
                let response = law.evaluate(&geometry, &body, &body, &ContactState::default(), 1e-6);
                let l = response.state.constants.unwrap().length;
                let w_prime = E * g.area / (l * l);

                // Central differences of the exact area.
                let h = 1e-9;
                let dx = |d: DVec2| {
                    (area(a, Pose2 { x: pa.x + d, ..pa }, b, pb) - area(a, Pose2 { x: pa.x - d, ..pa }, b, pb))
                        / (2.0 * h)
                };
                let gradient = DVec2::new(dx(DVec2::new(h, 0.0)), dx(DVec2::new(0.0, h)));
                let dh = 1e-7;
                let d_theta_i = (area(a, Pose2 { angle: pa.angle + dh, ..pa }, b, pb)
                    - area(a, Pose2 { angle: pa.angle - dh, ..pa }, b, pb))
                    / (2.0 * dh);
                let d_theta_j = (area(a, pa, b, Pose2 { angle: pb.angle + dh, ..pb })
                    - area(a, pa, b, Pose2 { angle: pb.angle - dh, ..pb }))
                    / (2.0 * dh);

                // The chord-end formula of the rotational derivative.
                let chord_formula = -0.5 * ((g.c2 - pa.x).length_squared() - (g.c1 - pa.x).length_squared());
                let scale_torque = w_prime * g.chord_length * 1e-2;
                let scale_area = g.chord_length * 1e-2;
                let errors = [
                    (response.force_on_i - (-w_prime * gradient)).length() / (w_prime * g.chord_length),
                    (chord_formula - d_theta_i).abs() / scale_area,
                    (response.torque_on_i - (-w_prime * d_theta_i)).abs() / scale_torque,
                    (response.torque_on_j - (-w_prime * d_theta_j)).abs() / scale_torque,
                ];
                for error in errors {
                    assert!(error < 1e-4, "shapes {ka}, {kb}, step {step}: relative error {errors:?}");
                    worst = worst.max(error);
                }
                checked += 1;
            }
        }
    }
    assert!(checked >= 100, "only {checked} two-crossing contacts checked");
    println!("{checked} contacts, worst relative error {worst:.2e}");
}

/// The thesis law's force is the same gradient direction scaled by E·A/(l·c) instead of E·A/l², a factor that
/// depends on the chord length and not on A alone: its work around a closed path of the overlap is not zero.
#[test]
fn thesis_force_is_the_conservative_force_times_l_over_c() {
    let geometry = ContactGeometry {
        area: 2e-8,
        normal: DVec2::Y,
        chord_length: 3e-3,
        arm_i: DVec2::new(0.0, -4e-3),
        arm_j: DVec2::new(1e-3, 4e-3),
        centroid_offset: 0.0,
        rocking: true,
    };
    let body = BodyMotion::free(0.3, 4e-6, DVec2::ZERO, 0.0);
    let thesis = ContactLaw::elastic(E).evaluate(&geometry, &body, &body, &ContactState::default(), 1e-6);
    let conservative = ContactLaw { elastic: NormalElastic::conservative(E), ..ContactLaw::elastic(E) }.evaluate(
        &geometry,
        &body,
        &body,
        &ContactState::default(),
        1e-6,
    );
    let l = thesis.state.constants.unwrap().length;
    let ratio = conservative.normal_force / thesis.normal_force;
    assert!((ratio - geometry.chord_length / l).abs() < 1e-12 * ratio);
    assert!((conservative.torque_on_j / thesis.torque_on_j - ratio).abs() < 1e-12 * ratio);
    // The conservative law stores exactly its potential.
    let potential = 0.5 * E * geometry.area.powi(2) / (l * l);
    assert!((conservative.state.normal_energy - potential).abs() < 1e-12 * potential);
}
