//! The sweep as it runs: the sweep file checked field by field (grids, names, seeds, plots), each parameter's values
//! as the RON text put into the scene, and the points, their full grid.

use super::file::{Parsed, Plot, Seeds, SweepFile, Values, render};
use crate::analysis::AnalysisKind;
use crate::failure::CommandFailure;
use crate::outputs::SUMMARY_FIELDS;
use gc2d_scene::{ErrorKind, SceneError, SourceText};
use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Most points one sweep may have (a grid with a step in the wrong unit would otherwise make millions).
pub const MAX_POINTS: usize = 100_000;

/// The column and directory name of the seed.
pub const SEED: &str = "seed";

/// A parameter with its values written out.
#[derive(Debug, Clone)]
pub struct ParameterSpec {
    /// Field path into the scene.
    pub path: String,
    /// Column and directory name.
    pub name: String,
    /// Each value as RON text, as put into the scene.
    pub values: Vec<String>,
    /// The parameter's index in the sweep file (for locating errors).
    pub index: usize,
}

/// A checked sweep file.
pub struct Sweep {
    /// The sweep file.
    pub path: PathBuf,
    /// Its text, for locating errors.
    pub source: Arc<SourceText>,
    /// The base scene file.
    pub scene: PathBuf,
    /// The output directory.
    pub out: PathBuf,
    /// The parameters.
    pub parameters: Vec<ParameterSpec>,
    /// The seeds; `None` keeps the base scene's seed.
    pub seeds: Option<Seeds>,
    /// What the file says, for the run, analysis and plot options.
    pub file: SweepFile,
}

/// One point of the sweep: a value of every parameter and a seed.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Its place in the sweep, from 0 (the first parameter varies slowest, the seed fastest).
    pub index: usize,
    /// The value of each parameter, as RON text, in the order of the sweep file.
    pub values: Vec<String>,
    /// The random seed.
    pub seed: u64,
}

/// The column of the sweep's table that a parameter named `name` would clash with: the fixed columns, the fields of
/// `summary.json` and the reports of the analyses (`energy.kinetic_j`, `mill.…`), by their first part. `None` where
/// the name is free.
fn taken_column(name: &str) -> Option<&'static str> {
    let first = name.split(['.', '[']).next().unwrap_or(name);
    let fixed = ["point", "outcome"].into_iter();
    let report_stem = |kind: AnalysisKind| Path::new(kind.report_file()).file_stem().and_then(|s| s.to_str());
    let analyses = [AnalysisKind::Pile, AnalysisKind::Mill, AnalysisKind::Feedpipe].into_iter().filter_map(report_stem);
    fixed.chain(SUMMARY_FIELDS).chain(analyses).find(|column| *column == first)
}

impl Sweep {
    /// Checks the parsed file read from `path`; `out` overrides its output directory.
    pub fn new(path: &Path, parsed: Parsed, out: Option<PathBuf>) -> Result<Self, CommandFailure> {
        let Parsed { file, source } = parsed;
        let error = |field: String, message: String| {
            CommandFailure::input(render(&SceneError::new(ErrorKind::Value, field, message).located(Some(&source))))
        };
        let folder = path.parent().unwrap_or(Path::new(""));
        let scene = lexically_tidy(&folder.join(&file.scene));
        let out = out.unwrap_or_else(|| match &file.out {
            Some(out) => lexically_tidy(&folder.join(out)),
            None => PathBuf::from("out").join(path.file_stem().unwrap_or_default()),
        });
        let mut parameters = Vec::new();
        let mut names = HashSet::from([SEED.to_owned()]);
        let mut paths = HashSet::new();
        for (index, parameter) in file.parameters.iter().enumerate() {
            let field = |name: &str| format!("parameters[{index}].{name}");
            if let Err(what) = super::apply::check_syntax(&parameter.path) {
                return Err(error(field("path"), format!("`{}` is not a field path: {what}", parameter.path)));
            }
            if parameter.path == "run.seed" {
                return Err(error(field("path"), "the seed is set by `seeds`, not as a parameter".into()));
            }
            if !paths.insert(parameter.path.as_str()) {
                return Err(error(
                    field("path"),
                    format!(
                        "another parameter sets `{}` already: the later value would win in every run while the table \
                         showed both; give each path one parameter",
                        parameter.path
                    ),
                ));
            }
            let name = parameter.name.clone().unwrap_or_else(|| last_field(&parameter.path).to_owned());
            if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.') {
                return Err(error(
                    field(if parameter.name.is_some() { "name" } else { "path" }),
                    format!("`{name}` cannot name a column and a directory: use letters, digits, `_` and `.`"),
                ));
            }
            if let Some(column) = taken_column(&name) {
                return Err(error(
                    field(if parameter.name.is_some() { "name" } else { "path" }),
                    format!(
                        "`{name}` is the name of the table's column `{column}`, which every run fills: the table would \
                         have two columns of that name (pandas and polars refuse such a Parquet file); give the \
                         parameter a `name`"
                    ),
                ));
            }
            if !names.insert(name.clone()) {
                return Err(error(
                    field(if parameter.name.is_some() { "name" } else { "path" }),
                    format!("a second parameter (or the seed) is named `{name}`: give one a `name`"),
                ));
            }
            let values = match &parameter.values {
                Values::Grid { start, stop, step } => {
                    grid(*start, *stop, *step).map_err(|message| error(field("values"), message))?
                }
                Values::List(values) => (0..values.len())
                    .map(|k| list_value(&source, &format!("parameters[{index}].values[{k}]"), &values[k]))
                    .collect::<Vec<_>>(),
            };
            if values.is_empty() {
                return Err(error(field("values"), "the list of values is empty".into()));
            }
            if let Some((first, again)) = same_value_twice(&values) {
                let message = if first == again {
                    format!("the value `{again}` is given twice")
                } else {
                    format!("the value `{again}` is `{first}` again, written another way: the same run twice")
                };
                return Err(error(field("values"), message));
            }
            parameters.push(ParameterSpec { path: parameter.path.clone(), name, values, index });
        }
        let seeds = match &file.seeds {
            None => None,
            Some(Seeds::Count(0)) => return Err(error("seeds".into(), "at least one seed is needed".into())),
            Some(Seeds::Count(n)) => Some(Seeds::Count(*n)),
            Some(Seeds::List(list)) => {
                if list.is_empty() {
                    return Err(error("seeds".into(), "the list of seeds is empty".into()));
                }
                if let Some(twice) = first_repeat(list) {
                    return Err(error("seeds".into(), format!("the seed {twice} is given twice")));
                }
                Some(Seeds::List(list.clone()))
            }
        };
        let seed_count = match &seeds {
            None => 1,
            Some(Seeds::Count(n)) => usize::try_from(*n).unwrap_or(usize::MAX),
            Some(Seeds::List(list)) => list.len(),
        };
        let count = parameters.iter().map(|p| p.values.len()).chain([seed_count]).try_fold(1usize, usize::checked_mul);
        if count.is_none_or(|n| n > MAX_POINTS) {
            return Err(error(
                "parameters".into(),
                format!("the grid has more than {MAX_POINTS} points: check the steps and the seed count"),
            ));
        }
        if let Some(every) = file.run.checkpoint_every_s
            && !(every.is_finite() && every > 0.0)
        {
            return Err(error("run.checkpoint_every_s".into(), format!("must be a positive time in s, got {every}")));
        }
        if let Some(warm_up) = file.analysis.warm_up_s
            && !(warm_up.is_finite() && warm_up >= 0.0)
        {
            return Err(error("analysis.warm_up_s".into(), format!("must be a time ≥ 0 in s, got {warm_up}")));
        }
        Ok(Self { path: path.to_path_buf(), source, scene, out, parameters, seeds, file })
    }

    /// Every point: the full grid of the parameters' values, each with every seed. `base_seed` is the base scene's.
    pub fn points(&self, base_seed: u64) -> Vec<Point> {
        let seeds: Vec<u64> = match &self.seeds {
            None => vec![base_seed],
            Some(Seeds::Count(n)) => (0..*n).map(|k| base_seed.wrapping_add(k)).collect(),
            Some(Seeds::List(list)) => list.clone(),
        };
        let mut combinations: Vec<Vec<String>> = vec![Vec::new()];
        for parameter in &self.parameters {
            combinations = combinations
                .iter()
                .flat_map(|head| {
                    parameter.values.iter().map(move |value| {
                        let mut next = head.clone();
                        next.push(value.clone());
                        next
                    })
                })
                .collect();
        }
        combinations
            .into_iter()
            .flat_map(|values| seeds.iter().map(move |&seed| (values.clone(), seed)))
            .enumerate()
            .map(|(index, (values, seed))| Point { index, values, seed })
            .collect()
    }

    /// The directory name of a point: `rpm=1700_count=130_seed=1`.
    pub fn dir_name(&self, point: &Point) -> String {
        self.dir_name_parts(point).join("_")
    }

    /// The parts of the point's directory name, joined by `_`: one `name=value` per parameter, in order, then
    /// `seed=…`.
    pub fn dir_name_parts(&self, point: &Point) -> Vec<String> {
        let mut parts: Vec<String> =
            self.parameters.iter().zip(&point.values).map(|(p, v)| format!("{}={}", p.name, label(v))).collect();
        parts.push(format!("{SEED}={}", point.seed));
        parts
    }

    /// The point's values for a message: `mill.rotor.rpm = 1700, run.seed = 1`.
    pub fn describe(&self, point: &Point) -> String {
        let mut parts: Vec<String> =
            self.parameters.iter().zip(&point.values).map(|(p, v)| format!("{} = {v}", p.path)).collect();
        parts.push(format!("run.seed = {}", point.seed));
        parts.join(", ")
    }

    /// An error of the value at `field` (`analysis.kind`), located in the sweep file.
    pub fn field_error(&self, field: &str, message: String) -> CommandFailure {
        CommandFailure::input(render(
            &SceneError::new(ErrorKind::Value, field.to_owned(), message).located(Some(&self.source)),
        ))
    }

    /// The first mistake in the plots, located in the sweep file. A parameter in `wrong_paths` (its path is not in the
    /// scene, reported on its own) is not offered as the "did you mean" of a plot's x: its name may carry the typo.
    pub fn plot_error(&self, wrong_paths: &[usize]) -> Option<CommandFailure> {
        check_plots(&self.file.plots, &self.parameters, wrong_paths)
            .err()
            .map(|(field, message)| self.field_error(&field, message))
    }

    /// An error located at a parameter's `path` field in the sweep file.
    pub fn parameter_error(&self, parameter: &ParameterSpec, message: String, help: Option<String>) -> CommandFailure {
        let mut error =
            SceneError::new(ErrorKind::UnknownName, format!("parameters[{}].path", parameter.index), message);
        if let Some(help) = help {
            error = error.with_help(help);
        }
        CommandFailure::input(render(&error.located(Some(&self.source))))
    }
}

/// `path` with each `dir/..` pair dropped (`sweeps/../out/x` → `out/x`), as messages and run commands show it. Only
/// a `..` that follows a plain folder name goes; a leading one, or one after a root, stays.
fn lexically_tidy(path: &Path) -> PathBuf {
    use std::path::Component;
    let mut tidy: Vec<Component> = Vec::new();
    for component in path.components() {
        match (component, tidy.last()) {
            (Component::CurDir, _) => {}
            (Component::ParentDir, Some(Component::Normal(_))) => {
                tidy.pop();
            }
            _ => tidy.push(component),
        }
    }
    if tidy.is_empty() { PathBuf::from(".") } else { tidy.iter().collect() }
}

/// The plots name a parameter with numbers for values on x, and their outputs at all. The parameters whose index is
/// in `wrong_paths` are not suggested for a misspelled x.
fn check_plots(plots: &[Plot], parameters: &[ParameterSpec], wrong_paths: &[usize]) -> Result<(), (String, String)> {
    for (k, plot) in plots.iter().enumerate() {
        if parameters.is_empty() {
            return Err((
                format!("plots[{k}].x"),
                "this sweep has no parameters, only seeds, so there is nothing to plot against (the means over the \
                 seeds are in sweep_means.csv)"
                    .into(),
            ));
        }
        if let Some(parameter) = parameters.iter().find(|p| p.name == plot.x)
            && let Some(value) = parameter.values.iter().find(|v| v.parse::<f64>().is_err())
        {
            return Err((
                format!("plots[{k}].x"),
                format!("`{}` has the value `{value}`, which is not a number to put on an axis", plot.x),
            ));
        }
        if plot.x == SEED {
            return Err((
                format!("plots[{k}].x"),
                format!(
                    "`{SEED}` is not a parameter of this sweep: each point of a figure is the mean over the seeds (each \
                     seed's values are in sweep.csv); put a parameter on x"
                ),
            ));
        }
        if !parameters.iter().any(|p| p.name == plot.x) {
            let names: Vec<&str> = parameters.iter().map(|p| p.name.as_str()).collect();
            let offered: Vec<&str> =
                parameters.iter().filter(|p| !wrong_paths.contains(&p.index)).map(|p| p.name.as_str()).collect();
            let hint = gc2d_scene::error::suggest(&plot.x, &offered)
                .map_or(String::new(), |s| format!(", did you mean `{s}`?"));
            return Err((
                format!("plots[{k}].x"),
                format!(
                    "`{}` is not a parameter of this sweep{hint} (the parameters are {})",
                    plot.x,
                    names.join(", ")
                ),
            ));
        }
        if plot.y.is_empty() {
            return Err((format!("plots[{k}].y"), "name at least one output column".into()));
        }
    }
    Ok(())
}

/// The values start + k·step up to stop, each rounded to 12 significant digits (so 0.1 + 2·0.1 reads 0.3) and
/// written the way RON reads it back.
fn grid(start: f64, stop: f64, step: f64) -> Result<Vec<String>, String> {
    if !(start.is_finite() && stop.is_finite() && step.is_finite()) {
        return Err("start, stop and step must be finite numbers".into());
    }
    if step <= 0.0 {
        return Err(format!("the step must be positive, got {step}"));
    }
    if stop < start {
        return Err(format!("stop ({stop}) is below start ({start})"));
    }
    let steps = ((stop - start) / step + 1e-9).floor();
    if steps >= MAX_POINTS as f64 {
        return Err(format!("the grid has more than {MAX_POINTS} values: is the step in the right unit?"));
    }
    // A grid through zero reaches it only to round-off (−0.3 + 3·0.1 = 5.6e-17), which the rounding to 12 digits,
    // relative to the value itself, keeps: such a value is zero.
    let value = |k: usize| Some(start + k as f64 * step).filter(|v| v.abs() > 1e-9 * step).unwrap_or(0.0);
    Ok((0..=steps as usize).map(|k| number(value(k))).collect())
}

/// A grid value as RON text: integers without a decimal point (so they also fit integer fields such as a count),
/// others rounded to 12 significant digits.
fn number(value: f64) -> String {
    let rounded: f64 = format!("{value:.11e}").parse().unwrap_or(value);
    if rounded.fract() == 0.0 && rounded.abs() < 1e15 { format!("{}", rounded as i64) } else { format!("{rounded}") }
}

/// A listed value as written in the sweep file (its text at `field`), or as ron writes it where the text is not
/// found.
fn list_value(source: &SourceText, field: &str, value: &ron::Value) -> String {
    match source.span_of(field) {
        Some(span) if source.path_at(span.start) == Some(field) => source.text()[span].trim().to_owned(),
        _ => ron::to_string(value).unwrap_or_default(),
    }
}

/// The first value of a parameter's list that repeats an earlier one, with that earlier one: as numbers where both
/// read as numbers (`0.3`, `0.30` and `3e-1` are one value), else as text.
fn same_value_twice(values: &[String]) -> Option<(&str, &str)> {
    let key = |value: &str| value.parse::<f64>().map_or_else(|_| value.to_owned(), |number| format!("{number:e}"));
    let mut seen = std::collections::HashMap::new();
    values.iter().find_map(|value| seen.insert(key(value), value.as_str()).map(|first| (first, value.as_str())))
}

/// The first element that occurs twice.
fn first_repeat<T: std::hash::Hash + Eq + std::fmt::Display>(values: &[T]) -> Option<&T> {
    let mut seen = HashSet::new();
    values.iter().find(|v| !seen.insert(*v))
}

/// The last field name of a path: `materials[0].mu` → `mu`, `mill.rotor.rpm` → `rpm`.
fn last_field(path: &str) -> &str {
    let last = path.rsplit('.').next().unwrap_or(path);
    last.split('[').next().unwrap_or(last)
}

/// A value as part of a directory name: quotes dropped, anything but letters, digits, `.`, `+` and `-` as `-`.
fn label(value: &str) -> String {
    value
        .trim_matches('"')
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() || matches!(c, '.' | '+' | '-') { c } else { '-' })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grids_include_the_stop_and_read_as_ron_numbers() {
        assert_eq!(grid(800.0, 2000.0, 200.0).unwrap(), ["800", "1000", "1200", "1400", "1600", "1800", "2000"]);
        assert_eq!(grid(0.1, 0.3, 0.1).unwrap(), ["0.1", "0.2", "0.3"]);
        assert_eq!(grid(1.0, 1.9, 0.5).unwrap(), ["1", "1.5"]);
        assert_eq!(grid(2e-7, 2e-7, 1e-7).unwrap(), ["0.0000002"]);
        // Through zero: the middle value was 5.55111512313e-17, in the table, the directory name and the scene.
        assert_eq!(grid(-0.3, 0.3, 0.1).unwrap(), ["-0.3", "-0.2", "-0.1", "0", "0.1", "0.2", "0.3"]);
        assert!(grid(1.0, 0.0, 1.0).is_err());
        assert!(grid(0.0, 1.0, 0.0).is_err());
        assert!(grid(0.0, 1e9, 1e-3).is_err());
    }

    #[test]
    fn paths_lose_their_folder_and_parent_pairs() {
        let tidy = |p: &str| lexically_tidy(Path::new(p)).display().to_string();
        assert_eq!(tidy("sweeps/../out/mill_map"), "out/mill_map");
        assert_eq!(tidy("./sweeps/../../out"), "../out");
        assert_eq!(tidy("../scenes/./mill.ron"), "../scenes/mill.ron");
        assert_eq!(tidy("/a/b/../c"), "/a/c");
        assert_eq!(tidy("a/.."), ".");
    }

    #[test]
    fn names_and_labels() {
        assert_eq!(last_field("mill.rotor.rpm"), "rpm");
        assert_eq!(last_field("materials[0].youngs_modulus_pa"), "youngs_modulus_pa");
        assert_eq!(last_field("materials[1]"), "materials");
        assert_eq!(label("\"steel 2\""), "steel-2");
        assert_eq!(label("1.5e-3"), "1.5e-3");
    }
}
