//! The outputs an earlier run left in the directory that a fresh run (not `--resume`) is about to write, removed
//! before it starts: a directory never holds two runs mixed, the new run's time series beside the old run's
//! checkpoints and dumps, which `export` and `--resume DIR` would then take for the newest state.

use crate::numbered_files::CADENCE_FILE;
use crate::outputs::TIME_SERIES_COLUMNS;
use crate::sinks::FRAMES_DIR;
use crate::transits::TRANSITS_FILE;
use gc2d_analysis::particle_state::csv::DUMPS_DIR;
use std::io;
use std::path::{Path, PathBuf};

/// Files a run writes at the top of its directory (its `scene.ron` is written again by the new run).
const RUN_FILES: [&str; 6] =
    ["final.ckpt", "summary.json", "segments.csv", "timeseries.csv", "events.csv", TRANSITS_FILE];

/// Folders a run writes, each with the start of the names of the files it writes there.
const RUN_FOLDERS: [(&str, &str); 3] =
    [("checkpoints", "checkpoint-"), (DUMPS_DIR, "particles"), (FRAMES_DIR, "frame-")];

/// Whether `dir` holds a run of gc2d-rs: its `segments.csv`, or a `timeseries.csv` that starts with a run's header
/// (runs older than `segments.csv` wrote only that). Only such a directory's output files are a run's to replace.
pub fn holds_a_run(dir: &Path) -> bool {
    if dir.join("segments.csv").is_file() {
        return true;
    }
    let Ok(file) = std::fs::File::open(dir.join("timeseries.csv")) else { return false };
    let mut header = String::new();
    io::BufRead::read_line(&mut io::BufReader::new(file), &mut header).is_ok()
        && header.starts_with(&TIME_SERIES_COLUMNS.join(","))
}

/// The files in `out` that have the names of a run's outputs (the list above, and the numbered files of its
/// folders), in the order they are listed there.
fn output_files(out: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = RUN_FILES.iter().map(|name| out.join(name)).filter(|path| path.is_file()).collect();
    for (folder, prefix) in RUN_FOLDERS {
        let Ok(entries) = std::fs::read_dir(out.join(folder)) else { continue };
        let mut numbered: Vec<PathBuf> = entries
            .flatten()
            .filter(|entry| {
                entry.file_name().to_str().is_some_and(|name| name.starts_with(prefix) || name == CADENCE_FILE)
                    && entry.file_type().is_ok_and(|kind| kind.is_file())
            })
            .map(|entry| entry.path())
            .collect();
        numbered.sort();
        files.extend(numbered);
    }
    files
}

/// Refuses a fresh run into `out` where it holds files with the names of a run's outputs but no run
/// ([`holds_a_run`]): the user's own `events.csv`, say, which the run would overwrite and [`remove_earlier_run`]
/// must not remove. Names the files. Called before any output starts, so that a refusal leaves `out` as it was.
pub fn refuse_files_of_no_run(out: &Path) -> Result<(), String> {
    if holds_a_run(out) {
        return Ok(());
    }
    let found = output_files(out);
    if found.is_empty() {
        return Ok(());
    }
    let shown: Vec<String> = found.iter().take(3).map(|path| path.display().to_string()).collect();
    let more =
        if found.len() > shown.len() { format!(" and {} more", found.len() - shown.len()) } else { String::new() };
    Err(format!(
        "{} holds {}{more}, which have the names of a run's outputs, but no run of gc2d-rs (it has neither segments.csv \
         nor a timeseries.csv of a run): a run would overwrite them. Give --out an empty or new directory, or move \
         those files away",
        out.display(),
        shown.join(", ")
    ))
}

/// Removes from `out` the files an earlier run wrote there (the list above, and the folders left empty by it) and
/// returns how many it removed; nothing where `out` holds no run ([`holds_a_run`]). Files of other names stay, and so
/// do the `analysis/` and `export/` folders that `analyze` and `export` write. An error names the file that could not
/// be removed.
pub fn remove_earlier_run(out: &Path) -> Result<usize, String> {
    if !holds_a_run(out) {
        return Ok(0);
    }
    let files = output_files(out);
    for path in &files {
        match std::fs::remove_file(path) {
            Ok(()) => {}
            Err(e) if e.kind() == io::ErrorKind::NotFound => {}
            Err(e) => {
                return Err(format!("cannot remove {} of the earlier run in {}: {e}", path.display(), out.display()));
            }
        }
    }
    for (folder, _) in RUN_FOLDERS {
        // Only an empty folder goes; one that holds files of the user's stays as it is.
        let _ = std::fs::remove_dir(out.join(folder));
    }
    Ok(files.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_files_a_run_writes_are_removed() {
        let out = tempfile::tempdir().unwrap();
        let dir = out.path();
        for folder in ["checkpoints", "dumps", FRAMES_DIR, "analysis"] {
            std::fs::create_dir(dir.join(folder)).unwrap();
        }
        let run_files =
            ["final.ckpt", "timeseries.csv", "checkpoints/checkpoint-0000000100.ckpt", "frames/frame-00000.png"];
        let kept = ["notes.txt", "scene.ron", "dumps/my_table.csv", "analysis/analysis.json"];
        for file in run_files.iter().chain(&kept) {
            std::fs::write(dir.join(file), "x").unwrap();
        }
        std::fs::write(dir.join("timeseries.csv"), TIME_SERIES_COLUMNS.join(",") + "\n").unwrap();
        assert_eq!(remove_earlier_run(dir), Ok(run_files.len()));
        assert!(run_files.iter().all(|file| !dir.join(file).exists()));
        assert!(kept.iter().all(|file| dir.join(file).exists()), "a file of the user's was removed");
        assert!(!dir.join("checkpoints").exists() && dir.join("dumps").exists());
        assert_eq!(remove_earlier_run(dir), Ok(0), "nothing left to remove");
    }

    #[test]
    fn output_names_in_a_folder_without_a_run_are_refused_not_removed() {
        let out = tempfile::tempdir().unwrap();
        let dir = out.path();
        std::fs::create_dir(dir.join("dumps")).unwrap();
        let users = ["events.csv", "transits.csv", "dumps/particles_000001.csv"];
        for file in users {
            std::fs::write(dir.join(file), "the user's").unwrap();
        }
        let refusal = refuse_files_of_no_run(dir).unwrap_err();
        assert!(refusal.contains("events.csv") && refusal.contains("no run of gc2d-rs"), "{refusal}");
        assert!(users.iter().all(|file| dir.join(file).exists()), "a file of the user's was removed");
        // A timeseries.csv of the user's does not make the folder a run's either.
        std::fs::write(dir.join("timeseries.csv"), "t,x\n0,1\n").unwrap();
        assert!(!holds_a_run(dir) && refuse_files_of_no_run(dir).is_err());
        assert_eq!(remove_earlier_run(dir), Ok(0), "a folder without a run loses nothing");
        // With a run's header it does, and then its outputs are replaced.
        std::fs::write(dir.join("timeseries.csv"), TIME_SERIES_COLUMNS.join(",") + "\n").unwrap();
        assert!(holds_a_run(dir) && refuse_files_of_no_run(dir).is_ok());
        assert_eq!(remove_earlier_run(dir), Ok(4));
        let empty = tempfile::tempdir().unwrap();
        assert_eq!(refuse_files_of_no_run(empty.path()), Ok(()));
    }
}
