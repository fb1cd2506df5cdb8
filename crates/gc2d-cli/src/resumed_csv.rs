//! Continuing an append-only CSV output of a run (`events.csv`, `transits.csv`) when the run resumes from a
//! checkpoint: the rows the earlier process wrote after that checkpoint (and a half-written last line) are dropped, so
//! that the resumed process writes them again and the file ends up as one uninterrupted run would have written it.

use gc2d_analysis::particle_state::csv::split_fields;
use std::fs::File;
use std::io;
use std::path::Path;

/// Keeps the header of `path` and its rows whose time column (`time_column`, of `columns`) lies before
/// `resumed_at + slack`, and opens the file for appending. A header other than `columns` refuses the file: it was
/// written by another version (`what` names the file in the message).
pub fn continue_csv(
    path: &Path,
    columns: &[&str],
    time_column: usize,
    what: &str,
    resumed_at: f64,
    slack: f64,
) -> io::Result<File> {
    let text = std::fs::read_to_string(path)?;
    let mut lines = text.lines();
    let header = lines.next().unwrap_or_default();
    if header != columns.join(",") {
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!("its first line is not this version's {what} header; resume into a new --out directory"),
        ));
    }
    // Fields split as they are written, quoted ones whole: a name with a comma in it (material names are free text)
    // would otherwise count as two fields and drop its row.
    let time = |line: &str| {
        let fields = split_fields(line);
        (fields.len() == columns.len()).then(|| fields[time_column].parse::<f64>().ok()).flatten()
    };
    let mut kept = format!("{header}\n");
    for line in lines.filter(|line| time(line).is_some_and(|t| t < resumed_at + slack)) {
        kept.push_str(line);
        kept.push('\n');
    }
    std::fs::write(path, kept)?;
    std::fs::OpenOptions::new().append(true).open(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A quoted field with a comma in it (a material named `sand, wet`) is one field: its row is kept, where splitting
    /// at every comma counted one field too many and dropped it.
    #[test]
    fn rows_with_quoted_commas_are_kept_and_later_rows_dropped() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("events.csv");
        let rows = "time_s,material\n0.1,\"sand, wet\"\n0.2,glass\n0.3,\"sand, wet\"\n0.4,gla";
        std::fs::write(&path, rows).unwrap();
        drop(continue_csv(&path, &["time_s", "material"], 0, "events.csv", 0.25, 1e-6).unwrap());
        let kept = std::fs::read_to_string(&path).unwrap();
        assert_eq!(kept, "time_s,material\n0.1,\"sand, wet\"\n0.2,glass\n");
    }
}
