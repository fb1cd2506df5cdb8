//! The ball mill in steady state (reference ballmill.md §7.6): what the rotor puts in, the contacts dissipate.
//!
//! `tests/scenes/mill_ci.ron` is `scenes/mill.ron` (130 steel balls, 1700 rpm, the steel e(v), Mindlin friction) with
//! balls and walls 30 times softer than steel, which the stiffness study in docs/validation.md shows to change the
//! tail shares and the power by little; it runs the thesis's 0.2 s warm-up and 0.8 s averaging window in seconds.

mod common;

use common::scene_path;
use gc2d_engine::World;
use gc2d_scene::Scene;

/// Start of the averaging window, s (the thesis's warm-up).
const WARM_UP_S: f64 = 0.2;

/// What a mill run delivers over the averaging window.
struct Window {
    /// Work of the walls on the balls from the ledger, J.
    work_in: f64,
    /// Energy the contacts dissipated from the ledger, J.
    dissipated: f64,
    /// ∫ Σ F·v dt of the rotor over the window's steps (rectangle rule), J.
    rotor_work_from_power: f64,
    /// Mechanical energy (kinetic, potential, stored in contacts) at the window's two ends, J.
    energy_at_start: f64,
    energy_at_end: f64,
    /// Length of the window, s.
    duration: f64,
}

fn mechanical_energy(world: &World) -> f64 {
    let l = world.ledger();
    l.kinetic() + l.potential + l.contact_stored
}

/// Runs `scene` through its warm-up and averaging window and measures the window.
fn run_window(scene: &Scene) -> (World, Window) {
    let mut world = scene.build().expect("the CI mill builds");
    world.run_until(WARM_UP_S).expect("the warm-up runs");
    let (work_start, dissipated_start) = (world.ledger().work_walls, world.ledger().dissipated());
    let (energy_at_start, time_start) = (mechanical_energy(&world), world.time());
    let mut rotor_work_from_power = 0.0;
    while world.time() + 0.5 * world.time_step() < scene.run.end_time_s {
        world.step().expect("the mill runs");
        rotor_work_from_power += world.rotor_power().power_from_work * world.time_step();
    }
    let window = Window {
        work_in: world.ledger().work_walls - work_start,
        dissipated: world.ledger().dissipated() - dissipated_start,
        rotor_work_from_power,
        energy_at_start,
        energy_at_end: mechanical_energy(&world),
        duration: world.time() - time_start,
    };
    (world, window)
}

#[test]
fn a_steady_mill_dissipates_what_its_rotor_puts_in() {
    let scene = Scene::from_path(scene_path("mill_ci.ron")).unwrap();
    let (world, w) = run_window(&scene);
    let power = w.work_in / w.duration;
    let dissipation = w.dissipated / w.duration;
    eprintln!(
        "⟨P⟩ = {power:.3} W, ⟨D⟩ = {dissipation:.3} W, ∫ΣF·v dt / ΔW = {:.6}, E {:.4} → {:.4} J, ledger error {:.3e} J \
         of {:.3} J put in",
        w.rotor_work_from_power / w.work_in,
        w.energy_at_start,
        w.energy_at_end,
        world.ledger().balance_error(),
        world.ledger().work_in()
    );
    assert!(power > 1.0, "the rotor drives the balls: ⟨P⟩ = {power} W");
    assert!((power - dissipation).abs() <= 0.02 * power, "⟨P⟩ = {power} W, ⟨D⟩ = {dissipation} W");
    // The rotor's power, summed over the steps, is the work the ledger books for the walls.
    assert!(
        (w.rotor_work_from_power - w.work_in).abs() <= 1e-3 * w.work_in,
        "∫ Σ F·v dt = {} J, ledger {} J",
        w.rotor_work_from_power,
        w.work_in
    );
    // What is left between the two is the change of the balls' energy over the window, and the ledger's residual
    // (the first-order booking of the dashpot's dissipation, docs/model.md) stays below 1 % of what was put in.
    let residual = world.ledger().balance_error().abs();
    assert!(residual <= 0.01 * world.ledger().work_in(), "balance error {residual} J");
    // No ball is lost: all 130 are in the chamber.
    let bodies = world.bodies();
    assert_eq!(bodies.particles().count(), 130);
    assert!(bodies.particles().all(|id| bodies.pose[id.index()].position.length() + 0.0025 <= 0.073 + 1e-4));
}
