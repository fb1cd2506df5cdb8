//! The scene-type analyses of a finished run, as `gc2d-rs analyze --kind …` and a sweep's collection run them: one
//! name per kind, the file each writes, and one call that runs it.

use crate::outputs::{SCENE_COPY, run_scene};
use clap::ValueEnum;
use gc2d_analysis::{
    AnalysisError, AnalyzeOptions, BallIds, FeedpipeOptions, FeedpipeReport, MillOptions, Report, SceneKind,
    analyze_feedpipe, analyze_mill, analyze_run,
};
use gc2d_engine::World;
use gc2d_scene::Scene;
use serde::Deserialize;
use std::path::Path;

/// What a run is, for its analysis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Deserialize)]
pub enum AnalysisKind {
    /// A mill or a feed pipe by the run's scene, else a pile or a silo by the wall forces.
    Auto,
    /// A free heap on a floor.
    Pile,
    /// A column between side walls.
    Silo,
    /// A ball mill: collision statistics from events.csv and the power balance (run it with --events).
    Mill,
    /// A feed pipe: throughput, transit times and profiles across the pipe from transits.csv and the dumps.
    Feedpipe,
}

impl AnalysisKind {
    /// Its name on the command line (`pile`, `feedpipe`), as clap derives it.
    pub fn name(self) -> String {
        self.to_possible_value().map(|value| value.get_name().to_owned()).unwrap_or_default()
    }

    /// The report the analysis writes into the run directory: `analysis/analysis.json` for piles and silos,
    /// `analysis/mill.json`, `analysis/feedpipe.json`.
    pub fn report_file(self) -> &'static str {
        match self {
            AnalysisKind::Auto | AnalysisKind::Pile | AnalysisKind::Silo => "analysis/analysis.json",
            AnalysisKind::Mill => "analysis/mill.json",
            AnalysisKind::Feedpipe => "analysis/feedpipe.json",
        }
    }
}

/// The analysis `--kind auto` stands for in `run_dir`: the mill's where the run's `scene.ron` has a mill, the feed
/// pipe's where it has outlets, else `Auto` itself (the pile and silo analyses, which decide from the wall forces).
/// Without a readable `scene.ron`, `Auto`. Given kinds are kept. A mill run analysed as a pile gave a heap's numbers.
pub fn resolved_kind(run_dir: &Path, kind: AnalysisKind) -> AnalysisKind {
    if kind != AnalysisKind::Auto {
        return kind;
    }
    match Scene::from_path(run_dir.join(SCENE_COPY)) {
        Ok(scene) if scene.mill.is_some() => AnalysisKind::Mill,
        Ok(scene) if !scene.outlets.is_empty() => AnalysisKind::Feedpipe,
        _ => AnalysisKind::Auto,
    }
}

/// The settings of the analyses; each applies to the kinds its doc names, `None` chooses from the data.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AnalysisSettings {
    /// Pile and silo: half-width of the pressure window, m.
    pub window_half_width_m: Option<f64>,
    /// Pile and silo: cell size of the density and stress grids, m.
    pub grid_cell_m: Option<f64>,
    /// Mill and feed pipe: the warm-up left out of the averages, s.
    pub warm_up_s: Option<f64>,
    /// Feed pipe: bins across the pipe's section for the profiles.
    pub bins: usize,
}

/// Feed pipe profile bins when none are asked for.
pub const DEFAULT_BINS: usize = 12;

impl AnalysisSettings {
    /// Every setting chosen from the data, [`DEFAULT_BINS`] bins.
    pub fn automatic() -> AnalysisSettings {
        AnalysisSettings { bins: DEFAULT_BINS, ..AnalysisSettings::default() }
    }
}

/// What [`analyze`] returns: the report, and what the user should know before trusting it.
#[derive(Debug, Clone, PartialEq)]
pub struct AnalysisOutput {
    /// The report as pretty-printed JSON (in the report's field order).
    pub json: String,
    /// Why the numbers may mean little: a run that did not complete, a pile most of whose particles are not in it.
    pub warnings: Vec<String>,
}

/// Runs the `kind` analysis of the finished run in `run_dir`, which writes its tables, figures and
/// [`AnalysisKind::report_file`] there, and returns the report with its warnings.
pub fn analyze(run_dir: &Path, kind: AnalysisKind, settings: &AnalysisSettings) -> Result<AnalysisOutput, String> {
    let mut warnings: Vec<String> = unfinished_run(run_dir).into_iter().collect();
    let failed = |e: AnalysisError| e.to_string();
    let json = match kind {
        AnalysisKind::Mill => {
            let (balls, warning) = mill_balls(run_dir);
            warnings.extend(warning);
            let options = MillOptions { warm_up_s: settings.warm_up_s, balls };
            let report = analyze_mill(run_dir, &options).map_err(failed)?;
            warnings.extend(report.warnings.iter().cloned());
            serde_json::to_string_pretty(&report)
        }
        AnalysisKind::Feedpipe => {
            let options = FeedpipeOptions { warm_up_s: settings.warm_up_s, bins: settings.bins };
            let report = analyze_feedpipe(run_dir, &options).map_err(failed)?;
            warnings.extend(report.warnings.iter().cloned());
            warnings.extend(beside_the_section(&report));
            serde_json::to_string_pretty(&report)
        }
        AnalysisKind::Auto | AnalysisKind::Pile | AnalysisKind::Silo => {
            let scene = match kind {
                AnalysisKind::Pile => SceneKind::Pile,
                AnalysisKind::Silo => SceneKind::Silo,
                _ => SceneKind::Auto,
            };
            let options = AnalyzeOptions {
                scene,
                window_half_width: settings.window_half_width_m,
                grid_cell: settings.grid_cell_m,
            };
            let report = analyze_run(run_dir, &options).map_err(failed)?;
            warnings.extend(pile_not_formed(&report));
            if let Some(silo) = &report.silo {
                warnings.extend(silo.warnings.iter().cloned());
                warnings.extend(not_a_silo(silo.k));
            }
            warnings.extend(settings.grid_cell_m.and_then(|cell| coarser_grid(&report, cell)));
            serde_json::to_string_pretty(&report)
        }
    };
    Ok(AnalysisOutput { json: json.map_err(|e| e.to_string())?, warnings })
}

/// The balls of the mill run in `run_dir`: the bodies its `scene.ron` builds from `mill.balls`, so that ore grains
/// drawn as disks are not taken for balls. Where the scene is missing, unreadable, does not build or is not the scene
/// of the run's `final.ckpt` (edited, or copied from another run), the disk particles, with a warning that says why.
pub fn mill_balls(run_dir: &Path) -> (BallIds, Option<String>) {
    // A checkpoint that cannot be read fails the analysis itself, with its own message.
    let Ok(world) = World::load_checkpoint_file(run_dir.join("final.ckpt")) else { return (BallIds::Disks, None) };
    let origins = match run_scene(run_dir, &world, "the run's final.ckpt") {
        Ok(run) => run.body_origins,
        Err(why) => {
            let warning = format!(
                "{why}: the balls are taken to be the disk particles (ore grains drawn as disks count as balls)"
            );
            return (BallIds::Disks, Some(warning));
        }
    };
    // A single ball is named `mill.balls`, several `mill.balls #k` (`Scene::body_origins`).
    let is_ball = |origin: &String| origin == "mill.balls" || origin.starts_with("mill.balls #");
    let balls = match (origins.iter().position(is_ball), origins.iter().rposition(is_ball)) {
        (Some(first), Some(last)) => BallIds::Range(first..last + 1),
        _ => BallIds::Range(0..0),
    };
    (balls, None)
}

/// A warning where particle samples of the feed pipe's dumps lie beside the section its profiles span (beyond the
/// ends of its outlets on one line: an outlet narrower than the pipe): the profiles leave them out.
fn beside_the_section(report: &FeedpipeReport) -> Option<String> {
    let outside = report.samples_outside_section;
    let binned: usize = report.profile.iter().map(|bin| bin.samples).sum();
    let [from, to] = report.section_m.map(|p| p.map(crate::console::rounded));
    (outside > 0).then(|| {
        format!(
            "{outside} of the {} particle samples in the window lie beside the section the profiles span, ({}, {}) \
             to ({}, {}) m along the outlets: the profiles leave them out (the mean slip counts them)",
            outside + binned,
            from[0],
            from[1],
            to[0],
            to[1]
        )
    })
}

/// A warning where the grid cell asked for (`--grid`, m) would give more than
/// [`gc2d_analysis::density::MAX_GRID_CELLS_PER_AXIS`] test areas along an axis: the maps use larger squares, whose
/// side (the report's `grid_cell`) and count it names, with the rows of `density_grid.csv` that gives.
fn coarser_grid(report: &Report, cell: f64) -> Option<String> {
    let (side, size, capped) = match (&report.pile, &report.silo) {
        (Some(pile), _) => (pile.grid_cell, pile.grid_size, pile.grid_capped),
        (None, Some(silo)) => (silo.grid_cell, silo.grid_size, silo.grid_capped),
        (None, None) => return None,
    };
    let most = gc2d_analysis::density::MAX_GRID_CELLS_PER_AXIS;
    capped.then(|| {
        format!(
            "--grid {} m would give more than {most} test areas along an axis: the density and stress maps use \
             {} × {} squares of {} m (grid_cell), larger than asked; density_grid.csv has a row for each",
            crate::console::rounded(cell),
            size[0],
            size[1],
            crate::console::rounded(side)
        )
    })
}

/// A warning where the run in `run_dir` did not complete (its `summary.json` says `interrupted` or `failed`):
/// its final state is where it stopped.
fn unfinished_run(run_dir: &Path) -> Option<String> {
    let status = crate::sweep::outcome(run_dir)?;
    (status != "completed").then(|| {
        format!(
            "the run in {} did not complete (summary.json: {status}): the analysis describes the state where it \
             stopped",
            run_dir.display()
        )
    })
}

/// A warning where fewer than half of the particles are in the pile (its largest group in contact): the others are
/// still in flight or lie apart, and the pile's packing fraction, height and angle of repose describe a heap that has
/// not formed (a run of 17 falling grains gave a "pile" of one grain, a packing fraction of 1 and 77°).
fn pile_not_formed(report: &Report) -> Option<String> {
    let pile = report.pile.as_ref()?;
    (2 * pile.particles < report.particles).then(|| {
        format!(
            "only {} of the {} particles {} in the pile (its largest group in contact); the rest are in flight or \
             apart, so the pile's numbers describe a heap that has not formed: analyse a settled state",
            pile.particles,
            report.particles,
            if pile.particles == 1 { "is" } else { "are" }
        )
    })
}

/// A warning where the silo analysis's k = Σσ_xx/Σσ_zz is negative: the grains are not pressed against the walls
/// under their weight, as in a silo (a pile analysed as one gave k = −0.59), so k and the fits mean nothing.
fn not_a_silo(k: f64) -> Option<String> {
    (k < 0.0).then(|| {
        format!(
            "k = Σσ_xx/Σσ_zz is {}: the grains are not pressed sideways under their weight as in a silo, so k and \
             the Janssen fits mean nothing (is it a silo? --kind pile analyses a heap)",
            crate::console::rounded(k)
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_negative_stress_ratio_is_no_silo() {
        assert_eq!(not_a_silo(0.4), None);
        assert!(not_a_silo(-0.59).is_some_and(|w| w.contains("is -0.59") && w.contains("is it a silo?")));
    }

    #[test]
    fn kinds_are_named_as_on_the_command_line() {
        let names: Vec<String> = AnalysisKind::value_variants().iter().map(|k| k.name()).collect();
        assert_eq!(names, ["auto", "pile", "silo", "mill", "feedpipe"]);
    }
}
