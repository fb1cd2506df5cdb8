//! Slurm: a job-array script with a task per chunk of points. Each task runs `gc2d-rs sweep SWEEP --task $I`, which
//! runs (or resumes) its points. Shortly before the time limit Slurm sends the script SIGTERM (`--signal=B:TERM@…`);
//! the script passes it on to the sweep, whose runs write their final checkpoints, and requeues the task
//! (`scontrol requeue`), which then resumes where it stopped. `gc2d-rs sweep SWEEP --collect` gathers the results.

use crate::failure::CommandFailure;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// The script's name in `<out>/slurm/`.
pub const SCRIPT: &str = "sweep.sbatch";

/// What the job array asks of Slurm.
#[derive(Debug, Clone, PartialEq)]
pub struct SlurmOptions {
    /// Points per array task.
    pub points_per_task: usize,
    /// Each task's time limit, in Slurm's format (`minutes`, `HH:MM:SS`, `D-HH:MM:SS`).
    pub time: String,
    /// Seconds before the time limit at which the task is told to stop (SIGTERM) and requeue.
    pub signal_s: u32,
    /// Worker threads of each run, and the CPUs each task asks for.
    pub threads: usize,
    /// `--checkpoint-every` of the runs, s.
    pub checkpoint_every_s: Option<f64>,
}

/// The number of array tasks for `points` points.
pub fn task_count(points: usize, points_per_task: usize) -> usize {
    points.div_ceil(points_per_task.max(1))
}

/// The points (indices) of array task `task`, or an error when there is no such task.
pub fn task_points(task: usize, points: usize, points_per_task: usize) -> Result<Range<usize>, CommandFailure> {
    let per = points_per_task.max(1);
    let tasks = task_count(points, per);
    if task >= tasks {
        return Err(CommandFailure::input(format!(
            "--task {task}: the sweep has {tasks} task{} of up to {per} point{} (0 to {})",
            if tasks == 1 { "" } else { "s" },
            if per == 1 { "" } else { "s" },
            tasks.saturating_sub(1)
        )));
    }
    Ok(task * per..((task + 1) * per).min(points))
}

/// The paths the script names, made absolute (a task runs wherever Slurm starts it).
pub struct ScriptPaths {
    /// This program.
    pub exe: PathBuf,
    /// The sweep file.
    pub sweep: PathBuf,
    /// The sweep's output directory.
    pub out: PathBuf,
}

/// Writes `<out>/slurm/sweep.sbatch` for `points` points and returns its path.
pub fn write_script(paths: &ScriptPaths, points: usize, options: &SlurmOptions) -> Result<PathBuf, CommandFailure> {
    let Some(limit_s) = time_limit_s(&options.time) else {
        return Err(CommandFailure::input(format!(
            "--time {}: give Slurm's format, minutes (30), HH:MM:SS (2:00:00) or D-HH:MM:SS (1-12:00:00)",
            options.time
        )));
    };
    if limit_s == 0 {
        return Err(CommandFailure::input(
            "--time 0: give each task a time limit (Slurm reads 0 as none, and the tasks would never be told to \
             checkpoint)",
        ));
    }
    if options.signal_s == 0 || u64::from(options.signal_s) >= limit_s {
        return Err(CommandFailure::input(format!(
            "--signal-before {} s with --time {} ({limit_s} s): the signal must come after the task starts and \
             leave time to write the checkpoints, so between 1 s and the time limit (the default, 120 s, suits limits \
             of ten minutes and more)",
            options.signal_s, options.time
        )));
    }
    let folder = paths.out.join("slurm");
    std::fs::create_dir_all(&folder)
        .map_err(|e| CommandFailure::failed(format!("cannot create {}: {e}", folder.display())))?;
    let path = folder.join(SCRIPT);
    std::fs::write(&path, script(paths, points, options))
        .map_err(|e| CommandFailure::failed(format!("cannot write {}: {e}", path.display())))?;
    Ok(path)
}

/// The job-array script.
pub fn script(paths: &ScriptPaths, points: usize, options: &SlurmOptions) -> String {
    let tasks = task_count(points, options.points_per_task);
    let name = paths.sweep.file_stem().map_or_else(|| "sweep".into(), |s| s.to_string_lossy().into_owned());
    let log = paths.out.join("slurm").join("task-%a.log");
    let checkpoint = options.checkpoint_every_s.map_or(String::new(), |t| format!(" --checkpoint-every {t}"));
    format!(
        r#"#!/bin/bash
# gc2d-rs sweep {sweep}: {points} points in {tasks} array tasks of up to {per} points each.
# Submit with `sbatch {script}`; gather the results afterwards with `gc2d-rs sweep {sweep} --out {out} --collect`.
#SBATCH --job-name=gc2d-{name}
#SBATCH --array=0-{last}
#SBATCH --time={time}
#SBATCH --ntasks=1
#SBATCH --cpus-per-task={threads}
#SBATCH --requeue
#SBATCH --signal=B:TERM@{signal}
#SBATCH --open-mode=append
#SBATCH --output={log}

# {signal} s before the time limit Slurm sends this script SIGTERM: it is passed on to the sweep, whose run writes its
# final checkpoint, and the task goes back into the queue; run again, it skips finished points and resumes the rest.
requeue() {{
    kill -TERM "$child" 2>/dev/null
    wait "$child"
    echo "task $SLURM_ARRAY_TASK_ID: time limit near, checkpoint written; requeued"
    scontrol requeue "${{SLURM_ARRAY_JOB_ID}}_${{SLURM_ARRAY_TASK_ID}}"
    exit 0
}}
trap requeue TERM
{exe} sweep {sweep} --out {out} --task "$SLURM_ARRAY_TASK_ID" --points-per-task {per} --threads {threads}{checkpoint} --quiet &
child=$!
wait "$child"
"#,
        sweep = quote(&paths.sweep),
        script = quote(&paths.out.join("slurm").join(SCRIPT)),
        exe = quote(&paths.exe),
        out = quote(&paths.out),
        log = log.display(),
        last = tasks.saturating_sub(1),
        per = options.points_per_task.max(1),
        time = options.time,
        threads = options.threads.max(1),
        signal = options.signal_s,
    )
}

/// A path in single quotes for the shell.
fn quote(path: &Path) -> String {
    format!("'{}'", path.display().to_string().replace('\'', r"'\''"))
}

/// Seconds of a time limit in Slurm's formats: `minutes`, `minutes:seconds`, `hours:minutes:seconds`, `days-hours`,
/// `days-hours:minutes` and `days-hours:minutes:seconds`; `None` for anything else.
fn time_limit_s(time: &str) -> Option<u64> {
    // Each number at most 10⁹, so that no sum below overflows.
    let number = |s: &str| {
        let digits = !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
        digits.then(|| s.parse::<u64>().ok().filter(|&n| n <= 1_000_000_000))?
    };
    let parts = |s: &str| s.split(':').map(number).collect::<Option<Vec<u64>>>();
    match time.split_once('-') {
        Some((days, rest)) => {
            let days = number(days)?;
            match parts(rest)?.as_slice() {
                [h] => Some(((days * 24 + h) * 60) * 60),
                [h, m] => Some(((days * 24 + h) * 60 + m) * 60),
                [h, m, s] => Some(((days * 24 + h) * 60 + m) * 60 + s),
                _ => None,
            }
        }
        None => match parts(time)?.as_slice() {
            [m] => Some(m * 60),
            [m, s] => Some(m * 60 + s),
            [h, m, s] => Some((h * 60 + m) * 60 + s),
            _ => None,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tasks_cover_the_points_in_chunks() {
        assert_eq!(task_count(10, 3), 4);
        assert_eq!(task_points(3, 10, 3).unwrap(), 9..10);
        assert_eq!(task_points(0, 10, 1).unwrap(), 0..1);
        assert!(task_points(4, 10, 3).is_err());
    }

    #[test]
    fn slurm_time_formats() {
        for (time, seconds) in [
            ("30", 1800),
            ("2:00:00", 7200),
            ("1-12:00:00", 129_600),
            ("1-12", 129_600),
            ("1-0:30", 88_200),
            ("90:00", 5400),
            ("1:00", 60),
        ] {
            assert_eq!(time_limit_s(time), Some(seconds), "{time}");
        }
        for bad in ["", "2h", "1:2:3:4", "-1", "1-", "1-2:3:4:5", "99999999999999999999", "9999999999999999-0"] {
            assert_eq!(time_limit_s(bad), None, "{bad}");
        }
    }
}
