//! `gc2d-rs run --dump-every T`: the state of every living particle every T of simulated time, one file per dump and
//! format in `<out>/dumps/`: `particles_<k>.csv` (the rows and the file format are gc2d-analysis's
//! [`particle_state`]), with `--dump-format` also `particles_<k>.parquet` (the export's particle table) and
//! `particles_<k>.vtu` with the collection `particles.pvd` listing every dump's `.vtu` at its nominal time k·T.
//!
//! Dump k is written at the first step at or after k·T (within half a step): the same files, byte for byte, for any
//! thread count and for a run split by a checkpoint, whose resumed part rewrites the dumps the stopped part wrote
//! after its checkpoint.
//!
//! [`particle_state`]: gc2d_analysis::particle_state

use crate::export::rows::{ParticleRow, particle_rows};
use crate::export::{ExportFormat, particle_columns, vtk};
use crate::numbered_files::{FolderCadence, NumberedFolder};
use crate::parquet_table::write_parquet;
use crate::runner::FrameSink;
use gc2d_analysis::particle_state::csv::{DUMPS_DIR, dump_file_name, write_csv};
use gc2d_analysis::particle_states;
use gc2d_engine::World;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// The VTK collection of the dumps' `.vtu` files.
const COLLECTION: &str = "particles.pvd";

/// Writes a dump of the particles' state on its cadence.
pub struct StateDumps {
    dir: PathBuf,
    interval: f64,
    materials: Vec<String>,
    formats: Vec<ExportFormat>,
}

impl StateDumps {
    /// Dumps into `<out>/dumps/` every `interval` s in `formats` (each once, in a fixed order, however the option
    /// listed them); `materials` names the material ids.
    pub fn new(out: &Path, interval: f64, materials: Vec<String>, mut formats: Vec<ExportFormat>) -> Self {
        formats.sort();
        formats.dedup();
        Self { dir: out.join(DUMPS_DIR), interval, materials, formats }
    }

    /// Writes dump `index` of `world` in the format `format`; `rows` are the export's particle rows of `world`
    /// (Parquet and VTK write them; made once per dump).
    fn write(&self, world: &World, rows: &[ParticleRow], index: u64, format: ExportFormat) -> Result<(), String> {
        let name = dump_file_name(index);
        let path = match format {
            ExportFormat::Csv => self.dir.join(&name),
            ExportFormat::Parquet => self.dir.join(&name).with_extension("parquet"),
            ExportFormat::Vtk => self.dir.join(&name).with_extension("vtu"),
        };
        let failed = |e: &dyn std::fmt::Display| format!("cannot write {}: {e}", path.display());
        match format {
            ExportFormat::Csv => {
                let write = || -> std::io::Result<()> {
                    let mut file = BufWriter::new(std::fs::File::create(&path)?);
                    write_csv(&particle_states(world, &self.materials), &mut file)?;
                    file.flush()
                };
                write().map_err(|e| failed(&e))
            }
            ExportFormat::Parquet => write_parquet("particles", &particle_columns(rows), &path).map_err(|e| failed(&e)),
            ExportFormat::Vtk => {
                std::fs::write(&path, vtk::particles_vtu(world, rows)).map_err(|e| failed(&e))?;
                self.write_collection(index)
            }
        }
    }

    /// The dumps' folder as a [`NumberedFolder`].
    pub fn folder(&self) -> NumberedFolder<'_> {
        Self::folder_at(&self.dir)
    }

    /// The dumps' folder `dir` (a run's `<out>/dumps/`) as a [`NumberedFolder`], for a part that writes none.
    pub fn folder_at(dir: &Path) -> NumberedFolder<'_> {
        NumberedFolder { dir, prefix: "particles_", flag: "--dump-every", format_flag: "--dump-format" }
    }

    /// The interval and formats the dumps are written with.
    pub fn cadence(&self) -> FolderCadence {
        let names: Vec<String> = self
            .formats
            .iter()
            .filter_map(|f| clap::ValueEnum::to_possible_value(f).map(|v| v.get_name().to_owned()))
            .collect();
        FolderCadence { interval: self.interval, formats: names.join(","), region: None }
    }

    /// Makes `dumps/` ready for a part of the run that starts at `world`'s time (after
    /// [`NumberedFolder::refuse_other_cadence`] for a resumed one): a resumed part removes the earlier part's dumps
    /// from its own first one on, in every format, and writes `particles.pvd` again without them; every part records
    /// its cadence.
    pub fn prepare(&self, world: &World, resumed: bool) -> Result<(), String> {
        let folder = self.folder();
        if resumed {
            let first = crate::runner::first_tick(self.interval, world.time(), 0.5 * world.time_step());
            if folder.remove_from(first)? && self.dir.join(COLLECTION).is_file() {
                self.write_collection(first.saturating_sub(1))?;
            }
        }
        folder.record(&self.cadence())
    }

    /// Rewrites `particles.pvd` with every dump's `.vtu` up to `last` that exists, at its nominal time k·T.
    fn write_collection(&self, last: u64) -> Result<(), String> {
        let names: Vec<(f64, PathBuf)> = (0..=last)
            .map(|k| (nominal_time(k, self.interval), PathBuf::from(dump_file_name(k)).with_extension("vtu")))
            .filter(|(_, name)| self.dir.join(name).is_file())
            .collect();
        let entries: Vec<(f64, &Path)> = names.iter().map(|(t, name)| (*t, name.as_path())).collect();
        let path = self.dir.join(COLLECTION);
        std::fs::write(&path, vtk::collection(&entries)).map_err(|e| format!("cannot write {}: {e}", path.display()))
    }
}

/// The nominal time k·T of dump `k`, rounded to 12 significant digits: the product's last bit (3 × 0.1 =
/// 0.30000000000000004) would show in the collection as `3.0000000000000004e-1`.
fn nominal_time(k: u64, interval: f64) -> f64 {
    gc2d_scene::rounded_to_significant_digits(k as f64 * interval, 12)
}

impl FrameSink for StateDumps {
    fn interval(&self) -> f64 {
        self.interval
    }

    fn take(&mut self, world: &World) -> Result<(), String> {
        std::fs::create_dir_all(&self.dir).map_err(|e| format!("cannot create {}: {e}", self.dir.display()))?;
        let index = crate::runner::cadence_index(world, self.interval);
        let needs_rows = self.formats.iter().any(|&f| f != ExportFormat::Csv);
        let rows = if needs_rows { particle_rows(world, &self.materials, None) } else { Vec::new() };
        self.formats.iter().try_for_each(|&format| self.write(world, &rows, index, format))
    }
}

#[cfg(test)]
mod tests {
    use super::nominal_time;

    #[test]
    fn nominal_times_are_written_without_the_products_last_bit() {
        assert_eq!(3.0 * 0.1, 0.30000000000000004);
        assert_eq!(nominal_time(3, 0.1), 0.3);
        assert_eq!(format!("{:e}", nominal_time(3, 0.1)), "3e-1");
        assert_eq!(nominal_time(0, 0.1), 0.0);
        assert_eq!(nominal_time(7, 1.0 / 3.0), 2.33333333333);
        assert_eq!(nominal_time(1_000_000, 2.5e-4), 250.0);
    }
}
