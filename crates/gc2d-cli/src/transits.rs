//! `transits.csv`: one row per particle an outlet removed, with the inlet and time it came in and its mass (kg, or
//! kg/m per unit thickness) (docs/analysis.md,
//! "Feed pipe"). Written by every run of a scene with outlets; `gc2d-rs analyze RUN --kind feedpipe` reads it.
//!
//! Rows are written after the step that removed the particle, so the file is the same for any thread count; a resumed
//! run drops the rows the earlier run wrote after its checkpoint and writes them again.

use crate::csv_rows::write_whole_row;
use crate::resumed_csv::continue_csv;
use crate::runner::FrameSink;
use gc2d_engine::{Transit, World};
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// The file's name in a run directory.
pub const TRANSITS_FILE: &str = "transits.csv";

/// Column names of `transits.csv`, in order. `inlet` and `entered_s` are empty for a particle that did not come
/// through an inlet (present at the start, or from a source); `transit_time_s` is then empty too.
pub const TRANSIT_COLUMNS: [&str; 7] =
    ["particle", "inlet", "entered_s", "outlet", "left_s", "transit_time_s", "mass_kg"];

/// Appends the passages of every step to `transits.csv`; as a frame sink it flushes on the frame cadence and before
/// every checkpoint.
pub struct TransitsWriter {
    file: BufWriter<File>,
    flush_interval: f64,
}

impl TransitsWriter {
    /// Creates `path` (truncating it) with the header line.
    pub fn create(path: &Path, flush_interval: f64) -> io::Result<Self> {
        let mut file = BufWriter::new(File::create(path)?);
        writeln!(file, "{}", TRANSIT_COLUMNS.join(","))?;
        file.flush()?;
        Ok(Self { file, flush_interval })
    }

    /// Continues `path` for a run resumed at `resumed_at`: rows of particles removed after it (written by the earlier
    /// run after its checkpoint) and a half-written last line are dropped; the resumed run writes them again.
    pub fn continue_at(path: &Path, flush_interval: f64, resumed_at: f64, slack: f64) -> io::Result<Self> {
        let file = continue_csv(path, &TRANSIT_COLUMNS, 4, "transits", resumed_at, slack)?;
        Ok(Self { file: BufWriter::new(file), flush_interval })
    }

    fn write_row(&mut self, world: &World, transit: &Transit) -> io::Result<()> {
        let outlet = &world.outlets()[transit.outlet].outlet().name;
        // A removed particle's slot keeps its mass (slots are never reused).
        let mass = world.bodies().mass[transit.body.index()];
        match transit.entry {
            Some(entry) => write_whole_row(
                &mut self.file,
                format_args!(
                    "{},{},{},{},{},{:e},{mass:e}",
                    transit.body.0,
                    world.inlets()[entry.inlet].inlet().name,
                    entry.time,
                    outlet,
                    transit.time,
                    transit.time - entry.time
                ),
            ),
            None => write_whole_row(
                &mut self.file,
                format_args!("{},,,{},{},,{mass:e}", transit.body.0, outlet, transit.time),
            ),
        }
    }
}

impl FrameSink for TransitsWriter {
    fn interval(&self) -> f64 {
        self.flush_interval
    }

    /// Hands the rows written so far to the operating system.
    fn take(&mut self, _world: &World) -> Result<(), String> {
        self.flush()
    }

    /// Hands the rows written so far to the operating system (on the run's cadence, before a checkpoint and at its
    /// end).
    fn flush(&mut self) -> Result<(), String> {
        self.file.flush().map_err(|e| format!("{TRANSITS_FILE}: {e}"))
    }

    /// Writes the particles the outlets removed on the World's last step.
    fn after_step(&mut self, world: &World) -> Result<(), String> {
        for transit in world.transits() {
            self.write_row(world, transit).map_err(|e| format!("{TRANSITS_FILE}: {e}"))?;
        }
        Ok(())
    }
}
