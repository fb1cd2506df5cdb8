//! Loads a scene, prints its summary and runs it to its end time (or to the time given as the second argument),
//! reporting progress and the wall-clock time: `cargo run -p gc2d-scene --release --example run_scene -- scenes/pile.ron`.
//! A stand-in for `gc2d-rs run` until the command-line crate exists.

use gc2d_scene::Scene;
use std::time::Instant;

fn main() -> miette::Result<()> {
    let mut args = std::env::args().skip(1);
    let path = args.next().unwrap_or_else(|| "scenes/pile.ron".to_owned());
    let scene = Scene::from_path(&path)?;
    let summary = scene.summary()?;
    println!("{summary}");
    let end = args.next().and_then(|t| t.parse().ok()).unwrap_or(scene.run.end_time_s);
    let mut world = scene.build()?;
    let started = Instant::now();
    let reports = 10;
    for k in 1..=reports {
        world.run_until(end * k as f64 / reports as f64).map_err(|e| miette::miette!("{e}"))?;
        let stats = world.stats();
        println!(
            "t = {:.3} s: {} particles, {} contacts, {} inserted, {} skipped, {} removed, {:.1} s wall clock",
            world.time(),
            world.bodies().particles().count(),
            stats.contacts,
            stats.inserted,
            stats.insertions_skipped,
            stats.removed,
            started.elapsed().as_secs_f64()
        );
    }
    Ok(())
}
