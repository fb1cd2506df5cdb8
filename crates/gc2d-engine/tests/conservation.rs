//! Conservation of particles: a closed box loses none; a particle that leaves the `domain` is removed, counted, and
//! its energy is booked, so the ledger still balances.

mod common;

use common::*;
use gc2d_engine::World;
use gc2d_geometry::{Aabb, DVec2, Pose, regular_polygon};

#[test]
fn closed_box_keeps_every_particle_inside() {
    // 40 fast 9-gons (up to 2 m/s) bouncing for 0.1 s in a 6 cm box with damping and friction.
    let mut world = world(config(5e-6, law(E_THESIS, 0.3, 0.5), G));
    let inner = Aabb { min: DVec2::ZERO, max: DVec2::splat(0.06) };
    add_box(&mut world, inner, 0.005);
    let shape = regular_polygon(9, 2e-3).unwrap();
    for k in 0..40 {
        let position = DVec2::new(0.005 + 0.0125 * (k % 5) as f64, 0.005 + 0.007 * (k / 5) as f64);
        let velocity = DVec2::from_angle(k as f64) * 2.0;
        world.add_particle(&shape, Pose::new(position, 0.1 * k as f64), RHO_THESIS, velocity, 0.0).unwrap();
    }
    run_until(&mut world, 0.1);
    let b = world.bodies();
    assert_eq!(b.particles().count(), 40, "no particle may be lost");
    assert_eq!(world.stats().removed, 0);
    for id in b.particles() {
        let p = b.pose[id.index()].position;
        assert!(inner.min.cmple(p).all() && p.cmple(inner.max).all(), "particle {} escaped to {p}", id.0);
    }
}

/// Kinetic plus potential energy of one particle, as the ledger books it.
fn mechanical_energy(world: &World, i: usize) -> f64 {
    let b = world.bodies();
    0.5 * b.mass[i] * b.velocity[i].length_squared()
        + 0.5 * b.angular_velocity[i].powi(2) / b.inverse_inertia[i]
        + b.mass[i] * world.gravity() * b.pose[i].position.y
}

#[test]
fn particle_leaving_the_domain_is_removed_counted_and_booked() {
    let mut config = config(1e-5, law(E_THESIS, 0.5, 0.5), G);
    config.domain = Some(Aabb { min: DVec2::splat(-0.05), max: DVec2::splat(0.05) });
    let mut world = world(config);
    let shape = regular_polygon(7, 2e-3).unwrap();
    // One particle flies out through x = 0.05 at t = 0.05 s; the other goes up and comes back, staying inside.
    let leaving =
        world.add_particle(&shape, Pose::new(DVec2::ZERO, 0.0), RHO_THESIS, DVec2::new(1.0, 0.0), 3.0).unwrap();
    let staying =
        world.add_particle(&shape, Pose::new(DVec2::new(-0.02, 0.0), 0.0), RHO_THESIS, DVec2::new(0.0, 0.5), 0.0);
    let staying = staying.unwrap();
    let mut removal_time = None;
    let mut previous_balance = 0.0;
    while world.time() < 0.1 {
        step(&mut world);
        let ledger = *world.ledger();
        let scale = ledger.energy_scale();
        // Free flight: the ledger balances to round-off, measured 2.9e-14 of the scale at most (2026-11-28; 5.1e-5
        // when this test was written, the Gear start-up of the first step).
        assert!(ledger.balance_error().abs() < 1e-10 * scale, "t = {}: ledger {ledger:?}", world.time());
        if removal_time.is_none() && world.stats().removed == 1 {
            // Removing the particle and booking its energy leaves the balance as it was (measured change 3e-18 J).
            let change = ledger.balance_error() - previous_balance;
            assert!(change.abs() < 1e-12 * scale, "the removal changed the balance by {change:e} J");
            removal_time = Some(world.time());
            // The removed particle's columns keep its state at removal: that is what the ledger booked.
            let booked = world.ledger().energy_removed;
            let expected = mechanical_energy(&world, leaving.index());
            assert!((booked - expected).abs() <= 1e-12 * expected.abs(), "booked {booked}, its energy {expected}");
        }
        previous_balance = ledger.balance_error();
    }
    let removal_time = removal_time.expect("the particle must leave the domain");
    assert!((removal_time - 0.05).abs() <= 1e-5 + 1e-12, "removed at t = {removal_time}");
    assert!(!world.bodies().alive[leaving.index()]);
    assert!(world.bodies().alive[staying.index()]);
    assert_eq!(world.stats().removed, 1);
    assert_eq!(world.bodies().particles().collect::<Vec<_>>(), vec![staying]);
}
