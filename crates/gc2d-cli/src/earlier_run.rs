//! The outputs an earlier run left in the directory that a fresh run (not `--resume`) is about to write, removed
//! before it starts: a directory never holds two runs mixed, the new run's time series beside the old run's
//! checkpoints and dumps, which `export` and `--resume DIR` would then take for the newest state.

use crate::numbered_files::CADENCE_FILE;
use crate::transits::TRANSITS_FILE;
use gc2d_analysis::particle_state::csv::DUMPS_DIR;
use std::io;
use std::path::Path;

/// Files a run writes at the top of its directory (its `scene.ron` is written again by the new run).
const RUN_FILES: [&str; 6] =
    ["final.ckpt", "summary.json", "segments.csv", "timeseries.csv", "events.csv", TRANSITS_FILE];

/// Folders a run writes, each with the start of the names of the files it writes there.
const RUN_FOLDERS: [(&str, &str); 3] = [("checkpoints", "checkpoint-"), (DUMPS_DIR, "particles"), ("frames", "frame-")];

/// Removes from `out` the files an earlier run wrote there (the list above, and the folders left empty by it) and
/// returns how many it removed. Files of other names stay, and so do the `analysis/` and `export/` folders that
/// `analyze` and `export` write. An error names the file that could not be removed.
pub fn remove_earlier_run(out: &Path) -> Result<usize, String> {
    let mut removed = 0;
    let mut remove = |path: &Path| match std::fs::remove_file(path) {
        Ok(()) => {
            removed += 1;
            Ok(())
        }
        Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(format!("cannot remove {} of the earlier run in {}: {e}", path.display(), out.display())),
    };
    for name in RUN_FILES {
        remove(&out.join(name))?;
    }
    for (folder, prefix) in RUN_FOLDERS {
        let folder = out.join(folder);
        let Ok(entries) = std::fs::read_dir(&folder) else { continue };
        for entry in entries.flatten() {
            let is_run_file =
                entry.file_name().to_str().is_some_and(|name| name.starts_with(prefix) || name == CADENCE_FILE);
            if is_run_file && entry.file_type().is_ok_and(|kind| kind.is_file()) {
                remove(&entry.path())?;
            }
        }
        // Only an empty folder goes; one that holds files of the user's stays as it is.
        let _ = std::fs::remove_dir(&folder);
    }
    Ok(removed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_files_a_run_writes_are_removed() {
        let out = tempfile::tempdir().unwrap();
        let dir = out.path();
        for folder in ["checkpoints", "dumps", "frames", "analysis"] {
            std::fs::create_dir(dir.join(folder)).unwrap();
        }
        let run_files =
            ["final.ckpt", "timeseries.csv", "checkpoints/checkpoint-0000000100.ckpt", "frames/frame-00000.png"];
        let kept = ["notes.txt", "scene.ron", "dumps/my_table.csv", "analysis/analysis.json"];
        for file in run_files.iter().chain(&kept) {
            std::fs::write(dir.join(file), "x").unwrap();
        }
        assert_eq!(remove_earlier_run(dir), Ok(run_files.len()));
        assert!(run_files.iter().all(|file| !dir.join(file).exists()));
        assert!(kept.iter().all(|file| dir.join(file).exists()), "a file of the user's was removed");
        assert!(!dir.join("checkpoints").exists() && dir.join("dumps").exists());
        assert_eq!(remove_earlier_run(dir), Ok(0), "nothing left to remove");
    }
}
