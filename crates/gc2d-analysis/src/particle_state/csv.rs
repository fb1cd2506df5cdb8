//! [`ParticleState`] rows as CSV: one header line ([`PARTICLE_STATE_COLUMNS`]), one line per particle; numbers in
//! Rust's shortest round-trip scientific form (they read back bit for bit), material names quoted when they hold a
//! comma, a quote or a line break. A run's dumps are `<run>/dumps/particles_<k>.csv` ([`dump_file_name`]), k the
//! dump's index: dump k is the first state at or after k × the dump interval.

use super::{ParticleShape, ParticleState};
use crate::error::AnalysisError;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// Column names, in order (the fields of [`ParticleState`]).
pub const PARTICLE_STATE_COLUMNS: [&str; 14] = [
    "time_s",
    "id",
    "material",
    "shape",
    "x_m",
    "y_m",
    "phi_rad",
    "vx_m_s",
    "vy_m_s",
    "omega_rad_s",
    "fx_n",
    "fy_n",
    "torque_n_m",
    "contacts",
];

/// The directory of a run's dumps, inside the run directory.
pub const DUMPS_DIR: &str = "dumps";

/// `particles_<k>.csv` with k zero-padded to six digits.
pub fn dump_file_name(index: u64) -> String {
    format!("particles_{index:06}.csv")
}

/// Writes `rows` with the header line.
pub fn write_csv<W: Write>(rows: &[ParticleState], mut out: W) -> io::Result<()> {
    writeln!(out, "{}", PARTICLE_STATE_COLUMNS.join(","))?;
    for r in rows {
        writeln!(
            out,
            "{:e},{},{},{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{}",
            r.time_s,
            r.id,
            quoted(&r.material),
            r.shape.name(),
            r.x_m,
            r.y_m,
            r.phi_rad,
            r.vx_m_s,
            r.vy_m_s,
            r.omega_rad_s,
            r.fx_n,
            r.fy_n,
            r.torque_n_m,
            r.contacts
        )?;
    }
    Ok(())
}

/// Reads a file [`write_csv`] wrote; an error names the file, the line and the field.
pub fn read_csv(path: &Path) -> Result<Vec<ParticleState>, AnalysisError> {
    let text =
        std::fs::read_to_string(path).map_err(|source| AnalysisError::Io { path: path.to_path_buf(), source })?;
    let bad = |line: usize, what: String| AnalysisError::DamagedFile(format!("{}:{line}: {what}", path.display()));
    let mut lines = text.lines().enumerate();
    let header = lines.next().map_or("", |(_, l)| l);
    if header != PARTICLE_STATE_COLUMNS.join(",") {
        return Err(bad(1, "the header is not a particle-state header (written by another version?)".into()));
    }
    let mut rows = Vec::new();
    for (k, line) in lines.filter(|(_, l)| !l.is_empty()) {
        let n = k + 1;
        let fields = split_fields(line);
        if fields.len() != PARTICLE_STATE_COLUMNS.len() {
            return Err(bad(n, format!("{} fields, expected {}", fields.len(), PARTICLE_STATE_COLUMNS.len())));
        }
        let number = |i: usize| {
            fields[i].parse::<f64>().map_err(|_| bad(n, format!("`{}` is not a number", PARTICLE_STATE_COLUMNS[i])))
        };
        let integer = |i: usize| {
            fields[i].parse::<u32>().map_err(|_| bad(n, format!("`{}` is not a count", PARTICLE_STATE_COLUMNS[i])))
        };
        rows.push(ParticleState {
            time_s: number(0)?,
            id: integer(1)?,
            material: fields[2].clone(),
            shape: ParticleShape::from_name(&fields[3])
                .ok_or_else(|| bad(n, format!("shape `{}` is neither disk nor polygon", fields[3])))?,
            x_m: number(4)?,
            y_m: number(5)?,
            phi_rad: number(6)?,
            vx_m_s: number(7)?,
            vy_m_s: number(8)?,
            omega_rad_s: number(9)?,
            fx_n: number(10)?,
            fy_n: number(11)?,
            torque_n_m: number(12)?,
            contacts: integer(13)?,
        });
    }
    Ok(rows)
}

/// The dump files of the directory `dir` with their indices, in index order; none when it does not exist.
pub fn dump_files(dir: &Path) -> Result<Vec<(u64, PathBuf)>, AnalysisError> {
    let entries = match std::fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(source) => return Err(AnalysisError::Io { path: dir.to_path_buf(), source }),
    };
    let mut files: Vec<(u64, PathBuf)> = entries
        .filter_map(Result::ok)
        .filter_map(|entry| {
            let name = entry.file_name().into_string().ok()?;
            let index = name.strip_prefix("particles_")?.strip_suffix(".csv")?.parse().ok()?;
            Some((index, entry.path()))
        })
        .collect();
    files.sort();
    Ok(files)
}

/// How many missing file names a warning lists before it gives only their count.
const MISSING_LISTED: usize = 5;

/// A warning where dump files are missing from the numbered sequence between the first and the last of `indices`
/// (ascending, the dumps an analysis read): it names the missing files (the first [`MISSING_LISTED`] and their
/// count where there are more). The dumps before the first and after the last one read are not judged: a run resumed
/// into a new directory starts its numbering late, and one that ended between two dumps has no further one.
pub fn missing_dumps(indices: &[u64]) -> Option<String> {
    let missing: Vec<u64> =
        indices.windows(2).flat_map(|pair| pair[0].saturating_add(1)..pair[1]).take(MISSING_LISTED + 1).collect();
    let total: u64 = indices.windows(2).map(|pair| pair[1].saturating_sub(pair[0]).saturating_sub(1)).sum();
    let names: Vec<String> =
        missing.iter().take(MISSING_LISTED).map(|&k| format!("{DUMPS_DIR}/{}", dump_file_name(k))).collect();
    match total {
        0 => None,
        1 => Some(format!(
            "{} is missing from the numbered dumps (deleted, or lost): the dump-based statistics use the {} others",
            names[0],
            indices.len()
        )),
        _ => Some(format!(
            "{total} dump files are missing from the numbered dumps (deleted, or lost): {}{}; the dump-based \
             statistics use the {} others",
            names.join(", "),
            if total > MISSING_LISTED as u64 { ", …" } else { "" },
            indices.len()
        )),
    }
}

/// A warning where the dumps directory `dir` holds dumps only in formats the analyses cannot read (Parquet, VTK:
/// `particles_<k>.parquet`, `.vtu` without a `particles_<k>.csv`): it counts them per format and says that
/// `--dump-format csv` writes the CSV dumps the analyses read. `None` where every dump has its CSV file.
pub fn unreadable_dumps(dir: &Path) -> Result<Option<String>, AnalysisError> {
    let entries = match std::fs::read_dir(dir) {
        Ok(entries) => entries,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(None),
        Err(source) => return Err(AnalysisError::Io { path: dir.to_path_buf(), source }),
    };
    let readable: std::collections::BTreeSet<u64> = dump_files(dir)?.into_iter().map(|(k, _)| k).collect();
    // The formats as `--dump-format` names them, by the files' extensions.
    let mut unreadable: std::collections::BTreeMap<&str, usize> = std::collections::BTreeMap::new();
    for entry in entries.filter_map(Result::ok) {
        let Ok(name) = entry.file_name().into_string() else { continue };
        let Some((index, extension)) = name.strip_prefix("particles_").and_then(|rest| rest.split_once('.')) else {
            continue;
        };
        let format = match extension {
            "parquet" => "parquet",
            "vtu" => "vtk",
            _ => continue,
        };
        if index.parse::<u64>().is_ok_and(|k| !readable.contains(&k)) {
            *unreadable.entry(format).or_default() += 1;
        }
    }
    if unreadable.is_empty() {
        return Ok(None);
    }
    let counts: Vec<String> = unreadable.iter().map(|(format, n)| format!("{n} in {format}")).collect();
    let formats: Vec<&str> = unreadable.keys().copied().collect();
    Ok(Some(format!(
        "{} holds dumps in formats the analysis cannot read ({}, without a CSV copy), so they are left out of the \
         statistics from the dumps: run with `--dump-format csv` (csv is what `analyze` reads; \
         `--dump-format csv,{}` writes both) to make them usable",
        dir.display(),
        counts.join(", "),
        formats.join(",")
    )))
}

/// The warnings an analysis that read the dumps of `dir` with `indices` (ascending) gives about them: dumps only in
/// formats it cannot read ([`unreadable_dumps`]), then dump files missing from the numbering ([`missing_dumps`]). The
/// one place the mill and feed-pipe analyses take them from, so that both say the same.
pub fn dump_warnings(dir: &Path, indices: &[u64]) -> Result<Vec<String>, AnalysisError> {
    Ok(unreadable_dumps(dir)?.into_iter().chain(missing_dumps(indices)).collect())
}

/// A CSV field: as it is, or quoted (with quotes doubled) when it holds a comma, a quote or a line break. The one
/// quoting rule of the run's CSV outputs (dumps, events, exports).
pub fn quoted(text: &str) -> std::borrow::Cow<'_, str> {
    if text.contains([',', '"', '\n', '\r']) {
        std::borrow::Cow::Owned(format!("\"{}\"", text.replace('"', "\"\"")))
    } else {
        std::borrow::Cow::Borrowed(text)
    }
}

/// The fields of one CSV line, with quoted fields unquoted (the reverse of [`quoted`]).
pub fn split_fields(line: &str) -> Vec<String> {
    let mut fields = vec![String::new()];
    let mut in_quotes = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        let field = fields.last_mut().expect("there is always a field");
        match (c, in_quotes) {
            ('"', true) if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            ('"', _) => in_quotes = !in_quotes,
            (',', false) => fields.push(String::new()),
            _ => field.push(c),
        }
    }
    fields
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(id: u32, material: &str) -> ParticleState {
        ParticleState {
            time_s: 0.1 + 0.2,
            id,
            material: material.into(),
            shape: ParticleShape::Polygon,
            x_m: -1.0 / 3.0,
            y_m: 1e-300,
            phi_rad: std::f64::consts::PI,
            vx_m_s: 2.5,
            vy_m_s: -0.0,
            omega_rad_s: 7.0e8,
            fx_n: f64::MIN_POSITIVE,
            fy_n: -9.81,
            torque_n_m: 1.0 / 7.0,
            contacts: 3,
        }
    }

    #[test]
    fn rows_read_back_bit_for_bit_with_awkward_material_names() {
        let rows =
            vec![row(0, "steel"), row(7, "ore, \"hard\""), ParticleState { shape: ParticleShape::Disk, ..row(9, "") }];
        let dir = std::env::temp_dir().join(format!("gc2d-state-csv-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(dump_file_name(12));
        let mut bytes = Vec::new();
        write_csv(&rows, &mut bytes).unwrap();
        std::fs::write(&path, &bytes).unwrap();
        let back = read_csv(&path).unwrap();
        assert_eq!(back.len(), rows.len());
        for (a, b) in rows.iter().zip(&back) {
            assert_eq!(a.material, b.material);
            assert_eq!((a.id, a.shape, a.contacts), (b.id, b.shape, b.contacts));
            let bits = |r: &ParticleState| {
                [r.time_s, r.x_m, r.y_m, r.phi_rad, r.vx_m_s, r.vy_m_s, r.omega_rad_s, r.fx_n, r.fy_n, r.torque_n_m]
                    .map(f64::to_bits)
            };
            assert_eq!(bits(a), bits(b));
        }
        assert_eq!(dump_files(&dir).unwrap(), vec![(12, path.clone())]);
        std::fs::write(&path, b"time_s,id\n1,2\n").unwrap();
        let error = read_csv(&path).unwrap_err().to_string();
        assert!(error.contains("particles_000012.csv:1") && error.contains("header"), "{error}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// QA P2-10 h: a gap in the numbering is named; the numbering before the first dump read (a run resumed into a
    /// new directory) is not judged.
    #[test]
    fn gaps_between_the_dumps_read_are_named() {
        assert_eq!(missing_dumps(&[]), None);
        assert_eq!(missing_dumps(&[5, 6, 7]), None);
        let one = missing_dumps(&[0, 1, 3]).unwrap();
        assert!(one.starts_with("dumps/particles_000002.csv is missing") && one.ends_with("use the 3 others"), "{one}");
        let many = missing_dumps(&[0, 20]).unwrap();
        assert!(many.starts_with("19 dump files are missing"), "{many}");
        assert!(many.contains("particles_000005.csv, …; the dump-based statistics use the 2 others"), "{many}");
    }

    /// The mill and feed-pipe analyses take their dump warnings from one place: unreadable formats first, then gaps.
    #[test]
    fn dump_warnings_give_the_unreadable_formats_then_the_gaps() {
        let dir = std::env::temp_dir().join(format!("gc2d-dump-warnings-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("particles_000001.parquet"), "").unwrap();
        let warnings = dump_warnings(&dir, &[0, 2]).unwrap();
        assert_eq!(warnings.len(), 2, "{warnings:?}");
        assert!(warnings[0].contains("(1 in parquet, without a CSV copy)"), "{}", warnings[0]);
        assert_eq!(warnings[1], missing_dumps(&[0, 2]).unwrap());
        assert_eq!(dump_warnings(&dir.join("none"), &[3, 4]).unwrap(), Vec::<String>::new());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
