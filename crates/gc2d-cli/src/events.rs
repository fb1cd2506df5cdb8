//! `events.csv`: one row per finished contact episode, written while the run goes (`gc2d-rs run --events`).
//!
//! Each row is an episode from its first touching step to its first step apart (docs/model.md, "Contact events"):
//! the two bodies and their kinds and materials, the impact speeds at first touch, the largest overlap, the energy
//! dissipated, the impulse on body a, against a wall turning about a pivot the angular impulse it took, the contact
//! point at first touch (where the collision happened), and the scene's names of the two bodies (`walls[2]`,
//! `mill.balls #4`, `sources[0] #17`). Episodes still open when the run stops are in the final
//! checkpoint, not in the file; a resumed run writes them when they end.

use crate::csv_rows::write_whole_row;
use crate::object_names::ObjectNames;
use crate::resumed_csv::continue_csv;
use crate::runner::FrameSink;
use gc2d_analysis::particle_state::csv::quoted;
use gc2d_engine::{ContactEvent, ContactEventKind, World};
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// Column names of `events.csv`, in order.
pub const EVENT_COLUMNS: [&str; 20] = [
    "begin_time_s",
    "end_time_s",
    "a",
    "b",
    "kind_a",
    "kind_b",
    "material_a",
    "material_b",
    "impact_normal_speed_m_s",
    "impact_tangential_speed_m_s",
    "max_overlap_fraction",
    "dissipated_j",
    "impulse_on_a_x_n_s",
    "impulse_on_a_y_n_s",
    "wall_angular_impulse_n_m_s",
    "duration_s",
    "begin_x_m",
    "begin_y_m",
    "object_a",
    "object_b",
];

/// Appends the finished episodes of every step to `events.csv`; as a frame sink it flushes on the frame cadence and
/// before every checkpoint.
pub struct EventsWriter {
    file: BufWriter<File>,
    /// The scene's material names, by material id.
    materials: Vec<String>,
    /// The scene's names of the bodies.
    objects: ObjectNames,
    /// Simulated time between flushes, s.
    flush_interval: f64,
}

impl EventsWriter {
    /// Creates `path` (truncating it) with the header line; `materials` names the material ids, `objects` the
    /// bodies.
    pub fn create(path: &Path, materials: Vec<String>, objects: ObjectNames, flush_interval: f64) -> io::Result<Self> {
        let mut file = BufWriter::new(File::create(path)?);
        writeln!(file, "{}", EVENT_COLUMNS.join(","))?;
        file.flush()?;
        Ok(Self { file, materials, objects, flush_interval })
    }

    /// Continues `path` for a run resumed at `resumed_at`: episodes that ended after it (written by the earlier run
    /// after its checkpoint) and a half-written last line are dropped; the resumed run writes them again.
    pub fn continue_at(
        path: &Path,
        materials: Vec<String>,
        objects: ObjectNames,
        flush_interval: f64,
        resumed_at: f64,
        slack: f64,
    ) -> io::Result<Self> {
        let file = continue_csv(path, &EVENT_COLUMNS, 1, "events", resumed_at, slack)?;
        Ok(Self { file: BufWriter::new(file), materials, objects, flush_interval })
    }

    fn write_row(&mut self, world: &World, event: &ContactEvent) -> io::Result<()> {
        let kind = |id: gc2d_engine::BodyId| world.bodies().kind[id.index()].name();
        let name = |m: gc2d_engine::MaterialId| quoted(self.materials.get(m.index()).map_or("?", String::as_str));
        let e = &event.episode;
        let angular = event.wall_angular_impulse.map_or(String::new(), |l| format!("{l:e}"));
        write_whole_row(
            &mut self.file,
            format_args!(
                "{},{},{},{},{},{},{},{},{:e},{:e},{:e},{:e},{:e},{:e},{},{:e},{:e},{:e},{},{}",
                e.begin_time,
                event.time,
                event.a.0,
                event.b.0,
                kind(event.a),
                kind(event.b),
                name(event.materials[0]),
                name(event.materials[1]),
                e.impact_normal_speed,
                e.impact_tangential_speed,
                e.max_overlap,
                e.dissipated,
                e.impulse_on_a.x,
                e.impulse_on_a.y,
                angular,
                event.time - e.begin_time,
                e.begin_point.x,
                e.begin_point.y,
                quoted(&self.objects.name(world, event.a)),
                quoted(&self.objects.name(world, event.b)),
            ),
        )
    }
}

impl FrameSink for EventsWriter {
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
        self.file.flush().map_err(|e| format!("events.csv: {e}"))
    }

    /// Writes the episodes that ended on the World's last step.
    fn after_step(&mut self, world: &World) -> Result<(), String> {
        for event in world.contact_events().iter().filter(|e| e.kind == ContactEventKind::End) {
            self.write_row(world, event).map_err(|e| format!("events.csv: {e}"))?;
        }
        Ok(())
    }
}
