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
