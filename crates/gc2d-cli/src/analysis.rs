//! The scene-type analyses of a finished run, as `gc2d-rs analyze --kind …` and a sweep's collection run them: one
//! name per kind, the file each writes, and one call that runs it.

use clap::ValueEnum;
use gc2d_analysis::{
    AnalysisError, AnalyzeOptions, FeedpipeOptions, MillOptions, SceneKind, analyze_feedpipe, analyze_mill, analyze_run,
};
use serde::Deserialize;
use std::path::Path;

/// What a run is, for its analysis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Deserialize)]
pub enum AnalysisKind {
    /// Decide from the wall forces.
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

/// Runs the `kind` analysis of the finished run in `run_dir`, which writes its tables, figures and
/// [`AnalysisKind::report_file`] there, and returns the report as pretty-printed JSON (in the report's field order).
pub fn analyze(run_dir: &Path, kind: AnalysisKind, settings: &AnalysisSettings) -> Result<String, String> {
    let as_json = |report: Result<String, serde_json::Error>| report.map_err(|e| e.to_string());
    let failed = |e: AnalysisError| e.to_string();
    let scene = match kind {
        AnalysisKind::Auto => SceneKind::Auto,
        AnalysisKind::Pile => SceneKind::Pile,
        AnalysisKind::Silo => SceneKind::Silo,
        AnalysisKind::Mill => {
            let report = analyze_mill(run_dir, &MillOptions { warm_up_s: settings.warm_up_s }).map_err(failed)?;
            return as_json(serde_json::to_string_pretty(&report));
        }
        AnalysisKind::Feedpipe => {
            let options = FeedpipeOptions { warm_up_s: settings.warm_up_s, bins: settings.bins };
            let report = analyze_feedpipe(run_dir, &options).map_err(failed)?;
            return as_json(serde_json::to_string_pretty(&report));
        }
    };
    let options =
        AnalyzeOptions { scene, window_half_width: settings.window_half_width_m, grid_cell: settings.grid_cell_m };
    let report = analyze_run(run_dir, &options).map_err(failed)?;
    as_json(serde_json::to_string_pretty(&report))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds_are_named_as_on_the_command_line() {
        let names: Vec<String> = AnalysisKind::value_variants().iter().map(|k| k.name()).collect();
        assert_eq!(names, ["auto", "pile", "silo", "mill", "feedpipe"]);
    }
}
