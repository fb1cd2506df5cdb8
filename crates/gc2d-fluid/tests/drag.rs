//! Drag laws: direction and size of the force, Schiller–Naumann's limits and jump, buoyancy and the terminal speed.

use gc2d_fluid::drag::{
    SPHERE_DRAG_COEFFICIENT, buoyancy_force, drag_force, equivalent_radius, reynolds_number, terminal_speed,
};
use gc2d_fluid::{DragCoefficient, FluidProperties, ImmersedBody};
use gc2d_geometry::DVec2;
use std::f64::consts::PI;

const AIR: FluidProperties = FluidProperties { density_kg_m3: 1.25, dynamic_viscosity_pa_s: 1.8e-5 };

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(f64::MIN_POSITIVE)
}

#[test]
fn drag_pulls_the_particle_towards_the_fluid_velocity() {
    let ball = ImmersedBody::sphere_equivalent(0.02);
    let fluid_u = DVec2::new(0.0, 5.0);
    let particle_v = DVec2::new(1.0, 2.0);
    let slip = fluid_u - particle_v;
    let f = drag_force(&AIR, DragCoefficient::default(), &ball, slip);
    // Along the slip, ½·ρ·c_w·π·R²·|w|² in size.
    assert!(f.perp_dot(slip).abs() < 1e-15 && f.dot(slip) > 0.0);
    let size = 0.5 * 1.25 * 0.47 * PI * 0.02 * 0.02 * slip.length_squared();
    assert!(close(f.length(), size, 1e-14), "{f}");
    assert_eq!(drag_force(&AIR, DragCoefficient::default(), &ball, DVec2::ZERO), DVec2::ZERO);
    assert_eq!(drag_force(&AIR, DragCoefficient::SchillerNaumann, &ball, DVec2::ZERO), DVec2::ZERO);
    // Per unit thickness a disk meets the flow with its width 2R per metre of depth.
    let disk = ImmersedBody::per_unit_thickness(0.02, PI * 0.02 * 0.02);
    let f = drag_force(&AIR, DragCoefficient::Constant(1.2), &disk, DVec2::new(2.0, 0.0));
    assert!(close(f.x, 0.5 * 1.25 * 1.2 * 0.04 * 4.0, 1e-14) && f.y == 0.0);
}

#[test]
fn schiller_naumann_tends_to_stokes_and_jumps_by_0_39_percent_at_re_1000() {
    let r = 1e-4;
    let ball = ImmersedBody::sphere_equivalent(r);
    // Re = 1e-6: Stokes drag 6π·η·R·w, above it by the correction 0.15·Re^0.687 = 1.1e-5.
    let slip = DVec2::new(1e-6 * AIR.dynamic_viscosity_pa_s / (AIR.density_kg_m3 * 2.0 * r), 0.0);
    assert!(close(reynolds_number(&AIR, r, slip.x), 1e-6, 1e-12));
    let stokes = 6.0 * PI * AIR.dynamic_viscosity_pa_s * r * slip.x;
    let f = drag_force(&AIR, DragCoefficient::SchillerNaumann, &ball, slip).x;
    assert!(close(f / stokes - 1.0, 0.15 * 1e-6f64.powf(0.687), 1e-6) && f / stokes - 1.0 < 2e-5);
    // The force equals ½·ρ·c_w(Re)·A·|w|·w with c_w from the correlation, on both sides of Re = 1000.
    for re in [0.5, 10.0, 999.0, 1000.0, 5e4] {
        let w = re * AIR.dynamic_viscosity_pa_s / (AIR.density_kg_m3 * 2.0 * r);
        let c = DragCoefficient::SchillerNaumann.at_reynolds(re);
        let expected = 0.5 * AIR.density_kg_m3 * c * PI * r * r * w * w;
        assert!(close(
            drag_force(&AIR, DragCoefficient::SchillerNaumann, &ball, DVec2::new(w, 0.0)).x,
            expected,
            1e-12
        ));
    }
    let below = DragCoefficient::SchillerNaumann.at_reynolds(1000.0 - 1e-9);
    let above = DragCoefficient::SchillerNaumann.at_reynolds(1000.0);
    assert!(close(below, 0.43828, 1e-4) && above == 0.44, "{below} {above}");
    assert!(close(above / below - 1.0, 0.0039, 0.01), "the jump the docs state");
    assert_eq!(DragCoefficient::default().at_reynolds(1e5), SPHERE_DRAG_COEFFICIENT);
}

#[test]
fn terminal_speed_balances_weight_buoyancy_and_drag() {
    // The thesis's styrofoam ball (feedpipe.md §7.2): R = 0.02 m, 15 kg/m³ in air, c_w = 0.47: 3.4993 m/s.
    let (r, rho_p, g) = (0.02, 15.0, 9.81);
    let ball = ImmersedBody::sphere_equivalent(r);
    let mass = rho_p * 4.0 / 3.0 * PI * r * r * r;
    let w_t = terminal_speed(1.25, mass, &ball, 0.47, g);
    assert!((w_t - 3.4993).abs() < 5e-5, "{w_t}");
    let closed = (8.0 * r * g * (rho_p - 1.25) / (3.0 * 1.25 * 0.47)).sqrt();
    assert!(close(w_t, closed, 1e-14));
    // Falling at w_t through still air: weight + buoyancy + drag = 0.
    let gravity = DVec2::new(0.0, -g);
    let v = DVec2::new(0.0, -w_t);
    let total = mass * gravity
        + buoyancy_force(1.25, &ball, gravity)
        + drag_force(&AIR, DragCoefficient::Constant(0.47), &ball, DVec2::ZERO - v);
    assert!(total.length() < 1e-12 * mass * g, "{total}");
    // Buoyancy points up and weighs the displaced air.
    assert!(close(buoyancy_force(1.25, &ball, gravity).y, 1.25 * 4.0 / 3.0 * PI * r * r * r * g, 1e-15));
    // Per unit thickness: √(π·R·g·(ρ_p − ρ_f)/(ρ_f·c_w)) with densities per volume (feedpipe.md §7.1 item 10).
    let disk = ImmersedBody::per_unit_thickness(r, PI * r * r);
    let w_cyl = terminal_speed(1.25, rho_p * PI * r * r, &disk, 1.2, g);
    assert!(close(w_cyl, (PI * r * g * (rho_p - 1.25) / (1.25 * 1.2)).sqrt(), 1e-14));
    assert_eq!(terminal_speed(1.25, 1.0 * 4.0 / 3.0 * PI * r * r * r, &ball, 0.47, g), 0.0, "lighter than air");
}

#[test]
fn equivalent_radius_of_a_polygon() {
    assert!(close(equivalent_radius(PI * 0.3 * 0.3), 0.3, 1e-15));
    // A unit square is a disk of radius 1/√π.
    assert!(close(equivalent_radius(1.0), 1.0 / PI.sqrt(), 1e-15));
}
