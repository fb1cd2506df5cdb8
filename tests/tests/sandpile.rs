//! Poured polydisperse dip pile (reference §8.3, §10.3 item 19): RAND1 7-gons, r = 1.75 mm ± 25 %, E = 1e7 N/m,
//! γ = 0.75, μ = 0.6, poured through a funnel onto a floor of the same material.
//!
//! The CI-sized pile (about 250 particles) asserts rest, no losses, both flank angles in a band around the thesis
//! value and the floor pressure integrating to the pile's weight. The thesis-sized pile (about 2500 particles) is
//! `#[ignore]`d: it asserts the thesis's 26.8° ± 2.0° and takes far too long for CI.

mod common;

use common::{particle_weight, run_or_load_ensemble, run_scene};
use gc2d_analysis::scene_pile::auto_half_width;
use gc2d_analysis::{
    Facing, FlankOptions, ProfileOptions, Repose, Snapshot, WallSelection, angle_of_repose, pressure_profile,
    wall_forces,
};
use gc2d_engine::World;

/// What the tests assert about a settled pile.
struct PileMeasurement {
    particles: usize,
    removed: u64,
    /// Kinetic energy over M g d̄ (M total mass, d̄ mean equivalent-circle diameter).
    kinetic_ratio: f64,
    repose: Repose,
    /// ∫ p(x) dx over the floor profile (2.39) under the pile divided by the pile's weight.
    profile_over_weight: f64,
    /// Σ n·F of the pile on the floor divided by the pile's weight.
    floor_force_over_weight: f64,
}

fn measure(world: &World) -> PileMeasurement {
    let snapshot = Snapshot::from_world(world);
    let weight = particle_weight(world);
    let diameter = snapshot.mean_particle_diameter();
    let kinetic_ratio = world.ledger().kinetic() / (weight * diameter);
    // The pile is the largest cluster of touching grains: grains left wedged in the funnel, whose wedging forces on
    // its upward-facing walls are no part of the floor's load, and loose grains elsewhere are not in it.
    let pile = snapshot.restricted_to(&snapshot.largest_cluster());
    let pile_weight = pile.total_mass() * pile.gravity;
    let repose = angle_of_repose(&pile, &FlankOptions::default()).expect("a pile has an outline");
    let floor = wall_forces(&pile, WallSelection::facing(Facing::Up));
    let b = auto_half_width(&floor, diameter);
    // A step that divides the window 2b exactly: every force then lies in exactly 20 windows, so the rectangle rule
    // returns Σ n·F without the sampling error of the default step b/2.
    let options = ProfileOptions { half_width: b, step: 2.0 * b / 20.0, moving_average: 5 };
    let profile = pressure_profile(&floor, &options, None);
    PileMeasurement {
        particles: snapshot.particles.len(),
        removed: world.stats().removed,
        kinetic_ratio,
        repose,
        profile_over_weight: profile.integral() / pile_weight,
        floor_force_over_weight: profile.total_normal_force / pile_weight,
    }
}

fn report(name: &str, m: &PileMeasurement, seconds: f64) {
    let angle = |f: &Option<gc2d_analysis::FlankFit>| f.as_ref().map_or(f64::NAN, |f| f.angle_degrees);
    eprintln!(
        "{name}: {} particles, removed {}, run {seconds:.1} s, KE/(M g d) = {:.3e}, left {:.2}°, right {:.2}°, \
         area method {:?}/{:?}, height {:.4} m, width {:.4} m, ∫p dx / W = {:.5}, ΣF_n / W = {:.5}",
        m.particles,
        m.removed,
        m.kinetic_ratio,
        angle(&m.repose.left),
        angle(&m.repose.right),
        m.repose.area_left_degrees,
        m.repose.area_right_degrees,
        m.repose.shape.height,
        m.repose.shape.width,
        m.profile_over_weight,
        m.floor_force_over_weight,
    );
}

/// Kinetic energy below this fraction of M g d̄ counts as rest: the mean particle then moves with less energy than it
/// takes to lift it 1/1000 of its diameter.
const REST_KINETIC_RATIO: f64 = 1e-3;
/// The floor's share of the weight at rest (∫ p dx and Σ n·F), within 2 %.
const WEIGHT_TOLERANCE: f64 = 0.02;

fn flank(fit: &Option<gc2d_analysis::FlankFit>) -> f64 {
    fit.as_ref().map_or(f64::NAN, |f| f.angle_degrees)
}

/// The CI-sized pile (§10.3 item 19 at 1/10 of the particles). A pile of ~250 particles is 8 grains high, so the
/// flank fit (20 % top and 10 % foot left out) rests on a few points per flank and a single avalanche shifts it by
/// several degrees, and the grains falling from the funnel carry more energy per grain of pile than in the thesis,
/// flattening a small pile (docs/validation.md: 15°–23° per flank over seeds and funnel heights, against 21°–25° for
/// the thesis-sized pile while it was still being poured). The band is therefore wider than the thesis's
/// 26.8° ± 2.0° on the low side: the mean of both flanks must lie in 18°–35° (35° ≈ a little above arctan μ = 31°,
/// the steepest a cohesionless Coulomb slope holds), and each flank in 14°–35°. The thesis value itself is asserted
/// by `thesis_sandpile`. Also asserted: rest, no losses, no chatter on the last step (force alternation < 0.01) and
/// the floor carrying the pile's weight within 2 %.
#[test]
fn ci_sandpile() {
    let (world, elapsed) = run_scene("sandpile.ron");
    let m = measure(&world);
    report("sandpile", &m, elapsed.as_secs_f64());
    assert!(m.particles > 200, "only {} particles were poured", m.particles);
    assert!(m.kinetic_ratio < REST_KINETIC_RATIO, "not at rest: KE/(M g d) = {:.3e}", m.kinetic_ratio);
    assert_eq!(m.removed, 0, "particles left the domain");
    let alternation = world.force_alternation().ratio();
    assert!(alternation < 0.01, "the last step's contact forces alternate by {alternation} (chatter)");
    let (left, right) = (flank(&m.repose.left), flank(&m.repose.right));
    let mean = 0.5 * (left + right);
    assert!((18.0..=35.0).contains(&mean), "mean flank angle {mean:.2}° outside 18°–35°");
    for angle in [left, right] {
        assert!((14.0..=35.0).contains(&angle), "flank angle {angle:.2}° outside 14°–35°");
    }
    assert!((m.profile_over_weight - 1.0).abs() < WEIGHT_TOLERANCE, "∫p dx / W = {}", m.profile_over_weight);
    assert!((m.floor_force_over_weight - 1.0).abs() < WEIGHT_TOLERANCE, "ΣF_n / W = {}", m.floor_force_over_weight);
}

/// The thesis-sized pile (§8.3 dip-pile ensemble of nine seeds): ~2500 particles. Every member must come to rest
/// without losses with ∫p dx = W within 2 %; the ensemble's mean flank angle must lie within 26.8° ± 3° (the port
/// criterion of reference §10.3 item 19; the thesis's ± 2.0° is the spread of its nine seeds, printed beside it) and
/// its mean width within 0.46 ± 0.05 m. Run the seeds with `gc2d-rs sweep sweeps/sandpile_thesis.ron` or one by one
/// with `gc2d-rs run … --seed N`, as tests/README.md describes (about 1 h each on one thread); without
/// `GC2D_REGRESSION_RUN_DIR` the test runs the scene's own seed once.
/// Measured with the scene's GAUSS size spread (seeds 1–9): mean flank 26.24° ± 1.96°, width 0.424 m. With gc2d's
/// EQUAL spread (grains up to 1.67:1) two seeds gave 29.78° ± 0.88° and 0.410 m, steeper and narrower than the
/// thesis's; docs/validation.md has both.
#[test]
#[ignore = "thesis-sized: about 2500 particles, hours of run time per seed"]
fn thesis_sandpile() {
    let members = run_or_load_ensemble("sandpile_thesis.ron");
    let mut angles = Vec::new();
    let mut widths = Vec::new();
    for (name, world) in &members {
        let m = measure(world);
        report(name, &m, 0.0);
        assert!(m.kinetic_ratio < REST_KINETIC_RATIO, "{name} not at rest: KE/(M g d) = {:.3e}", m.kinetic_ratio);
        assert_eq!(m.removed, 0, "{name}: particles left the domain");
        assert!(
            (m.profile_over_weight - 1.0).abs() < WEIGHT_TOLERANCE,
            "{name}: ∫p dx / W = {}",
            m.profile_over_weight
        );
        angles.push(0.5 * (flank(&m.repose.left) + flank(&m.repose.right)));
        widths.push(m.repose.shape.width);
    }
    let seeds: std::collections::BTreeSet<u64> = members.iter().map(|(_, w)| w.config().seed).collect();
    assert_eq!(seeds.len(), members.len(), "the ensemble's members must differ in their seed: {seeds:?}");
    let n = angles.len() as f64;
    let mean = angles.iter().sum::<f64>() / n;
    let spread = (angles.iter().map(|a| (a - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0)).sqrt();
    let width = widths.iter().sum::<f64>() / n;
    eprintln!("ensemble of {n}: mean flank {mean:.2}° ± {spread:.2}° (thesis 26.8° ± 2.0°), width {width:.3} m (0.46)");
    assert!((mean - 26.8).abs() <= 3.0, "ensemble-mean flank angle {mean:.2}° not within 26.8° ± 3°");
    assert!((width - 0.46).abs() <= 0.05, "ensemble-mean width {width} m, thesis 0.46 ± 0.012 m");
}
