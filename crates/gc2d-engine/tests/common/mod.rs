//! Shared set-up of the engine's physics acceptance tests (reference §6, §10.3 level 1): material laws, Worlds,
//! walls and the few measurements several test files need.

#![allow(dead_code)] // each test file uses its own subset of these helpers

use gc2d_contact::{ContactLaw, CundallStrack, NormalDamping, NormalElastic};
use gc2d_engine::schedules::GravitySchedule;
use gc2d_engine::{
    BodyId, ContactModel, Integrator, InteractionTable, MassModel, SafetyLimits, World, WorldConfig, WorldError,
};
use gc2d_geometry::{Aabb, ConvexPolygon, DVec2, Pose, contact_geometry, rectangle};

/// Young's modulus of almost all of the thesis's production runs, N/m (reference §2.14).
pub const E_THESIS: f64 = 1e7;

/// Area density of the thesis's silo particles, kg/m² (reference §2.14).
pub const RHO_THESIS: f64 = 5000.0;

/// The default g, m/s².
pub const G: f64 = 9.81;

/// A contact law with Young's modulus `e`, damping γ and friction μ; a zero γ or μ switches the sub-model off.
pub fn law(e: f64, gamma: f64, mu: f64) -> ContactLaw {
    ContactLaw {
        elastic: NormalElastic::thesis(e),
        damping: (gamma > 0.0).then_some(NormalDamping { gamma }),
        friction: (mu > 0.0).then_some(CundallStrack { mu }),
        cohesion: None,
    }
}

/// A World configuration with one material whose bodies interact by `model` (an overlap-area or a penetration law),
/// masses per unit thickness, and the engine's defaults for everything not named.
pub fn config(dt: f64, model: impl Into<ContactModel>, g: f64) -> WorldConfig {
    WorldConfig {
        time_step: dt,
        integrator: Integrator::default(),
        interactions: InteractionTable::uniform(model),
        mass_model: MassModel::PerUnitThickness,
        gravity: GravitySchedule::constant(g),
        heating: None,
        safety: SafetyLimits::default(),
        domain: None,
        seed: 1,
    }
}

/// An empty World of spheres moving in the plane (sphere-equivalent masses) whose bodies interact by `model`.
pub fn sphere_world(model: impl Into<ContactModel>, dt: f64, g: f64) -> World {
    world(WorldConfig { mass_model: MassModel::SphereEquivalent, ..config(dt, model, g) })
}

/// An empty World built from `config`, which the tests expect to be valid.
pub fn world(config: WorldConfig) -> World {
    World::new(config).expect("valid test configuration")
}

/// Adds a static wall of the given outline at `pose`.
pub fn add_static_wall(world: &mut World, shape: &ConvexPolygon, pose: Pose) -> BodyId {
    world.add_wall(shape, pose, DVec2::ZERO, Default::default())
}

/// Encloses `inner` with four static walls of thickness `thickness` (floor, ceiling, left and right side).
pub fn add_box(world: &mut World, inner: Aabb, thickness: f64) -> [BodyId; 4] {
    let size = inner.max - inner.min;
    let centre = 0.5 * (inner.min + inner.max);
    let horizontal = rectangle(size.x + 2.0 * thickness, thickness).expect("wall outline");
    let vertical = rectangle(thickness, size.y).expect("wall outline");
    let half = 0.5 * thickness;
    [
        add_static_wall(world, &horizontal, Pose::new(DVec2::new(centre.x, inner.min.y - half), 0.0)),
        add_static_wall(world, &horizontal, Pose::new(DVec2::new(centre.x, inner.max.y + half), 0.0)),
        add_static_wall(world, &vertical, Pose::new(DVec2::new(inner.min.x - half, centre.y), 0.0)),
        add_static_wall(world, &vertical, Pose::new(DVec2::new(inner.max.x + half, centre.y), 0.0)),
    ]
}

/// Steps once, panicking with the engine's message on an error.
pub fn step(world: &mut World) {
    if let Err(error) = world.step() {
        panic!("step {} failed: {error}", world.steps());
    }
}

/// Steps until the World's first contact has come and gone (at most 100,000 steps, else it panics) and returns the
/// relative change of the kinetic energy over it: after/before − 1. For single elastic collisions and impacts.
pub fn kinetic_change_over_one_contact(world: &mut World) -> f64 {
    let before = world.ledger().kinetic();
    let mut touched = false;
    for _ in 0..100_000 {
        step(world);
        let touching = world.contacts().next().is_some();
        if touched && !touching {
            return world.ledger().kinetic() / before - 1.0;
        }
        touched |= touching;
    }
    panic!("the contact did not end within 100,000 steps");
}

/// Steps until `t_end`, panicking with the engine's message on an error.
pub fn run_until(world: &mut World, t_end: f64) {
    let result: Result<(), WorldError> = world.run_until(t_end);
    if let Err(error) = result {
        panic!("run failed at step {}: {error}", world.steps());
    }
}

/// The contact normal (from `b` towards `a`) the engine used in the last step: the contact geometry of the two
/// bodies' world vertices, which the World keeps at the predicted poses the narrowphase saw.
pub fn contact_normal(world: &World, a: BodyId, b: BodyId) -> Option<DVec2> {
    let bodies = world.bodies();
    contact_geometry(bodies.world_vertices_of(a), bodies.world_vertices_of(b)).map(|g| g.normal)
}

/// The force on `body` from its contact with `other` in the last step (zero when they did not touch).
pub fn contact_force_on(world: &World, body: BodyId, other: BodyId) -> DVec2 {
    world
        .contacts()
        .find_map(|(a, b, c)| {
            if (a, b) == (body, other) {
                Some(c.force_on_a)
            } else if (a, b) == (other, body) {
                Some(-c.force_on_a)
            } else {
                None
            }
        })
        .unwrap_or(DVec2::ZERO)
}

/// Σ m·v over the living particles.
pub fn momentum(world: &World) -> DVec2 {
    let b = world.bodies();
    b.particles().map(|id| b.mass[id.index()] * b.velocity[id.index()]).sum()
}

/// Position, velocity and angle of a body, for measurements along a direction.
pub fn position(world: &World, id: BodyId) -> DVec2 {
    world.bodies().pose[id.index()].position
}

/// Velocity of a body's centroid.
pub fn velocity(world: &World, id: BodyId) -> DVec2 {
    world.bodies().velocity[id.index()]
}

/// The least-squares slope of `ys` against `xs`.
pub fn fitted_slope(xs: &[f64], ys: &[f64]) -> f64 {
    let n = xs.len() as f64;
    let (mean_x, mean_y) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let covariance: f64 = xs.iter().zip(ys).map(|(x, y)| (x - mean_x) * (y - mean_y)).sum();
    let variance: f64 = xs.iter().map(|x| (x - mean_x).powi(2)).sum();
    covariance / variance
}
