//! How a subcommand fails: the exit code and the report to print, one type for every subcommand.

use crate::console;

/// A failed command: its exit code (1 a failure while running or writing, 2 invalid input, 130 interrupted; 0 for a
/// reader of stdout that has gone) and what to say on stderr (nothing when empty).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CommandFailure {
    /// The process exit code.
    pub code: u8,
    /// The message, one or more lines; `file:line:` first where a place in a file is known.
    pub report: String,
}

impl CommandFailure {
    /// Invalid input (exit code 2).
    pub fn input(report: impl Into<String>) -> Self {
        Self { code: 2, report: report.into() }
    }

    /// A failure while running or writing (exit code 1).
    pub fn failed(report: impl Into<String>) -> Self {
        Self { code: 1, report: report.into() }
    }

    /// A failed write to stdout: a reader that has gone (`| head`) ends the program quietly with exit code 0, any
    /// other error is a failure.
    pub fn stdout(error: &std::io::Error) -> Self {
        if console::is_closed(error) {
            Self { code: 0, report: String::new() }
        } else {
            Self::failed(format!("cannot write to standard output: {error}"))
        }
    }
}
