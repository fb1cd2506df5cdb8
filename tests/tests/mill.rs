//! The ball mill in steady state (reference ballmill.md §7.6, §3.9): what the rotor puts in, the contacts
//! dissipate; the median ball speed is stationary noise with friction, while frictionless balls lock into a ring.
//!
//! `tests/scenes/mill_ci.ron` is `scenes/mill.ron` (130 steel balls, 1700 rpm, the steel e(v), Mindlin friction) with
//! balls and walls 30 times softer than steel, which the stiffness study in docs/validation.md shows to change the
//! state of the mill (median speed, power) by little; it runs the thesis's 0.2 s warm-up and 0.8 s averaging window in
//! seconds. `mill_ci_frictionless.ron` is the negative control (constant e = 0.9, μ = 0).

mod common;

use common::scene_path;
use gc2d_analysis::mill_speeds::autocorrelation;
use gc2d_engine::World;
use gc2d_scene::Scene;
use std::f64::consts::TAU;
use std::sync::OnceLock;

/// Start of the averaging window, s (the thesis's warm-up).
const WARM_UP_S: f64 = 0.2;
/// Interval of the median-speed samples, s (ballmill.md §7.6: every 1–10 ms).
const SAMPLE_INTERVAL_S: f64 = 1e-3;
/// The rotor's tip speed, m/s (1700 rpm at 58 mm), and its half revolution (the bar's two arms pass), s.
const TIP_SPEED_M_S: f64 = 1700.0 * TAU / 60.0 * 0.058;
const ARM_PERIOD_S: f64 = 0.5 * 60.0 / 1700.0;

/// What a mill run delivers over the averaging window.
struct Window {
    /// Work of the walls on the balls from the ledger, J.
    work_in: f64,
    /// Energy the contacts dissipated from the ledger, J.
    dissipated: f64,
    /// ∫ Σ F·v dt of the rotor over the window's steps (rectangle rule), J.
    rotor_work_from_power: f64,
    /// Length of the window, s.
    duration: f64,
    /// The balls' median speed every [`SAMPLE_INTERVAL_S`], m/s.
    median_speeds: Vec<f64>,
}

/// A mill run through its window, and the World at its end.
struct MillRun {
    world: World,
    window: Window,
}

/// The median |v| of the particles, m/s.
fn median_speed(world: &World) -> f64 {
    let b = world.bodies();
    let mut speeds: Vec<f64> = b.particles().map(|id| b.velocity[id.index()].length()).collect();
    speeds.sort_by(f64::total_cmp);
    let n = speeds.len();
    if n % 2 == 1 { speeds[n / 2] } else { 0.5 * (speeds[n / 2 - 1] + speeds[n / 2]) }
}

/// Runs `file` of tests/scenes through its warm-up and averaging window and measures the window.
fn run_window(file: &str) -> MillRun {
    let scene = Scene::from_path(scene_path(file)).unwrap_or_else(|e| panic!("{file}: {e:?}"));
    let mut world = scene.build().expect("the CI mill builds");
    world.run_until(WARM_UP_S).expect("the warm-up runs");
    let (work_start, dissipated_start, time_start) =
        (world.ledger().work_walls, world.ledger().dissipated(), world.time());
    let mut rotor_work_from_power = 0.0;
    let mut median_speeds = Vec::new();
    let mut next_sample = time_start;
    while world.time() + 0.5 * world.time_step() < scene.run.end_time_s {
        if world.time() + 0.5 * world.time_step() >= next_sample {
            median_speeds.push(median_speed(&world));
            next_sample += SAMPLE_INTERVAL_S;
        }
        world.step().expect("the mill runs");
        rotor_work_from_power += world.rotor_power().power_from_work * world.time_step();
    }
    let window = Window {
        work_in: world.ledger().work_walls - work_start,
        dissipated: world.ledger().dissipated() - dissipated_start,
        rotor_work_from_power,
        duration: world.time() - time_start,
        median_speeds,
    };
    MillRun { world, window }
}

/// The reference CI mill, run once for all tests of this file.
fn reference() -> &'static MillRun {
    static RUN: OnceLock<MillRun> = OnceLock::new();
    RUN.get_or_init(|| run_window("mill_ci.ron"))
}

/// The window cut into this many batches of 0.1 s (about six passes of the rotor's arms) for the batch-means error.
const BATCHES: usize = 8;

/// The mean of a correlated series and its standard error by batch means: the series cut into [`BATCHES`] equal
/// batches, whose means scatter as independent samples when a batch outlasts the correlations.
///
/// The median speed of the mill carries fluctuations slower than its autocorrelation's first 1/e decay: over 0.8 s
/// windows of the CI mill, the two halves of one run differed by 2.5–8 % and the window means of runs with other seeds
/// and other summation orders by up to 10 % (2.32–2.56 m/s; docs/validation.md, "The CI mill's window means"). An
/// error summed from the autocorrelation up to 0.1 s put these differences at 4–6 standard errors, so the batches
/// measure the scatter instead.
struct BatchMeans {
    /// The batches' means, m/s.
    means: Vec<f64>,
    /// Mean of the batch means, m/s.
    mean: f64,
    /// Standard deviation of the batch means, m/s.
    deviation: f64,
}

impl BatchMeans {
    fn of(values: &[f64]) -> Self {
        let batch = values.len() / BATCHES;
        let means: Vec<f64> =
            values.chunks_exact(batch).take(BATCHES).map(|b| b.iter().sum::<f64>() / batch as f64).collect();
        let (mean, deviation) = mean_and_deviation(&means);
        Self { means, mean, deviation }
    }

    /// Standard error of the mean over all batches, m/s.
    fn standard_error(&self) -> f64 {
        self.deviation / (BATCHES as f64).sqrt()
    }
}

/// Mean and standard deviation.
fn mean_and_deviation(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, variance.sqrt())
}

#[test]
fn a_steady_mill_dissipates_what_its_rotor_puts_in() {
    let MillRun { world, window: w } = reference();
    let power = w.work_in / w.duration;
    let dissipation = w.dissipated / w.duration;
    eprintln!(
        "⟨P⟩ = {power:.3} W, ⟨D⟩ = {dissipation:.3} W, ∫ΣF·v dt / ΔW = {:.6}, ledger error {:.3e} J of {:.3} J put in",
        w.rotor_work_from_power / w.work_in,
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

#[test]
fn with_friction_the_median_speed_is_stationary_noise() {
    let speeds = &reference().window.median_speeds;
    let (mean, deviation) = mean_and_deviation(speeds);
    // The balls of the dense ring are braked by the chamber: they move at a quarter of the tip speed, with a spread
    // of several per cent from sample to sample.
    assert!((0.15..0.35).contains(&(mean / TIP_SPEED_M_S)), "median {mean} m/s");
    assert!(deviation > 0.05 * mean, "spread {deviation} m/s of {mean} m/s");
    // It forgets: the autocorrelation (the mill analysis's, over three rotor periods) falls below 1/e within three
    // passes of the rotor's arms …
    let rho = autocorrelation(speeds, SAMPLE_INTERVAL_S, 2.0 * ARM_PERIOD_S).expect("a noisy series");
    assert!(
        rho.decorrelation_lag_s <= 3.0 * ARM_PERIOD_S,
        "autocorrelation above 1/e for {} s",
        rho.decorrelation_lag_s
    );
    // … and the two halves of the window have the same mean within four standard errors, the error from the scatter
    // of the 0.1 s batches (`BatchMeans`): no drift beyond the mill's own slow fluctuations.
    let batches = BatchMeans::of(speeds);
    let (first, _) = mean_and_deviation(&batches.means[..BATCHES / 2]);
    let (second, _) = mean_and_deviation(&batches.means[BATCHES / 2..]);
    let standard_error = batches.deviation * (4.0 / BATCHES as f64).sqrt();
    eprintln!("halves: {first:.4} and {second:.4} m/s, σ = {standard_error:.4} m/s");
    assert!((first - second).abs() <= 4.0 * standard_error, "{first} against {second} m/s, σ = {standard_error}");
}

#[test]
fn frictionless_balls_lock_into_a_ring_that_turns_with_the_rotor() {
    let MillRun { window, .. } = run_window("mill_ci_frictionless.ron");
    let (mean, deviation) = mean_and_deviation(&window.median_speeds);
    eprintln!("frictionless: median {mean:.3} ± {deviation:.3} m/s, tip speed {TIP_SPEED_M_S:.2} m/s");
    // Nothing brakes them: the median ball moves at about three quarters of the tip speed, three times as fast as
    // with friction, and hardly varies (the thesis's smooth balls also roll in two layers along the wall, §3.9; the
    // event-driven method's collapse cycles do not occur with soft contacts, docs/validation.md).
    assert!(mean > 0.7 * TIP_SPEED_M_S, "median {mean} m/s");
    assert!(deviation < 0.02 * mean, "spread {deviation} m/s of {mean} m/s");
    let (with_friction, _) = mean_and_deviation(&reference().window.median_speeds);
    assert!(mean > 2.5 * with_friction, "{mean} against {with_friction} m/s with friction");
}

#[test]
fn a_mill_started_from_a_bed_at_rest_reaches_the_same_median_speed() {
    let bed = run_window("mill_ci_bed.ron");
    let from_bed = BatchMeans::of(&bed.window.median_speeds);
    let spread_out = BatchMeans::of(&reference().window.median_speeds);
    let standard_error = from_bed.standard_error().hypot(spread_out.standard_error());
    let (from_bed, spread_out) = (from_bed.mean, spread_out.mean);
    let power = |run: &MillRun| run.window.work_in / run.window.duration;
    eprintln!(
        "over the window: median speed {spread_out:.4} m/s spread out at 1 m/s, {from_bed:.4} m/s from a bed; ⟨P⟩ \
         {:.3} and {:.3} W",
        power(reference()),
        power(&bed)
    );
    // The same steady state within four standard errors of the two windows' batch means.
    assert!(
        (from_bed - spread_out).abs() <= 4.0 * standard_error,
        "{from_bed} against {spread_out} m/s, σ = {standard_error}"
    );
}
