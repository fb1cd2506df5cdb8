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
    /// The MCAP writer failed (an I/O error from the file, a full disk, or a record it refused). The message names
    /// the file and every cause in the error's chain, down to the operating system's reason: mcap's own message
    /// for an I/O error does not include it.
    #[error("cannot write {path} (MCAP writer): {}", with_causes(source))]
    Mcap {
        /// The recording's file.
        path: String,
        /// The writer's error.
        source: mcap::McapError,
    },
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

/// `error`'s message followed by those of its sources, each after `: `.
fn with_causes(error: &dyn std::error::Error) -> String {
    let mut message = error.to_string();
    let mut cause = error.source();
    while let Some(error) = cause {
        message.push_str(": ");
        message.push_str(&error.to_string());
        cause = error.source();
    }
    message
}
