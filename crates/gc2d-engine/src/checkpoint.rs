//! Restartable checkpoints: the whole state of a [`World`] in one file, so that a run split at a checkpoint ends
//! bitwise identical to the unsplit run (reference §10.1 item 19; gc2d's gso + gco pair, §9.10, §9.11).
//!
//! gc2d wrote the particles with their full predictor-corrector state (§3.5) and, per contact, the tangential spring
//! and the previous overlap area (§9.10), and recomputed everything else. gc2d-rs stores more, because more of its
//! state decides the next step's bits: the Gear states as scaled derivatives (converting to physical ones and back
//! rounds), the broadphase's endpoint order and its pair list *in list order* (forces are summed in pair order), the
//! warm-start features, the pair index, the contacts that ended but are not yet booked, the piston states, the
//! sources' next insertion times, the state of the random number generator, the energy ledger and the counters.
//! Only scratch buffers that every step clears before reading are left out.
//!
//! The file is a fixed header followed by the World in [postcard](https://docs.rs/postcard) encoding:
//!
//! | bytes | content |
//! |---|---|
//! | 8 | magic `GC2DCKPT` |
//! | 4 | format version, u32 little-endian ([`CHECKPOINT_FORMAT_VERSION`]) |
//! | 2 + n | program version (`CARGO_PKG_VERSION` of gc2d-engine): length u16 LE, then n UTF-8 bytes |
//! | 8 | payload length, u64 LE |
//! | 8 | FNV-1a 64 checksum of the payload, u64 LE |
//! | payload | the postcard-encoded World |
//!
//! postcard is not self-describing, so a reader must have the writer's exact layout: a file from another format or
//! program version is refused with an error naming both versions, and a truncated or corrupted file is refused by
//! its length or checksum before a byte of it is decoded.
//!
//! The checksum covers the payload only, so the header's program version is checked for plausibility before it is
//! compared: a length above [`MAX_PROGRAM_VERSION_LEN`], or bytes that do not form a version number
//! (`MAJOR.MINOR.PATCH` in digits, then optionally `-` or `+` and printable ASCII), is a damaged header
//! ([`CheckpointError::CorruptedHeader`]), never "another program version", and its bytes are never shown raw.
//! The file ends with the payload: the header gives its length, so a byte after it cannot be part of a checkpoint
//! and the file is refused ([`CheckpointError::TrailingBytes`]).

use crate::shape::ShapeKind;
use crate::world::World;
use std::fs::File;
use std::io::{self, BufReader, BufWriter, Read, Write};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// The first eight bytes of every checkpoint file.
pub const CHECKPOINT_MAGIC: [u8; 8] = *b"GC2DCKPT";

/// Version of the checkpoint layout. Bump it whenever a serialized type of the World changes; the test
/// `checkpoint_layout_is_pinned` fails until it is bumped.
pub const CHECKPOINT_FORMAT_VERSION: u32 = 18;

/// The program version written into, and required of, every checkpoint.
pub const PROGRAM_VERSION: &str = env!("CARGO_PKG_VERSION");

/// The longest program version a checkpoint's header may hold, bytes: a longer length field is damage (a version
/// like `0.1.0` takes five bytes, one with a pre-release and build tag a few dozen).
pub const MAX_PROGRAM_VERSION_LEN: usize = 64;

/// Why a checkpoint could not be written or read.
#[derive(Debug, Error)]
pub enum CheckpointError {
    /// The file could not be opened, read or written.
    #[error("checkpoint I/O failed: {0}")]
    Io(#[from] io::Error),
    /// The file does not start with [`CHECKPOINT_MAGIC`].
    #[error("not a gc2d-rs checkpoint: the file does not start with the magic bytes \"GC2DCKPT\"")]
    NotACheckpoint,
    /// The file uses another layout version.
    #[error("checkpoint format version {found} cannot be read by this program, which reads version {expected}")]
    FormatVersion {
        /// Version in the file.
        found: u32,
        /// Version this program reads.
        expected: u32,
    },
    /// The file was written by another program version (the layout may differ without a format bump, and restart
    /// equivalence is only promised within one version).
    #[error("checkpoint was written by gc2d-rs {found}; this is gc2d-rs {expected}, which only restarts its own")]
    ProgramVersion {
        /// Version in the file.
        found: String,
        /// Version of this program.
        expected: String,
    },
    /// A header field holds a value no writer produces: the length of the program version is beyond
    /// [`MAX_PROGRAM_VERSION_LEN`], or the version is not a version number. The header is not covered by the
    /// checksum, so this is how damage to it shows.
    #[error("checkpoint is corrupted (header): {field} {problem}")]
    CorruptedHeader {
        /// The damaged field.
        field: &'static str,
        /// What is wrong with it (file bytes appear only escaped, never raw).
        problem: String,
    },
    /// Bytes follow the payload whose length the header gives. A checkpoint file holds one checkpoint and nothing
    /// after it, so they are damage (data appended, or files joined); the file is refused rather than read in part,
    /// because a file that changed after it was written may have changed elsewhere too.
    #[error("checkpoint is corrupted: {extra} bytes follow the payload, where the header says the file ends")]
    TrailingBytes {
        /// Bytes after the payload.
        extra: u64,
    },
    /// The file ends before the header or the payload is complete.
    #[error("checkpoint is truncated: {what} needs {expected} bytes, only {found} are left in the file")]
    Truncated {
        /// The part that is incomplete.
        what: &'static str,
        /// Bytes that part needs.
        expected: u64,
        /// Bytes present.
        found: u64,
    },
    /// The payload's checksum does not match the header.
    #[error("checkpoint is corrupted: payload checksum {found:#018x} does not match the header's {expected:#018x}")]
    Corrupted {
        /// Checksum in the header.
        expected: u64,
        /// Checksum of the bytes read.
        found: u64,
    },
    /// The World could not be encoded, or the payload does not decode to a World.
    #[error("checkpoint payload could not be encoded or decoded: {0}")]
    Encoding(#[from] postcard::Error),
    /// The payload decoded, but to a World that breaks the engine's invariants.
    #[error("checkpoint holds an inconsistent World: {0}")]
    Inconsistent(String),
}

impl World {
    /// Writes the complete state to `writer` (header, then payload; see the [module docs](crate::checkpoint)).
    /// Restarting from it with [`World::load_checkpoint`] continues the run bit for bit.
    pub fn save_checkpoint<W: Write>(&self, mut writer: W) -> Result<(), CheckpointError> {
        let payload = postcard::to_stdvec(self)?;
        let version = PROGRAM_VERSION.as_bytes();
        let version_len = u16::try_from(version.len())
            .map_err(|_| CheckpointError::Inconsistent("program version string too long".into()))?;
        writer.write_all(&CHECKPOINT_MAGIC)?;
        writer.write_all(&CHECKPOINT_FORMAT_VERSION.to_le_bytes())?;
        writer.write_all(&version_len.to_le_bytes())?;
        writer.write_all(version)?;
        writer.write_all(&(payload.len() as u64).to_le_bytes())?;
        writer.write_all(&fnv1a64(&payload).to_le_bytes())?;
        writer.write_all(&payload)?;
        writer.flush()?;
        Ok(())
    }

    /// Reads one checkpoint from `reader`, which must end with it. Refuses, with an error saying why, anything that
    /// is not a complete, uncorrupted checkpoint of this format and program version, or that has bytes after it;
    /// never panics on bad input.
    pub fn load_checkpoint<R: Read>(mut reader: R) -> Result<World, CheckpointError> {
        let mut magic = [0; 8];
        read_header_field(&mut reader, &mut magic, "the magic number (GC2DCKPT)")?;
        if magic != CHECKPOINT_MAGIC {
            return Err(CheckpointError::NotACheckpoint);
        }
        let mut format = [0; 4];
        read_header_field(&mut reader, &mut format, "the format version")?;
        let format = u32::from_le_bytes(format);
        if format != CHECKPOINT_FORMAT_VERSION {
            return Err(CheckpointError::FormatVersion { found: format, expected: CHECKPOINT_FORMAT_VERSION });
        }
        let mut version_len = [0; 2];
        read_header_field(&mut reader, &mut version_len, "the program version length")?;
        let version_len = usize::from(u16::from_le_bytes(version_len));
        if version_len > MAX_PROGRAM_VERSION_LEN {
            return Err(CheckpointError::CorruptedHeader {
                field: "the program version length",
                problem: format!("is {version_len} bytes, more than the {MAX_PROGRAM_VERSION_LEN} a version may take"),
            });
        }
        let mut version = vec![0; version_len];
        read_header_field(&mut reader, &mut version, "the program version")?;
        if !is_version_number(&version) {
            return Err(CheckpointError::CorruptedHeader {
                field: "the program version",
                problem: format!("\"{}\" is not a version number", version.escape_ascii()),
            });
        }
        if version != PROGRAM_VERSION.as_bytes() {
            return Err(CheckpointError::ProgramVersion {
                found: String::from_utf8_lossy(&version).into_owned(),
                expected: PROGRAM_VERSION.to_owned(),
            });
        }
        let mut length = [0; 8];
        read_header_field(&mut reader, &mut length, "the payload length")?;
        let length = u64::from_le_bytes(length);
        let mut checksum = [0; 8];
        read_header_field(&mut reader, &mut checksum, "the checksum")?;
        let checksum = u64::from_le_bytes(checksum);
        // Reads at most `length` bytes, growing with the data actually present (a corrupted length allocates nothing).
        let mut payload = Vec::new();
        reader.by_ref().take(length).read_to_end(&mut payload)?;
        if payload.len() as u64 != length {
            return Err(CheckpointError::Truncated {
                what: "the payload",
                expected: length,
                found: payload.len() as u64,
            });
        }
        let found = fnv1a64(&payload);
        if found != checksum {
            return Err(CheckpointError::Corrupted { expected: checksum, found });
        }
        let extra = io::copy(&mut reader, &mut io::sink())?;
        if extra > 0 {
            return Err(CheckpointError::TrailingBytes { extra });
        }
        let (mut world, rest): (World, &[u8]) = postcard::take_from_bytes(&payload)?;
        if !rest.is_empty() {
            return Err(CheckpointError::Inconsistent(format!("{} bytes left over after the World", rest.len())));
        }
        check_consistency(&world)?;
        // Decoding grows the longer columns by doubling (serde preallocates at most 1 MiB of a sequence).
        world.shrink_to_fit();
        Ok(world)
    }

    /// Writes a checkpoint to `path` atomically: into `<path>.tmp`, synced to disk, then renamed over `path`, so a
    /// crash while writing (the power failure gc2d's checkpoints guard against) never leaves a half-written file
    /// under the real name.
    pub fn save_checkpoint_file(&self, path: impl AsRef<Path>) -> Result<(), CheckpointError> {
        let path = path.as_ref();
        let temporary = temporary_path(path);
        let mut writer = BufWriter::new(File::create(&temporary)?);
        self.save_checkpoint(&mut writer)?;
        writer.into_inner().map_err(|e| e.into_error())?.sync_all()?;
        std::fs::rename(&temporary, path)?;
        Ok(())
    }

    /// Reads a checkpoint written by [`World::save_checkpoint_file`] (or any file holding one checkpoint).
    pub fn load_checkpoint_file(path: impl AsRef<Path>) -> Result<World, CheckpointError> {
        World::load_checkpoint(BufReader::new(File::open(path)?))
    }

    /// The checksum a checkpoint of the current state carries (FNV-1a 64 of its payload): Worlds in the same state,
    /// bit for bit, give the same value. For checking determinism, e.g. across thread counts (`gc2d-rs bench`),
    /// without writing the state out.
    pub fn state_checksum(&self) -> Result<u64, CheckpointError> {
        Ok(fnv1a64(&postcard::to_stdvec(self)?))
    }
}

/// `<path>.tmp`, next to the target so that the final rename stays on one file system.
fn temporary_path(path: &Path) -> PathBuf {
    let mut name = path.as_os_str().to_owned();
    name.push(".tmp");
    PathBuf::from(name)
}

/// True for what a program version in a header can be: `MAJOR.MINOR.PATCH` in ASCII digits, optionally followed by
/// a pre-release (`-`) or build (`+`) tag of printable ASCII without spaces.
fn is_version_number(version: &[u8]) -> bool {
    let core_end = version.iter().position(|b| matches!(b, b'-' | b'+')).unwrap_or(version.len());
    let (core, tag) = version.split_at(core_end);
    let mut numbers = core.split(|&b| b == b'.');
    let numeric = numbers.by_ref().take(3).filter(|n| !n.is_empty() && n.iter().all(u8::is_ascii_digit)).count() == 3;
    numeric && numbers.next().is_none() && tag.iter().all(u8::is_ascii_graphic)
}

/// `read_exact` that reports an early end of input as [`CheckpointError::Truncated`].
fn read_header_field<R: Read>(reader: &mut R, field: &mut [u8], what: &'static str) -> Result<(), CheckpointError> {
    let mut filled = 0;
    while filled < field.len() {
        match reader.read(&mut field[filled..]) {
            Ok(0) => {
                return Err(CheckpointError::Truncated { what, expected: field.len() as u64, found: filled as u64 });
            }
            Ok(n) => filled += n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e.into()),
        }
    }
    Ok(())
}

/// FNV-1a, 64 bit. Every single-byte change alters the result (each step is a bijection of the running hash), which
/// is what a checksum against bit rot and partial writes needs; it is not a defence against deliberate tampering.
fn fnv1a64(bytes: &[u8]) -> u64 {
    const OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    bytes.iter().fold(OFFSET_BASIS, |hash, &byte| (hash ^ u64::from(byte)).wrapping_mul(PRIME))
}

/// The invariants the step relies on for indexing, checked through the public accessors: a decoded World that
/// passes the checksum satisfies them unless the file was forged, and then this turns a later panic into an error.
fn check_consistency(world: &World) -> Result<(), CheckpointError> {
    crate::integrator::TimeStep::new(world.config().time_step)
        .map_err(|e| CheckpointError::Inconsistent(e.to_string()))?;
    world.config().interactions.validate().map_err(|e| CheckpointError::Inconsistent(e.to_string()))?;
    let b = world.bodies();
    let n = b.len();
    let columns = [
        ("alive", b.alive.len()),
        ("shape", b.shape.len()),
        ("radius", b.radius.len()),
        ("material", b.material.len()),
        ("reach", b.reach.len()),
        ("travel", b.travel.len()),
        ("vertices", b.vertices.len()),
        ("pose", b.pose.len()),
        ("velocity", b.velocity.len()),
        ("angular_velocity", b.angular_velocity.len()),
        ("gear", b.gear.len()),
        ("mass", b.mass.len()),
        ("inertia", b.inertia.len()),
        ("inverse_mass", b.inverse_mass.len()),
        ("inverse_inertia", b.inverse_inertia.len()),
        ("area", b.area.len()),
        ("inscribed_radius", b.inscribed_radius.len()),
        ("force", b.force.len()),
        ("torque", b.torque.len()),
    ];
    if let Some((name, len)) = columns.iter().find(|(_, len)| *len != n) {
        return Err(CheckpointError::Inconsistent(format!("body column {name} has {len} entries for {n} bodies")));
    }
    if b.surface_velocity.len() > n {
        return Err(CheckpointError::Inconsistent(format!(
            "body column surface_velocity has {} entries for {n} bodies",
            b.surface_velocity.len()
        )));
    }
    if b.world_vertices.len() != b.body_vertices.len() {
        return Err(CheckpointError::Inconsistent("body-frame and world-frame vertex counts differ".into()));
    }
    let mut next_start = 0u64;
    for (i, range) in b.vertices.iter().enumerate() {
        let (start, len) = (u64::from(range.start), u64::from(range.len));
        let points_needed = match b.shape[i] {
            ShapeKind::Polygon => len >= 3,
            ShapeKind::Disk | ShapeKind::InnerCircle => len == 1,
            ShapeKind::Capsule => len == 2,
        };
        if start != next_start || !points_needed || start + len > b.body_vertices.len() as u64 {
            return Err(CheckpointError::Inconsistent(format!("body {i} has an invalid vertex range")));
        }
        next_start = start + len;
    }
    let materials = world.config().interactions.material_count();
    if let Some(i) = b.material.iter().position(|m| m.index() >= materials) {
        return Err(CheckpointError::Inconsistent(format!("body {i} has a material beyond the interaction table")));
    }
    if let Some((a, bb, _)) = world.pairs().find(|(a, bb, _)| !(a < bb && bb.index() < n)) {
        return Err(CheckpointError::Inconsistent(format!("pair ({}, {}) names a missing body", a.0, bb.0)));
    }
    Ok(())
}
