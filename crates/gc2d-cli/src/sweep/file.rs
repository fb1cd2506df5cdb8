//! The sweep file as written: a RON `Sweep(…)` read through serde, with ron's errors located in the file like a
//! scene's (file, line, column, field path, and a "did you mean" for misspelled field names).

use crate::analysis::AnalysisKind;
use crate::failure::CommandFailure;
use gc2d_scene::{ErrorKind, SceneError, SourceText, error::suggest};
use ron::extensions::Extensions;
use serde::Deserialize;
use std::sync::Arc;

/// A sweep file: the base scene, the parameters and their values, the seeds, where the runs go and what is plotted.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields, rename = "Sweep")]
pub struct SweepFile {
    /// The base scene, relative to the sweep file.
    pub scene: String,
    /// Directory of the run directories and the collected tables, relative to the sweep file. Default: `out/<sweep
    /// file name>` in the current directory.
    #[serde(default)]
    pub out: Option<String>,
    /// The parameters; the points are their full grid (every combination). Default: none (an ensemble of seeds).
    #[serde(default)]
    pub parameters: Vec<Parameter>,
    /// The random seeds each combination runs with (applied to `run.seed`). Default: the base scene's seed.
    #[serde(default)]
    pub seeds: Option<Seeds>,
    /// How each point runs.
    #[serde(default)]
    pub run: RunOptions,
    /// Options of the scene-type analysis run before collecting.
    #[serde(default)]
    pub analysis: AnalysisOptions,
    /// Figures drawn when collecting.
    #[serde(default)]
    pub plots: Vec<Plot>,
}

/// One parameter: a path into the scene and its values.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Parameter {
    /// Field path into the scene, as scene errors write it: `mill.rotor.rpm`, `materials[0].mu`, `run.end_time_s`.
    pub path: String,
    /// Column and directory name. Default: the path's last field name (`rpm`).
    #[serde(default)]
    pub name: Option<String>,
    /// The values it takes.
    pub values: Values,
}

/// The values of a parameter.
#[derive(Debug, Clone, Deserialize)]
pub enum Values {
    /// start, start + step, … up to stop (included when it is on the grid).
    Grid {
        /// First value.
        start: f64,
        /// Last value (included when start + k·step reaches it within 1e-9 steps).
        stop: f64,
        /// Spacing, positive.
        step: f64,
    },
    /// Values written as RON, each put into the scene as written (numbers, strings, lists, structures).
    List(Vec<ron::Value>),
}

/// The seeds of an ensemble.
#[derive(Debug, Clone, Deserialize)]
pub enum Seeds {
    /// This many seeds: the base scene's `run.seed` and the ones after it.
    Count(u64),
    /// These seeds.
    List(Vec<u64>),
}

/// How each point runs.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunOptions {
    /// Simulated time between periodic checkpoints, s (`gc2d-rs run --checkpoint-every`). Default: the scene's
    /// `run.checkpoint_interval_s`.
    #[serde(default)]
    pub checkpoint_every_s: Option<f64>,
    /// Write every contact episode (`gc2d-rs run --events`). Default: true for a mill scene (its analysis needs them),
    /// false otherwise.
    #[serde(default)]
    pub events: Option<bool>,
}

/// Options of the scene-type analysis.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnalysisOptions {
    /// The analysis run on every finished point that lacks its report (`gc2d-rs analyze --kind`): `Pile`, `Silo`,
    /// `Auto` (pile or silo), `Mill` or `Feedpipe`. Default: `Mill` for a mill scene, none otherwise.
    #[serde(default)]
    pub kind: Option<AnalysisKind>,
    /// Mill and feed pipe: the warm-up left out of the averages, s. Default: the automatic cut of `analyze`.
    #[serde(default)]
    pub warm_up_s: Option<f64>,
}

/// A figure: outputs against one parameter.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Plot {
    /// The parameter on the x axis (its name).
    pub x: String,
    /// The table's columns drawn against it, one figure each.
    pub y: Vec<String>,
}

/// A parsed sweep file and its text (for locating later errors).
pub struct Parsed {
    /// What the file says.
    pub file: SweepFile,
    /// Its name and text with the span index.
    pub source: Arc<SourceText>,
}

/// Parses the sweep file `text` read from `name`.
pub fn parse(text: &str, name: &str) -> Result<Parsed, CommandFailure> {
    let source = Arc::new(SourceText::new(name, text));
    let options = ron::Options::default().with_default_extension(Extensions::IMPLICIT_SOME);
    match options.from_str::<SweepFile>(text) {
        Ok(file) => Ok(Parsed { file, source }),
        Err(error) => Err(CommandFailure::input(render(&located(&error, &source)))),
    }
}

/// Ron's error at the field its position falls in (its line and column in the message when no field is found).
fn located(error: &ron::error::SpannedError, source: &Arc<SourceText>) -> SceneError {
    let offset = source.offset_of(error.span.start.line, error.span.start.col);
    let path = source.path_at(offset).unwrap_or("").to_owned();
    let describe = |prefix: &str| match &error.code {
        ron::Error::NoSuchStructField { expected, found, .. } => {
            let hint = suggest(found, expected).map_or(String::new(), |s| format!(", did you mean `{s}`?"));
            let fields = expected.iter().map(|f| format!("`{f}`")).collect::<Vec<_>>().join(", ");
            SceneError::new(ErrorKind::UnknownName, path.clone(), format!("{prefix}unknown field `{found}`{hint}"))
                .with_help(format!("the fields here are {fields} (docs/sweeps.md)"))
        }
        code => SceneError::new(ErrorKind::Syntax, path.clone(), format!("{prefix}{code}")),
    };
    let error_here = describe("").located(Some(source));
    if error_here.location().is_some() {
        return error_here;
    }
    let (line, column) = (error.span.start.line, error.span.start.col);
    describe(&format!("{}:{line}:{column}: ", source.name()))
}

/// Renders a located error with its source snippet.
pub fn render(error: &SceneError) -> String {
    format!("{:?}", miette::Report::new(error.clone()))
}
