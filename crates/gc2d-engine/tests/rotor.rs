//! A rotor blade striking a resting steel ball: the ball leaves at (1 + e(V))·V, the blade's angular impulse equals
//! the ball's angular momentum change about the axis, and the rotor's power from its torque, ω·τ, equals the power
//! its blade delivers through the contact, Σ F·v, at every step; summed over the steps, both are the ledger's wall work.

mod common;

use gc2d_contact::{ImpactLaw, NormalSpring, PenetrationDamping, PenetrationLaw};
use gc2d_engine::motion::Rotation;
use gc2d_engine::{BodyShape, ContactEventKind, TimeWindow, WallMotion, World};
use gc2d_geometry::{DVec2, Pose, cross};

/// E* of two steel bodies (E = 196.2 GPa, ν = 0.3), Pa.
const STEEL_E_STAR: f64 = 196.2e9 / (2.0 * (1.0 - 0.09));
/// Radius and density of the ball.
const RADIUS: f64 = 0.0025;
const DENSITY: f64 = 7700.0;
/// The rotor's angular velocity, rad/s, and the ball's distance from the pivot, m: the blade meets it at 5 m/s.
const OMEGA: f64 = 100.0;
const BALL_RADIUS_FROM_PIVOT: f64 = 0.05;
/// The blade: a capsule from the pivot out to 7 cm, 4 mm thick.
const BLADE_HALF_LENGTH: f64 = 0.035;
const BLADE_RADIUS: f64 = 0.002;

#[test]
fn a_blade_striking_a_resting_ball_throws_it_at_one_plus_e_times_its_speed() {
    let law = PenetrationLaw {
        damping: Some(PenetrationDamping::VelocityDependent(ImpactLaw::SteelReichardt)),
        ..PenetrationLaw::elastic(NormalSpring::Hertz { effective_modulus_pa: STEEL_E_STAR })
    };
    let mut world = common::sphere_world(law, 2e-8, 0.0);
    let pivot = DVec2::ZERO;
    let rotation =
        Rotation { pivot, angular_velocity: OMEGA, window: TimeWindow::new(0.0, f64::INFINITY), spin_up: 0.0 };
    let blade = world.add_wall(
        BodyShape::Capsule { half_length: BLADE_HALF_LENGTH, radius: BLADE_RADIUS },
        Pose::new(DVec2::new(BLADE_HALF_LENGTH, 0.0), 0.0),
        DVec2::ZERO,
        WallMotion::Rotating(rotation),
    );
    // The ball rests just above the blade's upper face, which turns towards it.
    let start = DVec2::new(BALL_RADIUS_FROM_PIVOT, BLADE_RADIUS + RADIUS + 1e-6);
    let ball = world.add_particle(BodyShape::Disk { radius: RADIUS }, Pose::new(start, 0.0), DENSITY, DVec2::ZERO, 0.0);
    let ball = ball.unwrap().index();
    world.record_contact_events();
    let (mass, inertia) = (world.bodies().mass[ball], world.bodies().inertia[ball]);
    let angular_momentum = |w: &World| {
        let b = w.bodies();
        mass * cross(b.pose[ball].position - pivot, b.velocity[ball]) + inertia * b.angular_velocity[ball]
    };
    let before = angular_momentum(&world);
    let mut end = None;
    let mut power_steps = 0;
    while end.is_none() {
        world.step().unwrap();
        let load = world.wall_load(blade, pivot);
        if load.contacts > 0 {
            let by_torque = -world.bodies().angular_velocity[blade.index()] * load.torque;
            assert!(
                (by_torque - load.power).abs() <= 1e-9 * load.power.abs(),
                "step {}: ω·τ = {by_torque} W, Σ F·v = {} W",
                world.steps(),
                load.power
            );
            power_steps += 1;
        }
        end = world.contact_events().iter().find(|e| e.kind == ContactEventKind::End).copied();
        assert!(world.time() < 2e-3, "no impact");
    }
    assert!(power_steps > 100, "the impact spans {power_steps} steps");
    let end = end.unwrap();
    let blade_speed = OMEGA * BALL_RADIUS_FROM_PIVOT;
    let speed = world.bodies().velocity[ball].length();
    let expected = (1.0 + ImpactLaw::SteelReichardt.restitution(blade_speed)) * blade_speed;
    assert!((speed - expected).abs() < 0.02 * expected, "the ball leaves at {speed} m/s, expected {expected} m/s");
    let gained = angular_momentum(&world) - before;
    let given = -end.wall_angular_impulse.expect("the blade turns about a pivot");
    assert!((given - gained).abs() < 1e-3 * gained.abs(), "angular impulse {given} against the ball's gain {gained}");
    // The rotor's work summed over the steps is the ledger's wall work (the blade is the only moving wall), by its
    // torque as by its force, and it is the ball's kinetic energy less what the contact dissipated.
    let work = world.rotor_work();
    let walls = world.ledger().work_walls;
    assert!(walls > 0.0);
    assert!((work.from_work - walls).abs() <= 1e-9 * walls, "Σ F·v Δt = {} J, ledger {walls} J", work.from_work);
    assert!((work.from_torque - walls).abs() <= 1e-9 * walls, "Σ ω τ Δt = {} J, ledger {walls} J", work.from_torque);
}
