//! Why an analysis could not be done.

use gc2d_engine::CheckpointError;
use std::path::PathBuf;
use thiserror::Error;

/// Errors of the analysis functions and of [`crate::analyze_run`].
#[derive(Debug, Error)]
pub enum AnalysisError {
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// What went wrong.
        source: std::io::Error,
    },
    /// `final.ckpt` could not be loaded.
    #[error("{path}: {source}")]
    Checkpoint {
        /// The checkpoint file.
        path: PathBuf,
        /// What went wrong.
        source: CheckpointError,
    },
    /// `analysis.json` could not be written.
    #[error("analysis.json: {0}")]
    Json(#[from] serde_json::Error),
    /// A figure could not be drawn.
    #[error("figure {file}: {message}")]
    Figure {
        /// The SVG file.
        file: String,
        /// The plotting library's message.
        message: String,
    },
    /// An input parameter is out of range (named with its value).
    #[error("invalid parameter: {0}")]
    InvalidParameter(String),
    /// A file of the run holds what the run cannot have written (a line cut short, a field that must be a number and
    /// is not, a row out of place): named with the file and the line.
    #[error("damaged file: {0}")]
    DamagedFile(String),
    /// There is too little data for the requested quantity.
    #[error("not enough data: {0}")]
    NotEnoughData(String),
}

/// A simulated time for a message, to 9 significant digits: a run's end is a sum of steps and reads 0.3 s, not
/// 0.3000000000065668 s.
pub(crate) fn time_text(seconds: f64) -> String {
    let rounded: f64 = format!("{seconds:.8e}").parse().unwrap_or(seconds);
    format!("{rounded}")
}

#[cfg(test)]
mod tests {
    use super::time_text;

    #[test]
    fn times_in_messages_lose_the_sums_last_bits() {
        assert_eq!(time_text(0.3000000000065668), "0.3");
        assert_eq!(time_text(0.5), "0.5");
        assert_eq!(time_text(1.23456789e-4), "0.000123456789");
        assert_eq!(time_text(f64::NAN), "NaN");
    }
}
