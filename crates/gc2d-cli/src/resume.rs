//! Where `gc2d-rs run --resume` continues from: a checkpoint file as given, or the newest state a run directory
//! holds. A long run killed without warning (a batch system's wall-time limit, a closed session) leaves no
//! `final.ckpt`, only its periodic checkpoints; naming the directory spares the user finding the newest one.

use crate::console;
use crate::dumps::StateDumps;
use crate::earlier_run::holds_a_run;
use crate::outputs::SCENE_COPY;
use crate::sinks::{FRAMES_DIR, PngFrames};
use gc2d_analysis::particle_state::csv::DUMPS_DIR;
use gc2d_engine::World;
use gc2d_scene::Scene;
use std::path::{Path, PathBuf};

/// The file a run resumes from and the World it holds.
pub struct ResumePoint {
    /// The checkpoint that was loaded.
    pub path: PathBuf,
    /// Its state.
    pub world: World,
    /// Whether it is a periodic checkpoint further on than the run directory's `final.ckpt`, which is readable (a
    /// later resumed part of the run was killed): worth a note where the state is shown.
    pub later_than_final: bool,
}

/// Loads the state to resume from.
///
/// A file is loaded as it is. A directory (a run's `--out`) resumes from whichever of
/// its `final.ckpt` and its highest-numbered `checkpoints/checkpoint-<step>.ckpt` has taken more steps: `final.ckpt`
/// is missing after a kill, and older than the numbered ones when a later resumed run was killed. A `final.ckpt` that
/// cannot be read gives a warning, and the newest periodic checkpoint is taken where there is one. Errors name the
/// file and say why it cannot be used; an unreadable newest periodic checkpoint is reported, not silently skipped.
pub fn load_resume_point(from: &Path) -> Result<ResumePoint, String> {
    load_newest_state(from, "resume from")
}

/// [`load_resume_point`] for another use: `purpose` says what the caller cannot do in its errors ("cannot
/// `purpose` `path`: …"), e.g. "draw" for `snapshot`, which draws a killed run's newest state too.
pub fn load_newest_state(from: &Path, purpose: &str) -> Result<ResumePoint, String> {
    let load = |path: &Path| load(path, purpose);
    if !from.is_dir() {
        return load(from);
    }
    let final_checkpoint = from.join("final.ckpt");
    // A periodic checkpoint's name carries its step, so it is only loaded when it is the newer one.
    let numbered = highest_numbered_checkpoint(&from.join("checkpoints"))?;
    let final_point = match final_checkpoint.is_file().then(|| load(&final_checkpoint)) {
        None => None,
        Some(Ok(point)) => Some(point),
        // A damaged final.ckpt (a full disk, a copy cut short) leaves the periodic checkpoints, as `export` uses them.
        Some(Err(e)) if numbered.is_some() => {
            console::err(&format!("warning: {e}; the newest periodic checkpoint is taken instead"));
            None
        }
        Some(Err(e)) => return Err(e),
    };
    let newest = match (final_point, numbered) {
        (Some(point), Some((step, _))) if point.world.steps() >= step => Some(point),
        (final_point, Some((_, path))) => Some(ResumePoint { later_than_final: final_point.is_some(), ..load(&path)? }),
        (point, None) => point,
    };
    newest.ok_or_else(|| {
        if let Some(running) = crate::run_lock::still_running_without_checkpoint(from) {
            return format!("cannot {purpose} {}: {running}", from.display());
        }
        format!(
            "cannot {purpose} {}: the directory holds neither final.ckpt nor checkpoints/checkpoint-<step>.ckpt \
             (give a run's output directory or a checkpoint file; runs write periodic checkpoints with \
             --checkpoint-every)",
            from.display()
        )
    })
}

/// The run directory that `--resume FROM` continues by default: FROM itself where it is a directory; for a checkpoint
/// file, the run directory that holds it (as `final.ckpt` or under `checkpoints/`), recognised as a run's by
/// [`holds_a_run`]. `None` for a checkpoint kept outside a run directory.
pub fn run_directory_of(from: &Path) -> Option<PathBuf> {
    if from.is_dir() {
        return Some(from.to_path_buf());
    }
    let folder = folder_holding(from)?;
    holds_a_run(folder).then(|| folder.to_path_buf())
}

/// The folder a checkpoint file's run would be: the one it lies in, or the one above where it lies under
/// `checkpoints/`.
fn folder_holding(checkpoint: &Path) -> Option<&Path> {
    let folder = checkpoint.parent()?;
    if folder.file_name().is_some_and(|name| name == "checkpoints") { folder.parent() } else { Some(folder) }
}

/// Why `scene` (read from `scene_path`) cannot continue the run in `run_dir`: it is not the scene that run started
/// from, its `scene.ron`, apart from what a resumed run may change (its name and description, end time, output
/// cadences, seed and view). A resumed run goes on with the checkpoint's World, so an edited material, wall or law
/// would be silently ignored, and a scene of another kind would name the outputs after objects that are not there.
/// `None` where they agree, or where `run_dir` holds no readable `scene.ron` (then nothing is known to compare).
pub fn another_scene(scene: &Scene, scene_path: &Path, run_dir: &Path) -> Option<String> {
    let copy_path = run_dir.join(SCENE_COPY);
    let copy = Scene::from_path(&copy_path).ok()?;
    let comparable = |scene: &Scene| {
        let mut scene = scene.clone();
        scene.name.clear();
        scene.description.clear();
        scene.view = None;
        scene.run.end_time_s = 0.0;
        scene.run.frames_per_second = 0.0;
        scene.run.checkpoint_interval_s = None;
        scene.run.seed = 0;
        // The copy names the files it reads by absolute paths ([`crate::outputs::write_scene_copy`]).
        scene.anchor_file_names(&scene.folder()).ok()?;
        scene.to_ron_string().ok()
    };
    let (given, started) = (comparable(scene)?, comparable(&copy)?);
    let (line, (now, before)) =
        given.lines().zip(started.lines()).enumerate().find(|(_, (a, b))| a != b).or_else(|| {
            let lines = given.lines().count().min(started.lines().count());
            (given.lines().count() != started.lines().count()).then_some((lines, ("(the end)", "(the end)")))
        })?;
    Some(format!(
        "{} is not the scene the run in {} started from ({}): line {} of both written out in full reads `{}` against \
         `{}` there. A resumed run goes on with the checkpoint's state, so changes to the scene would be ignored \
         (only its end time, output cadences, seed, name, description and view may change); resume with {}, or start \
         a new run of the changed scene",
        scene_path.display(),
        run_dir.display(),
        copy_path.display(),
        line + 1,
        now.trim(),
        before.trim(),
        copy_path.display()
    ))
}

/// Why the checkpoint at `path`, whose state is `world`, cannot be continued in the directory `out`: `out` holds a run
/// ([`holds_a_run`]) and the checkpoint is not one of that run's states. It is one where it lies in `out` (as
/// `final.ckpt` or under `checkpoints/`), or where `out` kept a checkpoint of the same step with the same state (a
/// copy of it). Any other checkpoint, of another seed, scene or run, would go on in `out` with its own history: the
/// time series would hold two runs' rows, and the run's later checkpoints would be removed as if the user went back.
/// `None` where it may be continued there, or `out` holds no run.
pub fn not_a_state_of_the_run_in(out: &Path, path: &Path, world: &World) -> Option<String> {
    if !holds_a_run(out) {
        return None;
    }
    let canonical = |p: &Path| p.canonicalize().ok();
    if folder_holding(path).and_then(canonical).is_some_and(|folder| canonical(out) == Some(folder)) {
        return None;
    }
    let steps = world.steps();
    let mut own = vec![out.join("final.ckpt")];
    if let Ok(entries) = std::fs::read_dir(out.join("checkpoints")) {
        own.extend(
            entries
                .flatten()
                .filter(|e| e.file_name().to_str().and_then(checkpoint_step) == Some(steps))
                .map(|e| e.path()),
        );
    }
    let state = world.state_checksum().ok();
    let mut same_step = false;
    for candidate in own.iter().filter(|candidate| candidate.is_file()) {
        let Ok(kept) = World::load_checkpoint_file(candidate) else { continue };
        if kept.steps() == steps {
            same_step = true;
            if state.is_some() && kept.state_checksum().ok() == state {
                return None;
            }
        }
    }
    let why = if same_step {
        format!("its checkpoint of step {steps} holds another state (another seed, scene or start)")
    } else {
        format!("it kept no checkpoint of step {steps}")
    };
    Some(format!(
        "{} is not one of the states of the run in {} ({why}). Continued there, it would mix another run's rows into \
         that run's time series and remove its later checkpoints. Give --out a new directory to go on from the \
         checkpoint there, or --resume {} to continue the run it holds",
        path.display(),
        out.display(),
        out.display()
    ))
}

/// What a resumed part is asked to write of the outputs that may have been on in the parts before it.
pub struct ResumedOutputs {
    /// It records contact events (`--events`, or a mill's default).
    pub events: bool,
    /// `--no-events` was given: the events file may end at the checkpoint.
    pub events_stopped: bool,
    /// It writes dumps.
    pub dumps: bool,
    /// `--dump-every` was given (0 stops the dumps at the checkpoint).
    pub dump_interval_given: bool,
    /// It draws pictures.
    pub pictures: bool,
    /// `--png-every` was given (0 stops the pictures at the checkpoint).
    pub picture_interval_given: bool,
}

/// Refuses a resumed part that would leave an output of the earlier parts (`events.csv`, the dumps, the pictures)
/// ending at the checkpoint without being asked to: a resume without `--events`, `--dump-every` or `--png-every`, the
/// options the first part was given, would silently cut that output short of the run. `--no-events`,
/// `--dump-every 0` and `--png-every 0` stop them on purpose.
pub fn refuse_silently_stopped_outputs(out: &Path, asked: &ResumedOutputs) -> Result<(), String> {
    let events = out.join("events.csv");
    if !asked.events && !asked.events_stopped && events.is_file() {
        return Err(format!(
            "{} holds the contact events of the run up to the checkpoint, and this part would record none: add \
             --events to continue it to the end (or --no-events to let it end at the checkpoint)",
            events.display()
        ));
    }
    let dumps_dir = out.join(DUMPS_DIR);
    let dumps = StateDumps::folder_at(&dumps_dir);
    if !asked.dumps
        && !asked.dump_interval_given
        && let Some(earlier) = dumps.recorded()?
    {
        return Err(format!(
            "{} holds the dumps of the run up to the checkpoint, and this part would write none: add --dump-every {} \
             --dump-format {} to continue them to the end (or --dump-every 0 to let them end at the checkpoint)",
            dumps_dir.display(),
            earlier.interval,
            if earlier.formats.is_empty() { "csv" } else { &earlier.formats }
        ));
    }
    let frames_dir = out.join(FRAMES_DIR);
    if !asked.pictures
        && !asked.picture_interval_given
        && let Some(earlier) = PngFrames::folder_at(&frames_dir).recorded()?
    {
        return Err(format!(
            "{} holds the pictures of the run up to the checkpoint, and this part would draw none: add --png-every {} \
             to continue them to the end (or --png-every 0 to let them end at the checkpoint)",
            frames_dir.display(),
            earlier.interval
        ));
    }
    Ok(())
}

/// How many differences [`another_checkpoint`] lists; the rest are counted.
const LISTED_DIFFERENCES: usize = 3;

/// Why `scene` (read from `scene_path`) cannot continue `point`: the World it builds differs from the checkpoint's in
/// what a resumed run may not change ([`Scene::compare_with_checkpoint`]). This catches what [`another_scene`]
/// cannot: a checkpoint resumed outside its run directory, and a run directory's `scene.ron` edited by hand. A scene
/// that does not build is refused with its own errors.
pub fn another_checkpoint(scene: &Scene, scene_path: &Path, point: &ResumePoint) -> Result<(), String> {
    let differences =
        scene.compare_with_checkpoint(&point.world).map_err(|e| format!("{:?}", miette::Report::new(e)))?.differences;
    if differences.is_empty() {
        return Ok(());
    }
    let mut listed = differences.iter().take(LISTED_DIFFERENCES).cloned().collect::<Vec<_>>().join("; ");
    if differences.len() > LISTED_DIFFERENCES {
        listed.push_str(&format!("; and {} more", differences.len() - LISTED_DIFFERENCES));
    }
    Err(format!(
        "{} does not continue {}: {listed}. A resumed run goes on with the checkpoint's state, so changes to the scene \
         would be ignored (only its end time, output cadences, seed, name, description and view may change); resume \
         with the scene the run started from, or start a new run of the changed scene",
        scene_path.display(),
        point.path.display()
    ))
}

fn load(path: &Path, purpose: &str) -> Result<ResumePoint, String> {
    World::load_checkpoint_file(path)
        .map(|world| ResumePoint { path: path.to_path_buf(), world, later_than_final: false })
        .map_err(|e| format!("cannot {purpose} {}: {e}", path.display()))
}

/// The step and path of the `checkpoint-<step>.ckpt` in `folder` with the largest step, if the folder exists and
/// holds any.
fn highest_numbered_checkpoint(folder: &Path) -> Result<Option<(u64, PathBuf)>, String> {
    let Ok(entries) = std::fs::read_dir(folder) else { return Ok(None) };
    let mut newest: Option<(u64, PathBuf)> = None;
    for entry in entries {
        let entry = entry.map_err(|e| format!("cannot list {}: {e}", folder.display()))?;
        let name = entry.file_name();
        let Some(step) = name.to_str().and_then(checkpoint_step) else { continue };
        if newest.as_ref().is_none_or(|(best, _)| step > *best) {
            newest = Some((step, entry.path()));
        }
    }
    Ok(newest)
}

/// The checkpoints of the run directory `out` that are further on than `steps`, the state a resumed run continues
/// from: `final.ckpt` and `checkpoints/checkpoint-<step>.ckpt` of a stretch a resume from an earlier checkpoint goes
/// back from. `resumed_from` (the checkpoint loaded) is never among them.
pub fn later_checkpoints(out: &Path, resumed_from: &Path, steps: u64) -> Vec<PathBuf> {
    let mut later: Vec<PathBuf> = Vec::new();
    let final_checkpoint = out.join("final.ckpt");
    let same = |a: &Path, b: &Path| a.canonicalize().ok().is_some_and(|a| b.canonicalize().ok() == Some(a));
    if final_checkpoint.is_file()
        && !same(&final_checkpoint, resumed_from)
        && World::load_checkpoint_file(&final_checkpoint).is_ok_and(|world| world.steps() > steps)
    {
        later.push(final_checkpoint);
    }
    if let Ok(entries) = std::fs::read_dir(out.join("checkpoints")) {
        let mut numbered: Vec<PathBuf> = entries
            .flatten()
            .filter(|e| e.file_name().to_str().and_then(checkpoint_step).is_some_and(|step| step > steps))
            .map(|e| e.path())
            .collect();
        numbered.sort();
        later.extend(numbered);
    }
    later
}

/// Refuses, unless `go_back` is given, a resume from a checkpoint earlier than the states the run directory `out`
/// holds (`later`, from [`later_checkpoints`]): going back to it removes them, with the rows, events, dumps and
/// frames after it, which may be hours of a finished run's work.
pub fn refuse_going_back(out: &Path, later: &[PathBuf], time: f64, go_back: bool) -> Result<(), String> {
    if go_back || later.is_empty() {
        return Ok(());
    }
    let named: Vec<String> = later.iter().take(LISTED_DIFFERENCES).map(|path| path.display().to_string()).collect();
    let rest = later.len() - named.len();
    Err(format!(
        "{} holds later states of the run than the checkpoint ({}{}): going back to t = {time:.6} s would remove them, \
         and the rows, events, dumps and frames after it. Add --go-back to do so, or give --out a new directory to \
         go on from the checkpoint there and keep the run as it is",
        out.display(),
        named.join(", "),
        if rest > 0 { format!(" and {rest} more") } else { String::new() }
    ))
}

/// Removes `later` ([`later_checkpoints`]): they belong to the abandoned stretch of the run, as its later rows, dumps
/// and frames do, and `--resume DIR`, `export` and `snapshot` would otherwise take one of them for the run's newest
/// state. An error names a file that could not be removed.
pub fn remove_later_checkpoints(later: &[PathBuf]) -> Result<(), String> {
    for path in later {
        std::fs::remove_file(path).map_err(|e| format!("cannot remove {}: {e}", path.display()))?;
    }
    Ok(())
}

/// `<path>.tmp`: where a checkpoint, `segments.csv` or `summary.json` is written before it is renamed over `path`.
pub fn temporary_path(path: &Path) -> PathBuf {
    let mut name = path.as_os_str().to_owned();
    name.push(".tmp");
    PathBuf::from(name)
}

/// Removes the temporary files a process killed while writing (SIGKILL between writing a file and renaming it) left in
/// the run directory `out`: `final.ckpt.tmp`, `segments.csv.tmp`, `summary.json.tmp`,
/// `checkpoints/checkpoint-<step>.ckpt.tmp` and `frames/frame-<k>.png.tmp`. They are never read (a resume takes only
/// renamed files), so they would only sit there, possibly half written. Called when a run (fresh or resumed) starts in `out`; files that
/// cannot be removed are left.
pub fn remove_temporary_files(out: &Path) {
    for name in ["final.ckpt", "segments.csv", "summary.json"] {
        let _ = std::fs::remove_file(temporary_path(&out.join(name)));
    }
    remove_files_named(&out.join("checkpoints"), |name| name.strip_suffix(".tmp").and_then(checkpoint_step).is_some());
    // A picture is written as `frame-<k>.png.tmp` and renamed too.
    remove_files_named(&out.join(FRAMES_DIR), |name| name.starts_with("frame-") && name.ends_with(".png.tmp"));
}

/// Removes the files in `folder` whose names are `temporary`, leaving any that cannot be removed.
fn remove_files_named(folder: &Path, temporary: impl Fn(&str) -> bool) {
    let Ok(entries) = std::fs::read_dir(folder) else { return };
    for entry in entries.flatten() {
        if entry.file_name().to_str().is_some_and(&temporary) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// The step of a periodic checkpoint's file name, `checkpoint-<step>.ckpt`.
fn checkpoint_step(file_name: &str) -> Option<u64> {
    file_name.strip_prefix("checkpoint-")?.strip_suffix(".ckpt")?.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_periodic_checkpoint_names_give_a_step() {
        assert_eq!(checkpoint_step("checkpoint-0001909091.ckpt"), Some(1_909_091));
        assert_eq!(checkpoint_step("checkpoint-0001909091.ckpt.tmp"), None);
        assert_eq!(checkpoint_step("final.ckpt"), None);
        assert_eq!(checkpoint_step("checkpoint-.ckpt"), None);
    }

    #[test]
    fn a_run_directory_without_a_checkpoint_says_whether_a_run_is_still_writing_it() {
        // QA docs 8: a run in progress was asked whether it was a run directory at all.
        let dir = tempfile::tempdir().unwrap();
        let running = crate::run_lock::lock_run_directory(dir.path()).unwrap();
        let error = load_newest_state(dir.path(), "draw").err().unwrap();
        assert!(error.contains("a gc2d-rs run is still writing") && error.contains("no checkpoint yet"), "{error}");
        let export = crate::export::export(dir.path(), None, &[], &dir.path().join("export")).unwrap_err();
        assert!(export.starts_with("cannot export: a gc2d-rs run is still writing"), "{export}");
        drop(running);
        let error = load_newest_state(dir.path(), "draw").err().unwrap();
        assert!(error.contains("holds neither final.ckpt"), "{error}");
    }

    #[test]
    fn a_checkpoint_belongs_to_a_run_directory_only_where_a_run_lies() {
        let dir = tempfile::tempdir().unwrap();
        let checkpoint = dir.path().join("checkpoints").join("checkpoint-0000000010.ckpt");
        std::fs::create_dir_all(checkpoint.parent().unwrap()).unwrap();
        // The user's own table of that name is not a run's time series.
        std::fs::write(dir.path().join("timeseries.csv"), "a,b\n1,2\n").unwrap();
        assert_eq!(run_directory_of(&checkpoint), None);
        assert_eq!(run_directory_of(&dir.path().join("final.ckpt")), None);
        std::fs::write(dir.path().join("segments.csv"), "").unwrap();
        assert_eq!(run_directory_of(&checkpoint).as_deref(), Some(dir.path()));
        assert_eq!(run_directory_of(&dir.path().join("final.ckpt")).as_deref(), Some(dir.path()));
    }
}
