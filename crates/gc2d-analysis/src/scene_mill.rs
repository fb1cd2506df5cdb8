//! Collision statistics, ball speeds, where the balls are and the power balance of a ball-mill run (reference
//! ballmill.md §7.6), from the run's `events.csv`, `dumps/` (per-particle state), `timeseries.csv` and `final.ckpt`.
//!
//! The balls are the particles the scene's `mill.balls` made ([`BallIds`]), every other particle is an ore grain;
//! without the scene, a disk particle is a ball and a polygon particle an ore grain. Per collision class (ball–ball, ball–ore, ore–ore, and
//! each particle kind against the chamber, a blade, the hub or another wall) and over all classes: the number of
//! episodes that began in the averaging window, per second and per particle and second; the impact normal speeds'
//! mode, quartiles and the fractions above 0.5, 1 and 3 m/s; their histogram with √N bins, area-normalised; and
//! ΣE_n = Σ ½·m·v_n² per second with m the mass of the class's first particle (the thesis's grinding-intensity
//! measure, (20-2)). Blade hits per revolution. On ore grains the stress-energy spectrum. From the dumps: the balls'
//! |v| distribution and its upper/lower split in the outer ring, the median |v| series with its automatic warm-up cut
//! and its autocorrelation, the radial profile and the sector maps. The power: the mean of the rotor's ω·τ and Σ F·v
//! over the window's rows, the mean power the walls put in and the mean dissipation from the ledger, and their
//! relative differences.

use crate::error::{AnalysisError, time_text};
use crate::figures::{Labels, Mark, PolarCell, SERIES_COLOURS, Series, bar_chart, line_chart, polar_cell_map};
use crate::mill_space::{ChamberFrame, RadialProfile, SectorCell, radial_profile, sector_map};
use crate::mill_speeds::{
    Autocorrelation, Histogram, SpeedDistribution, WarmUpCut, autocorrelation, quantile, warm_up_cut,
};
use crate::output::OutputDir;
use crate::particle_state::csv::{DUMPS_DIR, dump_files, dump_warnings, read_csv};
use crate::particle_state::{ParticleShape, ParticleState};
use crate::table::{Table, number};
use gc2d_engine::{Bodies, BodyKind, ShapeKind, WallMotion, World};
use gc2d_geometry::DVec2;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;

/// Speeds whose share the report gives, m/s.
pub const SPEED_THRESHOLDS: [f64; 3] = [0.5, 1.0, 3.0];

/// The columns of `events.csv` that hold names; every other one holds numbers (`wall_angular_impulse_n_m_s` is empty
/// where no body is a wall turning about a pivot), checked in every row, read by the analysis or not.
const EVENT_TEXT_COLUMNS: [&str; 6] = ["kind_a", "kind_b", "material_a", "material_b", "object_a", "object_b"];

/// Options of [`analyze_mill`].
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct MillOptions {
    /// Start of the averaging window, s: episodes that begin earlier and rows and dumps before it are left out.
    /// `None`: the automatic cut of the median-speed series ([`warm_up_cut`]), or 0 when the series is too short.
    pub warm_up_s: Option<f64>,
    /// Which particles are balls.
    pub balls: BallIds,
}

/// Which particles of a mill run are balls; every other particle is an ore grain.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize)]
pub enum BallIds {
    /// The disk particles (every particle, for speeds and places, where none is a disk): for a run whose scene is not
    /// at hand. Ore grains that are disks are then taken for balls.
    #[default]
    Disks,
    /// The particles with these body ids: the balls of the scene's `mill.balls`.
    Range(std::ops::Range<usize>),
}

impl BallIds {
    /// True when particle `id` of `bodies` is a ball.
    fn is_ball(&self, bodies: &Bodies, id: usize) -> bool {
        match self {
            BallIds::Disks => bodies.shape[id] == ShapeKind::Disk,
            BallIds::Range(range) => range.contains(&id),
        }
    }

    /// The balls among the particles of a dump (every particle where [`BallIds::Disks`] finds no disk).
    fn of_rows<'a>(&self, rows: &'a [ParticleState]) -> Vec<&'a ParticleState> {
        match self {
            BallIds::Disks => {
                let disks = rows.iter().any(|r| r.shape == ParticleShape::Disk);
                rows.iter().filter(|r| !disks || r.shape == ParticleShape::Disk).collect()
            }
            BallIds::Range(range) => rows.iter().filter(|r| range.contains(&(r.id as usize))).collect(),
        }
    }
}

/// The statistics of one collision class.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CollisionClass {
    /// `ball–ball`, `ball–ore`, `ore–ore`, `ball–chamber`, `ball–blade`, `ball–hub`, `ball–wall`, the same with `ore`,
    /// or `all`.
    pub class: String,
    /// Episodes that began in the window.
    pub collisions: usize,
    /// Per second.
    pub per_second: f64,
    /// Per second and per particle of the class's first kind (balls; ore grains for `ore–…`; balls for `all`).
    pub per_ball_per_second: f64,
    /// Centre of the fullest histogram bin, m/s (0 when every impact speed is 0; NaN, null, without collisions).
    pub mode_m_s: f64,
    /// Quartiles of the impact normal speed, m/s (NaN, null, without collisions).
    pub quartiles_m_s: [f64; 3],
    /// Shares of impacts faster than [`SPEED_THRESHOLDS`]; NaN (null in JSON, an empty CSV field) for a class without
    /// collisions: a share of no impacts is not 0.
    pub fractions_above: [f64; 3],
    /// Σ ½·m·v_n² per second, W.
    pub normal_energy_per_second_w: f64,
    /// Histogram of the impact normal speed: bin edges, m/s (one more than the densities; none without collisions or
    /// when every impact speed is 0).
    pub bin_edges_m_s: Vec<f64>,
    /// Probability densities per bin, s/m (the histogram's area is 1).
    pub densities: Vec<f64>,
}

/// The stress-energy spectrum of the ore grains: the energy ½·m_eff·v_n² of every collision an ore grain took
/// (m_eff = m_a·m_b/(m_a + m_b) between particles, the grain's mass against a wall).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StressEnergySpectrum {
    /// Ore collisions in the window with an impact (v_n > 0).
    pub events: usize,
    /// Ore collisions in the window without an approach speed (v_n = 0; left out of the bins).
    pub without_impact: usize,
    /// Stress events per second.
    pub per_second: f64,
    /// Median energy, J.
    pub median_j: f64,
    /// Mean energy, J.
    pub mean_j: f64,
    /// Σ energy per second, W.
    pub energy_per_second_w: f64,
    /// Bin edges, J: ⌈√N⌉ bins of equal width in log10 E from the smallest to the largest energy.
    pub bin_edges_j: Vec<f64>,
    /// Events per bin.
    pub counts: Vec<usize>,
    /// Share of the events per decade of energy (Σ density × bin width in decades = 1).
    pub densities_per_decade: Vec<f64>,
}

/// The rotor's power and the ledger's balance over the window.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MillPower {
    /// ⟨P_torque⟩: ω·τ summed over every step of the window (`rotor_work_torque_j`) divided by its length, W. A mean
    /// of the rows' instantaneous ω·τ would sample the short blade hits at the frame rate and miss most of them.
    pub mean_power_torque_w: f64,
    /// ⟨P_work⟩: Σ F·v summed over every step of the window (`rotor_work_j`) divided by its length, W.
    pub mean_power_work_w: f64,
    /// Work the walls put in over the window divided by its length, W (the ledger's).
    pub power_in_w: f64,
    /// ⟨D⟩: energy dissipated over the window divided by its length, W.
    pub dissipation_w: f64,
    /// (power in − ⟨D⟩)/power in.
    pub relative_imbalance: f64,
    /// (⟨P_torque⟩ − ⟨P_work⟩)/⟨P_torque⟩.
    pub relative_torque_work: f64,
    /// (⟨P_torque⟩ − ⟨D⟩)/⟨P_torque⟩.
    pub relative_torque_dissipation: f64,
}

/// How the window's start was chosen.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WarmUp {
    /// The start of the window used, s: the start given or cut, or the first time-series row after it where it falls
    /// between two rows (more than [`WarmUp::tolerance_s`] before that row).
    pub start_s: f64,
    /// True when the user gave it (`--warm-up`), false when it is the automatic cut.
    pub given: bool,
    /// The automatic cut (also computed when a start was given); `None` for a series of fewer than 8 samples, which
    /// is not cut (the window is the whole run unless a start is given).
    pub automatic: Option<WarmUpCut>,
    /// The median-speed series the cut and the autocorrelation use: `dumps` (balls' median |v| per dump) or
    /// `timeseries` (all particles', per time-series row, when the run has fewer than 8 dumps).
    pub series: &'static str,
    /// Half the run's time step, s: a row, dump or event this close to the start counts as at it (their times are
    /// sums of steps, a hair off the multiples of the frame interval they stand for).
    pub tolerance_s: f64,
}

/// The balls' speeds over the window's dumps.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BallSpeeds {
    /// Dumps in the window.
    pub dumps: usize,
    /// Every ball in every dump.
    pub all: SpeedDistribution,
    /// Balls in the outer ring (r > R − 2d) above the centre; `None` without a circular chamber (a wavy or polygonal
    /// one), which has no R in the final state.
    pub upper_outer: Option<SpeedDistribution>,
    /// Balls in the outer ring below the centre; `None` without a circular chamber.
    pub lower_outer: Option<SpeedDistribution>,
}

/// What [`analyze_mill`] computed, written as `mill.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MillReport {
    /// The averaging window, s.
    pub window_s: [f64; 2],
    /// How its start was chosen.
    pub warm_up: WarmUp,
    /// Balls (disk particles) in the final state.
    pub balls: usize,
    /// Ore grains (polygon particles) in the final state.
    pub ore_grains: usize,
    /// Rotor revolutions in the window: the angle it turned through over 2π, from its motion law in `final.ckpt`
    /// (angular velocity, spin-up ramp, time window), so a window that overlaps the spin-up counts the turns made.
    pub revolutions: f64,
    /// Blade hits per revolution.
    pub blade_hits_per_revolution: f64,
    /// Per collision class.
    pub classes: Vec<CollisionClass>,
    /// Every collision of the window together (class `all`).
    pub all_classes: CollisionClass,
    /// The ore grains' stress-energy spectrum, when there are ore grains.
    pub stress_energy: Option<StressEnergySpectrum>,
    /// Power balance.
    pub power: MillPower,
    /// Mean and standard deviation of the median-speed series over the window, m/s.
    pub median_speed_m_s: [f64; 2],
    /// The autocorrelation of the median-speed series over the window (its values are in
    /// `mill_autocorrelation.csv`).
    pub autocorrelation: Option<Autocorrelation>,
    /// The balls' speeds from the dumps (`None` without dumps in the window).
    pub ball_speeds: Option<BallSpeeds>,
    /// The chamber (`None` when the run has no circular chamber: no radial profile or sector maps then).
    pub chamber: Option<ChamberFrame>,
    /// The radial residence profile of the balls.
    pub radial_profile: Option<RadialProfile>,
    /// True when events.csv has the collisions' begin points (the sector maps' collision counts).
    pub collision_points_known: bool,
    /// The sector maps (also in `mill_sectors.csv`).
    #[serde(skip)]
    pub sectors: Vec<SectorCell>,
    /// The median-speed series over the whole run: (time s, median |v| m/s).
    #[serde(skip)]
    pub median_series: Vec<(f64, f64)>,
    /// What the user should know before trusting the numbers: dumps the analysis cannot read or that are missing, a
    /// chamber without the outer ring and the maps, samples whose every speed is 0 (also printed by `gc2d-rs analyze`
    /// and at the end of `gc2d-rs run`).
    pub warnings: Vec<String>,
    /// The files written into the analysis directory.
    pub files: Vec<String>,
}

impl MillReport {
    /// A few lines for the end of a run: median |v|, the powers, blade hits per revolution and the tail shares.
    pub fn summary(&self) -> String {
        let [from, to] = self.window_s;
        let how = match (self.warm_up.given, self.warm_up.automatic) {
            (true, _) => "fixed start",
            (false, Some(_)) => "automatic warm-up cut",
            (false, None) => "no warm-up cut: too few samples for the test",
        };
        let median = self.ball_speeds.as_ref().map_or(self.median_speed_m_s[0], |s| s.all.median_m_s);
        let median = match self.balls {
            0 => "no balls".to_string(),
            _ => format!("median ball speed {median:.3} m/s"),
        };
        let hits = match self.blade_hits_per_revolution {
            hits if hits.is_finite() => format!("{hits:.2} blade hits per revolution"),
            _ => "blade hits per revolution undefined (the rotor stands)".to_string(),
        };
        let p = &self.power;
        let f = &self.all_classes.fractions_above;
        let relative = p.relative_torque_dissipation;
        let relative =
            if relative.is_finite() { format!("{:+.2} %", 100.0 * relative) } else { "undefined".to_string() };
        let impacts = match self.all_classes.collisions {
            0 => "no collisions in the window".to_string(),
            n => format!(
                "impacts faster than 0.5 / 1 / 3 m/s: {:.1} / {:.1} / {:.2} % of {n} collisions",
                100.0 * f[0],
                100.0 * f[1],
                100.0 * f[2]
            ),
        };
        format!(
            "Mill over {from:.3}–{to:.3} s ({how}): {median}; <P_torque> {:.4} W, <P_work> {:.4} W, <D> {:.4} W \
             ((P − D)/P {relative});\n{hits}; {impacts}.",
            p.mean_power_torque_w, p.mean_power_work_w, p.dissipation_w,
        )
    }
}

/// `ball` or `ore` for particle `i`.
fn particle_kind(bodies: &Bodies, balls: &BallIds, i: usize) -> &'static str {
    if balls.is_ball(bodies, i) { "ball" } else { "ore" }
}

/// The collision class of an episode between bodies `a` and `b` of the final World.
fn class_of(bodies: &Bodies, balls: &BallIds, a: usize, b: usize) -> String {
    let wall = [a, b].into_iter().find(|&i| bodies.kind[i] == BodyKind::Wall);
    let particle = if bodies.kind[a] == BodyKind::Particle { a } else { b };
    let first = particle_kind(bodies, balls, particle);
    let second = match wall.map(|w| bodies.shape[w]) {
        None => {
            let other = particle_kind(bodies, balls, a + b - particle);
            return if first == other { format!("{first}–{first}") } else { "ball–ore".into() };
        }
        Some(ShapeKind::InnerCircle) => "chamber",
        Some(ShapeKind::Capsule) => "blade",
        Some(ShapeKind::Disk) => "hub",
        Some(ShapeKind::Polygon) => "wall",
    };
    format!("{first}–{second}")
}

/// The statistics of one class from its impact speeds and ΣE_n over the window of length `span` s, per `particles`.
fn class_report(class: &str, mut speeds: Vec<f64>, normal_energy: f64, span: f64, particles: usize) -> CollisionClass {
    speeds.sort_by(f64::total_cmp);
    let n = speeds.len();
    let histogram = Histogram::of(&speeds);
    CollisionClass {
        class: class.to_owned(),
        collisions: n,
        per_second: n as f64 / span,
        per_ball_per_second: n as f64 / span / particles.max(1) as f64,
        mode_m_s: histogram.mode,
        quartiles_m_s: [quantile(&speeds, 0.25), quantile(&speeds, 0.5), quantile(&speeds, 0.75)],
        fractions_above: SPEED_THRESHOLDS.map(|t| share_above(&speeds, t)),
        normal_energy_per_second_w: normal_energy / span,
        bin_edges_m_s: histogram.bin_edges,
        densities: histogram.densities,
    }
}

/// The share of `speeds` faster than `threshold`; NaN without speeds (a share of nothing is not 0).
fn share_above(speeds: &[f64], threshold: f64) -> f64 {
    if speeds.is_empty() {
        return f64::NAN;
    }
    speeds.iter().filter(|&&v| v > threshold).count() as f64 / speeds.len() as f64
}

/// Why a sample whose every value is 0 has no histogram bins.
const NO_BINS: &str = "no histogram bins (a sample at one value has no density)";

/// Warnings for the collision classes whose every impact normal speed is 0 (contacts without approach): no histogram
/// bins, a mode and quartiles of 0. One for `all` where its speeds are all 0 (then every class's are).
fn zero_impact_warnings(classes: &[CollisionClass], all: &CollisionClass) -> Vec<String> {
    let zero = |c: &&CollisionClass| c.collisions > 0 && c.bin_edges_m_s.is_empty();
    let named: Vec<&CollisionClass> = if zero(&all) { vec![all] } else { classes.iter().filter(zero).collect() };
    named
        .iter()
        .map(|c| {
            format!(
                "all {} impact normal speeds of class {} are 0: {NO_BINS}; mode and quartiles 0",
                c.collisions, c.class
            )
        })
        .collect()
}

/// Warnings for the ball-speed samples whose every value is 0 (balls at rest): no histogram bins, a mode, median,
/// P90 and mean of 0. One for `all` where its speeds are all 0 (then the outer ring's are too).
fn zero_ball_speed_warnings(speeds: &BallSpeeds) -> Vec<String> {
    let parts = [
        ("all", Some(&speeds.all)),
        ("upper_outer", speeds.upper_outer.as_ref()),
        ("lower_outer", speeds.lower_outer.as_ref()),
    ];
    let zero: Vec<(&str, &SpeedDistribution)> = parts
        .into_iter()
        .filter_map(|(name, d)| Some((name, d?)))
        .filter(|(_, d)| d.samples > 0 && d.histogram.bin_edges.is_empty())
        .collect();
    let named = if zero.first().is_some_and(|(name, _)| *name == "all") { &zero[..1] } else { &zero[..] };
    named
        .iter()
        .map(|(name, d)| {
            format!(
                "all {} ball speeds ({name}) in the window are 0 (the balls are at rest): {NO_BINS}; mode, median, \
                 P90 and mean 0",
                d.samples
            )
        })
        .collect()
}

/// The stress-energy spectrum of ore-collision `energies` (J) over a window of `span` s.
pub fn stress_energy_spectrum(mut energies: Vec<f64>, span: f64) -> StressEnergySpectrum {
    let without_impact = energies.iter().filter(|&&e| e <= 0.0 || e.is_nan()).count();
    energies.retain(|&e| e > 0.0);
    energies.sort_by(f64::total_cmp);
    let n = energies.len();
    // Without events, no bins: a decade from 1 J to 10 J stood in for the missing range.
    let bins = (n as f64).sqrt().ceil() as usize;
    let (mut lo, mut hi) = match (energies.first(), energies.last()) {
        (Some(a), Some(b)) => (a.log10(), b.log10()),
        _ => (0.0, 0.0),
    };
    if hi - lo < 1e-9 {
        (lo, hi) = (lo - 0.5, hi + 0.5);
    }
    let width = (hi - lo) / bins as f64;
    let mut counts = vec![0usize; bins];
    for e in &energies {
        counts[(((e.log10() - lo) / width) as usize).min(bins - 1)] += 1;
    }
    StressEnergySpectrum {
        events: n,
        without_impact,
        per_second: n as f64 / span,
        median_j: quantile(&energies, 0.5),
        mean_j: energies.iter().sum::<f64>() / n as f64,
        energy_per_second_w: energies.iter().sum::<f64>() / span,
        bin_edges_j: if n == 0 { Vec::new() } else { (0..=bins).map(|k| 10f64.powf(lo + k as f64 * width)).collect() },
        densities_per_decade: counts.iter().map(|&c| c as f64 / (n as f64 * width)).collect(),
        counts,
    }
}

/// The chamber of the final World: its inner-circle wall, with the balls' median diameter (the particles' largest
/// extent when there are no balls).
fn chamber_of(world: &World, balls: &BallIds) -> Option<ChamberFrame> {
    let bodies = world.bodies();
    let wall =
        (0..bodies.len()).find(|&i| bodies.kind[i] == BodyKind::Wall && bodies.shape[i] == ShapeKind::InnerCircle)?;
    let ball_ids: Vec<usize> = bodies.particles().map(|id| id.index()).filter(|&i| balls.is_ball(bodies, i)).collect();
    let extent = |i: usize| {
        let radius = if bodies.shape[i] == ShapeKind::Polygon { bodies.reach[i] } else { bodies.radius[i] };
        radius * bodies.pose[i].scale
    };
    let mut radii: Vec<f64> = if ball_ids.is_empty() {
        bodies.particles().map(|id| extent(id.index())).collect()
    } else {
        ball_ids.iter().map(|&i| extent(i)).collect()
    };
    radii.sort_by(f64::total_cmp);
    let pose = bodies.pose[wall];
    Some(ChamberFrame {
        centre_m: pose.position.into(),
        radius_m: bodies.radius[wall] * pose.scale,
        ball_diameter_m: 2.0 * quantile(&radii, 0.5),
    })
}

/// One dump reduced to the balls: its time and each ball's centre and speed.
struct BallDump {
    time: f64,
    balls: Vec<(DVec2, f64)>,
}

impl BallDump {
    /// The balls of `rows`.
    fn of(rows: &[ParticleState], ball_ids: &BallIds) -> Option<Self> {
        let time = rows.first()?.time_s;
        let balls = ball_ids.of_rows(rows).into_iter().map(|r| (DVec2::new(r.x_m, r.y_m), r.speed())).collect();
        Some(Self { time, balls })
    }

    fn median_speed(&self) -> f64 {
        let mut speeds: Vec<f64> = self.balls.iter().map(|b| b.1).collect();
        speeds.sort_by(f64::total_cmp);
        quantile(&speeds, 0.5)
    }
}

/// The run's dumps up to `end` (dumps a longer earlier run left behind are not read), with the warnings about dumps
/// in formats the analysis cannot read and dumps missing from their numbering ([`dump_warnings`]).
fn read_dumps(
    run_dir: &Path,
    end: f64,
    slack: f64,
    balls: &BallIds,
) -> Result<(Vec<BallDump>, Vec<String>), AnalysisError> {
    let dir = run_dir.join(DUMPS_DIR);
    let (mut dumps, mut indices) = (Vec::new(), Vec::new());
    for (index, path) in dump_files(&dir)? {
        if let Some(dump) = BallDump::of(&read_csv(&path)?, balls)
            && dump.time <= end + slack
        {
            dumps.push(dump);
            indices.push(index);
        }
    }
    Ok((dumps, dump_warnings(&dir, &indices)?))
}

/// The rotor's revolutions from `from` to `to` s: the angle its motion law (angular velocity, spin-up ramp, time
/// window; in the checkpoint) turns it through over 2π, the largest of the run's turning walls. Its angular velocity
/// at the end times the window's length counted a linear spin-up's revolutions twice.
fn revolutions_turned(world: &World, from: f64, to: f64) -> f64 {
    let turned = |motion: &WallMotion| match motion {
        WallMotion::Rotating(rotation) => (rotation.angle(to) - rotation.angle(from)).abs(),
        _ => 0.0,
    };
    world.moving_walls().iter().map(|wall| turned(&wall.motion)).fold(0.0, f64::max) / std::f64::consts::TAU
}

/// `t` with as many decimals as resolve `tolerance` (a tenth of it), trailing zeros cut: a row's time without the
/// round-off tail of its sum of steps (0.038 for 0.03799999999988285 with a half step of 3.5e-6).
fn to_tolerance(t: f64, tolerance: f64) -> String {
    let decimals = (-(0.1 * tolerance).log10()).ceil().clamp(0.0, 17.0) as usize;
    let text = format!("{t:.decimals$}");
    if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.').to_string() } else { text }
}

/// Computes the mill statistics of the run in `run_dir` without writing anything (what `gc2d-rs run` prints at its
/// end and [`analyze_mill`] writes).
pub fn mill_report(run_dir: &Path, options: &MillOptions) -> Result<MillReport, AnalysisError> {
    let checkpoint = run_dir.join("final.ckpt");
    let world = World::load_checkpoint_file(&checkpoint)
        .map_err(|source| AnalysisError::Checkpoint { path: checkpoint.clone(), source })?;
    let end = world.time();
    let bodies = world.bodies();
    let slack = 0.5 * world.time_step();
    let balls = bodies.particles().filter(|id| options.balls.is_ball(bodies, id.index())).count();
    let ore_grains = bodies.particles().count() - balls;
    // Collision classes, rates per ball and a warm-up cut of a pile or a drum look plausible and mean nothing.
    if balls == 0 {
        return Err(AnalysisError::NotEnoughData(
            "the run has no balls (its scene has no `mill`, or a mill without balls): a mill analysis needs them"
                .into(),
        ));
    }

    let events_path = run_dir.join("events.csv");
    if !events_path.exists() {
        return Err(AnalysisError::NotEnoughData(format!(
            "{} is missing: run the scene with `gc2d-rs run --events`",
            events_path.display()
        )));
    }
    let series = Table::read(&run_dir.join("timeseries.csv"))?;
    let series_file = "timeseries.csv";
    let time = series.column("time_s", series_file)?;
    let (dumps, mut warnings) = read_dumps(run_dir, end, slack, &options.balls)?;

    // The median-speed series: the balls' per dump, else the time series' column.
    let (median_series, source): (Vec<(f64, f64)>, _) = if dumps.len() >= 8 {
        (dumps.iter().map(|d| (d.time, d.median_speed())).collect(), "dumps")
    } else {
        let median = series.column("median_speed_m_s", series_file)?;
        (series.rows.iter().map(|r| (number(&r[time]), number(&r[median]))).collect(), "timeseries")
    };
    let (times, medians): (Vec<f64>, Vec<f64>) = median_series.iter().copied().unzip();
    let automatic = warm_up_cut(&times, &medians);
    // A series too short for the test is not cut.
    let asked = options.warm_up_s.unwrap_or(automatic.map_or(0.0, |cut| cut.cut_s));
    if !(asked.is_finite() && asked >= 0.0 && asked < end) {
        return Err(AnalysisError::InvalidParameter(format!(
            "the warm-up {asked} s must lie between 0 and the run's end, {} s",
            time_text(end)
        )));
    }
    // The rows, dumps and events of the window: those at or after its start, where a time within half a step of the
    // start counts as at it (a row's time is a sum of steps, a hair off its frame's multiple).
    let row_times: Vec<f64> = series.rows.iter().map(|r| number(&r[time])).collect();
    let first_row = row_times.iter().position(|&t| t >= asked - slack).filter(|&k| k + 2 <= row_times.len());
    let Some(first_row) = first_row else {
        let last_two = match row_times.as_slice() {
            [.., before, last] => {
                let (before, last) = (to_tolerance(*before, slack), to_tolerance(*last, slack));
                format!("; its last two rows are at {before} s and {last} s: give a warm-up at or before {before} s")
            }
            _ => String::new(),
        };
        return Err(AnalysisError::NotEnoughData(format!(
            "timeseries.csv has fewer than two rows in the window from {asked} s{last_two}"
        )));
    };
    // The window starts at its first row, the first time the power can be measured from: a start between two rows
    // moves to the next row, so that every number of the report covers the window `window_s` names.
    let start = if row_times[first_row] - asked > slack { row_times[first_row] } else { asked };
    let in_window = |t: f64| t >= start - slack;
    let span = end - start;
    let warm_up =
        WarmUp { start_s: start, given: options.warm_up_s.is_some(), automatic, series: source, tolerance_s: slack };

    // Collisions.
    let events = Table::read(&events_path)?;
    events.check_numbers(&EVENT_TEXT_COLUMNS, &["wall_angular_impulse_n_m_s"])?;
    let events_file = "events.csv";
    let (begin, a, b, speed) = (
        events.column("begin_time_s", events_file)?,
        events.column("a", events_file)?,
        events.column("b", events_file)?,
        events.column("impact_normal_speed_m_s", events_file)?,
    );
    let point_columns = events.column("begin_x_m", events_file).ok().zip(events.column("begin_y_m", events_file).ok());
    let mut by_class: BTreeMap<String, (Vec<f64>, f64)> = BTreeMap::new();
    let (mut all_speeds, mut all_energy, mut ore_energies, mut points) = (Vec::new(), 0.0, Vec::new(), Vec::new());
    for (k, row) in events.rows.iter().enumerate() {
        let (ia, ib) = (events.number(k, a)? as usize, events.number(k, b)? as usize);
        let began = events.number(k, begin)?;
        if began > end + slack {
            return Err(AnalysisError::DamagedFile(format!(
                "{}: an event begins at {began} s, after the run's end at {end} s (the file is damaged, or of \
                 another run)",
                events_path.display()
            )));
        }
        if !in_window(began) || ia.max(ib) >= bodies.len() {
            continue;
        }
        let v = events.number(k, speed)?.max(0.0);
        let first = if bodies.kind[ia] == BodyKind::Particle { ia } else { ib };
        let second = ia + ib - first;
        let (class, first) = match class_of(bodies, &options.balls, ia, ib) {
            // The class names the ball first.
            c if c == "ball–ore" && particle_kind(bodies, &options.balls, first) == "ore" => (c, second),
            c => (c, first),
        };
        let energy = 0.5 * bodies.mass[first] * v * v;
        let entry = by_class.entry(class).or_default();
        entry.0.push(v);
        entry.1 += energy;
        all_speeds.push(v);
        all_energy += energy;
        if [ia, ib].iter().any(|&i| bodies.kind[i] == BodyKind::Particle && !options.balls.is_ball(bodies, i)) {
            let (ma, mb) = (bodies.mass[ia], bodies.mass[ib]);
            let reduced = if ma.is_finite() && mb.is_finite() { ma * mb / (ma + mb) } else { ma.min(mb) };
            ore_energies.push(0.5 * reduced * v * v);
        }
        if let Some((x, y)) = point_columns {
            points.push(DVec2::new(number(&row[x]), number(&row[y])));
        }
    }
    let classes: Vec<CollisionClass> = by_class
        .into_iter()
        .map(|(class, (speeds, energy))| {
            let particles = if class.starts_with("ore") { ore_grains } else { balls };
            class_report(&class, speeds, energy, span, particles)
        })
        .collect();
    let all_classes = class_report("all", all_speeds, all_energy, span, balls);
    let stress_energy = (ore_grains > 0).then(|| stress_energy_spectrum(ore_energies, span));

    let rotor_speed = (0..bodies.len())
        .filter(|&i| bodies.kind[i] == BodyKind::Wall)
        .map(|i| bodies.angular_velocity[i].abs())
        .fold(0.0, f64::max);
    let revolutions = revolutions_turned(&world, start, end);
    let blade_hits: usize = classes.iter().filter(|c| c.class.ends_with("–blade")).map(|c| c.collisions).sum();
    let blade_hits_per_revolution = if revolutions > 0.0 { blade_hits as f64 / revolutions } else { f64::NAN };

    // Power.
    let (first, last) = (&series.rows[first_row], &series.rows[series.rows.len() - 1]);
    let change = |columns: &[usize]| {
        columns.iter().map(|&c| number(&last[c]) - number(&first[c])).sum::<f64>()
            / (number(&last[time]) - number(&first[time]))
    };
    let dissipation = [
        series.column("dissipated_normal_damping_j", series_file)?,
        series.column("dissipated_tangential_damping_j", series_file)?,
        series.column("dissipated_sliding_j", series_file)?,
    ];
    let power_in = change(&[series.column("work_in_j", series_file)?]);
    let dissipation_w = change(&dissipation);
    let (torque, work) = (
        change(&[series.column("rotor_work_torque_j", series_file)?]),
        change(&[series.column("rotor_work_j", series_file)?]),
    );
    let power = MillPower {
        mean_power_torque_w: torque,
        mean_power_work_w: work,
        power_in_w: power_in,
        dissipation_w,
        relative_imbalance: (power_in - dissipation_w) / power_in,
        relative_torque_work: (torque - work) / torque,
        relative_torque_dissipation: (torque - dissipation_w) / torque,
    };

    // The median-speed series over the window.
    let window_medians: Vec<f64> = median_series.iter().filter(|s| in_window(s.0)).map(|s| s.1).collect();
    let median_mean = window_medians.iter().sum::<f64>() / window_medians.len() as f64;
    let median_spread =
        (window_medians.iter().map(|m| (m - median_mean).powi(2)).sum::<f64>() / window_medians.len() as f64).sqrt();
    let window_times: Vec<f64> = median_series.iter().filter(|s| in_window(s.0)).map(|s| s.0).collect();
    let interval = match window_times.len() {
        0 | 1 => f64::NAN,
        n => (window_times[n - 1] - window_times[0]) / (n - 1) as f64,
    };
    let rotor_period = if rotor_speed > 0.0 { std::f64::consts::TAU / rotor_speed } else { f64::INFINITY };
    let autocorrelation = autocorrelation(&window_medians, interval, rotor_period);

    // Ball speeds and places from the window's dumps.
    let window_dumps: Vec<&BallDump> = dumps.iter().filter(|d| in_window(d.time)).collect();
    let chamber = chamber_of(&world, &options.balls);
    let samples: Vec<(DVec2, f64)> = window_dumps.iter().flat_map(|d| d.balls.iter().copied()).collect();
    if chamber.is_none() && !window_dumps.is_empty() {
        warnings.push(
            "the chamber is not a circle (a wavy or polygonal wall, which the final state gives no radius for): the \
             outer-ring ball speeds (upper_outer, lower_outer), the radial profile and the sector maps are not \
             defined and are left out (null)"
                .into(),
        );
    }
    let ball_speeds = (!window_dumps.is_empty()).then(|| {
        let outer = |upper: bool| {
            chamber.map(|c| {
                let centre = DVec2::from(c.centre_m);
                let speeds = samples
                    .iter()
                    .filter(|(p, _)| (*p - centre).length() > c.radius_m - 2.0 * c.ball_diameter_m)
                    .filter(|(p, _)| (p.y >= centre.y) == upper)
                    .map(|s| s.1)
                    .collect();
                SpeedDistribution::of(speeds)
            })
        };
        BallSpeeds {
            dumps: window_dumps.len(),
            all: SpeedDistribution::of(samples.iter().map(|s| s.1).collect()),
            upper_outer: outer(true),
            lower_outer: outer(false),
        }
    });
    let radial = chamber.filter(|_| !samples.is_empty()).map(|c| {
        let radii: Vec<f64> = samples.iter().map(|(p, _)| c.polar(*p).0).collect();
        radial_profile(&c, &radii)
    });
    let sectors = chamber.map_or_else(Vec::new, |c| sector_map(&c, &samples, &points, span));
    warnings.extend(zero_impact_warnings(&classes, &all_classes));
    warnings.extend(ball_speeds.iter().flat_map(zero_ball_speed_warnings));

    Ok(MillReport {
        window_s: [start, end],
        warm_up,
        balls,
        ore_grains,
        revolutions,
        blade_hits_per_revolution,
        classes,
        all_classes,
        stress_energy,
        power,
        median_speed_m_s: [median_mean, median_spread],
        autocorrelation,
        ball_speeds,
        chamber,
        radial_profile: radial,
        collision_points_known: point_columns.is_some(),
        sectors,
        median_series,
        warnings,
        files: Vec::new(),
    })
}

/// A histogram as a step line: (edge, density) at both ends of every bin.
fn steps(edges: &[f64], densities: &[f64]) -> Vec<(f64, f64)> {
    densities.iter().enumerate().flat_map(|(k, &d)| [(edges[k], d), (edges[k + 1], d)]).collect()
}

/// The radial profile's figure: the share of ball samples per ring and, for comparison, the ring's share of the area
/// (what a ball spread evenly over the chamber would give), each a staircase over the rings.
fn radial_profile_chart(path: &Path, profile: &RadialProfile) -> Result<(), AnalysisError> {
    let edges: Vec<f64> =
        profile.rings.first().map(|r| r.from_m).into_iter().chain(profile.rings.iter().map(|r| r.to_m)).collect();
    let share: Vec<f64> = profile.rings.iter().map(|r| r.share).collect();
    let area: Vec<f64> = profile.rings.iter().map(|r| r.area_share).collect();
    let (share, area) = (steps(&edges, &share), steps(&edges, &area));
    let labels = Labels { title: "Where the balls are: share per ring", x: "r (m)", y: "share" };
    line_chart(
        path,
        labels,
        &[
            Series { label: "share of ball samples", points: &share, color: SERIES_COLOURS[0], mark: Mark::Line },
            Series { label: "share of the area", points: &area, color: SERIES_COLOURS[1], mark: Mark::Line },
        ],
    )
}

/// Analyses the mill run in `run_dir` ([`mill_report`]) and writes its tables, figures and `mill.json` into its
/// `analysis/` directory.
pub fn analyze_mill(run_dir: &Path, options: &MillOptions) -> Result<MillReport, AnalysisError> {
    let mut report = mill_report(run_dir, options)?;
    let mut out = OutputDir::create(&run_dir.join("analysis"))?;
    let rows: Vec<String> = report
        .classes
        .iter()
        .chain([&report.all_classes])
        .map(|c| {
            let numbers = [
                c.per_second,
                c.per_ball_per_second,
                c.mode_m_s,
                c.quartiles_m_s[0],
                c.quartiles_m_s[1],
                c.quartiles_m_s[2],
                c.fractions_above[0],
                c.fractions_above[1],
                c.fractions_above[2],
                c.normal_energy_per_second_w,
            ];
            // An empty class has no mode or quartiles: an empty field, as `OutputDir::write_csv` writes them.
            let fields: Vec<String> =
                numbers.iter().map(|x| if x.is_finite() { x.to_string() } else { String::new() }).collect();
            format!("{},{},{}", c.class, c.collisions, fields.join(","))
        })
        .collect();
    out.write_text(
        "mill_collisions.csv",
        &format!(
            "class,collisions,per_second,per_ball_per_second,mode_m_s,q25_m_s,median_m_s,q75_m_s,above_0_5_m_s,\
             above_1_m_s,above_3_m_s,normal_energy_per_second_w\n{}\n",
            rows.join("\n")
        ),
    )?;
    let histogram_rows: Vec<String> = report
        .classes
        .iter()
        .flat_map(|c| {
            c.densities
                .iter()
                .enumerate()
                .map(move |(k, d)| format!("{},{},{},{}", c.class, c.bin_edges_m_s[k], c.bin_edges_m_s[k + 1], d))
        })
        .collect();
    out.write_text(
        "mill_speed_histograms.csv",
        &format!("class,from_m_s,to_m_s,density_s_m\n{}\n", histogram_rows.join("\n")),
    )?;
    let class_series: Vec<(String, Vec<(f64, f64)>)> =
        report.classes.iter().map(|c| (c.class.clone(), steps(&c.bin_edges_m_s, &c.densities))).collect();
    let series: Vec<Series> = class_series
        .iter()
        .enumerate()
        .map(|(k, (label, points))| Series {
            label,
            points,
            color: SERIES_COLOURS[k % SERIES_COLOURS.len()],
            mark: Mark::Line,
        })
        .collect();
    let labels = Labels { title: "Impact normal speed per class", x: "v_n (m/s)", y: "density (s/m)" };
    line_chart(&out.file("mill_impact_speeds.svg"), labels, &series)?;

    let (cut, tolerance) = (report.warm_up.start_s, report.warm_up.tolerance_s);
    let median_rows: Vec<Vec<f64>> =
        report.median_series.iter().map(|&(t, m)| vec![t, m, f64::from(u8::from(t >= cut - tolerance))]).collect();
    out.write_csv("mill_median_speed.csv", &["time_s", "median_speed_m_s", "in_window"], &median_rows)?;
    let (lo, hi) =
        report.median_series.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), s| (l.min(s.1), h.max(s.1)));
    let cut_line = [(cut, lo), (cut, hi)];
    let labels = Labels { title: "Median speed and the warm-up cut", x: "t (s)", y: "median |v| (m/s)" };
    line_chart(
        &out.file("mill_median_speed.svg"),
        labels,
        &[
            Series { label: "median |v|", points: &report.median_series, color: SERIES_COLOURS[0], mark: Mark::Line },
            Series { label: "start of the window", points: &cut_line, color: SERIES_COLOURS[3], mark: Mark::Line },
        ],
    )?;
    if let Some(a) = &report.autocorrelation {
        let rows: Vec<Vec<f64>> = a.values.iter().enumerate().map(|(k, &r)| vec![k as f64 * a.interval_s, r]).collect();
        out.write_csv("mill_autocorrelation.csv", &["lag_s", "autocorrelation"], &rows)?;
        let points: Vec<(f64, f64)> = rows.iter().map(|r| (r[0], r[1])).collect();
        let labels = Labels { title: "Autocorrelation of the median speed", x: "lag (s)", y: "ρ" };
        line_chart(
            &out.file("mill_autocorrelation.svg"),
            labels,
            &[Series { label: "ρ", points: &points, color: SERIES_COLOURS[0], mark: Mark::Line }],
        )?;
    }
    if let Some(s) = &report.ball_speeds {
        let parts: Vec<(&str, &SpeedDistribution)> =
            [("all", Some(&s.all)), ("upper_outer", s.upper_outer.as_ref()), ("lower_outer", s.lower_outer.as_ref())]
                .into_iter()
                .filter_map(|(name, d)| Some((name, d?)))
                .collect();
        let rows: Vec<String> = parts
            .iter()
            .flat_map(|(name, d)| {
                let h = &d.histogram;
                h.densities
                    .iter()
                    .enumerate()
                    .map(move |(k, v)| format!("{name},{},{},{v}", h.bin_edges[k], h.bin_edges[k + 1]))
            })
            .collect();
        out.write_text("mill_ball_speeds.csv", &format!("part,from_m_s,to_m_s,density_s_m\n{}\n", rows.join("\n")))?;
        let lines: Vec<(&str, Vec<(f64, f64)>)> = parts
            .iter()
            .filter(|(_, d)| d.samples > 0)
            .map(|(name, d)| (*name, steps(&d.histogram.bin_edges, &d.histogram.densities)))
            .collect();
        let series: Vec<Series> = lines
            .iter()
            .enumerate()
            .map(|(k, (label, points))| Series { label, points, color: SERIES_COLOURS[k], mark: Mark::Line })
            .collect();
        let labels = Labels { title: "Ball speeds", x: "|v| (m/s)", y: "density (s/m)" };
        line_chart(&out.file("mill_ball_speeds.svg"), labels, &series)?;
    }
    if let Some(p) = &report.radial_profile {
        let rows: Vec<Vec<f64>> = p.rings.iter().map(|r| vec![r.from_m, r.to_m, r.share, r.area_share]).collect();
        out.write_csv("mill_radial_profile.csv", &["from_m", "to_m", "share", "area_share"], &rows)?;
        radial_profile_chart(&out.file("mill_radial_profile.svg"), p)?;
    }
    if let Some(c) = report.chamber.filter(|_| !report.sectors.is_empty()) {
        let rows: Vec<Vec<f64>> = report
            .sectors
            .iter()
            .map(|s| {
                vec![
                    s.ring as f64,
                    s.sector as f64,
                    s.radii_m[0],
                    s.radii_m[1],
                    s.angles_rad[0],
                    s.angles_rad[1],
                    s.ball_share,
                    s.mean_speed_m_s,
                    s.collisions as f64,
                    s.collisions_per_second,
                ]
            })
            .collect();
        out.write_csv(
            "mill_sectors.csv",
            &[
                "ring",
                "sector",
                "from_m",
                "to_m",
                "from_rad",
                "to_rad",
                "ball_share",
                "mean_speed_m_s",
                "collisions",
                "collisions_per_second",
            ],
            &rows,
        )?;
        let (centre, radius) = (DVec2::from(c.centre_m), c.radius_m);
        let cells = |value: fn(&SectorCell) -> f64| -> Vec<PolarCell> {
            report.sectors.iter().map(|s| (s.radii_m, s.angles_rad, value(s))).collect()
        };
        let speed = cells(|s| s.mean_speed_m_s);
        polar_cell_map(&out.file("mill_sector_speed.svg"), "Mean ball speed (m/s)", centre, radius, &speed)?;
        if report.collision_points_known {
            let rate = cells(|s| s.collisions_per_second);
            let title = "Collisions per second, where they began";
            polar_cell_map(&out.file("mill_sector_collisions.svg"), title, centre, radius, &rate)?;
        }
    }
    if let Some(s) = &report.stress_energy {
        let rows: Vec<Vec<f64>> = s
            .counts
            .iter()
            .enumerate()
            .map(|(k, &c)| vec![s.bin_edges_j[k], s.bin_edges_j[k + 1], c as f64, s.densities_per_decade[k]])
            .collect();
        out.write_csv("mill_stress_energy.csv", &["from_j", "to_j", "events", "density_per_decade"], &rows)?;
        let bars: Vec<(f64, f64, f64)> = (0..s.counts.len())
            .map(|k| (s.bin_edges_j[k].log10(), s.bin_edges_j[k + 1].log10(), s.densities_per_decade[k]))
            .collect();
        let labels = Labels { title: "Stress energy on ore", x: "log10 E (J)", y: "share per decade" };
        bar_chart(&out.file("mill_stress_energy.svg"), labels, &bars)?;
    }
    let json_path = out.file("mill.json");
    report.files = out.written().to_vec();
    let json = serde_json::to_string_pretty(&report)?;
    std::fs::write(&json_path, json).map_err(|source| AnalysisError::Io { path: json_path.clone(), source })?;
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn row_times_are_written_to_the_tolerance_without_their_round_off_tail() {
        assert_eq!(to_tolerance(0.03799999999988285, 3.5e-6), "0.038");
        assert_eq!(to_tolerance(0.98999999, 5e-4), "0.99");
        assert_eq!(to_tolerance(1.0, 5e-4), "1");
    }

    #[test]
    fn the_stress_energy_spectrum_has_log_bins_of_unit_area_per_decade() {
        // Four impacts spread over three decades and one without approach: 2 bins of 1.5 decades.
        let s = stress_energy_spectrum(vec![1e-6, 1e-5, 0.0, 1e-4, 1e-3], 2.0);
        assert_eq!((s.events, s.without_impact, s.counts.clone()), (4, 1, vec![2, 2]));
        assert!((s.bin_edges_j[1] / 10f64.powf(-4.5) - 1.0).abs() < 1e-12);
        assert!(s.densities_per_decade.iter().all(|d| (d - 0.5 / 1.5).abs() < 1e-12));
        assert!((s.energy_per_second_w - 1.111e-3 / 2.0).abs() < 1e-15);
        assert_eq!(s.per_second, 2.0);
        assert!((s.median_j - 5.5e-5).abs() < 1e-18);
    }
}
