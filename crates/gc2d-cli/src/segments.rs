//! `segments.csv`: one row per process that worked on a run, the first and every resumed one, so that the compute
//! time of a run split over sessions, batch jobs or crashes adds up without bookkeeping by hand.
//!
//! A process writes its row when it starts and rewrites it on a cadence of simulated time and at its end, so a
//! process killed without warning (SIGKILL) still leaves its row with the wall time up to its last update and the
//! status `running`. The file is replaced atomically (written beside it, then renamed), never left half-written.

use crate::runner::FrameSink;
use gc2d_engine::World;
use std::io;
use std::path::{Path, PathBuf};
use std::time::{Instant, SystemTime, UNIX_EPOCH};

/// The header of `segments.csv`. `resumed_from` is last because a path may contain commas.
pub const SEGMENT_COLUMNS: &str = "started_unix_s,threads,from_time_s,to_time_s,steps,wall_s,status,resumed_from";

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
}

impl SegmentLog {
    /// Starts this process's row in `path`. A fresh run (`resumed_from` = `None`) starts a new file; a resumed run
    /// keeps the rows of the earlier processes (a missing or foreign file is started afresh). `interval` is the
    /// simulated time between updates.
    pub fn start(
        path: &Path,
        resumed_from: Option<&Path>,
        threads: usize,
        world: &World,
        interval: f64,
    ) -> io::Result<Self> {
        let earlier_rows = match resumed_from {
            Some(_) => earlier_rows(path),
            None => Vec::new(),
        };
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
            resumed_from: resumed_from.map(|p| p.display().to_string()).unwrap_or_default(),
            interval,
        };
        log.write(world, "running")?;
        Ok(log)
    }

    /// Rewrites this process's row with the World's time and steps, the wall time so far and `status`.
    pub fn write(&self, world: &World, status: &str) -> io::Result<()> {
        let row = format!(
            "{},{},{},{},{},{:.3},{status},{}",
            self.started_unix_s,
            self.threads,
            self.from_time_s,
            world.time(),
            world.steps() - self.from_steps,
            self.started.elapsed().as_secs_f64(),
            self.resumed_from
        );
        let mut text = String::from(SEGMENT_COLUMNS);
        for line in self.earlier_rows.iter().chain(std::iter::once(&row)) {
            text.push('\n');
            text.push_str(line);
        }
        text.push('\n');
        let mut temporary = self.path.clone().into_os_string();
        temporary.push(".tmp");
        std::fs::write(&temporary, text)?;
        std::fs::rename(&temporary, &self.path)
    }

    /// Wall-clock time of all processes of the run so far (the earlier rows' and this one's), s.
    pub fn total_wall_s(&self) -> f64 {
        self.earlier_wall_s + self.started.elapsed().as_secs_f64()
    }
}

impl FrameSink for SegmentLog {
    fn interval(&self) -> f64 {
        self.interval
    }

    fn take(&mut self, world: &World) -> Result<(), String> {
        self.write(world, "running").map_err(|e| format!("cannot write {}: {e}", self.path.display()))
    }
}

/// The data rows of an existing `segments.csv`, or none if it is missing or has another header.
fn earlier_rows(path: &Path) -> Vec<String> {
    let Ok(text) = std::fs::read_to_string(path) else { return Vec::new() };
    let mut lines = text.lines();
    if lines.next() != Some(SEGMENT_COLUMNS) {
        return Vec::new();
    }
    lines.filter(|line| !line.is_empty()).map(str::to_owned).collect()
}

/// The `wall_s` of a row.
fn wall_of(row: &str) -> Option<f64> {
    row.splitn(SEGMENT_COLUMNS.split(',').count(), ',').nth(WALL_COLUMN)?.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_wall_time_is_read_even_when_the_path_holds_commas() {
        let row = "1763766000,1,2.1,2.8,636364,4180.250,running,runs/a,b/checkpoint-0001909091.ckpt";
        assert_eq!(wall_of(row), Some(4180.25));
        assert_eq!(SEGMENT_COLUMNS.split(',').nth(WALL_COLUMN), Some("wall_s"));
    }
}
