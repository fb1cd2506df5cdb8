//! Text for the user on stdout and stderr without panicking when nobody reads it any more.
//!
//! `println!` and `eprintln!` panic when the write fails, which is what a pipe whose reader has exited does
//! (`gc2d-rs check scene.ron | head -1`). Here a closed stdout is reported to the caller, which ends the program
//! quietly with exit code 0 (as ripgrep does), and a failed write to stderr is ignored: there is nowhere else to say
//! it, and the exit code still tells what happened.

use std::io::{self, Write};

/// Writes `text` and a newline to stdout. `Err` when it cannot be written; [`is_closed`] tells whether that is
/// because the reader has gone.
pub fn out(text: &str) -> io::Result<()> {
    let mut stdout = io::stdout().lock();
    writeln!(stdout, "{text}")?;
    stdout.flush()
}

/// Writes `text` and a newline to stderr, ignoring failures.
pub fn err(text: &str) {
    let mut stderr = io::stderr().lock();
    let _ = writeln!(stderr, "{text}");
    let _ = stderr.flush();
}

/// True for the error of a write into a pipe that nobody reads any more.
pub fn is_closed(error: &io::Error) -> bool {
    error.kind() == io::ErrorKind::BrokenPipe
}
