//! The Recorder: observes a World after each step and writes a frame to an MCAP file when the cadence says so.
//!
//! Topics (all in frame `world`, x-y plane, SI units):
//! - `/particles` — `foxglove.SceneUpdate`: every living particle as a filled, outlined polygon, coloured by
//!   [`RecordOptions::colour_by`], packed by body slot into entities `particles/<k>` of 1024 slots, each one
//!   triangle list with per-vertex colours and one line list.
//! - `/walls` — `foxglove.SceneUpdate`: the walls, in the first frame and then only in frames where a wall moved.
//! - `/contacts` — `foxglove.SceneUpdate`: the force network (reference §5.5), if enabled: one entity `forces`
//!   with a line list per width class.
//! - `/fluid` — `foxglove.SceneUpdate`: in a World with a fluid, its velocity as arrows on a grid under the
//!   particles, coloured by speed (one entity `fluid`, one line list); the channel exists only then.
//! - `/stats` — JSON ([`FrameStats`](crate::FrameStats)): time, energies, contacts, overlap, coordination.
//!
//! The file also holds a Metadata record `gc2d-rs` (program version, seed, command line, cadence) and, if given,
//! the scene file as an attachment. Log times are simulated nanoseconds since t = 0.

use crate::RecordError;
use crate::cadence::Cadence;
use crate::frame::FrameBuilder;
use crate::mcap_file::{Channel, McapFile};
use crate::quantities::{ColourBy, ColourRange};
use crate::stats::{STATS_JSON_SCHEMA, STATS_SCHEMA_NAME};
use foxglove::schemas::SceneUpdate;
use gc2d_engine::World;
use std::collections::BTreeMap;
use std::path::Path;

/// Something that watches a World as it runs; the run loop calls [`Observer::observe`] after every step (and once
/// before the first). The engine knows nothing of observers: the loop that owns the World drives them.
pub trait Observer {
    /// Why observing failed.
    type Error;

    /// Looks at the World; cheap when there is nothing to do, since it runs every step.
    fn observe(&mut self, world: &World) -> Result<(), Self::Error>;
}

/// Force lines of the largest force are this many mean inscribed radii wide (unless set explicitly).
pub const DEFAULT_FORCE_WIDTH_RADII: f64 = 0.5;

/// How a recording looks and how often it samples the run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RecordOptions {
    /// Frames per simulated second ([`Cadence::DEFAULT_FRAMES_PER_SECOND`] by default).
    pub frames_per_second: f64,
    /// What the particle colours show.
    pub colour_by: ColourBy,
    /// The range the colour map spans.
    pub colour_range: ColourRange,
    /// Write the `/contacts` force network.
    pub force_network: bool,
    /// Width of the largest force's lines, m. `None`: [`DEFAULT_FORCE_WIDTH_RADII`] mean inscribed radii of the
    /// particles of the first frame.
    pub force_line_max_width: Option<f64>,
}

impl Default for RecordOptions {
    fn default() -> Self {
        Self {
            frames_per_second: Cadence::DEFAULT_FRAMES_PER_SECOND,
            colour_by: ColourBy::default(),
            colour_range: ColourRange::default(),
            force_network: true,
            force_line_max_width: None,
        }
    }
}

/// Where a run came from, stored in the recording.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RunInfo {
    /// Version of the program that ran the simulation.
    pub program_version: String,
    /// Seed of the run's random numbers.
    pub seed: u64,
    /// The command line, one argument per entry.
    pub command_line: Vec<String>,
    /// The scene file, stored as an attachment.
    pub scene: Option<SceneFile>,
}

/// A file to attach to the recording.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SceneFile {
    /// File name, as given on the command line.
    pub name: String,
    /// Media type, e.g. `text/plain`.
    pub media_type: String,
    /// Contents.
    pub data: Vec<u8>,
}

/// What a finished recording holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RecordingSummary {
    /// Frames written.
    pub frames: u64,
    /// Size of the file, bytes.
    pub bytes: u64,
}

/// The channels of a recording.
struct Channels {
    particles: Channel,
    walls: Channel,
    contacts: Channel,
    /// `/fluid`, added at the first frame that draws a fluid.
    fluid: Option<Channel>,
    stats: Channel,
}

/// Writes a run to an MCAP file, one frame per cadence tick.
pub struct Recorder {
    file: Option<McapFile>,
    channels: Channels,
    cadence: Cadence,
    builder: FrameBuilder,
    frames: u64,
    last_log_time: Option<u64>,
}

impl Recorder {
    /// Creates the recording at `path`, with its metadata and the scene attachment.
    pub fn create(path: &Path, options: RecordOptions, info: &RunInfo) -> Result<Self, RecordError> {
        let cadence = Cadence::new(options.frames_per_second)?;
        if let Some(w) = options.force_line_max_width
            && !(w > 0.0 && w.is_finite())
        {
            return Err(RecordError::InvalidOption(format!("force line width must be a positive length, got {w}")));
        }
        let mut file = McapFile::create(path, &format!("gc2d-rs {}", info.program_version))?;
        let channels = Channels {
            particles: file.add_protobuf_channel::<SceneUpdate>("/particles")?,
            walls: file.add_protobuf_channel::<SceneUpdate>("/walls")?,
            contacts: file.add_protobuf_channel::<SceneUpdate>("/contacts")?,
            fluid: None,
            stats: file.add_json_channel("/stats", STATS_SCHEMA_NAME, STATS_JSON_SCHEMA)?,
        };
        file.metadata("gc2d-rs", run_metadata(info, &options))?;
        if let Some(scene) = &info.scene {
            file.attach(&scene.name, &scene.media_type, &scene.data, 0)?;
        }
        file.end_frame()?;
        Ok(Self {
            file: Some(file),
            channels,
            cadence,
            builder: FrameBuilder::new(options),
            frames: 0,
            last_log_time: None,
        })
    }

    /// Frames written so far.
    pub fn frames(&self) -> u64 {
        self.frames
    }

    /// The cadence that decides when frames are due.
    pub fn cadence(&self) -> &Cadence {
        &self.cadence
    }

    /// Writes a frame of `world` now, due or not (e.g. the last state of a run). Returns false, writing nothing,
    /// when a frame at this simulated time was already written.
    pub fn record_frame(&mut self, world: &World) -> Result<bool, RecordError> {
        let log_time = simulated_nanoseconds(world.time());
        if self.last_log_time.is_some_and(|last| log_time <= last) {
            return Ok(false);
        }
        let Some(file) = self.file.as_mut() else { return Err(RecordError::Finished) };
        let frame = self.builder.build(world, log_time);
        file.write_protobuf(self.channels.particles, log_time, &frame.particles)?;
        if let Some(walls) = &frame.walls {
            file.write_protobuf(self.channels.walls, log_time, walls)?;
        }
        if let Some(contacts) = &frame.contacts {
            file.write_protobuf(self.channels.contacts, log_time, contacts)?;
        }
        if let Some(fluid) = &frame.fluid {
            let channel = match self.channels.fluid {
                Some(channel) => channel,
                None => *self.channels.fluid.insert(file.add_protobuf_channel::<SceneUpdate>("/fluid")?),
            };
            file.write_protobuf(channel, log_time, fluid)?;
        }
        file.write_json(self.channels.stats, log_time, &frame.stats.to_json())?;
        if self.frames == 0 {
            file.metadata("gc2d-rs.world", world_metadata(world))?;
        }
        file.end_frame()?;
        self.frames += 1;
        self.last_log_time = Some(log_time);
        self.cadence.mark_taken(world.time(), world.time_step());
        Ok(true)
    }

    /// Writes the summary and footer and closes the file.
    pub fn finish(mut self) -> Result<RecordingSummary, RecordError> {
        let file = self.file.take().ok_or(RecordError::Finished)?;
        let path = file.path().to_path_buf();
        file.finish()?;
        let bytes = std::fs::metadata(&path)
            .map_err(|source| RecordError::Io { path: path.display().to_string(), source })?
            .len();
        Ok(RecordingSummary { frames: self.frames, bytes })
    }
}

impl Observer for Recorder {
    type Error = RecordError;

    /// Writes a frame when the cadence says one is due; otherwise costs one comparison.
    fn observe(&mut self, world: &World) -> Result<(), RecordError> {
        if self.cadence.is_due(world.time(), world.time_step()) {
            self.record_frame(world)?;
        }
        Ok(())
    }
}

/// Simulated time as MCAP log time: nanoseconds since t = 0 (negative and non-finite times map to 0).
pub fn simulated_nanoseconds(time: f64) -> u64 {
    let ns = (time * 1e9).round();
    if ns.is_finite() && ns > 0.0 { ns.min(u64::MAX as f64) as u64 } else { 0 }
}

/// The `gc2d-rs` Metadata record.
fn run_metadata(info: &RunInfo, options: &RecordOptions) -> BTreeMap<String, String> {
    let mut m = BTreeMap::new();
    m.insert("program_version".into(), info.program_version.clone());
    m.insert("seed".into(), info.seed.to_string());
    m.insert("command_line".into(), serde_json::Value::from(info.command_line.clone()).to_string());
    m.insert("frames_per_second".into(), options.frames_per_second.to_string());
    m.insert("colour_by".into(), format!("{:?}", options.colour_by).to_lowercase());
    m.insert("log_time".into(), "simulated nanoseconds since t = 0".into());
    m
}

/// The `gc2d-rs.world` Metadata record, written with the first frame.
fn world_metadata(world: &World) -> BTreeMap<String, String> {
    let mut m = BTreeMap::new();
    m.insert("time_step".into(), world.time_step().to_string());
    m.insert("seed".into(), world.config().seed.to_string());
    // The largest E of the overlap-area laws; none where every pair has a penetration law (a Hertz mill), whose
    // moduli are the materials' (it said 0 there).
    let moduli =
        world.config().interactions.models().iter().filter_map(|m| m.overlap_area()).map(|l| l.elastic.e_modulus);
    if let Some(largest) = moduli.reduce(f64::max) {
        m.insert("e_modulus".into(), largest.to_string());
    }
    m.insert("bodies".into(), world.bodies().len().to_string());
    m
}
