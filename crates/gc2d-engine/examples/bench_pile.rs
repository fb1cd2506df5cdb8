//! Throughput of `World::step` on settled piles of the thesis's particles (reference §8.3, §10.5).
//!
//! ```sh
//! cargo run --release -p gc2d-engine --example bench_pile                 # both tables (about 15 minutes)
//! cargo run --release -p gc2d-engine --example bench_pile -- dense 2000   # dense piles of the given sizes only
//! cargo run --release -p gc2d-engine --example bench_pile -- layer 1000   # layers of the given sizes only
//! ```
//!
//! `gc2d-rs bench` measures the same piles (and squares and disks) with a cache of settled states and any thread
//! counts; this example stays for the LAMMPS comparison's bundle (../shared/bench/lammps), which ships it.
//!
//! Two tables. **Dense piles** (2,000 and 10,000 grains, twice as wide as high) are deposited (see
//! `gc2d_bench::deposition`), settled for `StandardPile::settle_time` on two threads, and stepped on a rayon pool of
//! 1 and of 2 threads. **Layers** 1 cm deep (1,000, 10,000 and 100,000 grains, the same local packing at every size)
//! settle likewise and are stepped on 1 thread for `LAYER_STEPS` steps, the same stretch of simulated time at every
//! size: their time per particle-step shows how the step scales.
//!
//! After `WARM_STEPS` untimed steps, the wall-clock time and the CPU time of all threads of the next steps are
//! measured (for dense piles about `PARTICLE_STEPS_PER_RUN` particle-steps). Printed per run: particle-steps and contact evaluations
//! (touching pairs) per wall-clock second, ns per particle-step (wall and CPU), box pairs and contacts per grain,
//! and memory per grain: `World::heap_bytes` (the capacities of all body columns, the broadphase axes and boxes, the
//! pair list with its index table and contact records, and the scratch buffers) divided by the number of grains, and
//! the part of it held by the body columns (`Bodies::heap_bytes`).
//! Nothing is cached on disk.

use gc2d_bench::StandardPile;
use gc2d_bench::timing::{load_average, measure, pool, table_header};
use gc2d_engine::World;
use std::time::Instant;

/// Particle-steps per measurement of a dense pile: the step count is this divided by the particle count.
const PARTICLE_STEPS_PER_RUN: u64 = 20_000_000;
/// Steps per measurement of a layer: the same stretch of simulated time (2 ms) at every size.
const LAYER_STEPS: u64 = 1_000;

/// A deposited pile of `particles` grains after its settling time on two threads.
fn settled_pile(particles: usize, pile: StandardPile) -> World {
    let started = Instant::now();
    let mut world = pile.build(particles);
    pool(2).install(|| world.run_until(pile.settle_time())).expect("the pile settles without blowing up");
    let stats = world.stats();
    eprintln!(
        "built and settled {particles} grains in {:.1} s: {} contacts, kinetic energy {:.3e} J",
        started.elapsed().as_secs_f64(),
        stats.contacts,
        world.ledger().kinetic()
    );
    world
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let sizes: Vec<usize> = args.iter().filter_map(|a| a.parse().ok()).collect();
    let only = |table: &str| args.is_empty() || args.iter().any(|a| a == table);
    let sizes_or = |default: &[usize]| if sizes.is_empty() { default.to_vec() } else { sizes.clone() };
    println!("load average before: {}", load_average());
    if only("dense") {
        println!("\ndense piles (twice as wide as high), settled {} s\n", StandardPile::Dense7gons.settle_time());
        println!("{}", table_header("grain"));
        for particles in sizes_or(&[2_000, 10_000]) {
            let mut world = settled_pile(particles, StandardPile::Dense7gons);
            for threads in [1, 2] {
                println!(
                    "{}",
                    measure(&mut world, threads, PARTICLE_STEPS_PER_RUN / particles as u64, false)
                        .expect("no blow-up")
                        .row()
                );
            }
        }
    }
    if only("layer") {
        println!("\nlayers 0.01 m deep, settled {} s\n", StandardPile::Layer.settle_time());
        println!("{}", table_header("grain"));
        for particles in sizes_or(&[1_000, 10_000, 100_000]) {
            let mut world = settled_pile(particles, StandardPile::Layer);
            println!("{}", measure(&mut world, 1, LAYER_STEPS, false).expect("no blow-up").row());
        }
    }
    println!("\nload average after: {}", load_average());
}
