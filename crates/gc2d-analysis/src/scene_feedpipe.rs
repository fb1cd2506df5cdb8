//! Conveying statistics of a feed-pipe run (issue 15 item 5; feedpipe.md §7.2), from the run's `transits.csv`,
//! `timeseries.csv`, `dumps/` (per-particle state) and `final.ckpt` (the scene's outlets and fluid).
//!
//! **The pipe's frame.** The flow direction is the first outlet's outward normal (the direction a particle crosses
//! it in); the cross-section runs along the outlet segment, from its `from` end (0) to its `to` end (its length),
//! widened over the other outlets on its line that face the same way (a top outlet given in parts). Profiles are
//! binned across that section, whatever the particle's position along the pipe; particles beside it are counted.
//!
//! **Window.** Averages start at the warm-up time: by default the first removal at an outlet (the pipe has filled);
//! they end at the run's last row. A removal or dump within half a time step of either end counts as inside.
//!
//! Outputs: per outlet the throughput over time (particles and kg per second, over a sliding window of
//! [`RATE_WINDOW_ROWS`] time-series rows) and its mean in the window; the transit-time distribution of the particles
//! that entered through an inlet (quantiles and a √N-bin histogram); and across the section, per bin, the particles'
//! concentration (time-averaged particles per metre of section), their mean velocity along the pipe, the fluid's
//! velocity along the pipe at the bin's centre (on the section halfway between the first inlet and the outlet) and at
//! the particles' centres, and the mean slip (particle minus fluid at its centre) along the pipe.

use crate::error::{AnalysisError, time_text};
use crate::figures::{Labels, Mark, SERIES_COLOURS, Series, bar_chart, line_chart};
use crate::mill_speeds::{Histogram, quantile};
use crate::output::OutputDir;
use crate::particle_state::ParticleState;
use crate::particle_state::csv::{DUMPS_DIR, dump_files, dump_warnings, read_csv};
use crate::table::{Table, number};
use gc2d_engine::World;
use gc2d_geometry::DVec2;
use serde::Serialize;
use std::path::Path;

/// Time-series rows the throughput is averaged over (a sliding window).
pub const RATE_WINDOW_ROWS: usize = 10;

/// Options of [`analyze_feedpipe`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FeedpipeOptions {
    /// Start of the averaging window, s. `None`: the first removal at an outlet.
    pub warm_up_s: Option<f64>,
    /// Bins across the section.
    pub bins: usize,
}

impl Default for FeedpipeOptions {
    fn default() -> Self {
        Self { warm_up_s: None, bins: 12 }
    }
}

/// One outlet's throughput.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OutletThroughput {
    /// The outlet's name.
    pub outlet: String,
    /// Particles it removed in the window, the count its rate is built from: those at or after the window's start,
    /// less the removal that opens a default window (it marks the start; N removals from it span N − 1 intervals).
    pub removed_in_window: usize,
    /// Particles it removed over the whole run, the window's warm-up included.
    pub removed_total: usize,
    /// Particles per second in the window: `removed_in_window` over the window's length. NaN (null in JSON) where a
    /// default window's opening removals are the only ones: one event marks a time, not a rate.
    pub particles_per_second: f64,
    /// Mass per second in the window, kg/s (kg/(m·s) per unit thickness); NaN (null) where the rate is.
    pub mass_per_second: f64,
}

/// The transit times of the particles that came through an inlet and left through an outlet in the window.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TransitTimes {
    /// How many.
    pub count: usize,
    /// Mean, s.
    pub mean_s: f64,
    /// 10 %, 50 % and 90 % quantiles, s.
    pub quantiles_s: [f64; 3],
    /// Shortest and longest, s.
    pub range_s: [f64; 2],
    /// Histogram bin edges, s.
    pub bin_edges_s: Vec<f64>,
    /// Probability densities per bin, 1/s.
    pub densities: Vec<f64>,
}

/// One bin across the section.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ProfileBin {
    /// Centre of the bin along the section, from the outlet's `from` end, m.
    pub position_m: f64,
    /// Particle samples (particles × dumps) in the bin.
    pub samples: usize,
    /// Time-averaged particles per metre of section.
    pub concentration_per_m: f64,
    /// The particles' mean velocity along the pipe, m/s (NaN for an empty bin).
    pub particle_velocity_m_s: f64,
    /// The fluid's velocity along the pipe at the bin's centre, on the section halfway between inlet and outlet, at
    /// the window's end, m/s.
    pub fluid_velocity_m_s: f64,
    /// The fluid's velocity along the pipe at the particles' centres, mean, m/s.
    pub fluid_at_particles_m_s: f64,
    /// Mean slip (particle minus fluid at its centre) along the pipe, m/s.
    pub slip_m_s: f64,
}

/// What `analyze --kind feedpipe` reports.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FeedpipeReport {
    /// The averaging window, s.
    pub window_s: [f64; 2],
    /// The flow direction (unit vector).
    pub flow_direction: [f64; 2],
    /// Per outlet.
    pub outlets: Vec<OutletThroughput>,
    /// Inlet-to-outlet transit times; `None` when no particle made the passage in the window.
    pub transit_times: Option<TransitTimes>,
    /// The section the profile spans, from its 0 end to its other end, m: the first outlet, widened over the outlets
    /// on its line that face the same way.
    pub section_m: [[f64; 2]; 2],
    /// The profile across the section.
    pub profile: Vec<ProfileBin>,
    /// Particle samples of the window's dumps beside the section (beyond its ends, across the pipe), which the
    /// profile leaves out; they count in the mean slip.
    pub samples_outside_section: usize,
    /// Mean slip over every particle sample in the window, along the pipe and across it, m/s.
    pub mean_slip_m_s: [f64; 2],
    /// Dumps in the window.
    pub dumps: usize,
    /// What the user should know before trusting the numbers: a window that could not start at the first removal,
    /// dumps the analysis cannot read or that are missing (also printed by `gc2d-rs analyze`).
    pub warnings: Vec<String>,
}

/// The pipe's frame: where the section starts, its unit direction and length, and the flow direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PipeFrame {
    /// The outlet's `from` end, m.
    pub origin: DVec2,
    /// Unit vector along the section (outlet `from` → `to`).
    pub across: DVec2,
    /// The section's length, m.
    pub width: f64,
    /// Unit flow direction (the outlet's outward normal).
    pub along: DVec2,
}

impl PipeFrame {
    /// The frame of outlet `from` → `to` (domain on the left).
    pub fn of_outlet(from: DVec2, to: DVec2) -> Self {
        let across = (to - from).normalize_or_zero();
        Self { origin: from, across, width: (to - from).length(), along: -across.perp() }
    }

    /// The frame widened over outlet `from` → `to` where it lies on the section's line and faces the same way (a top
    /// outlet given as two halves): the section then runs from the farther `from` end to the farther `to` end, the gap
    /// between the outlets included. Another outlet leaves the frame as it is.
    pub fn widened(self, from: DVec2, to: DVec2) -> Self {
        let scale = self.width.max((to - from).length());
        let on_line = [from, to].iter().all(|&p| (p - self.origin).dot(self.along).abs() <= 1e-9 * scale);
        if !on_line || (to - from).normalize_or_zero().dot(self.across) < 1.0 - 1e-9 {
            return self;
        }
        let ends = [0.0, self.width, self.section_coordinate(from), self.section_coordinate(to)];
        let (low, high) = ends.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &e| (l.min(e), h.max(e)));
        Self { origin: self.origin + self.across * low, width: high - low, ..self }
    }

    /// The section's ends, m: its `from` end (section coordinate 0) and its other end.
    pub fn ends(&self) -> [[f64; 2]; 2] {
        [self.origin.to_array(), (self.origin + self.across * self.width).to_array()]
    }

    /// The position of `p` along the section, m (0 at the outlet's `from` end).
    pub fn section_coordinate(&self, p: DVec2) -> f64 {
        (p - self.origin).dot(self.across)
    }
}

/// Per-bin sums of the particle samples of the dumps, for [`profile`].
#[derive(Debug, Clone, Default)]
struct BinSums {
    samples: usize,
    particle_velocity: f64,
    fluid_velocity: f64,
}

/// Most bins a profile across the pipe may have: far more than the particles across any pipe, and few enough that
/// a mistyped count does not ask for terabytes.
pub const MAX_BINS: usize = 10_000;

/// The profile across the section of `frame`, in `bins` bins, from the particle samples of `dumps` (each dump a list
/// of particle states at one time) with the fluid velocity `fluid(x, t)`; `fluid_at_bin(s)` gives the fluid's velocity
/// along the pipe at section coordinate s for the fluid-profile column. Also returns the mean slip along and across
/// the pipe over every sample, and the number of samples beside the section (left out of the bins).
pub fn profile(
    frame: &PipeFrame,
    bins: usize,
    dumps: &[Vec<ParticleState>],
    fluid: &dyn Fn(DVec2, f64) -> DVec2,
    fluid_at_bin: &dyn Fn(f64) -> f64,
) -> (Vec<ProfileBin>, [f64; 2], usize) {
    let width = frame.width / bins as f64;
    let mut sums = vec![BinSums::default(); bins];
    let (mut slip_sum, mut samples, mut outside) = (DVec2::ZERO, 0usize, 0usize);
    for dump in dumps {
        for p in dump {
            let x = DVec2::new(p.x_m, p.y_m);
            let v = DVec2::new(p.vx_m_s, p.vy_m_s);
            let u = fluid(x, p.time_s);
            slip_sum += v - u;
            samples += 1;
            let s = frame.section_coordinate(x);
            let k = (s / width).floor();
            if !(k >= 0.0 && (k as usize) < bins) {
                outside += 1;
                continue;
            }
            let bin = &mut sums[k as usize];
            bin.samples += 1;
            bin.particle_velocity += v.dot(frame.along);
            bin.fluid_velocity += u.dot(frame.along);
        }
    }
    let count = dumps.len().max(1) as f64;
    let profile = sums
        .iter()
        .enumerate()
        .map(|(k, b)| {
            let n = b.samples as f64;
            let mean = |sum: f64| if b.samples == 0 { f64::NAN } else { sum / n };
            let position_m = (k as f64 + 0.5) * width;
            ProfileBin {
                position_m,
                samples: b.samples,
                concentration_per_m: n / count / width,
                particle_velocity_m_s: mean(b.particle_velocity),
                fluid_velocity_m_s: fluid_at_bin(position_m),
                fluid_at_particles_m_s: mean(b.fluid_velocity),
                slip_m_s: mean(b.particle_velocity - b.fluid_velocity),
            }
        })
        .collect();
    let mean_slip = if samples == 0 { DVec2::NAN } else { slip_sum / samples as f64 };
    (profile, [mean_slip.dot(frame.along), mean_slip.dot(frame.across)], outside)
}

/// The transit-time statistics of `times` (s); `None` for none.
pub fn transit_times(mut times: Vec<f64>) -> Option<TransitTimes> {
    if times.is_empty() {
        return None;
    }
    times.sort_by(f64::total_cmp);
    let histogram = Histogram::of(&times);
    Some(TransitTimes {
        count: times.len(),
        mean_s: times.iter().sum::<f64>() / times.len() as f64,
        quantiles_s: [quantile(&times, 0.1), quantile(&times, 0.5), quantile(&times, 0.9)],
        range_s: [times[0], times[times.len() - 1]],
        bin_edges_s: histogram.bin_edges,
        densities: histogram.densities,
    })
}

/// A passage read from `transits.csv`.
struct Passage {
    outlet: String,
    left_s: f64,
    transit_time_s: f64,
    mass: f64,
}

/// The passages of `transits.csv` at `path` of the run whose final state is `world`, read strictly: every row must be
/// one the run could have written, or it is damage named by its line (a field that must be a number and is not, an
/// outlet or inlet the run does not have, a particle listed twice, a time outside the run or an entry after the exit,
/// a transit time that is not the exit less the entry, a mass that is not positive). The inlet, entry and transit
/// time are empty for a particle that did not come through an inlet (transit time NaN here).
fn read_transits(path: &Path, world: &World) -> Result<Vec<Passage>, AnalysisError> {
    if !path.exists() {
        return Err(AnalysisError::NotEnoughData(format!(
            "{} is missing: it is written by runs of scenes with outlets",
            path.display()
        )));
    }
    let table = Table::read(path)?;
    let what = "transits.csv";
    let column = |name: &str| table.column(name, what);
    let (particle, inlet, entered, outlet) =
        (column("particle")?, column("inlet")?, column("entered_s")?, column("outlet")?);
    let (left, transit, mass) = (column("left_s")?, column("transit_time_s")?, column("mass_kg")?);
    let outlets: Vec<&str> = world.outlets().iter().map(|o| o.outlet().name.as_str()).collect();
    let inlets: Vec<&str> = world.inlets().iter().map(|i| i.inlet().name.as_str()).collect();
    let end = world.time() + 0.5 * world.time_step();
    let mut seen = std::collections::HashSet::new();
    let mut passages = Vec::with_capacity(table.rows.len());
    for (k, r) in table.rows.iter().enumerate() {
        let damaged = |what: String| Err(table.damaged(k, &what));
        if !outlets.contains(&r[outlet].as_str()) {
            return damaged(format!("outlet `{}` is not one of the run's outlets ({})", r[outlet], outlets.join(", ")));
        }
        let id = table.number(k, particle)?;
        if !seen.insert(id.to_bits()) {
            return damaged(format!("particle {id} leaves twice"));
        }
        let left_s = table.number(k, left)?;
        if !(0.0..=end).contains(&left_s) {
            return damaged(format!("a particle leaves at {left_s} s, outside the run (0 to {} s)", world.time()));
        }
        let mass_kg = table.number(k, mass)?;
        if !(mass_kg > 0.0 && mass_kg.is_finite()) {
            return damaged(format!("a mass of {mass_kg} kg"));
        }
        let transit_time_s = if r[inlet].is_empty() && r[entered].is_empty() && r[transit].is_empty() {
            f64::NAN
        } else {
            if !inlets.contains(&r[inlet].as_str()) {
                return damaged(format!("inlet `{}` is not one of the run's inlets ({})", r[inlet], inlets.join(", ")));
            }
            let (entered_s, transit_s) = (table.number(k, entered)?, table.number(k, transit)?);
            if !(0.0..=left_s).contains(&entered_s) {
                return damaged(format!("a particle enters at {entered_s} s and leaves at {left_s} s"));
            }
            // The run writes the difference of the two times it writes, each to every digit.
            if (transit_s - (left_s - entered_s)).abs() > 1e-9 * left_s.max(1e-9) {
                return damaged(format!("a transit time of {transit_s} s between {entered_s} s and {left_s} s"));
            }
            transit_s
        };
        passages.push(Passage { outlet: r[outlet].clone(), left_s, transit_time_s, mass: mass_kg });
    }
    Ok(passages)
}

/// The statistics of the feed-pipe run in `run_dir`, without writing anything.
pub fn feedpipe_report(
    run_dir: &Path,
    options: &FeedpipeOptions,
) -> Result<(FeedpipeReport, Vec<RateSeries>), AnalysisError> {
    if !(1..=MAX_BINS).contains(&options.bins) {
        return Err(AnalysisError::InvalidParameter(format!(
            "{} bins: the profiles take 1 to {MAX_BINS} bins across the pipe",
            options.bins
        )));
    }
    let checkpoint = run_dir.join("final.ckpt");
    let world = World::load_checkpoint_file(&checkpoint)
        .map_err(|source| AnalysisError::Checkpoint { path: checkpoint.clone(), source })?;
    let first_outlet = world.outlets().first().ok_or_else(|| {
        AnalysisError::NotEnoughData("the run's scene has no outlet: a feed-pipe analysis needs one".into())
    })?;
    let frame = world
        .outlets()
        .iter()
        .fold(PipeFrame::of_outlet(first_outlet.outlet().from, first_outlet.outlet().to), |frame, state| {
            frame.widened(state.outlet().from, state.outlet().to)
        });
    let transits_path = run_dir.join("transits.csv");
    let passages = read_transits(&transits_path, &world)?;
    // Each outlet's rows against its own count in the final state: rows lost or added (a file edited, or of another
    // run) would change the throughput without a word.
    for state in world.outlets() {
        let name = state.outlet().name.as_str();
        let rows = passages.iter().filter(|p| p.outlet == name).count() as u64;
        if rows != state.counters().removed {
            return Err(AnalysisError::DamagedFile(format!(
                "{} has {rows} passages through outlet `{name}`, and the run's final state counts {} (the file is \
                 damaged, or of another run)",
                transits_path.display(),
                state.counters().removed
            )));
        }
    }
    let series = Table::read(&run_dir.join("timeseries.csv"))?;
    let time = series.column("time_s", "timeseries.csv")?;
    let times: Vec<f64> = series.rows.iter().map(|r| number(&r[time])).collect();
    let end = times.last().copied().unwrap_or(world.time());
    let first_removal = passages.iter().map(|p| p.left_s).fold(f64::INFINITY, f64::min);
    let start = options.warm_up_s.unwrap_or(if first_removal.is_finite() { first_removal } else { 0.0 });
    let mut warnings = Vec::new();
    if options.warm_up_s.is_none() && !first_removal.is_finite() {
        warnings.push(
            "no particle has left through an outlet yet (transits.csv has no passage), so the window cannot start at \
             the first removal, as it does by default: it falls back to the whole run (window_s from 0 s), while the \
             pipe is still filling (give --warm-up T to choose the window)"
                .into(),
        );
    }
    if options.warm_up_s.is_some() && !(start.is_finite() && start >= 0.0 && start < end) {
        return Err(AnalysisError::InvalidParameter(format!(
            "the warm-up {start} s must lie between 0 and the run's end, {} s",
            time_text(end)
        )));
    }
    if start >= end {
        return Err(AnalysisError::NotEnoughData(format!(
            "the window starts at {} s, after the run's end {} s",
            time_text(start),
            time_text(end)
        )));
    }
    // A removal or dump within half a step of an end of the window counts as at it: their times are sums of steps, a
    // hair off the multiples of the frame interval (and the `--warm-up`) they stand for.
    let slack = 0.5 * world.time_step();
    let in_window = |t: f64| t >= start - slack && t <= end + slack;
    // Where the first removal opens the window, it marks the window's start and is not one of its counts: N removals
    // at and after it span N − 1 intervals, and N/T overestimated the rate of a short window.
    let counted = |t: f64| in_window(t) && (options.warm_up_s.is_some() || t > start);
    let duration = end - start;
    // A default window opened by the only removals has no interval to measure a rate over: null, with a warning.
    let opened_only =
        options.warm_up_s.is_none() && first_removal.is_finite() && !passages.iter().any(|p| counted(p.left_s));
    let rate = |sum: f64| if opened_only { f64::NAN } else { sum / duration };
    if opened_only {
        warnings.push(opening_removals_only(passages.len(), start));
    }

    let mut outlets = Vec::new();
    let mut rates = Vec::new();
    for state in world.outlets() {
        let name = &state.outlet().name;
        let mine: Vec<&Passage> = passages.iter().filter(|p| &p.outlet == name).collect();
        let windowed: Vec<&&Passage> = mine.iter().filter(|p| counted(p.left_s)).collect();
        outlets.push(OutletThroughput {
            outlet: name.clone(),
            removed_in_window: windowed.len(),
            removed_total: mine.len(),
            particles_per_second: rate(windowed.len() as f64),
            // A fold from +0 (a float sum starts from −0, which an empty window kept and feedpipe.json showed).
            mass_per_second: rate(windowed.iter().fold(0.0, |sum, p| sum + p.mass)),
        });
        let column = series.column(&format!("outlet_{name}_removed"), "timeseries.csv")?;
        let removed: Vec<f64> = series.rows.iter().map(|r| number(&r[column])).collect();
        rates.push(RateSeries { outlet: name.clone(), points: sliding_rate(&times, &removed, RATE_WINDOW_ROWS) });
    }

    let transit = transit_times(
        passages
            .iter()
            .filter(|p| in_window(p.left_s) && p.transit_time_s.is_finite())
            .map(|p| p.transit_time_s)
            .collect(),
    );

    let (mut dumps, mut indices) = (Vec::new(), Vec::new());
    for (index, path) in dump_files(&run_dir.join(DUMPS_DIR))? {
        let states = read_csv(&path)?;
        if states.first().is_some_and(|s| in_window(s.time_s)) {
            dumps.push(states);
            indices.push(index);
        }
    }
    warnings.extend(dump_warnings(&run_dir.join(DUMPS_DIR), &indices)?);
    let fluid = world.fluid();
    let fluid_at = |x: DVec2, t: f64| fluid.and_then(|f| f.field.velocity(x, t).ok()).unwrap_or(DVec2::NAN);
    // The section halfway between the first inlet's midpoint and the outlet, for the fluid profile.
    let middle_shift = world
        .inlets()
        .first()
        .map_or(0.0, |i| (0.5 * (i.inlet().from + i.inlet().to) - frame.origin).dot(frame.along) * 0.5);
    let fluid_at_bin =
        |s: f64| fluid_at(frame.origin + frame.across * s + frame.along * middle_shift, end).dot(frame.along);
    let (profile, mean_slip_m_s, samples_outside_section) =
        profile(&frame, options.bins, &dumps, &fluid_at, &fluid_at_bin);
    let report = FeedpipeReport {
        window_s: [start, end],
        // Adding +0 turns a component of −0 (a turned unit vector's) into 0 for the JSON.
        flow_direction: (frame.along + DVec2::ZERO).to_array(),
        outlets,
        transit_times: transit,
        section_m: frame.ends(),
        profile,
        samples_outside_section,
        mean_slip_m_s,
        dumps: dumps.len(),
        warnings,
    };
    Ok((report, rates))
}

/// The warning for a default window whose opening removals (`removed` of them, all at `start` s) are the run's only
/// ones: they mark the window's start and are not counted, so no rate is measured.
fn opening_removals_only(removed: usize, start: f64) -> String {
    let opens = "the window (a default window starts at the first removal)";
    let start = time_text(start);
    let who = match removed {
        1 => format!("only one particle has left through an outlet, at {start} s: its removal opens {opens} and is"),
        n => format!(
            "all {n} particles that have left through an outlet left at {start} s: their removals open {opens} and are"
        ),
    };
    format!(
        "{who} not counted, so the throughput is not measured (particles_per_second and mass_per_second are null): \
         run longer, or give --warm-up T (every removal in a window given so counts)"
    )
}

/// An outlet's removal rate over time.
#[derive(Debug, Clone, PartialEq)]
pub struct RateSeries {
    /// The outlet's name.
    pub outlet: String,
    /// (time at the window's end, particles per second over the window).
    pub points: Vec<(f64, f64)>,
}

/// The rate of a cumulative count over a sliding window of `rows` rows: (t_k, (c_k − c_{k−rows})/(t_k − t_{k−rows})).
pub fn sliding_rate(times: &[f64], counts: &[f64], rows: usize) -> Vec<(f64, f64)> {
    (rows..times.len().min(counts.len()))
        .map(|k| (times[k], (counts[k] - counts[k - rows]) / (times[k] - times[k - rows])))
        .collect()
}

/// Runs [`feedpipe_report`] and writes its tables and figures into `<run_dir>/analysis/`.
pub fn analyze_feedpipe(run_dir: &Path, options: &FeedpipeOptions) -> Result<FeedpipeReport, AnalysisError> {
    let (report, rates) = feedpipe_report(run_dir, options)?;
    let mut out = OutputDir::create(&run_dir.join("analysis"))?;
    let throughput_rows: Vec<String> =
        rates.iter().flat_map(|r| r.points.iter().map(move |(t, rate)| format!("{},{t},{rate}", r.outlet))).collect();
    out.write_text(
        "feedpipe_throughput.csv",
        &format!("outlet,time_s,particles_per_second\n{}\n", throughput_rows.join("\n")),
    )?;
    let series: Vec<Series> = rates
        .iter()
        .enumerate()
        .map(|(k, r)| Series {
            label: &r.outlet,
            points: &r.points,
            color: SERIES_COLOURS[k % SERIES_COLOURS.len()],
            mark: Mark::Line,
        })
        .collect();
    let labels = Labels { title: "Throughput per outlet", x: "t (s)", y: "particles per second" };
    line_chart(&out.file("feedpipe_throughput.svg"), labels, &series)?;

    if let Some(t) = &report.transit_times {
        let rows: Vec<Vec<f64>> =
            t.densities.iter().enumerate().map(|(k, d)| vec![t.bin_edges_s[k], t.bin_edges_s[k + 1], *d]).collect();
        out.write_csv("feedpipe_transit_times.csv", &["from_s", "to_s", "density_1_s"], &rows)?;
        let bars: Vec<(f64, f64, f64)> = rows.iter().map(|r| (r[0], r[1], r[2])).collect();
        let labels = Labels { title: "Transit time, inlet to outlet", x: "transit time (s)", y: "density (1/s)" };
        bar_chart(&out.file("feedpipe_transit_times.svg"), labels, &bars)?;
    }

    let rows: Vec<Vec<f64>> = report
        .profile
        .iter()
        .map(|b| {
            vec![
                b.position_m,
                b.samples as f64,
                b.concentration_per_m,
                b.particle_velocity_m_s,
                b.fluid_velocity_m_s,
                b.fluid_at_particles_m_s,
                b.slip_m_s,
            ]
        })
        .collect();
    out.write_csv(
        "feedpipe_profile.csv",
        &[
            "position_m",
            "samples",
            "concentration_per_m",
            "particle_velocity_m_s",
            "fluid_velocity_m_s",
            "fluid_at_particles_m_s",
            "slip_m_s",
        ],
        &rows,
    )?;
    let column = |k: usize| -> Vec<(f64, f64)> { rows.iter().map(|r| (r[0], r[k])).collect() };
    let (particles, fluid, slip) = (column(3), column(4), column(6));
    let velocity_series = [
        Series { label: "particles", points: &particles, color: SERIES_COLOURS[0], mark: Mark::Dots },
        Series { label: "fluid", points: &fluid, color: SERIES_COLOURS[1], mark: Mark::Line },
        Series { label: "slip (particle − fluid at it)", points: &slip, color: SERIES_COLOURS[2], mark: Mark::Dots },
    ];
    let labels =
        Labels { title: "Velocity along the pipe across the section", x: "position across (m)", y: "velocity (m/s)" };
    line_chart(&out.file("feedpipe_velocity_profile.svg"), labels, &velocity_series)?;
    let concentration = column(2);
    let labels = Labels { title: "Concentration across the section", x: "position across (m)", y: "particles per m" };
    let concentration_series =
        [Series { label: "particles", points: &concentration, color: SERIES_COLOURS[0], mark: Mark::Line }];
    line_chart(&out.file("feedpipe_concentration.svg"), labels, &concentration_series)?;
    out.write_text("feedpipe.json", &serde_json::to_string_pretty(&report)?)?;
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::particle_state::ParticleShape;

    fn at(time_s: f64, x: f64, y: f64, vx: f64, vy: f64) -> ParticleState {
        ParticleState {
            time_s,
            id: 0,
            material: "m".into(),
            shape: ParticleShape::Disk,
            x_m: x,
            y_m: y,
            phi_rad: 0.0,
            vx_m_s: vx,
            vy_m_s: vy,
            omega_rad_s: 0.0,
            fx_n: 0.0,
            fy_n: 0.0,
            torque_n_m: 0.0,
            contacts: 0,
        }
    }

    #[test]
    fn a_synthetic_dump_gives_the_hand_computed_profile() {
        // An outlet across y = 1 from x = 0.1 to x = −0.1 (domain below): flow +y, section from x = 0.1 towards −x.
        let frame = PipeFrame::of_outlet(DVec2::new(0.1, 1.0), DVec2::new(-0.1, 1.0));
        assert_eq!(frame.along, DVec2::Y);
        assert!((frame.width - 0.2).abs() < 1e-15);
        // Two dumps; in bin 0 (x from 0.1 to 0) one particle at 2 m/s and one at 4 m/s; in bin 1 one at 1 m/s in
        // the first dump only. Fluid: u_y = 10·x + 5.
        let dumps =
            vec![vec![at(0.0, 0.05, 0.3, 0.0, 2.0), at(0.0, -0.05, 0.5, 0.0, 1.0)], vec![at(1.0, 0.02, 0.6, 0.5, 4.0)]];
        let fluid = |x: DVec2, _t: f64| DVec2::new(0.0, 10.0 * x.x + 5.0);
        let (bins, mean_slip, outside) = profile(&frame, 2, &dumps, &fluid, &|s: f64| 10.0 * (0.1 - s) + 5.0);
        assert_eq!((bins[0].samples, bins[1].samples, outside), (2, 1, 0));
        assert!((bins[0].concentration_per_m - 2.0 / 2.0 / 0.1).abs() < 1e-12);
        assert!((bins[1].concentration_per_m - 1.0 / 2.0 / 0.1).abs() < 1e-12);
        assert!((bins[0].particle_velocity_m_s - 3.0).abs() < 1e-12);
        assert!((bins[0].fluid_at_particles_m_s - 0.5 * (5.5 + 5.2)).abs() < 1e-12);
        assert!((bins[0].slip_m_s - (3.0 - 5.35)).abs() < 1e-12);
        assert!((bins[1].slip_m_s - (1.0 - 4.5)).abs() < 1e-12);
        assert!((bins[0].fluid_velocity_m_s - (10.0 * 0.05 + 5.0)).abs() < 1e-12);
        // Mean slip over the three samples: along (2 − 5.5 + 1 − 4.5 + 4 − 5.2)/3; across (section runs along −x):
        // −(0 + 0 + 0.5)/3.
        assert!((mean_slip[0] - (2.0 - 5.5 + 1.0 - 4.5 + 4.0 - 5.2) / 3.0).abs() < 1e-12);
        assert!((mean_slip[1] + 0.5 / 3.0).abs() < 1e-12);
    }

    /// QA P2-4: a top outlet given as two halves took the section from the first half only, and the profile dropped
    /// the particles beside it without a word.
    #[test]
    fn the_section_spans_the_outlets_on_its_line_and_counts_the_samples_beside_it() {
        let (right, middle, left) = (DVec2::new(0.03, 1.0), DVec2::new(0.0, 1.0), DVec2::new(-0.03, 1.0));
        let whole = PipeFrame::of_outlet(right, left);
        let halves = PipeFrame::of_outlet(right, middle).widened(middle, left);
        assert_eq!((halves.origin, halves.across, halves.along), (whole.origin, whole.across, whole.along));
        assert!((halves.width - 0.06).abs() < 1e-15);
        // Given the other way round, the section runs from the farther `from` end all the same.
        let reversed = PipeFrame::of_outlet(middle, left).widened(right, middle);
        assert_eq!((reversed.origin, reversed.width), (halves.origin, halves.width));
        // An outlet off the line, or across it the other way (a bottom outlet), leaves the section as it is.
        let first = PipeFrame::of_outlet(right, middle);
        for (from, to) in [(DVec2::new(0.0, 0.0), DVec2::new(-0.03, 0.0)), (left, middle)] {
            assert_eq!(first.widened(from, to), first);
        }
        // On the first half only, the particle at x = −0.015 lies beside the section: counted, not binned.
        let dumps = vec![vec![at(0.0, 0.015, 0.5, 0.0, 1.0), at(0.0, -0.015, 0.5, 0.0, 3.0)]];
        let fluid = |_: DVec2, _: f64| DVec2::ZERO;
        let (bins, slip, outside) = profile(&first, 1, &dumps, &fluid, &|_| 0.0);
        assert_eq!((bins[0].samples, bins[0].particle_velocity_m_s, outside, slip[0]), (1, 1.0, 1, 2.0));
        let (bins, _, outside) = profile(&halves, 2, &dumps, &fluid, &|_| 0.0);
        let binned: Vec<(usize, f64)> = bins.iter().map(|b| (b.samples, b.particle_velocity_m_s)).collect();
        assert_eq!((binned, outside), (vec![(1, 1.0), (1, 3.0)], 0));
    }

    /// QA #20: removals that all open the default window are named, one or several.
    #[test]
    fn the_warning_for_opening_removals_only_names_them() {
        let one = opening_removals_only(1, 0.5);
        assert!(one.starts_with("only one particle has left through an outlet, at 0.5 s: its removal opens"), "{one}");
        assert!(one.contains("and is not counted, so the throughput is not measured"), "{one}");
        let three = opening_removals_only(3, 0.5);
        assert!(three.starts_with("all 3 particles that have left through an outlet left at 0.5 s"), "{three}");
        assert!(three.contains("their removals open the window") && three.contains("and are not counted"), "{three}");
    }

    #[test]
    fn rates_and_transit_quantiles_follow_their_definitions() {
        let rates = sliding_rate(&[0.0, 0.1, 0.2, 0.3], &[0.0, 1.0, 3.0, 6.0], 2);
        assert_eq!(rates.len(), 2);
        for ((t, rate), (t_expected, expected)) in rates.into_iter().zip([(0.2, 15.0), (0.3, 25.0)]) {
            assert_eq!(t, t_expected);
            assert!((rate - expected).abs() < 1e-12, "{rate} against {expected}");
        }
        let t = transit_times(vec![3.0, 1.0, 2.0, 4.0, 5.0]).unwrap();
        assert_eq!((t.count, t.mean_s, t.range_s), (5, 3.0, [1.0, 5.0]));
        assert!((t.quantiles_s[1] - 3.0).abs() < 1e-12 && (t.quantiles_s[0] - 1.4).abs() < 1e-12);
        let area: f64 = t.densities.iter().zip(t.bin_edges_s.windows(2)).map(|(d, e)| d * (e[1] - e[0])).sum();
        assert!((area - 1.0).abs() < 1e-12);
        assert!(transit_times(Vec::new()).is_none());
    }
}
