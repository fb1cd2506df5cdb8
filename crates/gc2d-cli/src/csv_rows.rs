//! Rows of the CSV files a run appends to as it goes (`events.csv`, `transits.csv`), handed to their buffer whole:
//! a buffer that fills writes out what it holds, and `writeln!` hands a row over in pieces, so a reader of a running
//! run (polling the file) found it ending in the middle of a row, a cut number that still parses (`-6.` of
//! `-6.02e-3`).

use std::fmt;
use std::io::{self, Write};

/// Writes `row` and a line break to `file` in one call, so that a buffered writer only ever writes out whole rows.
pub fn write_whole_row(file: &mut impl Write, row: fmt::Arguments) -> io::Result<()> {
    let mut line = fmt::format(row);
    line.push('\n');
    file.write_all(line.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::write_whole_row;
    use std::io::{BufWriter, Write};

    /// With a buffer of 64 bytes and rows of 25, the file on disk ends with a whole row after every row written.
    #[test]
    fn a_buffered_file_holds_only_whole_rows() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("rows.csv");
        let mut file = BufWriter::with_capacity(64, std::fs::File::create(&path).unwrap());
        for k in 0..20 {
            let (force, object) = (-6.02e-3 * k as f64, format!("walls[{k}]"));
            write_whole_row(&mut file, format_args!("{k:04},{force:e},{object}")).unwrap();
            let on_disk = std::fs::read_to_string(&path).unwrap();
            assert!(on_disk.is_empty() || on_disk.ends_with('\n'), "after row {k}: {on_disk:?}");
        }
        file.flush().unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap().lines().count(), 20);
    }

    /// The same rows written with `writeln!` in pieces leave a cut row on disk: what the test above guards against.
    #[test]
    fn writeln_hands_a_row_over_in_pieces() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("rows.csv");
        let mut file = BufWriter::with_capacity(64, std::fs::File::create(&path).unwrap());
        let mut cut = false;
        for k in 0..20 {
            let (force, object) = (-6.02e-3 * k as f64, format!("walls[{k}]"));
            writeln!(file, "{k:04},{force:e},{object}").unwrap();
            let on_disk = std::fs::read_to_string(&path).unwrap();
            cut |= !on_disk.is_empty() && !on_disk.ends_with('\n');
        }
        assert!(cut, "writeln! wrote out a part of a row");
    }
}
