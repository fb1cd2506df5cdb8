//! Folders of files numbered on a cadence, `dumps/particles_<k>.*` and `frames/frame-<k>.png`, file k holding the
//! state at k·interval, across a resume. Each folder records its [`FolderCadence`] in [`CADENCE_FILE`]: the interval, the
//! formats written and, for pictures, the region they show. A resumed part that would number on another interval is
//! refused (two intervals under one numbering gave files whose number no longer told their time, and a
//! `particles.pvd` with wrong times), and so is one that would write other formats (an analysis reads the CSV dumps,
//! and would see only the earlier part's); the files an earlier part wrote from the resumed part's first tick on are
//! removed, in every format, so that none of them outlives the resumed part's own.

use gc2d_geometry::{Aabb, DVec2};
use std::path::Path;

/// The file in a numbered folder that records its [`FolderCadence`].
pub const CADENCE_FILE: &str = ".gc2d-cadence";

/// How a folder's files are numbered and written.
#[derive(Debug, Clone, PartialEq)]
pub struct FolderCadence {
    /// Simulated time between two files, s: file k holds the state at k·interval.
    pub interval: f64,
    /// The formats written, as the option lists them (`csv,vtk`; `png` for pictures).
    pub formats: String,
    /// The region the pictures show, m, once it is known (pictures only).
    pub region: Option<Aabb>,
}

impl FolderCadence {
    /// The record's text: one `key = value` line per field.
    fn text(&self) -> String {
        let mut text = format!("interval_s = {:?}\nformats = {}\n", self.interval, self.formats);
        if let Some(r) = self.region {
            text += &format!("region_m = {:?} {:?} {:?} {:?}\n", r.min.x, r.max.x, r.min.y, r.max.y);
        }
        text
    }

    /// Reads a record; `None` where it is not one. A record of one number (the first version's) is an interval alone.
    fn parse(text: &str) -> Option<Self> {
        if let Ok(interval) = text.trim().parse::<f64>() {
            return Some(Self { interval, formats: String::new(), region: None }).filter(|c| c.interval > 0.0);
        }
        let mut cadence = Self { interval: f64::NAN, formats: String::new(), region: None };
        for line in text.lines().filter(|line| !line.trim().is_empty()) {
            let (key, value) = line.split_once('=')?;
            match key.trim() {
                "interval_s" => cadence.interval = value.trim().parse().ok()?,
                "formats" => cadence.formats = value.trim().to_owned(),
                "region_m" => {
                    let numbers: Vec<f64> = value.split_whitespace().map(str::parse).collect::<Result<_, _>>().ok()?;
                    let [x0, x1, y0, y1] = numbers[..] else { return None };
                    cadence.region = Some(Aabb { min: DVec2::new(x0, y0), max: DVec2::new(x1, y1) });
                }
                _ => return None,
            }
        }
        (cadence.interval.is_finite() && cadence.interval > 0.0).then_some(cadence)
    }
}

/// The formats of a cadence record as a set: an earlier version recorded them in the order and with the repeats the
/// option was given (`parquet,csv`, `csv,csv`).
fn format_set(formats: &str) -> std::collections::BTreeSet<&str> {
    formats.split(',').map(str::trim).filter(|name| !name.is_empty()).collect()
}

/// A folder of numbered files: `<dir>/<prefix><k>.<extension>`.
pub struct NumberedFolder<'a> {
    /// The folder.
    pub dir: &'a Path,
    /// The start of the files' names, before the number.
    pub prefix: &'a str,
    /// The option that sets the interval, for messages (`--dump-every`).
    pub flag: &'a str,
    /// The option that sets the formats, for messages (`--dump-format`).
    pub format_flag: &'a str,
}

impl NumberedFolder<'_> {
    /// Refuses a resumed part that would number on another interval, or write other formats, than the folder's files
    /// were. Touches nothing.
    pub fn refuse_other_cadence(&self, ours: &FolderCadence) -> Result<(), String> {
        let Some(earlier) = self.recorded()? else { return Ok(()) };
        if earlier.interval != ours.interval {
            return Err(format!(
                "{} numbers its files on an interval of {} s, and this part would number on {} s, giving one number \
                 two times: resume with `{} {}`, or into a new --out",
                self.dir.display(),
                earlier.interval,
                ours.interval,
                self.flag,
                earlier.interval
            ));
        }
        if !earlier.formats.is_empty() && format_set(&earlier.formats) != format_set(&ours.formats) {
            return Err(format!(
                "{} holds files in {}, and this part would write {}, so that no format would cover the whole run: \
                 resume with `{} {}`, or into a new --out",
                self.dir.display(),
                earlier.formats,
                ours.formats,
                self.format_flag,
                earlier.formats
            ));
        }
        Ok(())
    }

    /// Removes the files numbered `first` or later (in every format), which a resumed part starting at its tick
    /// `first` writes again. Returns whether any file was removed; nothing happens in a folder that does not exist.
    pub fn remove_from(&self, first: u64) -> Result<bool, String> {
        let Ok(entries) = std::fs::read_dir(self.dir) else { return Ok(false) };
        let mut removed = false;
        for entry in entries.flatten() {
            let later = entry.file_name().to_str().and_then(|name| self.number_of(name)).is_some_and(|k| k >= first);
            if later && entry.file_type().is_ok_and(|kind| kind.is_file()) {
                std::fs::remove_file(entry.path())
                    .map_err(|e| format!("cannot remove {}: {e}", entry.path().display()))?;
                removed = true;
            }
        }
        Ok(removed)
    }

    /// Records `cadence` as the folder's (creating the folder).
    pub fn record(&self, cadence: &FolderCadence) -> Result<(), String> {
        std::fs::create_dir_all(self.dir).map_err(|e| format!("cannot create {}: {e}", self.dir.display()))?;
        let path = self.dir.join(CADENCE_FILE);
        std::fs::write(&path, cadence.text()).map_err(|e| format!("cannot write {}: {e}", path.display()))
    }

    /// The cadence recorded in the folder, if any (a folder an older version wrote has none).
    pub fn recorded(&self) -> Result<Option<FolderCadence>, String> {
        let path = self.dir.join(CADENCE_FILE);
        let Ok(text) = std::fs::read_to_string(&path) else { return Ok(None) };
        FolderCadence::parse(&text).map(Some).ok_or_else(|| {
            format!(
                "{} is damaged: it should hold the interval, formats and region the files were written with",
                path.display()
            )
        })
    }

    /// The number k of the file `name` (`<prefix><k>.<extension>`), if it is one of the folder's numbered files.
    fn number_of(&self, name: &str) -> Option<u64> {
        let (number, _extension) = name.strip_prefix(self.prefix)?.split_once('.')?;
        number.parse().ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dumps::StateDumps;

    fn cadence(interval: f64, formats: &str) -> FolderCadence {
        FolderCadence { interval, formats: formats.to_owned(), region: None }
    }

    #[test]
    fn a_resumed_part_removes_the_later_files_in_every_format_and_keeps_the_rest() {
        let dir = tempfile::tempdir().unwrap();
        let folder = NumberedFolder {
            dir: dir.path(),
            prefix: "particles_",
            flag: "--dump-every",
            format_flag: "--dump-format",
        };
        folder.record(&cadence(0.01, "csv,vtk")).unwrap();
        for name in ["particles_000001.csv", "particles_000002.vtu", "particles_000003.csv", "particles_000003.vtu"] {
            std::fs::write(dir.path().join(name), "").unwrap();
        }
        std::fs::write(dir.path().join("particles.pvd"), "").unwrap();
        folder.refuse_other_cadence(&cadence(0.01, "csv,vtk")).unwrap();
        assert!(folder.remove_from(2).unwrap());
        let mut left: Vec<String> =
            std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
        left.sort();
        assert_eq!(left, [CADENCE_FILE, "particles.pvd", "particles_000001.csv"]);
        let refused = folder.refuse_other_cadence(&cadence(0.02, "csv,vtk")).unwrap_err();
        assert!(refused.contains("interval of 0.01 s") && refused.contains("`--dump-every 0.01`"), "{refused}");
        let refused = folder.refuse_other_cadence(&cadence(0.01, "parquet")).unwrap_err();
        assert!(refused.contains("holds files in csv,vtk") && refused.contains("`--dump-format csv,vtk`"), "{refused}");
    }

    #[test]
    fn formats_recorded_in_another_order_or_twice_are_the_same_formats() {
        // QA docs 19: `parquet,csv` resumed with `csv,parquet`, and `csv,csv` with `csv`, were refused as other formats.
        let dir = tempfile::tempdir().unwrap();
        let folder = StateDumps::folder_at(dir.path());
        folder.record(&cadence(0.01, "parquet,csv")).unwrap();
        folder.refuse_other_cadence(&cadence(0.01, "csv,parquet")).unwrap();
        folder.record(&cadence(0.01, "csv,csv")).unwrap();
        folder.refuse_other_cadence(&cadence(0.01, "csv")).unwrap();
        assert!(folder.refuse_other_cadence(&cadence(0.01, "csv,vtk")).is_err());
    }

    #[test]
    fn the_dumps_record_each_format_once_in_one_order() {
        use crate::export::ExportFormat::{Csv, Parquet};
        let dumps = StateDumps::new(Path::new("out"), 0.01, Vec::new(), vec![Parquet, Csv, Csv]);
        assert_eq!(dumps.cadence().formats, "parquet,csv");
    }

    #[test]
    fn the_record_reads_back_with_its_region_and_the_first_versions_number_is_an_interval() {
        let region = Aabb { min: DVec2::new(-0.1, -0.01), max: DVec2::new(0.1, 0.2) };
        let recorded = FolderCadence { interval: 0.005, formats: "png".to_owned(), region: Some(region) };
        assert_eq!(FolderCadence::parse(&recorded.text()), Some(recorded));
        assert_eq!(FolderCadence::parse("0.002\n"), Some(cadence(0.002, "")));
        assert_eq!(FolderCadence::parse("interval_s = x\n"), None);
    }
}
