//! Contact events: the same for one and two threads and across a checkpoint split, the episodes' dissipated energy
//! adding up to the ledger's dissipation, and the impulse of a single impact matching the momentum change.

mod common;

use gc2d_contact::{
    ContactLaw, CundallStrack, NormalDamping, NormalElastic, NormalSpring, PenetrationDamping, PenetrationLaw,
    TangentialSpring, TangentialStiffness,
};
use gc2d_engine::clearance::Clearance;
use gc2d_engine::schedules::GravitySchedule;
use gc2d_engine::{
    BodyShape, ContactEvent, ContactEventKind, ContactModel, Integrator, InteractionTable, MassModel, MaterialId,
    MaterialPair, SafetyLimits, WallMotion, World, WorldConfig,
};
use gc2d_geometry::{DVec2, Pose, rectangle, regular_polygon};

/// Δt of the mixed scene, s.
const DT: f64 = 1e-5;

/// Area density of the mixed scene's particles, kg/m².
const DENSITY: f64 = 20.0;

/// Material ids of the mixed scene.
const WALL: MaterialId = MaterialId(0);
const BALL: MaterialId = MaterialId(1);
const GRAIN: MaterialId = MaterialId(2);

/// A box of 600 bodies falling under gravity: disks that meet each other and the walls by a damped linear spring
/// with friction, and 7-gons that meet everything by the overlap-area law.
fn mixed_scene() -> World {
    let spring = ContactModel::Penetration(PenetrationLaw {
        damping: Some(PenetrationDamping::Restitution(0.6)),
        tangential: Some(TangentialSpring {
            mu: 0.4,
            stiffness: TangentialStiffness::CundallStrack { stiffness_ratio: CundallStrack::STIFFNESS_FACTOR },
            damping_ratio: 0.0,
        }),
        ..PenetrationLaw::elastic(NormalSpring::Linear { stiffness_n_m: 2e4 })
    });
    let area = ContactModel::OverlapArea(ContactLaw {
        elastic: NormalElastic::thesis(1e5),
        damping: Some(NormalDamping { gamma: 0.5 }),
        friction: Some(CundallStrack { mu: 0.5 }),
        cohesion: None,
    });
    let pair = |a, b, model| MaterialPair { a, b, model };
    let table = InteractionTable::new(
        3,
        &[
            pair(WALL, WALL, area),
            pair(WALL, BALL, spring),
            pair(BALL, BALL, spring),
            pair(WALL, GRAIN, area),
            pair(BALL, GRAIN, area),
            pair(GRAIN, GRAIN, area),
        ],
    )
    .unwrap();
    let config = WorldConfig {
        time_step: DT,
        integrator: Integrator::default(),
        interactions: table,
        mass_model: MassModel::PerUnitThickness,
        gravity: GravitySchedule::constant(9.81),
        heating: None,
        safety: SafetyLimits::default(),
        domain: None,
        seed: 3,
    };
    let mut world = World::new(config).unwrap();
    let floor = rectangle(0.32, 0.01).unwrap();
    let side = rectangle(0.01, 0.5).unwrap();
    for (shape, x, y) in [(&floor, 0.15, -0.005), (&side, -0.005, 0.25), (&side, 0.305, 0.25)] {
        let id = world.add_wall(shape, Pose::new(DVec2::new(x, y), 0.0), DVec2::ZERO, WallMotion::Static);
        world.set_material(id, WALL).unwrap();
    }
    let grain = regular_polygon(7, 0.0045).unwrap();
    for k in 0..600 {
        let (column, row) = (k % 30, k / 30);
        let position = DVec2::new(0.005 + 0.01 * column as f64, 0.006 + 0.011 * row as f64);
        let scatter = |m: usize| 0.6 * ((k * m) % 13) as f64 / 13.0 - 0.3;
        let velocity = DVec2::new(scatter(7), scatter(5));
        let id = if (column / 2 + row) % 2 == 0 {
            world.add_particle(BodyShape::Disk { radius: 0.0045 }, Pose::new(position, 0.0), DENSITY, velocity, 0.0)
        } else {
            world.add_particle(&grain, Pose::new(position, 0.1 * k as f64), DENSITY, velocity, 0.0)
        };
        world.set_material(id.unwrap(), if (column / 2 + row) % 2 == 0 { BALL } else { GRAIN }).unwrap();
    }
    world.record_contact_events();
    world
}

/// Steps `steps` times on a pool of `threads` threads, collecting the events.
fn run(world: &mut World, steps: u64, threads: usize) -> Vec<ContactEvent> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| {
        let mut events = Vec::new();
        for _ in 0..steps {
            world.step().unwrap();
            events.extend_from_slice(world.contact_events());
        }
        events
    })
}

#[test]
fn events_are_the_same_for_any_thread_count_and_across_a_checkpoint_split() {
    let steps = 3000;
    let one = run(&mut mixed_scene(), steps, 1);
    let ends = one.iter().filter(|e| e.kind == ContactEventKind::End).count();
    assert!(ends > 500, "the scene should have many finished episodes, has {ends}");
    assert!(one.iter().any(|e| e.materials == [BALL, BALL]) && one.iter().any(|e| e.materials == [GRAIN, GRAIN]));
    let two = run(&mut mixed_scene(), steps, 2);
    assert!(one == two, "events differ between one and two threads");

    let mut first = mixed_scene();
    let mut split = run(&mut first, steps / 2, 2);
    let mut bytes = Vec::new();
    first.save_checkpoint(&mut bytes).unwrap();
    let mut resumed = World::load_checkpoint(bytes.as_slice()).unwrap();
    resumed.record_contact_events();
    split.extend(run(&mut resumed, steps - steps / 2, 2));
    assert!(one == split, "events differ across a checkpoint split");
}

#[test]
fn the_episodes_dissipate_what_the_ledger_books() {
    let mut world = mixed_scene();
    let events = run(&mut world, 3000, 2);
    let ended: f64 =
        events.iter().filter(|e| e.kind == ContactEventKind::End).map(|e| e.episode.dissipated).sum::<f64>();
    let open: f64 = world.open_contact_episodes().map(|(_, _, episode)| episode.dissipated).sum();
    let ledger = world.ledger();
    let booked = ledger.dissipated_normal_damping + ledger.dissipated_tangential_damping + ledger.dissipated_sliding;
    assert!(booked > 0.0);
    assert!(((ended + open) - booked).abs() <= 1e-9 * booked, "episodes {ended} + {open} J, ledger {booked} J");
}

#[test]
fn an_impact_reports_its_speed_and_an_impulse_equal_to_the_momentum_change() {
    let law = ContactModel::Penetration(PenetrationLaw {
        damping: Some(PenetrationDamping::Restitution(0.5)),
        ..PenetrationLaw::elastic(NormalSpring::Linear { stiffness_n_m: 1e5 })
    });
    let mut world = common::sphere_world(law, 1e-6, 0.0);
    let wall = rectangle(0.02, 0.01).unwrap();
    world.add_wall(&wall, Pose::new(DVec2::new(0.0, -0.005), 0.0), DVec2::ZERO, WallMotion::Static);
    let velocity = DVec2::new(0.3, -1.0);
    let ball = world
        .add_particle(
            BodyShape::Disk { radius: 0.0025 },
            Pose::new(DVec2::new(0.0, 0.0025 + 1e-7), 0.0),
            7700.0,
            velocity,
            0.0,
        )
        .unwrap();
    world.record_contact_events();
    let mass = world.bodies().mass[ball.index()];
    let mut events = Vec::new();
    while !events.iter().any(|e: &ContactEvent| e.kind == ContactEventKind::End) {
        world.step().unwrap();
        events.extend_from_slice(world.contact_events());
        assert!(world.time() < 0.01, "no impact");
    }
    let begin = events[0];
    assert_eq!(begin.kind, ContactEventKind::Begin);
    assert!((begin.episode.impact_normal_speed - 1.0).abs() < 1e-3, "{}", begin.episode.impact_normal_speed);
    assert!((begin.episode.impact_tangential_speed - 0.3).abs() < 1e-3, "{}", begin.episode.impact_tangential_speed);
    let end = events.last().unwrap();
    // The wall is body a; the impulse on the ball is the opposite of the one on a. The impulse sums the sampled
    // forces times Δt, the integrator integrates them to higher order: they agree to O(Δt/t_c), t_c ≈ 230 Δt here.
    let momentum_change = mass * (world.bodies().velocity[ball.index()] - velocity);
    let impulse_on_ball = -end.episode.impulse_on_a;
    let error = (impulse_on_ball - momentum_change).length() / momentum_change.length();
    assert!(error < 1e-3, "impulse {impulse_on_ball} against the momentum change {momentum_change} ({error:.1e})");
    assert!(end.episode.dissipated > 0.0 && end.episode.max_overlap > 0.0);
}

/// A body that changes material may change its pairs' contact model, and only the polygon walk keeps a pair's
/// clearance up to date: its pairs forget their clearance, the others keep theirs, and the run goes on (in debug
/// builds every pair skipped as apart is checked against the walk).
#[test]
fn a_change_of_material_drops_the_clearance_of_the_body_s_pairs() {
    let mut world = mixed_scene();
    run(&mut world, 1000, 1);
    let with_clearance = |world: &World| {
        world.pairs().filter(|(_, _, c)| c.clearance != Clearance::NONE).map(|(a, b, _)| (a, b)).collect::<Vec<_>>()
    };
    let before = with_clearance(&world);
    let (body, _) = *before.first().expect("grains apart keep a clearance");
    world.set_material(body, BALL).unwrap();
    let after = with_clearance(&world);
    assert!(after.iter().all(|&(a, b)| a != body && b != body));
    let others: Vec<_> = before.iter().copied().filter(|&(a, b)| a != body && b != body).collect();
    assert_eq!(after, others, "the other pairs keep theirs");
    run(&mut world, 50, 1);
}
