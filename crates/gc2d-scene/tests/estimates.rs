//! `check`'s rough estimates of memory and run time: the memory model (bodies as built, what the first step adds
//! per body, the engine's bytes per box pair) against the World's own count of its heap (`World::heap_bytes`) once
//! pairs have formed, and the run time from the documented throughput.

use gc2d_scene::Scene;
use gc2d_scene::summary::{
    BOX_PAIRS_PER_PARTICLE, FIRST_STEP_BYTES_PER_BODY, PARTICLE_STEPS_PER_SECOND, bytes_per_box_pair,
};

/// A 40 x 40 block of 7-gons up to 2 mm across on a 2 mm grid, each thrown at 1 m/s in a random direction, so that
/// neighbours meet within a few hundred steps.
const BLOCK: &str = "Scene(
    run: (end_time_s: 0.01),
    walls: [Wall(shape: Rectangle(width_m: 0.2, height_m: 0.01), position_m: (0.04, -0.005))],
    blocks: [(x_range_m: (0.0011, 0.0791), y_range_m: (0.0011, 0.0791), grid_spacing_m: (0.002, 0.002),
              shape: (semi_axes_m: (0.001, 0.001), corners: 7), speed_range_m_s: (1, 1))],
)";

#[test]
fn the_memory_estimate_uses_the_engines_sizes_per_body_and_per_box_pair() {
    let scene = Scene::from_str(BLOCK, "block.ron").unwrap_or_else(|e| panic!("{}", e.render_plain()));
    let summary = scene.summary().unwrap();
    assert_eq!(summary.particles, 1600);
    let mut world = scene.build().unwrap();
    assert_eq!(world.heap_bytes(), summary.heap_bytes_at_start);
    for _ in 0..400 {
        world.step().unwrap();
    }
    let pairs = world.pairs().count();
    assert!(pairs > 800, "{pairs} box pairs");
    // The estimate's model with the pairs the World really holds, against the World's own count of its heap: equal
    // up to the capacity slack of the growing buffers.
    let bodies = (summary.particles + summary.wall_bodies) as f64;
    let model = summary.heap_bytes_at_start as f64
        + bodies * FIRST_STEP_BYTES_PER_BODY as f64
        + pairs as f64 * bytes_per_box_pair() as f64;
    let measured = world.heap_bytes() as f64;
    assert!(measured >= 0.9 * model && measured <= 1.6 * model, "model {model} B, measured {measured} B");
    // A dense packing's 2.3 pairs per particle: the estimate adds them in place of the measured ones.
    let dense = model + (1600.0 * BOX_PAIRS_PER_PARTICLE - pairs as f64) * bytes_per_box_pair() as f64;
    assert!((summary.memory_estimate_bytes() - dense).abs() < 1e-6 * dense);
}

#[test]
fn the_run_time_estimate_is_the_particle_steps_at_the_documented_rate() {
    let summary = Scene::from_str(BLOCK, "block.ron").unwrap().summary().unwrap();
    let steps = summary.steps();
    assert_eq!(summary.particle_steps(), steps as f64 * 1600.0);
    assert_eq!(summary.run_time_estimate_s(), steps as f64 * 1600.0 / PARTICLE_STEPS_PER_SECOND);
    let text = summary.to_string();
    assert!(text.contains("  memory (rough estimate): "), "{text}");
    assert!(text.contains("for up to 1600 particles"), "{text}");
    assert!(text.contains("  run time (rough estimate for one core): "), "{text}");
}

#[test]
fn the_summary_counts_one_of_a_kind_in_the_singular_and_whole_particle_steps() {
    // QA docs: "1 bodies", "up to 1 insertions", "up to 1 particles" and an estimate of "5207.5 particle-steps".
    let text = "Scene(
        run: (end_time_s: 3e-3, time_step_s: 1e-5),
        walls: [Wall(shape: Rectangle(width_m: 0.2, height_m: 0.01), position_m: (0, -0.1))],
        sources: [(position_m: (0, 0), width_m: 0.01, window_s: (0, 1e-3), interval_s: 3e-3,
                   shape: (semi_axes_m: (0.001, 0.001), corners: 7))],
    )";
    let summary =
        Scene::from_str(text, "one.ron").unwrap_or_else(|e| panic!("{}", e.render_plain())).summary().unwrap();
    assert_eq!((summary.wall_bodies, summary.particles, summary.planned_insertions), (1, 0, 1));
    assert_eq!(summary.particle_steps(), 150.0, "300 steps × (0 + 1) / 2");
    let shown = summary.to_string();
    for phrase in ["walls: 1 body (0 moving)", "(up to 1 insertion)", "for up to 1 particle (", "(150 particle-steps"] {
        assert!(shown.contains(phrase), "{phrase} in {shown}");
    }
}
