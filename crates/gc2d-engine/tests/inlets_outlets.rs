//! Inlets and outlets (issue 15 item 3): exact insertion steps, postponed insertions, outward crossings only, the
//! particle count balancing at every step, and a checkpoint resume that stays bitwise identical.

use gc2d_contact::{ContactLaw, NormalDamping, NormalElastic};
use gc2d_engine::schedules::GravitySchedule;
use gc2d_engine::{
    DiskRecipe, GearC0, Inlet, Integrator, InteractionTable, MassModel, MaterialId, Outlet, ParticleRecipe,
    SafetyLimits, WallMotion, World, WorldConfig,
};
use gc2d_geometry::{Aabb, DVec2, Pose, Randomization, rectangle};

const DT: f64 = 1e-3;
/// Radius of the fed disks, m.
const RADIUS: f64 = 0.01;
/// Density of every particle, kg/m²: heavy enough that Δt = 1 ms is below the stable bound of the soft contacts.
const DENSITY: f64 = 1e4;

fn world(gravity: f64, domain: Option<Aabb>) -> World {
    World::new(WorldConfig {
        time_step: DT,
        integrator: Integrator::Gear6(GearC0::VelocityDependent),
        interactions: InteractionTable::uniform(ContactLaw {
            elastic: NormalElastic::thesis(1e5),
            damping: Some(NormalDamping { gamma: 0.3 }),
            friction: None,
            cohesion: None,
        }),
        mass_model: MassModel::PerUnitThickness,
        gravity: GravitySchedule::constant(gravity),
        heating: None,
        safety: SafetyLimits::default(),
        domain,
        seed: 11,
    })
    .unwrap()
}

fn disk(radius: f64) -> ParticleRecipe {
    ParticleRecipe::Disk(DiskRecipe { radius, size_randomization: Randomization::Const, size_variation: 0.0 })
}

/// An inlet along `from` → `to` (domain on the left) feeding `rate` disks per second at `velocity`.
fn inlet(from: DVec2, to: DVec2, rate: f64, velocity: DVec2) -> Inlet {
    Inlet {
        name: "feed".into(),
        from,
        to,
        rate,
        start: 0.0,
        stop: f64::INFINITY,
        velocity,
        angular_velocity: 0.0,
        recipe: disk(RADIUS),
        density: DENSITY,
        material: MaterialId(0),
    }
}

/// Particles present at the start and inserted since, against those alive and removed: equal at every step.
fn assert_balanced(world: &World, initial: u64) {
    let s = world.stats();
    let alive = world.bodies().particles().count() as u64;
    assert_eq!(
        initial + s.inserted + s.injected,
        alive + s.removed + s.removed_at_outlets,
        "particle count out of balance at step {}",
        world.steps()
    );
    let injected: u64 = world.inlets().iter().map(|i| i.counters().injected).sum();
    let removed: u64 = world.outlets().iter().map(|o| o.counters().removed).sum();
    assert_eq!((injected, removed), (s.injected, s.removed_at_outlets));
}

#[test]
fn ten_per_second_for_one_second_give_ten_particles_at_their_due_steps() {
    let mut world = world(0.0, None);
    world.add_inlet(inlet(DVec2::new(-0.05, 0.0), DVec2::new(0.05, 0.0), 10.0, DVec2::new(0.0, 1.0))).unwrap();
    let mut steps_of_injection = Vec::new();
    for _ in 0..1000 {
        let before = world.stats().injected;
        world.step().unwrap();
        if world.stats().injected > before {
            steps_of_injection.push(world.steps());
        }
        assert_balanced(&world, 0);
    }
    assert_eq!(world.bodies().particles().count(), 10);
    assert_eq!(steps_of_injection, (0..10).map(|k| 1 + 100 * k).collect::<Vec<u64>>());
    assert_eq!(world.inlets()[0].counters().postponed, 0);
    // Each particle starts on the segment with the inlet's velocity (no gravity, no contacts: it keeps it).
    for (k, id) in world.bodies().particles().enumerate() {
        let i = id.index();
        let flight = (1000 - steps_of_injection[k]) as f64 * DT;
        let position = world.bodies().pose[i].position;
        assert!(position.x.abs() <= 0.05, "{position}");
        assert!((position.y - flight).abs() < 1e-12, "particle {k} at {position}, {flight} m expected");
        assert!((world.bodies().velocity[i] - DVec2::new(0.0, 1.0)).length() < 1e-12);
    }
}

#[test]
fn a_covered_inlet_postpones_every_step_and_a_blocked_one_catches_up_without_drift() {
    // Covered by a wall for good: one postponed insertion per step, nothing inserted.
    let mut covered = world(0.0, None);
    let lid = rectangle(0.2, 0.05).unwrap();
    covered.add_wall(&lid, Pose::new(DVec2::ZERO, 0.0), DVec2::ZERO, WallMotion::Static);
    covered.add_inlet(inlet(DVec2::new(-0.05, 0.0), DVec2::new(0.05, 0.0), 10.0, DVec2::new(0.0, 1.0))).unwrap();
    for _ in 0..250 {
        covered.step().unwrap();
        assert_balanced(&covered, 0);
    }
    assert_eq!(covered.inlets()[0].counters().injected, 0);
    assert_eq!(covered.inlets()[0].counters().postponed, 250);
    assert_eq!(covered.stats().postponed, 250);

    // A particle of radius 2R sits on a short inlet and moves away at the feed speed: the first particle waits until
    // the spot is free, the later ones keep their due steps 101, 201, …
    let mut blocked = world(0.0, None);
    let blocker_radius = 2.0 * RADIUS;
    blocked
        .add_particle(
            gc2d_engine::BodyShape::Disk { radius: blocker_radius },
            Pose::new(DVec2::ZERO, 0.0),
            DENSITY,
            DVec2::new(0.0, 1.0),
            0.0,
        )
        .unwrap();
    let half = 1e-6;
    blocked.add_inlet(inlet(DVec2::new(-half, 0.0), DVec2::new(half, 0.0), 10.0, DVec2::new(0.0, 1.0))).unwrap();
    let mut steps_of_injection = Vec::new();
    for _ in 0..1000 {
        let blocker_y_before = blocked.bodies().pose[0].position.y;
        blocked.step().unwrap();
        let counters = blocked.inlets()[0].counters();
        if counters.injected as usize > steps_of_injection.len() {
            steps_of_injection.push(blocked.steps());
            if steps_of_injection.len() == 1 {
                // Free now, taken on the step before (the spot test is exact for disks).
                let clearance = blocker_radius + RADIUS;
                assert!(blocked.bodies().pose[0].position.y >= clearance - half, "inserted while blocked");
                assert!(blocker_y_before < clearance + half, "inserted a step late");
                assert_eq!(counters.postponed, blocked.steps() - 1);
            }
        }
        assert_balanced(&blocked, 1);
    }
    let first = steps_of_injection[0];
    assert!((25..35).contains(&first), "first insertion at step {first}");
    let expected: Vec<u64> = std::iter::once(first).chain((1..10).map(|k| 1 + 100 * k)).collect();
    assert_eq!(steps_of_injection, expected);
    assert_eq!(blocked.inlets()[0].counters().postponed, first - 1);
}

#[test]
fn an_outlet_removes_an_outward_crossing_only_and_books_its_energy() {
    let mut world = world(0.0, None);
    // Domain below the outlet (walking from +x to −x, the left is −y).
    world.add_outlet(Outlet { name: "top".into(), from: DVec2::new(0.1, 0.0), to: DVec2::new(-0.1, 0.0) }).unwrap();
    let shape = gc2d_engine::BodyShape::Disk { radius: RADIUS };
    let mut add = |x: f64, y: f64, vy: f64| {
        world.add_particle(shape.clone(), Pose::new(DVec2::new(x, y), 0.0), DENSITY, DVec2::new(0.0, vy), 0.0).unwrap()
    };
    let outward = add(0.0, -0.0505, 1.0);
    let inward = add(0.05, 0.0495, -1.0);
    let beside = add(0.3, -0.0505, 1.0);
    let mass = world.bodies().mass[outward.index()];
    let mut removed_at = None;
    for _ in 0..100 {
        let y_before = world.bodies().pose[outward.index()].position.y;
        world.step().unwrap();
        assert_balanced(&world, 3);
        if removed_at.is_none() && !world.bodies().alive[outward.index()] {
            removed_at = Some(world.steps());
            assert!(y_before <= 0.0, "removed a step late");
        } else if removed_at.is_none() {
            assert!(world.bodies().pose[outward.index()].position.y <= 0.0, "crossed but kept");
        }
    }
    assert_eq!(removed_at, Some(51));
    assert!(world.bodies().alive[inward.index()] && world.bodies().alive[beside.index()]);
    assert!(world.bodies().pose[inward.index()].position.y < -0.04);
    assert!(world.bodies().pose[beside.index()].position.y > 0.04);
    assert_eq!(world.outlets()[0].counters().removed, 1);
    assert_eq!(world.stats().removed, 0);
    let kinetic = 0.5 * mass * 1.0;
    assert!((world.ledger().energy_removed - kinetic).abs() < 1e-12 * kinetic, "{}", world.ledger().energy_removed);
    assert!(world.ledger().balance_error().abs() < 1e-9 * kinetic);
}

/// An inlet at the bottom feeding upward and sideways, an outlet at the top across part of the width, and a domain
/// that takes the particles drifting past the outlet's end.
fn feed_and_drain() -> World {
    let domain = Aabb { min: DVec2::new(-0.2, -0.1), max: DVec2::new(0.07, 0.25) };
    let mut world = world(0.0, Some(domain));
    world.add_inlet(inlet(DVec2::new(-0.05, 0.0), DVec2::new(0.05, 0.0), 30.0, DVec2::new(0.3, 1.0))).unwrap();
    world.add_outlet(Outlet { name: "top".into(), from: DVec2::new(0.05, 0.2), to: DVec2::new(-0.05, 0.2) }).unwrap();
    world
}

#[test]
fn the_particle_count_balances_at_every_step_with_outlets_and_the_domain_removing() {
    let mut world = feed_and_drain();
    for _ in 0..1000 {
        world.step().unwrap();
        assert_balanced(&world, 0);
    }
    let s = world.stats();
    assert_eq!((s.injected, s.postponed), (30, 0), "30 per second over 1 s, never blocked");
    assert!(s.removed_at_outlets > 5 && s.removed > 5, "{s:?}");
    assert!(world.ledger().balance_error().abs() < 1e-9, "{}", world.ledger().balance_error());
}

#[test]
fn a_run_resumed_from_a_checkpoint_is_bitwise_identical() {
    let mut whole = feed_and_drain();
    for _ in 0..600 {
        whole.step().unwrap();
    }
    let mut first = feed_and_drain();
    for _ in 0..250 {
        first.step().unwrap();
    }
    let mut bytes = Vec::new();
    first.save_checkpoint(&mut bytes).unwrap();
    let mut resumed = World::load_checkpoint(bytes.as_slice()).unwrap();
    for _ in 250..600 {
        resumed.step().unwrap();
    }
    let (mut a, mut b) = (Vec::new(), Vec::new());
    whole.save_checkpoint(&mut a).unwrap();
    resumed.save_checkpoint(&mut b).unwrap();
    assert!(a == b, "the resumed run's state differs from the uninterrupted run's");
    assert_eq!(whole.stats(), resumed.stats());
    assert!(whole.stats().injected > 0 && whole.stats().removed_at_outlets > 0);
}

#[test]
fn an_inlet_whose_velocity_points_out_of_the_domain_is_refused() {
    let mut world = world(9.81, None);
    let outward = inlet(DVec2::new(0.05, 0.0), DVec2::new(-0.05, 0.0), 10.0, DVec2::new(0.0, 1.0));
    let error = world.add_inlet(outward).unwrap_err().to_string();
    assert!(error.contains("does not point into the domain"), "{error}");
    let zero = inlet(DVec2::ZERO, DVec2::ZERO, 10.0, DVec2::new(0.0, 1.0));
    assert!(world.add_inlet(zero).is_err());
    let no_rate = inlet(DVec2::new(-0.05, 0.0), DVec2::new(0.05, 0.0), 0.0, DVec2::new(0.0, 1.0));
    assert!(world.add_inlet(no_rate).is_err());
    assert!(world.add_outlet(Outlet { name: "top".into(), from: DVec2::ONE, to: DVec2::ONE }).is_err());
    assert!(world.inlets().is_empty() && world.outlets().is_empty());
}
