//! `gc2d-rs run --dump-every T`: the state of every living particle every T of simulated time, one CSV per dump in
//! `<out>/dumps/particles_<k>.csv` (the rows and the file format are gc2d-analysis's [`particle_state`]).
//!
//! Dump k is written at the first step at or after k·T (within half a step): the same files, byte for byte, for any
//! thread count and for a run split by a checkpoint, whose resumed part rewrites the dumps the stopped part wrote
//! after its checkpoint.
//!
//! [`particle_state`]: gc2d_analysis::particle_state

use crate::runner::FrameSink;
use gc2d_analysis::particle_state::csv::{DUMPS_DIR, dump_file_name, write_csv};
use gc2d_analysis::particle_states;
use gc2d_engine::World;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Writes a dump of the particles' state on its cadence.
pub struct StateDumps {
    dir: PathBuf,
    interval: f64,
    materials: Vec<String>,
}

impl StateDumps {
    /// Dumps into `<out>/dumps/` every `interval` s; `materials` names the material ids.
    pub fn new(out: &Path, interval: f64, materials: Vec<String>) -> Self {
        Self { dir: out.join(DUMPS_DIR), interval, materials }
    }

    /// The index of the last dump time reached at the World's time: ⌊(t + Δt/2)/T⌋.
    fn index(&self, world: &World) -> u64 {
        ((world.time() + 0.5 * world.time_step()) / self.interval).floor().max(0.0) as u64
    }
}

impl FrameSink for StateDumps {
    fn interval(&self) -> f64 {
        self.interval
    }

    fn take(&mut self, world: &World) -> Result<(), String> {
        std::fs::create_dir_all(&self.dir).map_err(|e| format!("cannot create {}: {e}", self.dir.display()))?;
        let path = self.dir.join(dump_file_name(self.index(world)));
        let write = || -> std::io::Result<()> {
            let mut file = BufWriter::new(std::fs::File::create(&path)?);
            write_csv(&particle_states(world, &self.materials), &mut file)?;
            file.flush()
        };
        write().map_err(|e| format!("cannot write {}: {e}", path.display()))
    }
}
