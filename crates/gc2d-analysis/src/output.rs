//! Writing the analysis directory: CSV tables and the list of files written.

use crate::error::AnalysisError;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The output directory and the names of the files written into it, in order.
#[derive(Debug)]
pub struct OutputDir {
    path: PathBuf,
    written: Vec<String>,
}

impl OutputDir {
    /// Creates `path` (and its parents) if needed.
    pub fn create(path: &Path) -> Result<Self, AnalysisError> {
        std::fs::create_dir_all(path).map_err(|source| AnalysisError::Io { path: path.to_path_buf(), source })?;
        Ok(Self { path: path.to_path_buf(), written: Vec::new() })
    }

    /// The full path of `name` inside the directory, recorded as written.
    pub fn file(&mut self, name: &str) -> PathBuf {
        self.written.push(name.to_string());
        self.path.join(name)
    }

    /// Names of the files written so far.
    pub fn written(&self) -> &[String] {
        &self.written
    }

    /// Writes a CSV table with a header line; non-finite numbers are written as empty fields.
    pub fn write_csv(&mut self, name: &str, header: &[&str], rows: &[Vec<f64>]) -> Result<(), AnalysisError> {
        let mut text = header.join(",");
        text.push('\n');
        for row in rows {
            for (k, value) in row.iter().enumerate() {
                if k > 0 {
                    text.push(',');
                }
                if value.is_finite() {
                    let _ = write!(text, "{value}");
                }
            }
            text.push('\n');
        }
        self.write_text(name, &text)
    }

    /// Writes `text` to `name`.
    pub fn write_text(&mut self, name: &str, text: &str) -> Result<(), AnalysisError> {
        let path = self.file(name);
        std::fs::write(&path, text).map_err(|source| AnalysisError::Io { path, source })
    }
}
