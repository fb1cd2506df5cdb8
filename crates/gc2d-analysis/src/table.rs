//! CSV outputs of a run (`timeseries.csv`, `events.csv`, `transits.csv`) read as columns by name.

use crate::error::AnalysisError;
use crate::particle_state::csv::split_fields;
use std::path::Path;

/// A CSV file read as columns by name.
pub(crate) struct Table {
    /// Column names.
    pub header: Vec<String>,
    /// Rows, each with as many fields as the header (quoted fields unquoted).
    pub rows: Vec<Vec<String>>,
    /// The line of each row in the file (from 1), for errors.
    lines: Vec<usize>,
    /// The file, for errors.
    path: std::path::PathBuf,
}

impl Table {
    /// Reads `path`. A line with more or fewer fields than the header is an error naming the file and the line: the
    /// analyses read files of a run that ended, whose rows are all whole, so such a line is damage (a file cut short,
    /// an edit), and leaving it out silently would change counts and sums without a word.
    pub fn read(path: &Path) -> Result<Self, AnalysisError> {
        let text =
            std::fs::read_to_string(path).map_err(|source| AnalysisError::Io { path: path.to_path_buf(), source })?;
        let damaged = |line: usize, what: String| {
            AnalysisError::DamagedFile(format!(
                "{}:{line}: {what} (the file is damaged: cut short or edited)",
                path.display()
            ))
        };
        // Every row a run writes ends with a line break: a last line without one was cut inside.
        if !text.is_empty() && !text.ends_with('\n') {
            return Err(damaged(text.lines().count(), "the last line ends without a line break".to_owned()));
        }
        let mut lines = text.lines();
        let header = split_fields(lines.next().unwrap_or_default());
        let (mut rows, mut numbers) = (Vec::new(), Vec::new());
        for (k, line) in lines.enumerate().filter(|(_, line)| !line.is_empty()) {
            let row = split_fields(line);
            if row.len() != header.len() {
                return Err(damaged(k + 2, format!("{} fields, expected {}", row.len(), header.len())));
            }
            rows.push(row);
            numbers.push(k + 2);
        }
        Ok(Self { rows, header, lines: numbers, path: path.to_path_buf() })
    }

    /// Row `row`'s field in column `column` as a number, where the file must hold one: an error naming the file, the
    /// line and the column otherwise (a field that is not a number is damage, and read as NaN it would pass every
    /// comparison unseen).
    pub fn number(&self, row: usize, column: usize) -> Result<f64, AnalysisError> {
        let field = &self.rows[row][column];
        field.parse().map_err(|_| {
            AnalysisError::DamagedFile(format!(
                "{}:{}: `{field}` in column `{}` is not a number (the file is damaged: cut short or edited)",
                self.path.display(),
                self.lines[row],
                self.header[column]
            ))
        })
    }

    /// The error for row `row` holding what a run cannot have written (`what`): damage, naming the file and the line.
    pub fn damaged(&self, row: usize, what: &str) -> AnalysisError {
        AnalysisError::DamagedFile(format!(
            "{}:{}: {what} (the file is damaged, or of another run)",
            self.path.display(),
            self.lines[row]
        ))
    }

    /// Checks that every field is a number, but in the columns `text` (which hold names) and, where empty, in the
    /// columns `may_be_empty`: the file's first field that is not is an error naming the file, the line and the
    /// column, as [`Table::number`] gives, also in a column the analysis does not read.
    pub fn check_numbers(&self, text: &[&str], may_be_empty: &[&str]) -> Result<(), AnalysisError> {
        let checked: Vec<(usize, bool)> = (self.header.iter().enumerate())
            .filter(|(_, name)| !text.contains(&name.as_str()))
            .map(|(column, name)| (column, may_be_empty.contains(&name.as_str())))
            .collect();
        for (row, fields) in self.rows.iter().enumerate() {
            for &(column, empty_allowed) in &checked {
                if !(empty_allowed && fields[column].is_empty()) {
                    self.number(row, column)?;
                }
            }
        }
        Ok(())
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
