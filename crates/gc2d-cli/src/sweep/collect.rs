//! Gathering the sweep's results into one table, a row per point: the point's name, its parameter values and seed,
//! the run's outcome, then every number of its `summary.json` and of each scene-type analysis it has
//! (`analysis/<kind>.json`, the sweep's analysis run first where its report is missing), read generically as
//! flattened JSON, so that fields an analysis gains later appear as new columns.

use super::scenes::PointScene;
use super::spec::{SEED, Sweep};
use super::state::outcome;
use crate::analysis::{AnalysisSettings, analyze};
use crate::failure::CommandFailure;
use gc2d_analysis::particle_state::csv::quoted;
use serde_json::Value;
use std::collections::HashMap;
use std::path::Path;

/// Numeric arrays up to this length become a column per element (`quartiles_m_s[1]`); longer ones are left out, and so
/// are arrays whose length differs between the points (histograms with a bin count that follows the sample count).
pub const MAX_ARRAY_COLUMNS: usize = 8;

/// Longest list of points without results that the warning names.
const LISTED_POINTS: usize = 10;

/// One point's results.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// The run directory's name.
    pub point: String,
    /// The parameter values as written in the scene.
    pub parameters: Vec<String>,
    /// The seed.
    pub seed: u64,
    /// `completed`, `interrupted` or `failed`; `None` when the point has no summary yet.
    pub outcome: Option<String>,
    /// The numbers by column name.
    pub numbers: HashMap<String, f64>,
}

/// The table: the parameter names, the numeric columns in the order first met, and the rows in point order.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// Names of the parameter columns.
    pub parameters: Vec<String>,
    /// Names of the numeric columns.
    pub numbers: Vec<String>,
    /// One per point.
    pub rows: Vec<Row>,
}

impl Table {
    /// The values of numeric column `name` (`None` where a row lacks it), or `None` if there is no such column.
    pub fn column(&self, name: &str) -> Option<Vec<Option<f64>>> {
        self.numbers
            .contains(&name.to_owned())
            .then(|| self.rows.iter().map(|r| r.numbers.get(name).copied()).collect())
    }
}

/// The settings a sweep analysed a point's run with, kept in its run directory (`sweep-analysis.json`, outside
/// `analysis/`, whose reports become columns), so that
/// a sweep file whose analysis settings have changed since (another warm-up) analyses the run again rather than
/// mixing two averaging windows in one table.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
struct AnalysisRecord {
    /// The analysis, as `--kind` spells it.
    kind: String,
    /// `analysis.warm_up_s` of the sweep file; `None` for the automatic cut.
    warm_up_s: Option<f64>,
}

impl AnalysisRecord {
    /// The record's file in the run directory `dir`.
    fn path(dir: &Path) -> std::path::PathBuf {
        dir.join("sweep-analysis.json")
    }

    /// The record of the run directory `dir`; `None` where there is none (or it cannot be read).
    fn read(dir: &Path) -> Option<Self> {
        serde_json::from_str(&std::fs::read_to_string(Self::path(dir)).ok()?).ok()
    }

    /// Writes the record into the run directory `dir`.
    fn write(&self, dir: &Path) -> Result<(), String> {
        let path = Self::path(dir);
        let text = serde_json::to_string_pretty(self).map_err(|e| e.to_string())?;
        std::fs::write(&path, text + "\n").map_err(|e| format!("cannot write {}: {e}", path.display()))
    }

    /// The settings in words: `mill analysis, warm-up 0.01 s`.
    fn describe(&self) -> String {
        match self.warm_up_s {
            Some(warm_up) => format!("{} analysis, warm-up {warm_up} s", self.kind),
            None => format!("{} analysis, automatic warm-up", self.kind),
        }
    }
}

/// Reads every point's results (running the mill analysis where a finished mill run lacks it). Problems with single
/// points (a missing summary, an analysis that fails) are listed in the returned warnings, not fatal.
pub fn collect(sweep: &Sweep, points: &[PointScene]) -> (Table, Vec<String>) {
    let mut warnings = Vec::new();
    let mut numbers: Vec<String> = Vec::new();
    let mut rows: Vec<Row> = Vec::with_capacity(points.len());
    let mut without_summary: Vec<&str> = Vec::new();
    for point in points {
        let dir = &point.dir;
        let outcome = outcome(dir);
        let mut values = Vec::new();
        let summary = dir.join("summary.json");
        if !summary.exists() {
            without_summary.push(&point.name);
        } else {
            match read_json(&summary) {
                Ok(summary) => flatten("", &summary, &mut values),
                Err(message) => warnings.push(format!("{}: {message}", point.name)),
            }
        }
        if let Some(kind) = point.analysis
            && outcome.as_deref() == Some("completed")
        {
            let asked = AnalysisRecord { kind: kind.name(), warm_up_s: sweep.file.analysis.warm_up_s };
            let made = AnalysisRecord::read(dir);
            let report = dir.join(kind.report_file());
            // A report made by hand (`analyze`, no record) is kept; one the sweep made with other settings is not.
            let stale = report.is_file() && made.as_ref().is_some_and(|made| *made != asked);
            if stale {
                warnings.push(format!(
                    "{}: analysed again, its report was made with other settings ({}; now {})",
                    point.name,
                    made.as_ref().map_or(String::new(), AnalysisRecord::describe),
                    asked.describe()
                ));
            }
            if stale || !report.is_file() {
                let settings = AnalysisSettings { warm_up_s: asked.warm_up_s, ..AnalysisSettings::automatic() };
                match analyze(dir, kind, &settings) {
                    Ok(output) => {
                        warnings.extend(output.warnings.iter().map(|w| format!("{}: {w}", point.name)));
                        if let Err(e) = asked.write(dir) {
                            warnings.push(format!("{}: {e}", point.name));
                        }
                    }
                    Err(e) => warnings.push(format!("{}: the {} analysis failed: {e}", point.name, kind.name())),
                }
            }
        }
        for (kind, path) in analyses(dir) {
            match read_json(&path) {
                Ok(report) => flatten(&kind, &report, &mut values),
                Err(message) => warnings.push(format!("{}: {message}", point.name)),
            }
        }
        for (name, _) in &values {
            if !numbers.contains(name) {
                numbers.push(name.clone());
            }
        }
        rows.push(Row {
            point: point.name.clone(),
            parameters: point.point.values.clone(),
            seed: point.point.seed,
            outcome,
            numbers: values.into_iter().collect(),
        });
    }
    if !without_summary.is_empty() {
        let listed = &without_summary[..without_summary.len().min(LISTED_POINTS)];
        let more = without_summary.len() - listed.len();
        warnings.push(format!(
            "{} of {} points have no summary.json yet (not run, or still running): {}{}",
            without_summary.len(),
            points.len(),
            listed.join(", "),
            if more > 0 { format!(" and {more} more") } else { String::new() }
        ));
    }
    let uneven = uneven_arrays(&numbers, &rows);
    numbers.retain(|name| !array_family(name).is_some_and(|family| uneven.contains(family)));
    for row in &mut rows {
        row.numbers.retain(|name, _| !array_family(name).is_some_and(|family| uneven.contains(family)));
    }
    let parameters = sweep.parameters.iter().map(|p| p.name.clone()).collect();
    (Table { parameters, numbers, rows }, warnings)
}

/// The array a column is an element of: `mill.quartiles_m_s` for `mill.quartiles_m_s[1]`.
fn array_family(name: &str) -> Option<&str> {
    let (family, index) = name.strip_suffix(']')?.rsplit_once('[')?;
    index.bytes().all(|b| b.is_ascii_digit()).then_some(family)
}

/// The numeric arrays whose length differs between the rows that have them (histograms, whose bin count follows
/// the number of samples): their elements are not the same quantity from row to row.
fn uneven_arrays(numbers: &[String], rows: &[Row]) -> std::collections::HashSet<String> {
    let mut lengths: HashMap<&str, std::collections::HashSet<usize>> = HashMap::new();
    for row in rows {
        let mut here: HashMap<&str, usize> = HashMap::new();
        for name in numbers.iter().filter(|n| row.numbers.contains_key(*n)) {
            if let Some(family) = array_family(name) {
                *here.entry(family).or_default() += 1;
            }
        }
        for (family, length) in here {
            lengths.entry(family).or_default().insert(length);
        }
    }
    lengths.into_iter().filter(|(_, l)| l.len() > 1).map(|(family, _)| family.to_owned()).collect()
}

/// The scene-type analyses of a run directory: `analysis/<kind>.json`, by kind, in name order.
fn analyses(dir: &Path) -> Vec<(String, std::path::PathBuf)> {
    let Ok(entries) = std::fs::read_dir(dir.join("analysis")) else { return Vec::new() };
    let mut found: Vec<(String, std::path::PathBuf)> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .filter_map(|p| Some((p.file_stem()?.to_string_lossy().into_owned(), p.clone())))
        .collect();
    found.sort();
    found
}

fn read_json(path: &Path) -> Result<Value, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("cannot read {}: {e}", path.display()))
}

/// The numbers of a JSON value with their dotted names: objects by key (`energy.kinetic_j`), booleans as 1 or 0,
/// short numeric arrays by index (`quartiles_m_s[1]`), arrays of objects by each object's first text field
/// (`classes[ball–ball].per_second`) or else by index; strings, nulls and long arrays are left out.
pub fn flatten(prefix: &str, value: &Value, out: &mut Vec<(String, f64)>) {
    let join = |key: &str| if prefix.is_empty() { key.to_owned() } else { format!("{prefix}.{key}") };
    match value {
        Value::Number(n) => {
            if let Some(x) = n.as_f64() {
                out.push((prefix.to_owned(), x));
            }
        }
        Value::Bool(b) => out.push((prefix.to_owned(), f64::from(u8::from(*b)))),
        Value::Object(map) => map.iter().for_each(|(key, v)| flatten(&join(key), v, out)),
        Value::Array(items) if items.len() <= MAX_ARRAY_COLUMNS && items.iter().all(Value::is_number) => {
            items.iter().enumerate().for_each(|(i, v)| flatten(&format!("{prefix}[{i}]"), v, out));
        }
        Value::Array(items) if items.iter().all(Value::is_object) => {
            let keys: Vec<Option<&str>> = items.iter().map(first_text).collect();
            let distinct = keys.iter().flatten().collect::<std::collections::HashSet<_>>().len() == items.len();
            for (i, item) in items.iter().enumerate() {
                let key = match keys[i] {
                    Some(key) if distinct => key.to_owned(),
                    _ => i.to_string(),
                };
                flatten(&format!("{prefix}[{key}]"), item, out);
            }
        }
        _ => {}
    }
}

/// The first text field of a JSON object.
fn first_text(value: &Value) -> Option<&str> {
    value.as_object()?.values().find_map(Value::as_str)
}

/// Writes the table as CSV: `point`, the parameters, `seed`, `outcome`, then the numbers (empty where a row lacks
/// one; numbers in Rust's shortest form that reads back to the same f64).
pub fn write_csv(table: &Table, path: &Path) -> Result<(), CommandFailure> {
    let mut text = String::new();
    let header: Vec<String> = ["point".to_owned()]
        .into_iter()
        .chain(table.parameters.iter().cloned())
        .chain([SEED.to_owned(), "outcome".to_owned()])
        .chain(table.numbers.iter().cloned())
        .map(|h| quoted(&h).into_owned())
        .collect();
    text.push_str(&header.join(","));
    text.push('\n');
    for row in &table.rows {
        let mut fields = vec![quoted(&row.point).into_owned()];
        fields.extend(row.parameters.iter().map(|v| quoted(v.trim_matches('"')).into_owned()));
        fields.push(row.seed.to_string());
        fields.push(row.outcome.clone().unwrap_or_default());
        fields.extend(table.numbers.iter().map(|n| row.numbers.get(n).map_or(String::new(), |&x| number(x))));
        text.push_str(&fields.join(","));
        text.push('\n');
    }
    std::fs::write(path, text).map_err(|e| CommandFailure::failed(format!("cannot write {}: {e}", path.display())))
}

/// A number in Rust's shortest form that reads back to the same f64: plain for integers and for magnitudes from 1e-3
/// to 1e15, with an exponent otherwise (`8.968520370800093e-16`).
pub fn number(x: f64) -> String {
    let magnitude = x.abs();
    if x.fract() == 0.0 && magnitude < 1e15 || (1e-3..1e15).contains(&magnitude) {
        x.to_string()
    } else {
        format!("{x:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_flattens_to_named_numbers() {
        let json: Value = serde_json::from_str(
            r#"{"a": 1, "b": {"c": 2.5, "ok": true, "s": "x"}, "q": [1, 2, 3], "long": [1,2,3,4,5,6,7,8,9],
                "classes": [{"class": "ball–ball", "n": 4}, {"class": "ball–hub", "n": 5}], "none": null}"#,
        )
        .unwrap();
        let mut out = Vec::new();
        flatten("mill", &json, &mut out);
        let names: Vec<&str> = out.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(
            names,
            [
                "mill.a",
                "mill.b.c",
                "mill.b.ok",
                "mill.classes[ball–ball].n",
                "mill.classes[ball–hub].n",
                "mill.q[0]",
                "mill.q[1]",
                "mill.q[2]"
            ]
        );
        assert_eq!(out[2].1, 1.0);
        assert_eq!(out[4].1, 5.0);
    }

    /// Every number of a summary is read back to its bits: the sweep's table differed from the summaries it was
    /// collected from by 1 ulp in 28 of 488 cells (QA outputs #2), serde_json's default parser being inexact there.
    #[test]
    fn numbers_read_back_to_their_bits() {
        let written = 0.42117151542727155_f64;
        let json: Value = serde_json::from_str(&format!(r#"{{"kinetic_j": {written}}}"#)).unwrap();
        let mut out = Vec::new();
        flatten("energy", &json, &mut out);
        assert_eq!(out[0].1.to_bits(), written.to_bits(), "{} read back as {}", written, out[0].1);
    }

    #[test]
    fn numbers_read_back_exactly() {
        for x in [0.0, 5882.0, 0.05, 8.968520370800093e-16, 1.7e-6, -2.5e20, 0.1 + 0.2] {
            assert_eq!(number(x).parse::<f64>().unwrap().to_bits(), x.to_bits(), "{x}");
        }
        assert_eq!(number(5882.0), "5882");
        assert_eq!(number(1.7e-6), "1.7e-6");
    }

    #[test]
    fn array_elements_name_their_array() {
        assert_eq!(array_family("mill.quartiles_m_s[1]"), Some("mill.quartiles_m_s"));
        assert_eq!(array_family("mill.classes[ball–hub].n"), None);
        assert_eq!(array_family("mill.classes[ball–hub]"), None);
        assert_eq!(array_family("time_s"), None);
    }
}
