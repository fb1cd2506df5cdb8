//! Collision statistics and the power balance of a ball-mill run (reference ballmill.md §7.6), from the run's
//! `events.csv` (`gc2d-rs run --events`), `timeseries.csv` and final checkpoint.
//!
//! Per collision class (ball–ball, ball–chamber, ball–blade, ball–hub, ball–wall for other walls): the number of
//! episodes that began in the averaging window, per second and per ball and second; the impact normal speeds'
//! mode, quartiles and the fractions above 0.5, 1 and 3 m/s; their histogram with √N bins, area-normalised; and
//! ΣE_n = Σ ½·m·v_n² per second with m the ball's mass (the thesis's grinding-intensity measure, (20-2)). Blade
//! hits per revolution. The power: the mean of the rotor's ω·τ and Σ F·v over the window's rows, the mean power the
//! walls put in and the mean dissipation from the ledger, and the median-speed series' mean and spread.

use crate::error::AnalysisError;
use crate::output::OutputDir;
use gc2d_engine::{BodyKind, ShapeKind, World};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;

/// Speeds whose share the report gives, m/s.
pub const SPEED_THRESHOLDS: [f64; 3] = [0.5, 1.0, 3.0];

/// Options of [`analyze_mill`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MillOptions {
    /// Start of the averaging window, s: episodes that begin earlier and rows before it are left out (the thesis
    /// discards 0.2 s of warm-up).
    pub warm_up_s: f64,
}

impl Default for MillOptions {
    fn default() -> Self {
        Self { warm_up_s: 0.2 }
    }
}

/// The statistics of one collision class.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CollisionClass {
    /// `ball–ball`, `ball–chamber`, `ball–blade`, `ball–hub` or `ball–wall`.
    pub class: String,
    /// Episodes that began in the window.
    pub collisions: usize,
    /// Per second.
    pub per_second: f64,
    /// Per ball and second.
    pub per_ball_per_second: f64,
    /// Centre of the fullest histogram bin, m/s.
    pub mode_m_s: f64,
    /// Quartiles of the impact normal speed, m/s.
    pub quartiles_m_s: [f64; 3],
    /// Shares of impacts faster than [`SPEED_THRESHOLDS`].
    pub fractions_above: [f64; 3],
    /// Σ ½·m·v_n² per second, W.
    pub normal_energy_per_second_w: f64,
    /// Histogram of the impact normal speed: bin edges, m/s (one more than the densities).
    pub bin_edges_m_s: Vec<f64>,
    /// Probability densities per bin, s/m (the histogram's area is 1).
    pub densities: Vec<f64>,
}

/// The rotor's power and the ledger's balance over the window.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MillPower {
    /// Mean of ω·τ over the window's rows, W.
    pub mean_power_torque_w: f64,
    /// Mean of Σ F·v over the window's rows, W.
    pub mean_power_work_w: f64,
    /// Work the walls put in over the window divided by its length, W (the ledger's).
    pub power_in_w: f64,
    /// Energy dissipated over the window divided by its length, W.
    pub dissipation_w: f64,
    /// (power in − dissipation)/power in.
    pub relative_imbalance: f64,
}

/// What [`analyze_mill`] computed, written as `mill.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MillReport {
    /// The averaging window, s.
    pub window_s: [f64; 2],
    /// Balls (particles) in the final state.
    pub balls: usize,
    /// Rotor revolutions in the window (from its angular velocity at the end).
    pub revolutions: f64,
    /// Blade hits per revolution.
    pub blade_hits_per_revolution: f64,
    /// Per collision class.
    pub classes: Vec<CollisionClass>,
    /// Power balance.
    pub power: MillPower,
    /// Mean and standard deviation of the median particle speed over the window's rows, m/s.
    pub median_speed_m_s: [f64; 2],
    /// The files written into the analysis directory.
    pub files: Vec<String>,
}

/// A CSV file read as columns by name.
struct Table {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Table {
    fn read(path: &Path) -> Result<Self, AnalysisError> {
        let text =
            std::fs::read_to_string(path).map_err(|source| AnalysisError::Io { path: path.to_path_buf(), source })?;
        let mut lines = text.lines();
        let header: Vec<String> = lines.next().unwrap_or_default().split(',').map(str::to_owned).collect();
        let rows =
            lines.map(|l| l.split(',').map(str::to_owned).collect::<Vec<_>>()).filter(|r| r.len() == header.len());
        Ok(Self { rows: rows.collect(), header })
    }

    /// The index of column `name`, or an error naming the file's kind.
    fn column(&self, name: &str, what: &str) -> Result<usize, AnalysisError> {
        self.header.iter().position(|h| h == name).ok_or_else(|| {
            AnalysisError::NotEnoughData(format!("{what} has no column `{name}` (written by another version?)"))
        })
    }
}

fn number(field: &str) -> f64 {
    field.parse().unwrap_or(f64::NAN)
}

/// The collision class of an episode between bodies `a` and `b` of the final World.
fn class_of(world: &World, a: usize, b: usize) -> &'static str {
    let bodies = world.bodies();
    let wall = [a, b].into_iter().find(|&i| bodies.kind[i] == BodyKind::Wall);
    match wall.map(|w| bodies.shape[w]) {
        None => "ball–ball",
        Some(ShapeKind::InnerCircle) => "ball–chamber",
        Some(ShapeKind::Capsule) => "ball–blade",
        Some(ShapeKind::Disk) => "ball–hub",
        Some(ShapeKind::Polygon) => "ball–wall",
    }
}

/// The `q`-quantile of sorted `values` by linear interpolation.
fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let position = q * (sorted.len() - 1) as f64;
    let (low, high) = (position.floor() as usize, position.ceil() as usize);
    sorted[low] + (sorted[high] - sorted[low]) * (position - low as f64)
}

/// The statistics of one class from its impact speeds and ΣE_n over the window of length `span` s.
fn class_report(class: &str, mut speeds: Vec<f64>, normal_energy: f64, span: f64, balls: usize) -> CollisionClass {
    speeds.sort_by(f64::total_cmp);
    let n = speeds.len();
    let bins = (n as f64).sqrt().ceil().max(1.0) as usize;
    let top = speeds.last().copied().unwrap_or(0.0).max(f64::MIN_POSITIVE);
    let width = top / bins as f64;
    let mut counts = vec![0usize; bins];
    for &v in &speeds {
        counts[((v / width) as usize).min(bins - 1)] += 1;
    }
    let densities: Vec<f64> = counts.iter().map(|&c| c as f64 / (n.max(1) as f64 * width)).collect();
    let fullest = counts.iter().enumerate().max_by_key(|&(k, &c)| (c, std::cmp::Reverse(k))).map_or(0, |(k, _)| k);
    CollisionClass {
        class: class.to_owned(),
        collisions: n,
        per_second: n as f64 / span,
        per_ball_per_second: n as f64 / span / balls.max(1) as f64,
        mode_m_s: (fullest as f64 + 0.5) * width,
        quartiles_m_s: [quantile(&speeds, 0.25), quantile(&speeds, 0.5), quantile(&speeds, 0.75)],
        fractions_above: SPEED_THRESHOLDS.map(|t| speeds.iter().filter(|&&v| v > t).count() as f64 / n.max(1) as f64),
        normal_energy_per_second_w: normal_energy / span,
        bin_edges_m_s: (0..=bins).map(|k| k as f64 * width).collect(),
        densities,
    }
}

/// Analyses the mill run in `run_dir` and writes `mill.json`, `mill_collisions.csv` and
/// `mill_speed_histograms.csv` into its `analysis/` directory.
pub fn analyze_mill(run_dir: &Path, options: &MillOptions) -> Result<MillReport, AnalysisError> {
    let checkpoint = run_dir.join("final.ckpt");
    let world = World::load_checkpoint_file(&checkpoint)
        .map_err(|source| AnalysisError::Checkpoint { path: checkpoint.clone(), source })?;
    let start = options.warm_up_s;
    let end = world.time();
    if !(start.is_finite() && start >= 0.0 && start < end) {
        return Err(AnalysisError::InvalidParameter(format!(
            "the warm-up {start} s must lie between 0 and the run's end, {end} s"
        )));
    }
    let span = end - start;
    let bodies = world.bodies();
    let balls = bodies.particles().count();

    let events_path = run_dir.join("events.csv");
    if !events_path.exists() {
        return Err(AnalysisError::NotEnoughData(format!(
            "{} is missing: run the scene with `gc2d-rs run --events`",
            events_path.display()
        )));
    }
    let events = Table::read(&events_path)?;
    let what = "events.csv";
    let (begin, a, b, speed) = (
        events.column("begin_time_s", what)?,
        events.column("a", what)?,
        events.column("b", what)?,
        events.column("impact_normal_speed_m_s", what)?,
    );
    let mut by_class: BTreeMap<&'static str, (Vec<f64>, f64)> = BTreeMap::new();
    for row in &events.rows {
        let (Ok(ia), Ok(ib)) = (row[a].parse::<usize>(), row[b].parse::<usize>()) else { continue };
        if number(&row[begin]) < start || ia.max(ib) >= bodies.len() {
            continue;
        }
        let v = number(&row[speed]).max(0.0);
        let ball = if bodies.kind[ia] == BodyKind::Particle { ia } else { ib };
        let entry = by_class.entry(class_of(&world, ia, ib)).or_default();
        entry.0.push(v);
        entry.1 += 0.5 * bodies.mass[ball] * v * v;
    }
    let classes: Vec<CollisionClass> = by_class
        .into_iter()
        .map(|(class, (speeds, energy))| class_report(class, speeds, energy, span, balls))
        .collect();

    let rotor_speed = (0..bodies.len())
        .filter(|&i| bodies.kind[i] == BodyKind::Wall)
        .map(|i| bodies.angular_velocity[i].abs())
        .fold(0.0, f64::max);
    let revolutions = rotor_speed * span / std::f64::consts::TAU;
    let blade_hits = classes.iter().find(|c| c.class == "ball–blade").map_or(0, |c| c.collisions);
    let blade_hits_per_revolution = if revolutions > 0.0 { blade_hits as f64 / revolutions } else { f64::NAN };

    let series = Table::read(&run_dir.join("timeseries.csv"))?;
    let what = "timeseries.csv";
    let time = series.column("time_s", what)?;
    let window: Vec<&Vec<String>> = series.rows.iter().filter(|r| number(&r[time]) >= start).collect();
    let (first, last) = match (window.first(), window.last()) {
        (Some(first), Some(last)) if window.len() >= 2 => (first, last),
        _ => return Err(AnalysisError::NotEnoughData("timeseries.csv has fewer than two rows in the window".into())),
    };
    let mean = |column: usize| window.iter().map(|r| number(&r[column])).sum::<f64>() / window.len() as f64;
    let change = |columns: &[usize]| {
        columns.iter().map(|&c| number(&last[c]) - number(&first[c])).sum::<f64>()
            / (number(&last[time]) - number(&first[time]))
    };
    let dissipation = [
        series.column("dissipated_normal_damping_j", what)?,
        series.column("dissipated_tangential_damping_j", what)?,
        series.column("dissipated_sliding_j", what)?,
    ];
    let power_in = change(&[series.column("work_in_j", what)?]);
    let dissipation_w = change(&dissipation);
    let power = MillPower {
        mean_power_torque_w: mean(series.column("rotor_power_torque_w", what)?),
        mean_power_work_w: mean(series.column("rotor_power_work_w", what)?),
        power_in_w: power_in,
        dissipation_w,
        relative_imbalance: (power_in - dissipation_w) / power_in,
    };
    let median_column = series.column("median_speed_m_s", what)?;
    let median_mean = mean(median_column);
    let median_spread = (window.iter().map(|r| (number(&r[median_column]) - median_mean).powi(2)).sum::<f64>()
        / window.len() as f64)
        .sqrt();

    let mut out = OutputDir::create(&run_dir.join("analysis"))?;
    let rows: Vec<String> = classes
        .iter()
        .map(|c| {
            format!(
                "{},{},{},{},{},{},{},{},{},{},{},{}",
                c.class,
                c.collisions,
                c.per_second,
                c.per_ball_per_second,
                c.mode_m_s,
                c.quartiles_m_s[0],
                c.quartiles_m_s[1],
                c.quartiles_m_s[2],
                c.fractions_above[0],
                c.fractions_above[1],
                c.fractions_above[2],
                c.normal_energy_per_second_w
            )
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
    let histogram_rows: Vec<String> = classes
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
    let json_path = out.file("mill.json");
    let mut report = MillReport {
        window_s: [start, end],
        balls,
        revolutions,
        blade_hits_per_revolution,
        classes,
        power,
        median_speed_m_s: [median_mean, median_spread],
        files: Vec::new(),
    };
    report.files = out.written().to_vec();
    let json = serde_json::to_string_pretty(&report)?;
    std::fs::write(&json_path, json).map_err(|source| AnalysisError::Io { path: json_path.clone(), source })?;
    Ok(report)
}
