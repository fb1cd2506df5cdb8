//! Which part of the overlap-area law changes the energy of an elastic collision (issue 19, item 1).
//!
//! Single collisions of two regular 7-gons (circumradius 5 mm, ρ = 5000 kg/m², E = 1e7 N/m, 0.5 m/s head-on with
//! an impact parameter, γ = μ = 0) at a grid of orientations, integrated by velocity Verlet with the exact overlap
//! geometry of `gc2d_geometry::contact_geometry`. Each variant changes one ingredient of the law:
//!
//! - `thesis`: F = E·A/l along the chord normal at the chord midpoint, l frozen at first contact (gc2d);
//! - `live-l`: the same with l recomputed every step from the current arms;
//! - `centroid`: the thesis force applied at the overlap's centroid instead of the chord midpoint;
//! - `no-torque`: the thesis force without its torques (rotations stay as they were);
//! - `conservative`: F = E·A·c/l² (the gradient of W = E·A²/(2l²)) at the chord midpoint.
//!
//! Prints, per variant and Δt, the relative change of the kinetic energy over the collision (mean, smallest,
//! largest), and how many collisions had a step with more than two outline crossings.
//!
//! Run: `cargo run --release -p gc2d-contact --example area_law_study`

use gc2d_geometry::{ContactKind, DVec2, OverlapPolygon, contact_geometry, cross, overlap_polygon, regular_polygon};

/// Circumradius of the 7-gons, m.
const RADIUS: f64 = 5e-3;
/// Area density, kg/m².
const DENSITY: f64 = 5000.0;
/// Young's modulus (2D), N/m.
const E: f64 = 1e7;
/// Relative speed of approach, m/s.
const SPEED: f64 = 0.5;

/// One ingredient of the law changed at a time.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Variant {
    Thesis,
    LiveL,
    Centroid,
    NoTorque,
    Conservative,
}

/// A rigid body in the plane.
#[derive(Clone, Copy)]
struct Body {
    position: DVec2,
    angle: f64,
    velocity: DVec2,
    angular_velocity: f64,
    mass: f64,
    inertia: f64,
}

impl Body {
    fn kinetic(&self) -> f64 {
        0.5 * self.mass * self.velocity.length_squared() + 0.5 * self.inertia * self.angular_velocity.powi(2)
    }

    fn world(&self, local: &[DVec2]) -> Vec<DVec2> {
        let rotation = DVec2::from_angle(self.angle);
        local.iter().map(|&p| self.position + rotation.rotate(p)).collect()
    }
}

/// Force on i and torques on i and j, and whether the outlines crossed more than twice.
fn contact(variant: Variant, local: &[DVec2], i: &Body, j: &Body, frozen: &mut Option<f64>) -> (DVec2, f64, f64, bool) {
    let (vi, vj) = (i.world(local), j.world(local));
    let Some(g) = contact_geometry(&vi, &vj) else {
        *frozen = None;
        return (DVec2::ZERO, 0.0, 0.0, false);
    };
    let arm_length = |x: DVec2| {
        let (ri, rj) = ((g.point - i.position).length(), (g.point - x).length());
        ri * rj / (ri + rj)
    };
    let l_now = arm_length(j.position);
    let l = *frozen.get_or_insert(l_now);
    let (magnitude, point) = match variant {
        Variant::Thesis | Variant::NoTorque => (E * g.area / l, g.point),
        Variant::LiveL => (E * g.area / l_now, g.point),
        Variant::Centroid => (E * g.area / l, centroid(&vi, &vj)),
        Variant::Conservative => (E * g.area * g.chord_length / (l * l), g.point),
    };
    let force = magnitude * g.normal;
    let (torque_i, torque_j) = if variant == Variant::NoTorque {
        (0.0, 0.0)
    } else {
        (cross(point - i.position, force), -cross(point - j.position, force))
    };
    (force, torque_i, torque_j, g.kind == ContactKind::MultipleCrossings)
}

fn centroid(a: &[DVec2], b: &[DVec2]) -> DVec2 {
    let mut out = OverlapPolygon::new();
    overlap_polygon(a, b, &mut out);
    let v = out.vertices();
    let (mut sum, mut twice_area) = (DVec2::ZERO, 0.0);
    for k in 0..v.len() {
        let (p, q) = (v[k] - v[0], v[(k + 1) % v.len()] - v[0]);
        let w = cross(p, q);
        sum += w * (p + q);
        twice_area += w;
    }
    v[0] + sum / (3.0 * twice_area)
}

/// The relative change of the kinetic energy over one collision, and whether it crossed more than twice.
fn collide(variant: Variant, local: &[DVec2], angles: (f64, f64), offset: f64, dt: f64) -> (f64, bool) {
    let props = gc2d_geometry::ConvexPolygon::new(local).unwrap().0.mass_properties(DENSITY);
    let body = |x: f64, angle: f64, v: f64| Body {
        position: DVec2::new(x, offset * x.signum()),
        angle,
        velocity: DVec2::new(v, 0.0),
        angular_velocity: 0.0,
        mass: props.mass,
        inertia: props.inertia,
    };
    let gap = 2.0 * RADIUS + 1e-4;
    let (mut i, mut j) = (body(-0.5 * gap, angles.0, 0.5 * SPEED), body(0.5 * gap, angles.1, -0.5 * SPEED));
    let before = i.kinetic() + j.kinetic();
    let mut frozen = None;
    let mut multiple = false;
    let mut touched = false;
    let (mut f, mut ti, mut tj, _) = contact(variant, local, &i, &j, &mut frozen);
    for _ in 0..10_000_000 {
        for (b, force, torque) in [(&mut i, f, ti), (&mut j, -f, tj)] {
            b.velocity += 0.5 * dt * force / b.mass;
            b.angular_velocity += 0.5 * dt * torque / b.inertia;
            b.position += dt * b.velocity;
            b.angle += dt * b.angular_velocity;
        }
        let m;
        (f, ti, tj, m) = contact(variant, local, &i, &j, &mut frozen);
        multiple |= m;
        for (b, force, torque) in [(&mut i, f, ti), (&mut j, -f, tj)] {
            b.velocity += 0.5 * dt * force / b.mass;
            b.angular_velocity += 0.5 * dt * torque / b.inertia;
        }
        touched |= frozen.is_some();
        if touched && frozen.is_none() {
            break;
        }
    }
    ((i.kinetic() + j.kinetic()) / before - 1.0, multiple)
}

fn main() {
    let shape = regular_polygon(7, RADIUS).unwrap();
    let local = shape.vertices().to_vec();
    let props = shape.mass_properties(DENSITY);
    let inscribed = RADIUS * (std::f64::consts::PI / 7.0).cos();
    let bound = std::f64::consts::PI / 10.0 * (std::f64::consts::PI * inscribed * inscribed * DENSITY / E).sqrt();
    println!("7-gon: m = {:.4} kg, I = {:.3e} kg m^2, thesis bound {:.3e} s", props.mass, props.inertia, bound);
    let steps = 12;
    let sector = std::f64::consts::TAU / 7.0;
    for dt in [1e-6, 0.25e-6] {
        for variant in [Variant::Thesis, Variant::LiveL, Variant::Centroid, Variant::NoTorque, Variant::Conservative] {
            let (mut sum, mut lo, mut hi, mut n, mut multiple) = (0.0, f64::INFINITY, f64::NEG_INFINITY, 0, 0);
            for a in 0..steps {
                for b in 0..steps {
                    for offset in [0.0, 0.3 * RADIUS] {
                        let angles = (a as f64 * sector / steps as f64, b as f64 * sector / steps as f64);
                        let (change, m) = collide(variant, &local, angles, offset, dt);
                        sum += change;
                        lo = f64::min(lo, change);
                        hi = f64::max(hi, change);
                        n += 1;
                        multiple += m as usize;
                    }
                }
            }
            println!(
                "dt {dt:.2e}  {variant:>12?}: mean {:+.3e}  min {lo:+.3e}  max {hi:+.3e}  ({n} collisions, {multiple} with >2 crossings)",
                sum / n as f64
            );
        }
    }
}
