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

/// A simulated time (or any computed quantity) for a message, rounded to 9 significant digits: a time summed step by
/// step reads 0.3, not 0.29999999999908655; the files keep every digit.
pub fn rounded(value: f64) -> String {
    gc2d_scene::significant_digits(value, 9)
}

#[cfg(test)]
mod rounding_tests {
    use super::rounded;

    #[test]
    fn summed_times_read_as_their_decimal() {
        assert_eq!(rounded(0.29999999999908655), "0.3");
        assert_eq!(rounded(0.001000800000000009), "0.0010008");
        assert_eq!(rounded(1.2999999999999998e-6), "1.3e-6");
        assert_eq!(rounded(0.0), "0");
        assert_eq!(rounded(f64::INFINITY), "inf");
    }
}
