//! Throughput of `World::step` on a settled dense pile of 10,000 exact disks (the engine issue's "dense pile of
//! 10,000 disks: particle-steps per second on 1 and 2 threads", reported in docs/performance.md).
//!
//! ```sh
//! cargo run --release -p gc2d-engine --example bench_disk_pile          # 10,000 disks (about 4 minutes)
//! cargo run --release -p gc2d-engine --example bench_disk_pile -- 2000  # another number of disks
//! ```
//!
//! The disks and their law are `gc2d_bench::disk_material`'s: they start on a hexagonal lattice a little wider than
//! the largest disk, in a box twice as wide as the settled pile is high, and settle under gravity for
//! `StandardPile::Disks.settle_time()` on two threads (not timed, but reported). `gc2d-rs bench --pile disks`
//! measures the same pile with a cache of the settled state and any thread counts.
//!
//! While the pile settles, its kinetic energy and the deepest overlap of that step are printed every
//! `SETTLE_REPORT_INTERVAL`. Measured for 10,000 disks: the kinetic energy peaks near 10⁻² J in the first 0.1 s
//! while the lattice collapses, and has fallen to about 2·10⁻⁶ J (a few mm/s r.m.s.) by 0.35 s, where it levels off;
//! settling 0.4 s (69,554 steps) took 3.5 minutes on the shared two cores.
//!
//! Then, like `bench_pile`, after `WARM_STEPS` untimed steps the wall-clock and CPU time (of all threads) of about
//! `PARTICLE_STEPS_PER_RUN` particle-steps are measured on a rayon pool of 1 and of 2 threads. Printed per run:
//! particle-steps per wall-clock second, wall and CPU ns per particle-step, box pairs and contacts per disk.

use gc2d_bench::StandardPile;
use gc2d_bench::timing::{load_average, measure, pool, table_header};
use std::time::Instant;

/// Disks in the pile unless the command line names another count.
const DEFAULT_DISKS: usize = 10_000;
/// Interval of the kinetic-energy reports while the pile settles, s.
const SETTLE_REPORT_INTERVAL: f64 = 0.05;
/// Particle-steps per measurement: the step count is this divided by the number of disks.
const PARTICLE_STEPS_PER_RUN: u64 = 20_000_000;

fn main() {
    let disks = std::env::args().nth(1).map_or(DEFAULT_DISKS, |a| a.parse().expect("a number of disks"));
    println!("load average before: {}", load_average());
    let started = Instant::now();
    let mut world = StandardPile::Disks.build(disks);
    let settle_time = StandardPile::Disks.settle_time();
    let built = started.elapsed().as_secs_f64();
    pool(2).install(|| {
        let reports = (settle_time / SETTLE_REPORT_INTERVAL).round() as u32;
        for report in 1..=reports {
            world.run_until(f64::from(report) * SETTLE_REPORT_INTERVAL).expect("the pile settles without blowing up");
            println!(
                "  t = {:.2} s: kinetic energy {:.3e} J, largest overlap {:.2} % of the smaller diameter",
                world.time(),
                world.ledger().kinetic(),
                100.0 * world.stats().max_overlap_fraction
            );
        }
    });
    println!(
        "built {disks} disks in {built:.1} s, settled {settle_time} s ({} steps of {:.3e} s) in {:.1} s on 2 threads: \
         {} contacts, kinetic energy {:.3e} J, largest overlap {:.2} % of the smaller diameter",
        world.steps(),
        world.time_step(),
        started.elapsed().as_secs_f64() - built,
        world.stats().contacts,
        world.ledger().kinetic(),
        100.0 * world.stats().max_overlap_fraction,
    );
    println!();
    println!("{}", table_header("disk"));
    for threads in [1, 2] {
        println!(
            "{}",
            measure(&mut world, threads, PARTICLE_STEPS_PER_RUN / disks as u64, false).expect("no blow-up").row()
        );
    }
    println!("\nload average after: {}", load_average());
}
