//! `segments.csv`: one row per process that worked on a run, the first and every resumed one, so that the compute
//! time of a run split over sessions, batch jobs or crashes adds up without bookkeeping by hand.
//!
//! A process writes its row when it starts and rewrites it on a cadence of simulated time and at its end, so a
//! process killed without warning (SIGKILL) still leaves its row with the wall time up to its last update and the
//! status `running`. A resumed process cuts such a row back to the time it resumes from (status `killed`, steps to
//! match, wall time kept), so that no row claims progress past the checkpoint the run continues from. The file is
//! replaced atomically (written beside it, then renamed), never left half-written.
//!
//! Each row also carries the largest force-alternation window of the run up to that row's last update (the chatter
//! watch's, `crate::chatter`), so that a resumed run's `summary.json` describes the chatter of the whole run: the
//! resumed process starts from the largest window the earlier rows saw up to the time it resumes from.

use crate::chatter::AlternationWindow;
use crate::runner::FrameSink;
use gc2d_engine::World;
use std::io;
use std::path::{Path, PathBuf};
use std::time::{Instant, SystemTime, UNIX_EPOCH};

/// The header of `segments.csv`. `resumed_from` is last because a path may contain commas. `largest_alternation` and
/// `largest_alternation_time_s` are the run's largest force-alternation window so far (its alternation and the
/// simulated time at its end, s), empty before a whole window was run.
pub const SEGMENT_COLUMNS: &str = "started_unix_s,threads,from_time_s,to_time_s,steps,wall_s,status,\
                                   largest_alternation,largest_alternation_time_s,resumed_from";

/// The header written before the rows carried the chatter columns; such a file's rows are read with those columns
/// empty.
const COLUMNS_WITHOUT_CHATTER: &str = "started_unix_s,threads,from_time_s,to_time_s,steps,wall_s,status,resumed_from";

/// Column of `wall_s` in [`SEGMENT_COLUMNS`].
const WALL_COLUMN: usize = 5;

/// This process's row of a run's `segments.csv`, and the rows of the processes before it.
pub struct SegmentLog {
    path: PathBuf,
    earlier_rows: Vec<String>,
    earlier_wall_s: f64,
    started_unix_s: u64,
    started: Instant,
    threads: usize,
    from_time_s: f64,
    from_steps: u64,
    resumed_from: String,
    interval: f64,
    largest: Option<AlternationWindow>,
}

impl SegmentLog {
    /// Starts this process's row in `path`. A fresh run (`resumed_from` = `None`) starts a new file; a resumed run
    /// keeps the rows of the earlier processes (a missing or foreign file is started afresh). `origin` is the
    /// `segments.csv` of the run a checkpoint continued in a new directory comes from: its chatter watch goes on from
    /// there, as in the run's own directory. `interval` is the simulated time between updates.
    pub fn start(
        path: &Path,
        resumed_from: Option<&Path>,
        origin: Option<&Path>,
        threads: usize,
        world: &World,
        interval: f64,
    ) -> io::Result<Self> {
        let slack = 0.5 * world.time_step();
        let rows = if resumed_from.is_some() { earlier_rows(path) } else { Vec::new() };
        let origin_rows = match origin {
            Some(origin) if resumed_from.is_some() && rows.is_empty() => earlier_rows(origin),
            _ => Vec::new(),
        };
        let largest = largest_up_to(if rows.is_empty() { &origin_rows } else { &rows }, world.time() + slack);
        let earlier_rows: Vec<String> = rows.iter().map(|row| cut_back(row, world.time(), slack)).collect();
        let earlier_wall_s = earlier_rows.iter().filter_map(|row| wall_of(row)).sum();
        let started_unix_s = SystemTime::now().duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs());
        let log = Self {
            path: path.to_path_buf(),
            earlier_rows,
            earlier_wall_s,
            started_unix_s,
            started: Instant::now(),
            threads,
            from_time_s: world.time(),
            from_steps: world.steps(),
            resumed_from: resumed_from.map(crate::outputs::absolute_path_text).unwrap_or_default(),
            interval,
            largest,
        };
        log.write(world, "running")?;
        Ok(log)
    }

    /// Rewrites this process's row with the World's time and steps, the wall time so far and `status`.
    pub fn write(&self, world: &World, status: &str) -> io::Result<()> {
        self.write_with_wall_time(world, status, self.started.elapsed().as_secs_f64())
    }

    /// Writes this process's last row with `status` and returns the wall-clock time of all processes of the run, s:
    /// the earlier rows' and the one just written, read from the clock once, so that `summary.json`'s total is the
    /// sum of the rows (to their millisecond rounding) however long the write takes.
    pub fn finish(&self, world: &World, status: &str) -> (io::Result<()>, f64) {
        let wall_s = self.started.elapsed().as_secs_f64();
        (self.write_with_wall_time(world, status, wall_s), self.earlier_wall_s + wall_s)
    }

    /// Rewrites this process's row with the World's time and steps, `wall_s` and `status`.
    fn write_with_wall_time(&self, world: &World, status: &str, wall_s: f64) -> io::Result<()> {
        let (alternation, time) = match self.largest {
            Some(window) => (window.alternation.to_string(), window.time_s.to_string()),
            None => (String::new(), String::new()),
        };
        let row = format!(
            "{},{},{},{},{},{:.3},{status},{alternation},{time},{}",
            self.started_unix_s,
            self.threads,
            self.from_time_s,
            world.time(),
            world.steps() - self.from_steps,
            wall_s,
            self.resumed_from
        );
        let mut text = String::from(SEGMENT_COLUMNS);
        for line in self.earlier_rows.iter().chain(std::iter::once(&row)) {
            text.push('\n');
            text.push_str(line);
        }
        text.push('\n');
        let temporary = crate::resume::temporary_path(&self.path);
        std::fs::write(&temporary, text)?;
        std::fs::rename(&temporary, &self.path)
    }

    /// The largest force-alternation window of the earlier processes up to the time this one resumes from (none for
    /// a fresh run): where the chatter watch of a resumed run starts.
    pub fn earlier_chatter(&self) -> Option<AlternationWindow> {
        self.largest
    }
}

impl FrameSink for SegmentLog {
    fn interval(&self) -> f64 {
        self.interval
    }

    fn take(&mut self, world: &World) -> Result<(), String> {
        self.write(world, "running").map_err(|e| format!("cannot write {}: {e}", self.path.display()))
    }

    fn largest_alternation(&mut self, window: AlternationWindow) {
        self.largest = Some(window);
    }
}

/// The data rows of an existing `segments.csv` in today's columns (a file written before the chatter columns has
/// them added empty), or none if it is missing or has another header.
fn earlier_rows(path: &Path) -> Vec<String> {
    let Ok(text) = std::fs::read_to_string(path) else { return Vec::new() };
    let mut lines = text.lines();
    let header = lines.next();
    let rows = lines.filter(|line| !line.is_empty());
    if header == Some(SEGMENT_COLUMNS) {
        rows.map(str::to_owned).collect()
    } else if header == Some(COLUMNS_WITHOUT_CHATTER) {
        rows.map(|row| match row.splitn(COLUMNS_WITHOUT_CHATTER.split(',').count(), ',').collect::<Vec<_>>()[..] {
            [ref before @ .., resumed_from] if before.len() == 7 => format!("{},,,{resumed_from}", before.join(",")),
            _ => row.to_owned(),
        })
        .collect()
    } else {
        Vec::new()
    }
}

/// The largest force-alternation window the rows carry that ended by `time`. Each row's window is the largest of the
/// run up to that row's last update, so the largest of those ending by `time` is the run's up to `time`, except that
/// a row updated after `time` (a process killed past the checkpoint the run resumes from) whose largest window came
/// after `time` says nothing about its windows before: those are lost, and the earlier rows' largest stands.
fn largest_up_to(rows: &[String], time: f64) -> Option<AlternationWindow> {
    let column = SEGMENT_COLUMNS.split(',').position(|c| c == "largest_alternation")?;
    rows.iter()
        .filter_map(|row| {
            let mut fields = row.splitn(SEGMENT_COLUMNS.split(',').count(), ',').skip(column);
            let alternation = fields.next()?.parse::<f64>().ok()?;
            let time_s = fields.next()?.parse::<f64>().ok()?;
            (alternation.is_finite() && time_s <= time).then_some(AlternationWindow { alternation, time_s })
        })
        .reduce(|a, b| if b.alternation > a.alternation { b } else { a })
}

/// An earlier row as the run resumed at `time` keeps it. A row that claims progress past `time` (a process killed
/// after its last checkpoint had run on, or one whose later checkpoint the user passed over) is cut back: `to_time_s`
/// to `time` (not before its `from_time_s`), `steps` in proportion (Δt is fixed for a run). A `running` status, which
/// only a killed process leaves (the resumed one holds the directory's lock, so no other runs there), becomes `killed`,
/// also where the row ends at `time` (a process killed right after a checkpoint); a `completed` or `interrupted` row
/// that is cut back becomes `superseded` (its end was not where it now ends: a later process went back to an earlier
/// checkpoint). A cut row's largest force-alternation window is left empty where it ended after `time`: it lay in the
/// part cut away, and the row says nothing of the windows before. `wall_s` stays: that time was spent. Other rows
/// ending within `slack` (half a step) of `time`, and rows that do not parse, are kept as they are.
fn cut_back(row: &str, time: f64, slack: f64) -> String {
    let fields: Vec<&str> = row.splitn(SEGMENT_COLUMNS.split(',').count(), ',').collect();
    let (Some(from), Some(to), Some(steps)) = (
        fields.get(2).and_then(|f| f.parse::<f64>().ok()),
        fields.get(3).and_then(|f| f.parse::<f64>().ok()),
        fields.get(4).and_then(|f| f.parse::<u64>().ok()),
    ) else {
        return row.to_owned();
    };
    if fields.len() < 7 || (to <= time + slack && fields[6] != "running") {
        return row.to_owned();
    }
    let mut cut: Vec<String> = fields.iter().map(|f| (*f).to_owned()).collect();
    if to > time + slack {
        let kept_to = time.max(from);
        let kept_steps = if to > from { (steps as f64 * (kept_to - from) / (to - from)).round() as u64 } else { 0 };
        cut[3] = kept_to.to_string();
        cut[4] = kept_steps.to_string();
        if matches!(fields[6], "completed" | "interrupted") {
            cut[6] = "superseded".to_owned();
        }
        if fields.get(8).and_then(|f| f.parse::<f64>().ok()).is_some_and(|window_end| window_end > kept_to + slack) {
            cut[7].clear();
            cut[8].clear();
        }
    }
    if fields[6] == "running" {
        cut[6] = "killed".to_owned();
    }
    cut.join(",")
}

/// The `wall_s` of a row.
fn wall_of(row: &str) -> Option<f64> {
    row.splitn(SEGMENT_COLUMNS.split(',').count(), ',').nth(WALL_COLUMN)?.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_past_the_resume_time_are_cut_back_to_it() {
        // Killed at t = 0.5 after 500 steps from 0.1; the resume continues from the checkpoint at t = 0.3.
        let row = "1763766000,2,0.1,0.5,500,12.500,running,0.02,0.45,runs/a,b/checkpoint-0000000100.ckpt";
        assert_eq!(
            cut_back(row, 0.3, 5e-4),
            "1763766000,2,0.1,0.3,250,12.500,killed,,,runs/a,b/checkpoint-0000000100.ckpt"
        );
        // A completed run resumed from an earlier checkpoint: its row no longer ends where it completed, and its largest
        // window (at 0.256 s) lies in the part cut away, while one at 0.05 s stays.
        let completed = "1763766000,2,0,0.3,300,1.496,completed,0.002,0.256,";
        assert_eq!(cut_back(completed, 0.1, 5e-4), "1763766000,2,0,0.1,100,1.496,superseded,,,");
        let early_window = "1763766000,2,0,0.3,300,1.496,completed,0.002,0.05,";
        assert_eq!(cut_back(early_window, 0.1, 5e-4), "1763766000,2,0,0.1,100,1.496,superseded,0.002,0.05,");
        // A row that ended at the resume time is kept; so is one ending within half a step of it.
        let finished = "1763766000,2,0,0.1,100,1.000,interrupted,,,";
        assert_eq!(cut_back(finished, 0.1, 5e-4), finished);
        assert_eq!(cut_back(finished, 0.0999, 5e-4), finished);
        // A process killed right after a checkpoint left its row ending there, still `running`: it is `killed`.
        let killed_at_checkpoint = "1763766000,2,0,0.3,300,3.000,running,,,";
        assert_eq!(cut_back(killed_at_checkpoint, 0.3, 5e-4), "1763766000,2,0,0.3,300,3.000,killed,,,");
        // Resumed from a checkpoint before the row began: nothing of it is kept.
        assert_eq!(
            cut_back(row, 0.05, 5e-4),
            "1763766000,2,0.1,0.1,0,12.500,killed,,,runs/a,b/checkpoint-0000000100.ckpt"
        );
        assert_eq!(cut_back("not a row", 0.0, 0.0), "not a row");
    }

    #[test]
    fn the_earlier_chatter_is_the_largest_window_up_to_the_resume_time() {
        let rows: Vec<String> = [
            // The first process warned at 0.003 s; the second, killed at 0.05 s after the checkpoint at 0.04 s, saw a
            // larger window at 0.045 s (past the checkpoint: it does not count).
            "1763766000,2,0,0.02,6452,1.000,interrupted,1.0,0.0031,",
            "1763766001,2,0.02,0.05,9677,1.500,running,1.2,0.045,out/checkpoints/checkpoint-0000006452.ckpt",
            "1763766002,2,0.04,0.04,0,0.100,running,,,out/checkpoints/checkpoint-0000012903.ckpt",
            "not a row",
        ]
        .map(str::to_owned)
        .to_vec();
        assert_eq!(largest_up_to(&rows, 0.04), Some(AlternationWindow { alternation: 1.0, time_s: 0.0031 }));
        assert_eq!(largest_up_to(&rows, 0.05), Some(AlternationWindow { alternation: 1.2, time_s: 0.045 }));
        assert_eq!(largest_up_to(&rows, 0.001), None);
    }

    #[test]
    fn a_file_written_before_the_chatter_columns_is_continued() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("segments.csv");
        std::fs::write(&path, format!("{COLUMNS_WITHOUT_CHATTER}\n1763766000,2,0,0.1,100,1.000,interrupted,\n1763766001,2,0.1,0.2,100,1.000,completed,runs/a,b/final.ckpt\n")).unwrap();
        assert_eq!(
            earlier_rows(&path),
            [
                "1763766000,2,0,0.1,100,1.000,interrupted,,,",
                "1763766001,2,0.1,0.2,100,1.000,completed,,,runs/a,b/final.ckpt"
            ]
        );
        std::fs::write(&path, "some,other,file\n1,2,3\n").unwrap();
        assert!(earlier_rows(&path).is_empty());
    }

    #[test]
    fn the_wall_time_is_read_even_when_the_path_holds_commas() {
        let row = "1763766000,1,2.1,2.8,636364,4180.250,running,0.003,2.5,runs/a,b/checkpoint-0001909091.ckpt";
        assert_eq!(wall_of(row), Some(4180.25));
        assert_eq!(SEGMENT_COLUMNS.split(',').nth(WALL_COLUMN), Some("wall_s"));
    }

    #[test]
    fn the_total_of_a_finished_run_is_the_sum_of_its_rows() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("segments.csv");
        let scene_path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/scenes/tiny_pile.ron");
        let text = std::fs::read_to_string(scene_path).unwrap();
        let world = gc2d_scene::Scene::from_str(&text, "tiny_pile.ron").unwrap().build().unwrap();
        std::fs::write(&path, format!("{SEGMENT_COLUMNS}\n1763766000,2,0,0,0,2.250,interrupted,,,\n")).unwrap();
        let log = SegmentLog::start(&path, Some(Path::new("final.ckpt")), None, 1, &world, 1.0).unwrap();
        std::thread::sleep(std::time::Duration::from_millis(20));
        let (written, total) = log.finish(&world, "completed");
        written.unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let rows: Vec<f64> = text.lines().skip(1).map(|row| wall_of(row).unwrap()).collect();
        assert_eq!(rows.len(), 2, "{text}");
        assert!(rows[1] >= 0.02, "{text}");
        assert!((total - rows.iter().sum::<f64>()).abs() <= 0.0005, "total {total} s, rows {text}");
    }
}
