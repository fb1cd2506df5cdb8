//! Friction validation (reference §6.1, §10.3 level 1 items 5 and 6): a block on an incline rests just below
//! Θ = arctan μ and slides with a = g(sin Θ − μ cos Θ) just above it; a block pulled by a drag spring starts to slide
//! when the spring force reaches μ·m·g.

mod common;

use common::*;
use gc2d_engine::schedules::DragSpring;
use gc2d_engine::{BodyId, TimeWindow, World};
use gc2d_geometry::{DVec2, Pose, rectangle};

/// The incline's block: a flat 40 mm × 4 mm rectangle, ρ = 5000 kg/m² (m = 0.8 kg). Flat because the contact law
/// puts the whole normal force at the chord midpoint: a block can only carry the tipping moment of friction,
/// m·g·sin Θ·h/2, by lifting a corner, and for tan Θ·h/w above ≈ 0.08 that corner contact rocks and the block walks
/// down the slope under the thesis law these tests check (docs/model.md, "Validation of the engine"; the Winkler
/// formulation, which holds square and tall blocks, is tested in `crates/gc2d-scene/tests/incline_rest.rs`).
const INCLINE_BLOCK: DVec2 = DVec2::new(0.04, 0.004);
/// Δt of the incline runs. The corner contact of this flat block is a stiff rocking mode: at 10 µs (0.4 of the §3.6
/// bound of 25 µs) it oscillates at the Nyquist frequency and the block slides; 2.5 µs is stable.
const INCLINE_DT: f64 = 2.5e-6;
/// γ of the friction tests (the thesis's default).
const GAMMA: f64 = 0.5;

/// A static floor tilted by `theta` (its top surface through the origin) with a block lying on it, just touching,
/// started with speed `v0` down the slope.
struct Incline {
    world: World,
    block: BodyId,
    downhill: DVec2,
}

fn incline(theta: f64, mu: f64, v0: f64) -> Incline {
    let mut world = world(config(INCLINE_DT, law(E_THESIS, GAMMA, mu), G));
    let uphill = DVec2::from_angle(theta);
    let normal = uphill.perp();
    let floor_thickness = 0.02;
    let floor = rectangle(0.5, floor_thickness).unwrap();
    add_static_wall(&mut world, &floor, Pose::new(-0.5 * floor_thickness * normal, theta));
    let shape = rectangle(INCLINE_BLOCK.x, INCLINE_BLOCK.y).unwrap();
    let pose = Pose::new(0.5 * INCLINE_BLOCK.y * normal, theta);
    let block = world.add_particle(&shape, pose, RHO_THESIS, -v0 * uphill, 0.0).unwrap();
    Incline { world, block, downhill: -uphill }
}

impl Incline {
    fn downhill_position(&self) -> f64 {
        position(&self.world, self.block).dot(self.downhill)
    }

    fn downhill_velocity(&self) -> f64 {
        velocity(&self.world, self.block).dot(self.downhill)
    }
}

const MUS: [f64; 3] = [0.2, 0.4, 0.6];

#[test]
fn block_below_the_friction_angle_stops_and_stays_at_rest() {
    // Started at 1 cm/s down the slope, the block decelerates at g(μ cos Θ − sin Θ) ≈ 0.18 m/s² and stops within
    // about 0.06 s, after 1 to 1.2 times v0²/2a (measured 1.055, 1.064, 1.152: it slides further while its contact
    // loads up during the first milliseconds, when the cap μF⊥ is still below μ·m·g·cos Θ). From 0.1 s to 0.3 s its centroid must not creep by more than 1e-5 of the block's width
    // (the reference proposes 1e-3 over 1 s). Measured: 2e-8 (μ = 0.2, 0.4) and 4.8e-6 (μ = 0.6) of the width.
    for mu in MUS {
        let theta = mu.atan() - 1f64.to_radians();
        let mut incline = incline(theta, mu, 0.01);
        let deceleration = G * (mu * theta.cos() - theta.sin());
        run_until(&mut incline.world, 0.1);
        let slid = incline.downhill_position();
        let expected_slide = 0.01 * 0.01 / (2.0 * deceleration);
        assert!(
            (1.0..1.2).contains(&(slid / expected_slide)),
            "μ = {mu}: slid {slid:e} m before stopping, expected v0²/2a = {expected_slide:e} m"
        );
        let start = incline.downhill_position();
        run_until(&mut incline.world, 0.3);
        let creep = (incline.downhill_position() - start).abs() / INCLINE_BLOCK.x;
        assert!(creep < 1e-5, "μ = {mu}, Θ = {:.2}°: creep {creep:e} of the block's width", theta.to_degrees());
        assert!(incline.downhill_velocity().abs() < 1e-5, "μ = {mu}: still moving at {}", incline.downhill_velocity());
    }
}

#[test]
fn block_above_the_friction_angle_slides_with_the_coulomb_acceleration() {
    // The acceleration is the slope of a least-squares line through the downhill velocity from 0.02 s to 0.15 s.
    // Measured relative errors 2.4e-7, 6.2e-7, 1.0e-6; the bound is 1e-3.
    for mu in MUS {
        let theta = mu.atan() + 1f64.to_radians();
        let mut incline = incline(theta, mu, 0.0);
        let (mut times, mut velocities) = (Vec::new(), Vec::new());
        while incline.world.time() < 0.15 {
            step(&mut incline.world);
            if incline.world.time() > 0.02 {
                times.push(incline.world.time());
                velocities.push(incline.downhill_velocity());
            }
        }
        let measured = fitted_slope(&times, &velocities);
        let expected = G * (theta.sin() - mu * theta.cos());
        assert!(
            (measured / expected - 1.0).abs() < 1e-3,
            "μ = {mu}: acceleration {measured} m/s², Coulomb {expected} m/s²"
        );
    }
}

/// The pull test's block: 20 mm × 10 mm at ρ = 500 kg/m², m = 0.1 kg as in the thesis.
const PULL_BLOCK: DVec2 = DVec2::new(0.02, 0.01);
const PULL_DENSITY: f64 = 500.0;
const PULL_DT: f64 = 5e-6;
/// Drag spring stiffness, N/m (gc2d's default `DRAG_K`).
const PULL_STIFFNESS: f64 = 100.0;
/// The pulling point starts to move once the block has settled on the floor.
const PULL_START: f64 = 0.01;

/// Pulls a resting block along +x and returns the spring force at the onset of sliding and μ·m·g.
///
/// Onset: the block counts as resting while its speed is below 1 % of the pulling speed; sliding is confirmed when
/// its speed first exceeds half the pulling speed; the onset force is the spring force at the last resting step
/// before that. The pulling speed is proportional to μ (2.2 cm/s per unit μ), so every run takes the same
/// ≈ 0.45 s to reach μ·m·g, and the force added between the true onset and the 1 % threshold,
/// v·sqrt(2·0.01·K·m), stays below 1 % of μ·m·g.
fn pull(mu: f64) -> (f64, f64) {
    let mut world = world(config(PULL_DT, law(E_THESIS, GAMMA, mu), G));
    let floor = rectangle(0.5, 0.02).unwrap();
    add_static_wall(&mut world, &floor, Pose::new(DVec2::new(0.0, -0.01), 0.0));
    let shape = rectangle(PULL_BLOCK.x, PULL_BLOCK.y).unwrap();
    let block =
        world.add_particle(&shape, Pose::new(DVec2::new(0.0, 0.5 * PULL_BLOCK.y), 0.0), PULL_DENSITY, DVec2::ZERO, 0.0);
    let block = block.unwrap();
    let mass = world.bodies().mass[block.index()];
    let speed = 0.022 * mu;
    // Fixed at the middle of the block's base, so the pull and the friction form no tipping couple.
    let fixing_point = DVec2::new(0.0, -0.5 * PULL_BLOCK.y);
    let spring = DragSpring {
        stiffness: PULL_STIFFNESS,
        fixing_point,
        pulling_start: DVec2::ZERO, // the base's midpoint in the world: the spring starts unstretched
        direction_angle: 0.0,
        speed,
        window: TimeWindow::new(PULL_START, f64::INFINITY),
    };
    world.add_drag_spring(block, spring).unwrap();
    let mut last_resting_force = None;
    while world.time() < 1.0 {
        step(&mut world);
        let v = velocity(&world, block).x;
        let force = spring.force_and_torque(world.bodies().pose[block.index()], world.time()).0.x;
        if world.time() > PULL_START && v.abs() < 0.01 * speed {
            last_resting_force = Some(force);
        }
        if v > 0.5 * speed {
            let onset = last_resting_force.expect("the block must rest before it slides");
            return (onset, mu * mass * G);
        }
    }
    panic!("μ = {mu}: the block never slid");
}

#[test]
fn pulled_block_starts_to_slide_at_mu_m_g() {
    // Measured: +1.0 % for every μ, which is the detection lag v·sqrt(2·0.01·K·m)/(μ·m·g) = 0.99 %.
    for mu in [0.1, 0.3, 0.5, 0.8] {
        let (onset, coulomb) = pull(mu);
        assert!(
            (onset / coulomb - 1.0).abs() < 0.05,
            "μ = {mu}: sliding began at {onset} N, μ·m·g = {coulomb} N ({:+.2} %)",
            100.0 * (onset / coulomb - 1.0)
        );
    }
}

#[test]
fn a_belt_drags_a_block_to_its_surface_speed() {
    // A wall's virtual surface velocity (gc2d's drums and belts, §2.11): a block set down at rest on a floor whose
    // surface moves at 5 cm/s slides, accelerated by kinetic friction at μ·g, until it moves with the surface, then
    // rides along. A block on an ordinary floor beside it, added before the belt (a particle with a lower id than the
    // belt), stays at rest. Measured: 0.978 of μ·g·t at half the catch-up time (the contact loads up during the first
    // steps), then the belt's speed within 5e-5, and the other block at 8e-14 m/s.
    let (mu, belt_speed) = (0.4, 0.05);
    let mut world = world(config(INCLINE_DT, law(E_THESIS, GAMMA, mu), G));
    let floor = rectangle(0.2, 0.02).unwrap();
    let block = rectangle(INCLINE_BLOCK.x, INCLINE_BLOCK.y).unwrap();
    let on_floor = |x: f64| Pose::new(DVec2::new(x, 0.5 * INCLINE_BLOCK.y), 0.0);
    add_static_wall(&mut world, &floor, Pose::new(DVec2::new(-0.15, -0.01), 0.0));
    let resting = world.add_particle(&block, on_floor(-0.15), RHO_THESIS, DVec2::ZERO, 0.0).unwrap();
    let belt_pose = Pose::new(DVec2::new(0.15, -0.01), 0.0);
    world.add_wall(&floor, belt_pose, DVec2::new(belt_speed, 0.0), gc2d_engine::WallMotion::Static);
    let riding = world.add_particle(&block, on_floor(0.1), RHO_THESIS, DVec2::ZERO, 0.0).unwrap();

    let catch_up = belt_speed / (mu * G);
    run_until(&mut world, 0.5 * catch_up);
    let speed = velocity(&world, riding).x;
    assert!(
        (0.95..1.0).contains(&(speed / (0.5 * belt_speed))),
        "after half the catch-up time v/(μg) the block moves at {speed} m/s, expected about {}",
        0.5 * belt_speed
    );
    run_until(&mut world, 4.0 * catch_up);
    let speed = velocity(&world, riding).x;
    assert!((speed / belt_speed - 1.0).abs() < 1e-3, "the block rides at {speed} m/s on a belt at {belt_speed}");
    assert!(
        velocity(&world, resting).length() < 1e-9,
        "the block on the plain floor moves: {}",
        velocity(&world, resting)
    );
}
