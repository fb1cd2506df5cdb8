//! What can go wrong while recording.

use thiserror::Error;

/// Why a recording or a snapshot could not be written.
#[derive(Debug, Error)]
pub enum RecordError {
    /// The output file could not be created or written.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file concerned.
        path: String,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// The MCAP writer refused a record.
    #[error("MCAP writer: {0}")]
    Mcap(#[from] mcap::McapError),
    /// A message could not be encoded.
    #[error("cannot encode a {topic} message: {reason}")]
    Encode {
        /// The topic of the message.
        topic: &'static str,
        /// The encoder's reason.
        reason: String,
    },
    /// An option is outside its range.
    #[error("invalid recording option: {0}")]
    InvalidOption(String),
    /// The recording was already finished.
    #[error("the recording is already finished")]
    Finished,
    /// The live view could not be started.
    #[error("live view: {0}")]
    Live(String),
    /// The PNG snapshot could not be drawn or encoded.
    #[error("PNG snapshot: {0}")]
    Png(String),
}
