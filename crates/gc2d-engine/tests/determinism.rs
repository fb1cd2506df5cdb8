//! Determinism across thread counts (ARCHITECTURE.md, "Decisions already taken"): the same World stepped inside
//! rayon pools of 1, 2 and 8 threads ends bitwise identical, positions, velocities and ledger alike; also a strip
//! wide enough for the broadphase's y axis in bands, and across a checkpoint split. The pool of one thread adds the
//! contact forces in the narrowphase pass, the others by ranges of bodies afterwards, so they compare the two ways;
//! and on several threads, the predictor, gravity and the corrector in the passes of the vertex transform and the
//! forces or in passes of their own; and the closing pass's sums in the corrector's pass or in a pass of their own.

mod common;

use common::*;
use gc2d_engine::schedules::HeatingSchedule;
use gc2d_engine::{World, WorldConfig};
use gc2d_geometry::{Aabb, AngleMode, DVec2, Pose, ellipse_polygon};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const COLUMNS: usize = 45;
const ROWS: usize = 24;
/// Nominal semi-axis of the 7-gons, m (the thesis's r = 1.5 mm), varied by ±10 %.
const RADIUS: f64 = 1.5e-3;
/// Lattice spacing: two largest radii plus 0.1 mm, so nothing overlaps at the start.
const SPACING: f64 = 2.0 * 1.1 * RADIUS + 1e-4;
const STEPS: usize = 3000;
// The engine's threshold for parallel stages.
const _: () = assert!(COLUMNS * ROWS > 512);

/// 1,080 random RAND1 7-gons on a lattice in a closed box, flying in random directions at up to 1 m/s, so that
/// about 160 contacts are active by the end of the 6 ms run and the pair list holds more than eight of the
/// narrowphase's chunks of 64 pairs, whose sums are added in chunk order (docs/model.md, "Narrowphase and ledger
/// shortcuts"). More than the engine's 512-body threshold for parallel stages, and many of the closing pass's fixed
/// chunks of 32 bodies, whose sums are also added in chunk order.
fn random_pile() -> World {
    random_lattice(COLUMNS, ROWS, 0.0, None, None)
}

/// A strip of the same 1,080 7-gons 540 wide and 2 high (1.8 m by 1 cm): wide enough that the broadphase splits its y
/// axis into bands (broadphase::bands), and the grains flying at up to 1 m/s change bands during the run. The walls
/// stand half a lattice spacing further out (a 7-gon's farthest vertex from its centroid can reach past the spacing).
fn random_strip() -> World {
    random_lattice(COLUMNS * ROWS / 2, 2, 0.5 * SPACING, None, None)
}

/// Random 7-gons on a lattice of `columns` by `rows` in a closed box `margin` wider on every side, flying in random
/// directions; heated by `heating` and bounded by `domain` if given.
fn random_lattice(
    columns: usize,
    rows: usize,
    margin: f64,
    heating: Option<HeatingSchedule>,
    domain: Option<Aabb>,
) -> World {
    let mut world = world(WorldConfig { heating, domain, ..config(2e-6, law(E_THESIS, 0.5, 0.6), G) });
    let lattice = DVec2::new(columns as f64, rows as f64) * SPACING;
    let inner = Aabb { min: DVec2::splat(-margin), max: lattice + DVec2::splat(margin) };
    add_box(&mut world, inner, 0.01);
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for row in 0..rows {
        for column in 0..columns {
            let size = RADIUS * rng.random_range(0.9..1.1);
            let shape = ellipse_polygon(7, size, size, AngleMode::Rand1, &mut rng).unwrap();
            let centre = DVec2::new(column as f64 + 0.5, row as f64 + 0.5) * SPACING;
            let pose = Pose::new(centre, rng.random_range(0.0..std::f64::consts::TAU));
            let velocity = DVec2::from_angle(rng.random_range(0.0..std::f64::consts::TAU)) * rng.random_range(0.0..1.0);
            world.add_particle(&shape, pose, RHO_THESIS, velocity, rng.random_range(-50.0..50.0)).unwrap();
        }
    }
    world
}

/// What a run ends with, and how busy it was.
struct RunEnd {
    /// Every number that defines the particles' state after the run, as bits.
    bits: Vec<u64>,
    /// The ledger, printed (Debug prints the shortest decimal that reads back to the same f64, so equal strings mean
    /// equal bits).
    ledger: String,
    /// The checksum of the whole state, pair records and broadphase included (`World::state_checksum`).
    state: u64,
    /// The most contacts seen in one step.
    most_contacts: usize,
    /// The most box pairs seen in one step.
    most_pairs: usize,
}

/// The random pile run inside a rayon pool of `threads` threads.
fn run_in_pool(threads: usize) -> RunEnd {
    run_scene_in_pool(random_pile, threads, None)
}

/// The random pile recording contact events, with a heating schedule whose window never opens (gc2d's default): the
/// grains keep their size, but the predictor and the vertex transform run as passes of their own.
fn random_pile_in_separate_passes() -> World {
    let mut world = random_lattice(COLUMNS, ROWS, 0.0, Some(HeatingSchedule::default()), None);
    world.record_contact_events();
    world
}

/// [`random_pile_in_separate_passes`] in a domain of 1 km around it, which removes no particle but makes the closing
/// pass a pass of its own after the corrector's, as every stage that removes or adds particles does.
fn random_pile_with_a_closing_pass_of_its_own() -> World {
    let domain = Aabb { min: DVec2::splat(-1e3), max: DVec2::splat(1e3) };
    let mut world = random_lattice(COLUMNS, ROWS, 0.0, Some(HeatingSchedule::default()), Some(domain));
    world.record_contact_events();
    world
}

/// The World `scene` builds, run for [`STEPS`] steps inside a rayon pool of `threads` threads; with `split_at`, saved
/// to a checkpoint after that many steps and loaded back to run the rest.
fn run_scene_in_pool(scene: fn() -> World, threads: usize, split_at: Option<usize>) -> RunEnd {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| {
        let mut world = scene();
        let mut most_contacts = 0;
        let mut most_pairs = 0;
        for k in 0..STEPS {
            if split_at == Some(k) {
                let mut bytes = Vec::new();
                world.save_checkpoint(&mut bytes).unwrap();
                world = World::load_checkpoint(bytes.as_slice()).unwrap();
            }
            step(&mut world);
            most_contacts = most_contacts.max(world.stats().contacts);
            most_pairs = most_pairs.max(world.stats().box_pairs);
        }
        let b = world.bodies();
        let bits = b
            .particles()
            .flat_map(|id| {
                let i = id.index();
                let (p, v) = (b.pose[i].position, b.velocity[i]);
                [p.x, p.y, b.pose[i].angle, v.x, v.y, b.angular_velocity[i]]
            })
            .map(f64::to_bits)
            .collect();
        let state = world.state_checksum().unwrap();
        RunEnd { bits, ledger: format!("{:?}", world.ledger()), state, most_contacts, most_pairs }
    })
}

/// 70 threads: more than `home_threads::MAX_RANGES` (64), so the bodies are cut into 64 ranges and six threads have
/// none of their own.
#[test]
fn pile_is_bitwise_identical_on_1_2_8_and_70_threads() {
    let one = run_in_pool(1);
    assert_eq!(one.bits.len(), 6 * COLUMNS * ROWS);
    let (contacts, pairs) = (one.most_contacts, one.most_pairs);
    assert!(contacts > 50, "the run must exercise contacts, saw at most {contacts}");
    // Measured: 160 contacts and 920 box pairs in the busiest step (fifteen chunks of the narrowphase's sums).
    assert!(pairs > 8 * 64, "the run must fill more than eight chunks of pairs, saw at most {pairs} pairs");
    for threads in [2, 8, 70] {
        let other = run_in_pool(threads);
        let first_difference = one.bits.iter().zip(&other.bits).position(|(a, b)| a != b);
        assert_eq!(first_difference, None, "{threads} threads: particle {:?} differs", first_difference.map(|k| k / 6));
        assert_eq!(one.ledger, other.ledger, "{threads} threads: the ledger differs");
        assert_eq!(one.state, other.state, "{threads} threads: the state's checksum differs");
    }
}

/// The broadphase's y axis in bands (a strip 1.8 m wide and 7 mm high): the same bits on 1, 2 and 8 threads and
/// across a checkpoint split, and the same pairs as one y axis would find (the contact counts agree; the pair order,
/// and with it the last bits of the sums, may differ from one axis, so the states are not compared with it).
#[test]
fn a_strip_in_bands_is_bitwise_identical_on_1_2_and_8_threads_and_across_a_checkpoint() {
    let mut strip = random_strip();
    step(&mut strip);
    assert!(strip.y_bands() >= 4, "the strip must be wide enough for bands, got {}", strip.y_bands());
    assert_eq!(random_pile().y_bands(), 1);
    let one = run_scene_in_pool(random_strip, 1, None);
    assert!(one.most_contacts > 50, "the run must exercise contacts, saw at most {}", one.most_contacts);
    for (threads, split_at) in [(2, None), (8, None), (2, Some(STEPS / 3))] {
        let other = run_scene_in_pool(random_strip, threads, split_at);
        let first_difference = one.bits.iter().zip(&other.bits).position(|(a, b)| a != b);
        let run = format!("{threads} threads, split at {split_at:?}");
        assert_eq!(first_difference, None, "{run}: particle {:?} differs", first_difference.map(|k| k / 6));
        assert_eq!(one.ledger, other.ledger, "{run}: the ledger differs");
        assert_eq!(one.state, other.state, "{run}: the state's checksum differs");
    }
}

/// On several threads a World with gravity as its only body force adds each range's contact forces and weights and
/// corrects it in one pass, and predicts each range in the vertex transform's pass; recording contact events (which
/// read the velocities before the corrector) and a heating schedule (whose scale the predictor sets after the
/// particles) keep those passes apart. The closing pass's chunks are summed in the corrector's pass in both, and in a
/// pass of their own where a domain is set. All end with the same bits.
#[test]
fn fused_passes_give_the_bits_of_separate_ones() {
    let fused = run_in_pool(2);
    assert!(fused.most_contacts > 50, "the run must exercise contacts, saw at most {}", fused.most_contacts);
    for scene in [random_pile_in_separate_passes, random_pile_with_a_closing_pass_of_its_own] {
        let separate = run_scene_in_pool(scene, 2, None);
        let first_difference = fused.bits.iter().zip(&separate.bits).position(|(a, b)| a != b);
        assert_eq!(first_difference, None, "particle {:?} differs", first_difference.map(|k| k / 6));
        assert_eq!(fused.ledger, separate.ledger, "the ledger differs");
    }
}
