//! Janssen silo (reference §7.1, §10.3 item 13): a vertical column filled slowly from the top with 8–10-gons,
//! μ = 0.5. The wall pressure σ_xx(z) saturates with depth; k = σ_xx/σ_zz, ρ_rel and the Janssen μ_j are measured;
//! the floor and the walls' friction carry the column's weight.
//!
//! The CI-sized column (about 400 particles of r = 2.5 mm) asserts rest, broad bands for k, ρ_rel and μ_j, the walls'
//! share of the weight, the approach to saturation and the force balance. The thesis-sized column (10,000 particles
//! of r = 1 mm) is `#[ignore]`d: it asserts the thesis's k = 0.64 ± 0.19, ρ_rel = 0.78 ± 0.03 and μ_j = 0.33 ± 0.1
//! and takes far too long for CI.

mod common;

use common::{particle_weight, run_or_load_scene, run_scene};
use gc2d_analysis::scene_pile::auto_half_width;
use gc2d_analysis::{
    AnalyzeOptions, Facing, ProfileOptions, SceneKind, SiloReport, Snapshot, WallSelection, analyze_snapshot,
    pressure_profile, wall_forces,
};
use gc2d_engine::World;

/// What the tests assert about a filled, settled column.
struct SiloMeasurement {
    particles: usize,
    removed: u64,
    report: SiloReport,
    /// (depth, σ_xx) of the mean of both walls' profiles (2.40), from the floor up to the fill surface.
    sigma_xx: Vec<(f64, f64)>,
    /// (max − min)/mean of σ_xx over the deepest quarter of the column.
    last_quarter_variation: f64,
    /// μ_j from the plateau alone, ρ g r / mean σ_xx over the deepest quarter (3.4 at z → ∞): a check on the fit,
    /// which ties the saturation depth to the column-mean k.
    plateau_mu_j: f64,
    /// σ_xx at the bottom over the hydrostatic ρ g z there (1 for a fluid with k = 1).
    bottom_over_hydrostatic: f64,
    /// (floor normal force + wall friction) over the particles' weight.
    support_over_weight: f64,
    /// Wall friction over the particles' weight: the share of the weight the side walls carry.
    wall_share: f64,
    kinetic_ratio: f64,
}

fn measure(world: &World) -> SiloMeasurement {
    let snapshot = Snapshot::from_world(world);
    let weight = particle_weight(world);
    let diameter = snapshot.mean_particle_diameter();
    let out = tempfile::tempdir().expect("a temporary directory");
    let options = AnalyzeOptions { scene: SceneKind::Silo, ..AnalyzeOptions::default() };
    let report = analyze_snapshot(&snapshot, &options, out.path()).expect("silo analysis").silo.expect("a silo");

    let left = wall_forces(&snapshot, WallSelection::facing(Facing::Right));
    let right = wall_forces(&snapshot, WallSelection::facing(Facing::Left));
    let floor = wall_forces(&snapshot, WallSelection::facing(Facing::Up));
    let both: Vec<_> = left.iter().chain(&right).copied().collect();
    let b = auto_half_width(&both, diameter);
    let profile_options = ProfileOptions { half_width: b, step: 0.5 * b, moving_average: 1 };
    let range = Some((report.floor_level + b, report.fill_surface - b));
    let (pl, pr) =
        (pressure_profile(&left, &profile_options, range), pressure_profile(&right, &profile_options, range));
    let sigma_xx: Vec<(f64, f64)> = pl
        .positions
        .iter()
        .zip(pl.pressure.iter().zip(&pr.pressure))
        .map(|(&y, (&a, &c))| (report.fill_surface - y, 0.5 * (a + c)))
        .collect();
    let depth = report.fill_height;
    let deep: Vec<f64> = sigma_xx.iter().filter(|(z, _)| *z >= 0.75 * depth).map(|p| p.1).collect();
    let (lo, hi) = deep.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| (l.min(v), h.max(v)));
    let mean = deep.iter().sum::<f64>() / deep.len().max(1) as f64;
    let (bottom_depth, bottom_sigma) = sigma_xx.iter().copied().fold((0.0, 0.0), |a, p| if p.0 > a.0 { p } else { a });

    // The particles drag the side walls down (force_on_wall.y < 0): the walls carry −Σ F_y of the column.
    let friction: f64 = both.iter().map(|f| -f.force_on_wall.y).sum();
    let floor_force: f64 = floor.iter().map(|f| f.normal_force).sum();
    eprintln!(
        "floor {:.5} W, wall friction {:.5} W, all wall contacts {:.5} W",
        floor_force / weight,
        friction / weight,
        all_wall_support(&snapshot) / weight
    );
    SiloMeasurement {
        particles: snapshot.particles.len(),
        removed: world.stats().removed,
        sigma_xx,
        last_quarter_variation: (hi - lo) / mean,
        plateau_mu_j: report.bulk_density * snapshot.gravity * report.half_width / mean,
        bottom_over_hydrostatic: bottom_sigma / (report.bulk_density * snapshot.gravity * bottom_depth),
        support_over_weight: (floor_force + friction) / weight,
        wall_share: friction / weight,
        kinetic_ratio: world.ledger().kinetic() / (weight * diameter),
        report,
    }
}

/// −Σ F_y over every force the particles exert on walls: what all walls together carry, N.
fn all_wall_support(snapshot: &Snapshot) -> f64 {
    use gc2d_analysis::BodyRef;
    snapshot
        .contacts
        .iter()
        .map(|c| match (c.a, c.b) {
            (BodyRef::Wall(_), BodyRef::Particle(_)) => c.force_on_a.y,
            (BodyRef::Particle(_), BodyRef::Wall(_)) => c.force_on_b().y,
            _ => 0.0,
        })
        .map(|fy| -fy)
        .sum()
}

fn print(name: &str, m: &SiloMeasurement, seconds: f64) {
    let r = &m.report;
    eprintln!(
        "{name}: {} particles, removed {}, run {seconds:.1} s, KE/(M g d) = {:.3e}, r = {:.4} m, fill {:.4} m, \
         k = {:.3} (rows {:.3} ± {:.3}), ρ_rel = {:.3} (rows {:.3} ± {:.3}), μ_j = {:?}, janssen error {:?}, \
         k free: (μ_j, k, saturation depth) = {:?}, error {:?}, last-quarter variation {:.3}, plateau μ_j {:.3}, σ_xx(bottom)/ρgz = {:.3}, support/W = {:.5}, \
         walls carry {:.3} W",
        m.particles,
        m.removed,
        m.kinetic_ratio,
        r.half_width,
        r.fill_height,
        r.k,
        r.k_mean,
        r.k_std,
        r.packing_fraction,
        r.packing_fraction_mean,
        r.packing_fraction_std,
        r.janssen.map(|f| (f.mu_j, f.relative_rms_residual, f.saturation_depth)),
        r.janssen_error,
        r.janssen_free_k.map(|f| (f.mu_j, f.k, f.saturation_depth)),
        r.janssen_free_k_error,
        m.last_quarter_variation,
        m.plateau_mu_j,
        m.bottom_over_hydrostatic,
        m.support_over_weight,
        m.wall_share,
    );
    for (z, s) in &m.sigma_xx {
        eprintln!("  z = {z:.4} m  σ_xx = {s:.2} N/m");
    }
}

/// The CI-sized column (§10.3 item 13 with r_p = 2.5 mm, ~400 particles, 20 cm of fill, see the scene's header).
/// Asserted: rest, no losses, no chatter on the last step (force alternation < 0.01), k and ρ_rel in broad bands
/// around the thesis's, the Janssen effect (the side walls' friction carries at least 10 % of the weight, and the
/// plateau's μ_j = ρ g r / σ_xx,∞ is within 0.15–0.6, around the thesis's 0.33), the approach to saturation (σ_xx
/// over the deepest quarter varies by less than 60 %), the force balance of a single step within 2 %, and that the
/// Janssen fit returns. The bands hold every one of 35 trajectories of this column (seeds 2–10 on four binaries whose
/// contacts differ in the last bits, docs/validation.md "The CI silo's Janssen fits"), which the fits' μ_j (0.0001 to
/// 0.092, and 0.08 to 0.35 with k free) and a variation under 30 % (five of them above) do not. Measured values are
/// in docs/validation.md.
#[test]
fn ci_silo() {
    let (world, elapsed) = run_scene("silo.ron");
    let m = measure(&world);
    print("silo", &m, elapsed.as_secs_f64());
    assert!(m.particles > 350, "only {} particles were filled in", m.particles);
    assert_eq!(m.removed, 0, "particles left the domain");
    assert!(m.kinetic_ratio < 1e-3, "not at rest: KE/(M g d) = {:.3e}", m.kinetic_ratio);
    let alternation = world.force_alternation().ratio();
    assert!(alternation < 0.01, "the last step's contact forces alternate by {alternation} (chatter)");
    assert!((0.4..=1.0).contains(&m.report.k), "k = {}", m.report.k);
    assert!((0.70..=0.90).contains(&m.report.packing_fraction), "ρ_rel = {}", m.report.packing_fraction);
    assert!((0.15..=0.6).contains(&m.plateau_mu_j), "the plateau's μ_j = {}", m.plateau_mu_j);
    assert!(m.report.janssen.is_some(), "no Janssen fit: {:?}", m.report.janssen_error);
    assert!(m.wall_share >= 0.1, "the side walls carry only {:.3} of the weight", m.wall_share);
    assert!(m.last_quarter_variation < 0.6, "σ_xx varies by {:.3} over the last quarter", m.last_quarter_variation);
    assert!((m.support_over_weight - 1.0).abs() < 0.02, "support / W = {}", m.support_over_weight);
}

/// Issue 19 item 6, the gentle-fill experiment: does the fill's impact speed make the column denser than the thesis's?
/// The CI column filled gently (`silo_gentle.ron`: four narrow sources each drop a grain 1.5 cm above the grains
/// under it every 80 ms, landing at about 0.6 m/s) against the same column filled from its line at 41 cm (`silo.ron`,
/// up to 2.8 m/s). Asserted for seed 2: both at rest with every grain in; the gentle column is looser by at least
/// 0.01 (measured 0.8177 against 0.8313; over seeds 2–6 the means are 0.827 and 0.811, docs/validation.md),
/// a fifth of the thesis silo's excess of 0.07, so the fill is not the main cause. About 7 minutes on two cores;
/// with `GC2D_REGRESSION_RUN_DIR` the finished runs `silo/` and `silo_gentle/` of `gc2d-rs run` are read instead.
#[test]
#[ignore = "an experiment: about 7 minutes"]
fn gentle_fill_packs_looser_but_not_as_loose_as_the_thesis() {
    let (fast_world, fast_time) = run_or_load_scene("silo.ron");
    let (gentle_world, gentle_time) = run_or_load_scene("silo_gentle.ron");
    let (fast, gentle) = (measure(&fast_world), measure(&gentle_world));
    print("silo", &fast, fast_time.as_secs_f64());
    print("silo_gentle", &gentle, gentle_time.as_secs_f64());
    for m in [&fast, &gentle] {
        assert!(m.particles > 350 && m.removed == 0, "{} grains filled in, {} lost", m.particles, m.removed);
        assert!(m.kinetic_ratio < 1e-3, "not at rest: KE/(M g d) = {:.3e}", m.kinetic_ratio);
    }
    let (fast_rho, gentle_rho) = (fast.report.packing_fraction, gentle.report.packing_fraction);
    assert!(gentle_rho < fast_rho - 0.01, "gentle fill ρ_rel = {gentle_rho}, fast fill {fast_rho}");
    assert!(gentle_rho > 0.78 + 0.02, "the gentle fill alone reaches the thesis's ρ_rel: {gentle_rho}");
}

/// The thesis-sized column (§7.1): 10,000 particles of r = 1 mm; k = 0.64 ± 0.19, ρ_rel = 0.78 ± 0.03,
/// μ_j = 0.33 ± 0.1, saturation and the force balance within 2 %. About 6.6 hours of wall time on this two-core machine.
/// Measured (seed 2): k = 0.573 and μ_j = 0.350 meet the thesis's; ρ_rel = 0.853 and a 46 % σ_xx variation over the
/// deepest quarter (the 32 cm column is 1.3 saturation lengths deep) do not, so this test fails; docs/validation.md
/// has the numbers and the candidate causes.
#[test]
#[ignore = "thesis-sized: 10,000 particles, hours of run time"]
fn thesis_silo() {
    let (world, elapsed) = run_or_load_scene("silo_thesis.ron");
    let m = measure(&world);
    print("silo_thesis", &m, elapsed.as_secs_f64());
    assert_eq!(m.removed, 0, "particles left the domain");
    assert!((m.report.k - 0.64).abs() <= 0.19, "k = {}", m.report.k);
    assert!((m.report.packing_fraction - 0.78).abs() <= 0.03, "ρ_rel = {}", m.report.packing_fraction);
    let mu_j = m.report.janssen.map_or(f64::NAN, |f| f.mu_j);
    assert!((mu_j - 0.33).abs() <= 0.1, "μ_j = {mu_j}");
    assert!(m.last_quarter_variation < 0.2, "σ_xx varies by {} over the last quarter", m.last_quarter_variation);
    assert!((m.support_over_weight - 1.0).abs() < 0.02, "support / W = {}", m.support_over_weight);
}
