//! Exact disks under penetration laws, through the whole engine: the Hertz contact time and elasticity, the realised
//! restitution of a damped linear spring and of the steel e(v) law, the sliding-to-rolling transition, and an
//! elastic disk gas in a circular chamber.

mod common;

use common::{G, sphere_world, step};
use gc2d_contact::{
    CundallStrack, ImpactLaw, NormalSpring, PenetrationDamping, PenetrationLaw, TangentialSpring, TangentialStiffness,
};
use gc2d_engine::{BodyShape, MassModel, WallMotion, World, WorldConfig};
use gc2d_geometry::{DVec2, Pose, rectangle};
use std::f64::consts::PI;

/// Steel after the mill thesis: ρ = 7700 kg/m³, E = 196.2 GPa, ν = 0.3.
const STEEL_DENSITY: f64 = 7700.0;
const STEEL_E: f64 = 196.2e9;
const STEEL_NU: f64 = 0.3;

/// E* of two steel bodies, Pa.
fn steel_effective_modulus() -> f64 {
    1.0 / (2.0 * (1.0 - STEEL_NU * STEEL_NU) / STEEL_E)
}

/// A World with one material whose bodies interact by `law`, masses by `mass_model`, gravity `g`.
fn world_of(law: PenetrationLaw, dt: f64, g: f64, mass_model: MassModel) -> World {
    common::world(WorldConfig { mass_model, ..common::config(dt, law, g) })
}

/// A steel disk of radius `radius` at `position` moving with `velocity`; its slot.
fn add_disk(world: &mut World, radius: f64, position: DVec2, velocity: DVec2) -> usize {
    let pose = Pose::new(position, 0.0);
    world.add_particle(BodyShape::Disk { radius }, pose, STEEL_DENSITY, velocity, 0.0).unwrap().index()
}

/// What one impact did: its contact time and the relative speed after it.
struct Impact {
    contact_time: f64,
    relative_speed_after: f64,
}

/// Steps until the bodies have touched and separated again; `relative_speed` gives the velocity of one body relative
/// to the other (or to the wall) along the line of impact.
fn impact(world: &mut World, relative_speed: impl Fn(&World) -> f64) -> Impact {
    let (mut first, mut last) = (None, None);
    for _ in 0..2_000_000 {
        step(world);
        if world.contacts().next().is_some() {
            first.get_or_insert(world.time());
            last = Some(world.time());
        } else if last.is_some() {
            let contact_time = last.unwrap() - first.unwrap() + world.time_step();
            return Impact { contact_time, relative_speed_after: relative_speed(world) };
        }
    }
    panic!("the bodies did not separate");
}

/// Hertz's contact time of two spheres: t_c = 2.868·(m*²/(R*·E*²·v))^{1/5} (Johnson, Contact Mechanics, §11.4),
/// with the constant 2.868 = 2·∫₀¹ dx/√(1 − x^{5/2})·(15/16)^{2/5}.
fn hertz_contact_time(effective_mass: f64, effective_radius: f64, effective_modulus: f64, speed: f64) -> f64 {
    let integral = {
        // ∫₀¹ dx/√(1 − x^{5/2}) by the substitution x = (1 − u²)^{2/5}, which removes the end singularity:
        // dx = −(4/5)·u·(1 − u²)^{−3/5} du and √(1 − x^{5/2}) = u, so the integrand is (4/5)(1 − u²)^{−3/5}, smooth
        // enough on [0, 1) for a fine midpoint rule.
        let n = 2_000_000;
        (0..n).map(|k| (k as f64 + 0.5) / n as f64).map(|u| 0.8 * (1.0 - u * u).powf(-0.6)).sum::<f64>() / n as f64
    };
    let constant = 2.0 * integral * (15.0f64 / 16.0).powf(0.4);
    constant
        * (effective_mass * effective_mass / (effective_radius * effective_modulus * effective_modulus * speed))
            .powf(0.2)
}

/// Radius (m) and relative speed (m/s) of the steel head-on impact.
const HEAD_ON_RADIUS: f64 = 0.025;
const HEAD_ON_SPEED: f64 = 0.01;

/// Hertz's contact time of the steel head-on impact, s.
fn head_on_contact_time() -> f64 {
    let mass = STEEL_DENSITY * 4.0 / 3.0 * PI * HEAD_ON_RADIUS.powi(3);
    hertz_contact_time(0.5 * mass, 0.5 * HEAD_ON_RADIUS, steel_effective_modulus(), HEAD_ON_SPEED)
}

/// Two steel spheres meeting head on at [`HEAD_ON_SPEED`] under an elastic Hertz law, 1e-8 m apart at the start, at
/// Δt = t_c/4000, optionally in still air (ρ_f = 1.2 kg/m³, c_w = 0.47, buoyancy on).
fn steel_head_on(air: bool) -> Impact {
    let law = PenetrationLaw::elastic(NormalSpring::Hertz { effective_modulus_pa: steel_effective_modulus() });
    let mut world = sphere_world(law, head_on_contact_time() / 4000.0, 0.0);
    if air {
        world
            .set_fluid(gc2d_engine::Fluid {
                field: gc2d_fluid::FluidField::Uniform(DVec2::ZERO),
                properties: gc2d_fluid::FluidProperties { density_kg_m3: 1.2, dynamic_viscosity_pa_s: 1.8e-5 },
                drag: gc2d_fluid::DragCoefficient::Constant(0.47),
                buoyancy: true,
            })
            .unwrap();
    }
    let (radius, speed, gap) = (HEAD_ON_RADIUS, HEAD_ON_SPEED, 1e-8);
    let a = add_disk(&mut world, radius, DVec2::new(-radius - gap, 0.0), DVec2::new(0.5 * speed, 0.0));
    let b = add_disk(&mut world, radius, DVec2::new(radius + gap, 0.0), DVec2::new(-0.5 * speed, 0.0));
    impact(&mut world, |w: &World| w.bodies().velocity[a].x - w.bodies().velocity[b].x)
}

#[test]
fn hertz_head_on_of_steel_spheres_takes_the_analytic_contact_time_and_is_elastic() {
    let expected = head_on_contact_time();
    let result = steel_head_on(false);
    let time_error = (result.contact_time - expected).abs() / expected;
    assert!(
        time_error < 0.005,
        "contact time {} s against Hertz's {expected} s ({time_error:.2e})",
        result.contact_time
    );
    let restitution = -result.relative_speed_after / HEAD_ON_SPEED;
    assert!((restitution - 1.0).abs() < 1e-5, "e = {restitution}");
}

#[test]
fn hertz_head_on_in_still_air_differs_from_vacuum_by_the_drag_bound() {
    // The same impact in still air. During the contact the drag on a sphere is at most ½·ρ_f·c_w·π·R²·(v/2)² ≈
    // 1.4e-8 N, an impulse of about 2e-12 N·s over t_c against a momentum of 2.5e-3 N·s: contact time and
    // restitution may change by 1e-6 at most, and the contact time still matches Hertz.
    let (vacuum, air) = (steel_head_on(false), steel_head_on(true));
    assert!((air.contact_time - vacuum.contact_time).abs() <= 1e-6 * vacuum.contact_time);
    assert!((air.relative_speed_after - vacuum.relative_speed_after).abs() <= 1e-6 * HEAD_ON_SPEED);
    let expected = head_on_contact_time();
    assert!((air.contact_time - expected).abs() < 0.005 * expected);
}

#[test]
fn linear_spring_realises_its_target_restitution_at_every_speed() {
    let radius: f64 = 0.0025;
    let stiffness = 1e6;
    let mass = STEEL_DENSITY * 4.0 / 3.0 * PI * radius.powi(3);
    let period = PI * (0.5 * mass / stiffness).sqrt();
    for target in [0.1, 0.5, 0.9, 0.99] {
        for speed in [0.1, 1.0, 5.0] {
            let law = PenetrationLaw {
                damping: Some(PenetrationDamping::Restitution(target)),
                ..PenetrationLaw::elastic(NormalSpring::Linear { stiffness_n_m: stiffness })
            };
            let mut world = sphere_world(law, period / 1000.0, 0.0);
            let gap = 1e-9;
            let a = add_disk(&mut world, radius, DVec2::new(-radius - gap, 0.0), DVec2::new(0.5 * speed, 0.0));
            let b = add_disk(&mut world, radius, DVec2::new(radius + gap, 0.0), DVec2::new(-0.5 * speed, 0.0));
            let relative = |w: &World| w.bodies().velocity[a].x - w.bodies().velocity[b].x;
            let restitution = -impact(&mut world, relative).relative_speed_after / speed;
            let error = (restitution - target).abs() / target;
            assert!(error < 0.005, "target e = {target} at {speed} m/s: realised {restitution} ({error:.2e})");
        }
    }
}

#[test]
fn steel_impact_law_is_realised_on_a_steel_wall_from_slow_to_fast() {
    let radius: f64 = 0.0025;
    let e_star = steel_effective_modulus();
    let law = PenetrationLaw {
        damping: Some(PenetrationDamping::VelocityDependent(ImpactLaw::SteelReichardt)),
        ..PenetrationLaw::elastic(NormalSpring::Hertz { effective_modulus_pa: e_star })
    };
    for speed in [0.1, 0.5, 1.0, 3.0, 10.0, 30.0, 50.0] {
        let mass = STEEL_DENSITY * 4.0 / 3.0 * PI * radius.powi(3);
        let contact_time = hertz_contact_time(mass, radius, e_star, speed);
        let mut world = sphere_world(law, contact_time / 400.0, 0.0);
        let wall = rectangle(0.02, 0.01).unwrap();
        world.add_wall(&wall, Pose::new(DVec2::new(0.0, -0.005), 0.0), DVec2::ZERO, WallMotion::Static);
        let ball = add_disk(&mut world, radius, DVec2::new(0.0, radius + 1e-9), DVec2::new(0.0, -speed));
        let restitution = impact(&mut world, |w| w.bodies().velocity[ball].y).relative_speed_after / speed;
        let expected = (0.985 / (speed + 0.9494).powf(0.291)).min(1.0);
        let error = (restitution - expected).abs() / expected;
        assert!(error < 0.02, "at {speed} m/s: e = {restitution}, the law's {expected} ({error:.2e})");
    }
}

/// A disk launched sliding without spin on a floor: Coulomb friction slows it and spins it up until it rolls, at
/// v = v0/(1 + m·R²/I) after t = (v0 − v)/(μ·g): 2/3·v0 after v0/(3μg) per unit thickness (I = ½mR²), 5/7·v0 after
/// 2v0/(7μg) as a sphere (I = 2/5·mR²).
#[test]
fn a_sliding_disk_starts_to_roll_at_the_analytic_speed_and_time() {
    let (radius, v0, mu) = (0.0025, 0.5, 0.3);
    for (mass_model, fraction) in [(MassModel::PerUnitThickness, 2.0 / 3.0), (MassModel::SphereEquivalent, 5.0 / 7.0)] {
        let law = PenetrationLaw {
            damping: Some(PenetrationDamping::Restitution(0.1)),
            tangential: Some(TangentialSpring {
                mu,
                stiffness: TangentialStiffness::CundallStrack { stiffness_ratio: CundallStrack::STIFFNESS_FACTOR },
                damping_ratio: 0.0,
            }),
            ..PenetrationLaw::elastic(NormalSpring::Linear { stiffness_n_m: 1e5 })
        };
        let mut world = world_of(law, 1e-6, G, mass_model);
        let floor = rectangle(1.0, 0.01).unwrap();
        world.add_wall(&floor, Pose::new(DVec2::new(0.45, -0.005), 0.0), DVec2::ZERO, WallMotion::Static);
        let disk = add_disk(&mut world, radius, DVec2::new(0.0, radius), DVec2::new(v0, 0.0));
        let slip = |w: &World| w.bodies().velocity[disk].x + w.bodies().angular_velocity[disk] * radius;
        while slip(&world) > 1e-4 * v0 {
            step(&mut world);
            assert!(world.time() < 1.0, "still sliding after 1 s");
        }
        let expected_time = (1.0 - fraction) * v0 / (mu * G);
        let speed = world.bodies().velocity[disk].x;
        assert!((speed - fraction * v0).abs() < 0.01 * fraction * v0, "{mass_model:?}: rolls at {speed} m/s");
        let time_error = (world.time() - expected_time).abs() / expected_time;
        assert!(time_error < 0.01, "{mass_model:?}: rolls after {} s, expected {expected_time} s", world.time());
    }
}

#[test]
fn an_overlap_too_deep_for_a_penetration_law_is_measured_by_the_diameter() {
    // QA P2-11: the stop message called a penetration law's depth over the smaller diameter a share of the area.
    // Two steel disks at 1 m/s under a Hertz law a million times too soft press into each other far beyond 5 %.
    let law = PenetrationLaw::elastic(NormalSpring::Hertz { effective_modulus_pa: 1e-6 * steel_effective_modulus() });
    let mut world = sphere_world(law, 1e-7, 0.0);
    let (radius, gap) = (HEAD_ON_RADIUS, 1e-8);
    add_disk(&mut world, radius, DVec2::new(-radius - gap, 0.0), DVec2::new(0.5, 0.0));
    add_disk(&mut world, radius, DVec2::new(radius + gap, 0.0), DVec2::new(-0.5, 0.0));
    let error = world.run_until(1.0).expect_err("the overlap must stop the run");
    match &error {
        gc2d_engine::WorldError::Safety(gc2d_engine::SafetyError::ExcessiveOverlap { measure, percent, .. }) => {
            assert_eq!(*measure, "diameter (the depth)");
            // The check runs after the step that crossed the 5 % limit.
            assert!(*percent > 5.0 && *percent < 5.5, "{percent} % of the diameter");
        }
        other => panic!("expected ExcessiveOverlap, got {other:?}"),
    }
    assert!(error.to_string().contains("of the smaller particle's diameter (the depth)"), "{error}");
}
