//! Determinism across thread counts (ARCHITECTURE.md, "Decisions already taken"): the same World stepped inside
//! rayon pools of 1, 2 and 8 threads ends bitwise identical, positions, velocities and ledger alike.

mod common;

use common::*;
use gc2d_engine::World;
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
// The closing ledger pass must have more than one of its chunks of 1,024 bodies.
const _: () = assert!(COLUMNS * ROWS > 1024);

/// 1,080 random RAND1 7-gons on a lattice in a closed box, flying in random directions at up to 1 m/s, so that
/// about 160 contacts are active by the end of the 6 ms run and the pair list holds more than eight of the
/// narrowphase's chunks of 64 pairs, whose sums are added in chunk order (docs/model.md, "Narrowphase and ledger
/// shortcuts"). More than the engine's 512-body threshold for parallel stages, and more than one of the closing
/// ledger pass's fixed chunks of 1,024 bodies, whose sums are also added in chunk order.
fn random_pile() -> World {
    let mut world = world(config(2e-6, law(E_THESIS, 0.5, 0.6), G));
    let inner = Aabb { min: DVec2::ZERO, max: DVec2::new(COLUMNS as f64 * SPACING, ROWS as f64 * SPACING) };
    add_box(&mut world, inner, 0.01);
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for row in 0..ROWS {
        for column in 0..COLUMNS {
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
    /// The most contacts seen in one step.
    most_contacts: usize,
    /// The most box pairs seen in one step.
    most_pairs: usize,
}

/// The random pile run inside a rayon pool of `threads` threads.
fn run_in_pool(threads: usize) -> RunEnd {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| {
        let mut world = random_pile();
        let mut most_contacts = 0;
        let mut most_pairs = 0;
        for _ in 0..STEPS {
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
        RunEnd { bits, ledger: format!("{:?}", world.ledger()), most_contacts, most_pairs }
    })
}

#[test]
fn pile_is_bitwise_identical_on_1_2_and_8_threads() {
    let one = run_in_pool(1);
    assert_eq!(one.bits.len(), 6 * COLUMNS * ROWS);
    let (contacts, pairs) = (one.most_contacts, one.most_pairs);
    assert!(contacts > 50, "the run must exercise contacts, saw at most {contacts}");
    // Measured: 160 contacts and 920 box pairs in the busiest step (fifteen chunks of the narrowphase's sums).
    assert!(pairs > 8 * 64, "the run must fill more than eight chunks of pairs, saw at most {pairs} pairs");
    for threads in [2, 8] {
        let other = run_in_pool(threads);
        let first_difference = one.bits.iter().zip(&other.bits).position(|(a, b)| a != b);
        assert_eq!(first_difference, None, "{threads} threads: particle {:?} differs", first_difference.map(|k| k / 6));
        assert_eq!(one.ledger, other.ledger, "{threads} threads: the ledger differs");
    }
}
