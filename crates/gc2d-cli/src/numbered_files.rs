//! Folders of files numbered on a cadence, `dumps/particles_<k>.*` and `frames/frame-<k>.png`, file k holding the
//! state at k·interval, across a resume. Each folder records its interval in [`CADENCE_FILE`]; a resumed part that
//! would number on another interval is refused (two intervals under one numbering gave files whose number no longer
//! told their time, and a `particles.pvd` with wrong times), and the files an earlier part wrote from the resumed
//! part's first tick on are removed, in every format, so that none of them outlives the resumed part's own.

use std::path::Path;

/// The file in a numbered folder that records the interval its files are numbered on, s.
pub const CADENCE_FILE: &str = ".gc2d-cadence";

/// A folder of numbered files: `<dir>/<prefix><k>.<extension>`.
pub struct NumberedFolder<'a> {
    /// The folder.
    pub dir: &'a Path,
    /// The start of the files' names, before the number.
    pub prefix: &'a str,
    /// The option that sets the interval, for messages (`--dump-every`).
    pub flag: &'a str,
}

impl NumberedFolder<'_> {
    /// Refuses a resumed part that would number on `interval` where the folder's files were numbered on another.
    /// Touches nothing.
    pub fn refuse_other_interval(&self, interval: f64) -> Result<(), String> {
        match self.recorded_interval()? {
            Some(earlier) if earlier != interval => Err(format!(
                "{} numbers its files on an interval of {earlier} s, and this part would number on {interval} s, \
                 giving one number two times: resume with `{} {earlier}`, or into a new --out",
                self.dir.display(),
                self.flag
            )),
            _ => Ok(()),
        }
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

    /// Records `interval` as the folder's cadence (creating the folder).
    pub fn record_interval(&self, interval: f64) -> Result<(), String> {
        std::fs::create_dir_all(self.dir).map_err(|e| format!("cannot create {}: {e}", self.dir.display()))?;
        let path = self.dir.join(CADENCE_FILE);
        std::fs::write(&path, format!("{interval:?}\n")).map_err(|e| format!("cannot write {}: {e}", path.display()))
    }

    /// The interval recorded in the folder, if any (a folder an older version wrote has none).
    fn recorded_interval(&self) -> Result<Option<f64>, String> {
        let path = self.dir.join(CADENCE_FILE);
        let Ok(text) = std::fs::read_to_string(&path) else { return Ok(None) };
        match text.trim().parse::<f64>() {
            Ok(interval) if interval.is_finite() && interval > 0.0 => Ok(Some(interval)),
            _ => Err(format!(
                "{} is damaged: it should hold the interval in seconds, not `{}`",
                path.display(),
                text.trim()
            )),
        }
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

    #[test]
    fn a_resumed_part_removes_the_later_files_in_every_format_and_keeps_the_rest() {
        let dir = tempfile::tempdir().unwrap();
        let folder = NumberedFolder { dir: dir.path(), prefix: "particles_", flag: "--dump-every" };
        folder.record_interval(0.01).unwrap();
        for name in ["particles_000001.csv", "particles_000002.vtu", "particles_000003.csv", "particles_000003.vtu"] {
            std::fs::write(dir.path().join(name), "").unwrap();
        }
        std::fs::write(dir.path().join("particles.pvd"), "").unwrap();
        folder.refuse_other_interval(0.01).unwrap();
        assert!(folder.remove_from(2).unwrap());
        let mut left: Vec<String> =
            std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
        left.sort();
        assert_eq!(left, [CADENCE_FILE, "particles.pvd", "particles_000001.csv"]);
        let refused = folder.refuse_other_interval(0.02).unwrap_err();
        assert!(refused.contains("interval of 0.01 s") && refused.contains("`--dump-every 0.01`"), "{refused}");
    }
}
