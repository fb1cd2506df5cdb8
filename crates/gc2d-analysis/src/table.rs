//! CSV outputs of a run (`timeseries.csv`, `events.csv`, `transits.csv`) read as columns by name.

use crate::error::AnalysisError;
use std::path::Path;

/// A CSV file read as columns by name.
pub(crate) struct Table {
    /// Column names.
    pub header: Vec<String>,
    /// Rows with as many fields as the header (shorter or longer lines, such as a half-written last one, are left
    /// out).
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// Reads `path`.
    pub fn read(path: &Path) -> Result<Self, AnalysisError> {
        let text =
            std::fs::read_to_string(path).map_err(|source| AnalysisError::Io { path: path.to_path_buf(), source })?;
        let mut lines = text.lines();
        let header: Vec<String> = lines.next().unwrap_or_default().split(',').map(str::to_owned).collect();
        let rows =
            lines.map(|l| l.split(',').map(str::to_owned).collect::<Vec<_>>()).filter(|r| r.len() == header.len());
        Ok(Self { rows: rows.collect(), header })
    }

    /// The index of column `name`, or an error naming the file's kind.
    pub fn column(&self, name: &str, what: &str) -> Result<usize, AnalysisError> {
        self.header.iter().position(|h| h == name).ok_or_else(|| {
            AnalysisError::NotEnoughData(format!("{what} has no column `{name}` (written by another version?)"))
        })
    }
}

/// A field as a number; NaN where it is not one (an empty field).
pub(crate) fn number(field: &str) -> f64 {
    field.parse().unwrap_or(f64::NAN)
}
