//! Safety before speed (reference §3.6, §10.4): an unstable Δt is refused with the safe value, a tunnelling
//! particle stops the run with the time, the bodies and a Δt to try, and a NaN or infinity never passes silently.

mod common;

use common::*;
use gc2d_engine::integrator::max_stable_time_step_elongated;
use gc2d_engine::{MaterialId, SafetyError, World, WorldError};
use gc2d_geometry::{DVec2, Pose, rectangle, square};

const SIDE: f64 = 0.01;

/// The §3.6 bound of a square of side `SIDE` at ρ = 5000 kg/m², E = 1e7 N/m: inscribed radius SIDE/2, 62 µs.
fn safe_time_step() -> f64 {
    max_stable_time_step_elongated(0.5 * SIDE, RHO_THESIS, E_THESIS).unwrap()
}

/// The stable bound offered for that square at γ = 0.5: two squares face on, flat-contact stiffness 4E and damping
/// γ·sqrt(E·m/2)·4 both give 0.2·sqrt(m/(8E)) = 15.8 µs (docs/model.md, "Automatic Δt").
fn offered_time_step() -> f64 {
    0.2 * (SIDE * SIDE * RHO_THESIS / (8.0 * E_THESIS)).sqrt()
}

fn falling_square(dt: f64, allow_unsafe: bool) -> World {
    let mut config = config(dt, law(E_THESIS, 0.5, 0.5), G);
    config.safety.allow_unsafe_time_step = allow_unsafe;
    let mut world = world(config);
    world.add_particle(square(SIDE).unwrap(), Pose::new(DVec2::ZERO, 0.0), RHO_THESIS, DVec2::ZERO, 0.0).unwrap();
    world
}

#[test]
fn time_step_above_the_bound_is_refused_with_the_safe_value() {
    let safe = safe_time_step();
    assert!((safe - 6.2e-5).abs() < 1e-6, "bound {safe:e}");
    let offered = offered_time_step();
    let stable = falling_square(safe, false).stable_time_step().unwrap();
    assert!((stable / offered - 1.0).abs() < 1e-12, "stable bound {stable:e}");
    // A run at the §3.6 bound is still allowed.
    falling_square(safe, false).step().expect("Δt at the §3.6 bound is allowed");
    let mut world = falling_square(1.5 * safe, false);
    let error = world.step().expect_err("Δt above the bound must be refused");
    match &error {
        WorldError::Safety(SafetyError::UnsafeTimeStep { dt, safe_dt, particle, .. }) => {
            assert_eq!((*dt, *safe_dt, *particle), (1.5 * safe, stable, 0));
        }
        other => panic!("expected UnsafeTimeStep, got {other:?}"),
    }
    let message = error.to_string();
    assert!(message.contains(&format!("{stable:.3e}")), "the message must name the safe Δt: {message}");
    assert_eq!(world.steps(), 0, "a refused World does not advance");

    let mut allowed = falling_square(1.5 * safe, true);
    run_until(&mut allowed, 100.0 * 1.5 * safe);
    // Free fall. A body starts with zero acceleration in its Gear state, so its velocity lags by half a step for
    // good: measured v = −g·(t − Δt/2), 0.5 % below −g·t after 100 steps.
    let t = allowed.time();
    let v = allowed.bodies().velocity[0].y;
    assert!((v / (-G * t) - 1.0).abs() < 1e-2, "free-fall speed {v}, expected {}", -G * t);
}

#[test]
fn tunnelling_into_a_thin_wall_stops_with_the_time_bodies_and_a_time_step() {
    // A 1 cm square at 10 m/s and Δt = 1 ms (16× the bound) jumps 1 cm per step: after one step it sits across a
    // 2 mm wall, overlapping it by 20 % of its area.
    let dt = 1e-3;
    let mut config = config(dt, law(E_THESIS, 0.5, 0.5), 0.0);
    config.safety.allow_unsafe_time_step = true;
    let mut world = world(config);
    let wall = add_static_wall(&mut world, &rectangle(0.002, 0.1).unwrap(), Pose::new(DVec2::ZERO, 0.0));
    let start = Pose::new(DVec2::new(-0.008, 0.0), 0.0);
    let particle = world.add_particle(square(SIDE).unwrap(), start, RHO_THESIS, DVec2::new(10.0, 0.0), 0.0).unwrap();
    let error = world.run_until(1.0).expect_err("the tunnelling must stop the run");
    let suggested = 0.5 * offered_time_step();
    match &error {
        WorldError::Safety(SafetyError::ExcessiveOverlap { time, step, a, b, percent, suggested_dt, .. }) => {
            assert_eq!((*step, *a, *b), (1, wall.0, particle.0));
            assert!((time - dt).abs() < 1e-15, "time {time}");
            assert!((percent - 20.0).abs() < 1e-6, "overlap {percent} %");
            assert_eq!(*suggested_dt, suggested, "a Δt to try: half the stable bound, below Δt/4");
        }
        other => panic!("expected ExcessiveOverlap, got {other:?}"),
    }
    let message = error.to_string();
    assert!(message.contains(&format!("{suggested:.3e}")), "the message must suggest a Δt: {message}");
    assert!(message.contains("reduce the time step"), "one step made the overlap: {message}");
    if let WorldError::Safety(SafetyError::ExcessiveOverlap { approach_per_step, approach_speed_m_s, .. }) = &error {
        assert!(*approach_per_step > 1.0, "one step's approach {approach_per_step} of the depth");
        assert!(*approach_speed_m_s > 10.0, "thrown back by the overlap's force: {approach_speed_m_s}");
    }
    assert_eq!(world.steps(), 1, "the run stops at the step that tunnelled");
}

#[test]
fn an_impact_too_hard_for_a_soft_contact_advises_stiffness_not_a_smaller_time_step() {
    // The case in small (issue 19 item 5): a 1 cm square at 3.6 m/s hits a wall face on with a soft contact
    // (E = 1e4 N/m) at Δt = 1 µs, where a step moves it 3.6 µm against an overlap 0.5 mm deep at 5 %: the overlap
    // grows over many steps beyond 5 %. A smaller Δt would not change it, so the advice must be the stiffness or the
    // overlap limit.
    let e = 1e4;
    let dt = 1e-6;
    let mut world = world(config(dt, law(e, 0.5, 0.5), 0.0));
    add_static_wall(&mut world, &rectangle(0.01, 0.1).unwrap(), Pose::new(DVec2::ZERO, 0.0));
    let start = Pose::new(DVec2::new(-0.0101, 0.0), 0.0);
    world.add_particle(square(SIDE).unwrap(), start, RHO_THESIS, DVec2::new(3.6, 0.0), 0.0).unwrap();
    let error = world.run_until(0.1).expect_err("the overlap exceeds the limit");
    match &error {
        WorldError::Safety(SafetyError::ExcessiveOverlap { approach_per_step, approach_speed_m_s, .. }) => {
            assert!(*approach_per_step < 0.25, "the overlap grew over many steps: {approach_per_step}");
            assert!(*approach_speed_m_s > 0.0 && *approach_speed_m_s <= 3.6, "{approach_speed_m_s}");
        }
        other => panic!("expected ExcessiveOverlap, got {other:?}"),
    }
    let message = error.to_string();
    assert!(message.contains("too soft") && message.contains("max_overlap_fraction"), "{message}");
    assert!(!message.contains("reduce the time step"), "{message}");
}

/// Steps `world` up to `steps` times and checks that every step either fails or leaves every particle and every
/// ledger entry finite. Returns the error, if one stopped the run.
fn run_checking_finiteness(world: &mut World, steps: usize) -> Option<WorldError> {
    for _ in 0..steps {
        if let Err(error) = world.step() {
            return Some(error);
        }
        let b = world.bodies();
        for id in b.particles() {
            let i = id.index();
            let finite = b.pose[i].position.is_finite()
                && b.pose[i].angle.is_finite()
                && b.velocity[i].is_finite()
                && b.angular_velocity[i].is_finite();
            assert!(finite, "step {} returned Ok with particle {i} not finite: {:?}", world.steps(), b.pose[i]);
        }
        let l = world.ledger();
        let entries = [l.total(), l.dissipated(), l.work_in(), l.opening_residual, l.balance_error(), l.energy_scale()];
        assert!(entries.iter().all(|e| e.is_finite()), "step {} returned Ok with a ledger {l:?}", world.steps());
    }
    None
}

#[test]
fn non_finite_numbers_never_pass_silently() {
    let mut relaxed = config(1e-5, law(E_THESIS, 0.5, 0.5), G);
    relaxed.safety.allow_unsafe_time_step = true;

    // A speed whose kinetic energy overflows.
    let mut world = common::world(relaxed.clone());
    world
        .add_particle(square(SIDE).unwrap(), Pose::new(DVec2::ZERO, 0.0), RHO_THESIS, DVec2::new(1e160, 0.0), 0.0)
        .unwrap();
    let error = run_checking_finiteness(&mut world, 3).expect("an infinite kinetic energy must stop the run");
    assert!(matches!(error, WorldError::Safety(SafetyError::NotFinite { body: 0, .. })), "{error:?}");

    // A position that overflows within a few steps.
    let mut world = common::world(relaxed.clone());
    world
        .add_particle(
            square(SIDE).unwrap(),
            Pose::new(DVec2::new(1.7e308, 0.0), 0.0),
            RHO_THESIS,
            DVec2::new(1e308, 0.0),
            0.0,
        )
        .unwrap();
    let error = run_checking_finiteness(&mut world, 3).expect("an overflowing position must stop the run");
    assert!(matches!(error, WorldError::Safety(SafetyError::NotFinite { body: 0, .. })), "{error:?}");

    // A violent collision with every blow-up limit switched off: squares at 1 km/s, Δt 100× the bound. Whatever
    // the numbers do, a step that returns Ok has finite state.
    let mut violent = relaxed;
    violent.time_step = 100.0 * safe_time_step();
    violent.gravity = gc2d_engine::schedules::GravitySchedule::constant(0.0);
    violent.safety.max_overlap_fraction = f64::INFINITY;
    violent.safety.max_energy_gain_fraction = f64::INFINITY;
    violent.safety.max_travel_fraction = f64::INFINITY;
    let mut world = common::world(violent);
    let shape = square(SIDE).unwrap();
    for (x, v) in [(-0.006, 1e3), (0.006, -1e3)] {
        world.add_particle(&shape, Pose::new(DVec2::new(x, 0.0), 0.3), RHO_THESIS, DVec2::new(v, 0.0), 0.0).unwrap();
    }
    run_checking_finiteness(&mut world, 200);
}

#[test]
fn a_source_inserting_a_particle_too_small_for_the_time_step_stops_the_run() {
    use gc2d_engine::{DropHeight, DropSource, ParticleRecipe, TimeWindow};
    use gc2d_geometry::{AngleMode, Randomization, ShapeRecipe};
    // The World starts empty, so the first step has nothing to check; the inserted square sets the bound.
    let mut world = world(config(1.5 * safe_time_step(), law(E_THESIS, 0.5, 0.5), G));
    world
        .add_source(DropSource {
            position: DVec2::ZERO,
            width: 0.0,
            height: DropHeight::Absolute,
            window: TimeWindow::new(0.0, 1.0),
            interval: 0.01,
            recipe: ParticleRecipe::Polygon(ShapeRecipe {
                // SPECIAL_RECTANGLE with 4 corners on semi-axes a gives a square of side a·√2.
                semi_axes: DVec2::splat(SIDE / 2f64.sqrt()),
                size_variation: 0.0,
                size_randomization: Randomization::Const,
                corners: 4,
                corner_variation: 0,
                corner_randomization: Randomization::Const,
                angle_mode: AngleMode::SpecialRectangle,
                rotation: 0.0,
                rotation_randomization: Randomization::Const,
            }),
            density: RHO_THESIS,
            material: MaterialId::default(),
        })
        .unwrap();
    match world.step() {
        Err(WorldError::Safety(SafetyError::UnsafeTimeStep { safe_dt, .. })) => {
            assert!((safe_dt - offered_time_step()).abs() < 1e-12 * safe_dt, "bound {safe_dt:e}");
        }
        other => panic!("expected UnsafeTimeStep after the insertion, got {other:?}"),
    }
}
