//! Heating (the particles' size factor s(t), reference §1.6) in the energy ledger and in the particles' spin: a
//! spinning particle keeps its angular momentum I·ω while I grows with s², and the work the expansion does on the
//! contacts it presses deeper is booked as `work_heating`, so the ledger still balances (docs/model.md, "Mass under
//! heating").

mod common;

use common::{E_THESIS, RHO_THESIS, add_box, law, step};
use gc2d_contact::{NormalSpring, PenetrationLaw};
use gc2d_engine::schedules::HeatingSchedule;
use gc2d_engine::time_window::TimeWindow;
use gc2d_engine::{BodyShape, ContactModel, Integrator, World, WorldConfig};
use gc2d_geometry::{Aabb, DVec2, Pose, regular_polygon, square};

/// Heating by a = `amplitude` at 2 Hz, slope 4, from t = 0 to `end`.
fn heating(amplitude: f64, end: f64) -> HeatingSchedule {
    HeatingSchedule { window: TimeWindow::new(0.0, end), amplitude, frequency: 2.0, slope: 4.0 }
}

/// A World heated by `schedule` whose bodies interact by `model`, with gravity `g`.
fn heated_world(model: impl Into<ContactModel>, dt: f64, g: f64, schedule: HeatingSchedule) -> World {
    common::world(WorldConfig { heating: Some(schedule), ..common::config(dt, model, g) })
}

/// Particle `index`'s angular momentum about its centroid, I(s)·ω.
fn angular_momentum(world: &World, index: usize) -> f64 {
    let b = world.bodies();
    let scale = b.pose[index].scale;
    b.inertia[index] * HeatingSchedule::inertia_factor(scale) * b.angular_velocity[index]
}

#[test]
fn a_spinning_particle_keeps_its_angular_momentum_while_heated() {
    for integrator in [Integrator::default(), Integrator::VelocityVerlet] {
        let config = WorldConfig {
            heating: Some(heating(0.1, 1.0)),
            integrator,
            ..common::config(1e-4, law(E_THESIS, 0.0, 0.0), 0.0)
        };
        let mut world = common::world(config);
        let hexagon = regular_polygon(6, 0.01).unwrap();
        let id = world.add_particle(&hexagon, Pose::new(DVec2::ZERO, 0.0), RHO_THESIS, DVec2::ZERO, 10.0).unwrap();
        let start = angular_momentum(&world, id.index());
        let initial_rotational = world.ledger().kinetic_rotational;
        let mut largest_scale: f64 = 1.0;
        for _ in 0..10_000 {
            step(&mut world);
            let momentum = angular_momentum(&world, id.index());
            assert!((momentum / start - 1.0).abs() < 1e-12, "{integrator:?}: I·ω {momentum} against {start}");
            largest_scale = largest_scale.max(world.bodies().pose[id.index()].scale);
            let l = world.ledger();
            let change = l.kinetic_rotational - initial_rotational;
            let work = l.work_heating;
            assert!((work - change).abs() <= 1e-12 * initial_rotational, "{integrator:?}: {work} against {change}");
            assert!(l.balance_error().abs() <= 1e-12 * initial_rotational, "balance error {}", l.balance_error());
        }
        assert!(largest_scale > 1.099, "the particle grew to s = {largest_scale}");
    }
}

/// Three disks in a row, touching and at rest, without gravity, pushed apart by heating: all the kinetic energy they
/// gain is the heating's work on their two contacts (a Hertz contact deepens by R_i + R_j per unit of ln s).
#[test]
fn heating_pushes_touching_disks_apart_with_the_work_it_books() {
    let spring = NormalSpring::Hertz { effective_modulus_pa: 1e8 };
    let mut world = heated_world(PenetrationLaw::elastic(spring), 1e-6, 0.0, heating(0.01, 0.25));
    for k in 0..3 {
        let pose = Pose::new(DVec2::new(0.02 * f64::from(k), 0.0), 0.0);
        world.add_particle(BodyShape::Disk { radius: 0.01 }, pose, 7700.0, DVec2::ZERO, 0.0).unwrap();
    }
    while world.time() < 0.25 {
        step(&mut world);
    }
    let l = world.ledger();
    // Measured: the kinetic energy 1.1613213765e-4 J against the booked work 1.1613213979e-4 J (1.8e-8 apart; 1.5e-4
    // before the Hertz spring's stiffening with the growing radius was booked too).
    assert!(l.kinetic() > 1e-4, "the disks gained {} J", l.kinetic());
    assert!(
        (l.kinetic() / l.work_heating - 1.0).abs() < 1e-6,
        "kinetic {} against work {}",
        l.kinetic(),
        l.work_heating
    );
    assert!(l.balance_error().abs() < 1e-6 * l.work_heating, "balance error {}", l.balance_error());
}

/// A pile of hexagons and squares settled in a box under gravity, with damping and friction (the thesis's law), then
/// heated through one cycle: the expansion's work on the contacts, most of it given back as the particles shrink, is
/// booked, so the balance error stays where settling left it.
#[test]
fn a_heated_damped_pile_balances_its_ledger() {
    let schedule = HeatingSchedule { window: TimeWindow::new(0.4, 0.9), ..heating(0.02, 0.9) };
    // Δt well below the bound: at 2e-5 s the flat contacts chatter, and the balance error grows by the dissipation
    // the chatter books whether heated or not (docs/validation.md, "Damping limit of flat contacts").
    let mut world = heated_world(law(E_THESIS, 0.3, 0.5), 5e-6, 9.81, schedule);
    add_box(&mut world, Aabb { min: DVec2::new(-0.05, 0.0), max: DVec2::new(0.05, 0.2) }, 0.01);
    let hexagon = regular_polygon(6, 0.006).unwrap();
    let small = square(0.009).unwrap();
    for row in 0..5 {
        for column in 0..8 {
            let shape = if (row + column) % 2 == 0 { &hexagon } else { &small };
            let position = DVec2::new(-0.042 + 0.012 * f64::from(column), 0.007 + 0.013 * f64::from(row));
            world.add_particle(shape, Pose::new(position, 0.1 * f64::from(row)), RHO_THESIS, DVec2::ZERO, 0.0).unwrap();
        }
    }
    while world.time() < 0.4 {
        step(&mut world);
    }
    let settled = *world.ledger();
    let (mut gross_work, mut last_work, mut largest_drift): (f64, f64, f64) = (0.0, settled.work_heating, 0.0);
    while world.time() < 0.9 {
        step(&mut world);
        let l = world.ledger();
        gross_work += (l.work_heating - last_work).abs();
        last_work = l.work_heating;
        largest_drift = largest_drift.max((l.balance_error() - settled.balance_error()).abs());
    }
    let l = world.ledger();
    let (net_work, dissipated) = (l.work_heating - settled.work_heating, l.dissipated() - settled.dissipated());
    assert!(gross_work > 0.1, "the heating did {gross_work} J of work in and out");
    assert!(net_work > 0.0 && dissipated > 0.0, "net work {net_work}, dissipated {dissipated}");
    assert!(largest_drift < 1e-3 * gross_work, "the balance error moved by {largest_drift} J");
}
