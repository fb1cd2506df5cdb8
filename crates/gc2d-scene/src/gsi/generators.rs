//! GENERATE_BLOCK and DROPSOURCE (reference §9.7, §9.8, §1.2): the shared shape commands with each object's
//! defaults, the lattice, the initial velocities and the drop source's timing.

use std::f64::consts::TAU;

use gc2d_engine::DropHeight;
use gc2d_geometry::{AngleMode, Randomization};

use super::diagnostics::{GsiErrorKind, GsiWarningKind};
use super::reader::ObjectReader;
use super::scene::{GsiBlock, GsiDropSource, GsiShape, PartSizeReading, Sourced};
use crate::schema::GridType;

/// The shape defaults that differ between GENERATE_BLOCK and DROPSOURCE, with the object's name and the default
/// PART_SIZE as the warning about a missing one shows it.
struct ShapeDefaults {
    object: &'static str,
    part_size: [f64; 2],
    part_size_text: &'static str,
    size_variation: f64,
    corners: u64,
}

const BLOCK_SHAPE: ShapeDefaults = ShapeDefaults {
    object: "GENERATE_BLOCK",
    part_size: [1.0, 1.0],
    part_size_text: "1 1 (m)",
    size_variation: 0.5,
    corners: 6,
};
const DROP_SHAPE: ShapeDefaults = ShapeDefaults {
    object: "DROPSOURCE",
    part_size: [0.01, 0.01],
    part_size_text: "0.01 0.01 (m)",
    size_variation: 0.1,
    corners: 8,
};

/// Reads the shape commands. PART_SIZE is provisionally read as semi-axes; the file-wide reading is settled once all
/// objects are read (see `part_size`). A missing PART_SIZE warns: the default sets the size of every particle.
fn read_shape(reader: &mut ObjectReader<'_, '_>, defaults: &ShapeDefaults) -> GsiShape {
    let part_size = reader.vector("PART_SIZE", defaults.part_size);
    reader.warn_if_defaulted(
        &part_size,
        GsiWarningKind::DefaultUsed {
            keyword: "PART_SIZE",
            object: defaults.object,
            default: defaults.part_size_text,
            consequence: "every particle's size is this default (semi-axes or full axes as the file's PART_SIZE \
                          reading says)",
        },
    );
    GsiShape {
        part_size,
        reading: PartSizeReading::SemiAxes,
        size_variation: reader.float("PART_VAR_SIZE", defaults.size_variation),
        size_randomization: reader.option("RANDOM_SIZE", Randomization::Const),
        corners: reader.whole("PART_NUM_CORNERS", defaults.corners),
        corner_variation: reader.whole("PART_VAR_CORNERS", 2),
        corner_randomization: reader.option("RANDOM_NUM_CORNERS", Randomization::Const),
        angle_mode: reader.option("PART_RANDOM_POS_CORNERS", AngleMode::Regular),
        rotation: reader.clockwise_angle("PART_ROT", 0.0),
        rotation_randomization: reader.option("RANDOM_ROT", Randomization::Const),
    }
}

/// Converts a GENERATE_BLOCK; `None` after an error (a lattice that cannot be laid out).
pub(super) fn read_block(reader: &mut ObjectReader<'_, '_>) -> Option<GsiBlock> {
    let block = GsiBlock {
        line: reader.line(),
        x_range: reader.bounds("X_RANGE", [0.0, 10.0]),
        y_range: reader.bounds("Y_RANGE", [0.0, 10.0]),
        grid_distance: reader.vector("GRID_DISTANCE", [2.0, 2.0]),
        grid_type: reader.option("GRID_TYPE", GridType::Fcc),
        shape: read_shape(reader, &BLOCK_SHAPE),
        velocity_direction_range: reader.bounds("ANGLE_RANGE", [0.0, TAU]),
        speed_range: reader.bounds("VELOCITY_RANGE", [0.0, 0.0]),
    };
    match block.check_grid() {
        Ok(()) => Some(block),
        Err((line, reason)) => {
            reader.diagnostics.error(line, GsiErrorKind::BadGrid { reason });
            None
        }
    }
}

/// Converts a DROPSOURCE.
pub(super) fn read_drop_source(reader: &mut ObjectReader<'_, '_>) -> GsiDropSource {
    GsiDropSource {
        line: reader.line(),
        position: reader.vector("POS", [0.0, 0.01]),
        width: reader.float("WIDTH", 0.0),
        height: read_drop_height(reader),
        window: reader.window("TIME", [0.0, 1.0]),
        interval: reader.float("DELTA_T", 0.1),
        shape: read_shape(reader, &DROP_SHAPE),
    }
}

/// `TYPE`: ABS inserts at the source's y, REL that far above the highest particle below the source.
fn read_drop_height(reader: &mut ObjectReader<'_, '_>) -> Sourced<DropHeight> {
    let word = reader.word("TYPE", "ABS");
    let line = word.line();
    match word.value.to_ascii_uppercase().as_str() {
        "ABS" => word.map(|_| DropHeight::Absolute),
        "REL" => word.map(|_| DropHeight::AboveHighest),
        _ => {
            let message = format!("unknown drop height type `{}`; expected ABS or REL", word.value);
            reader.diagnostics.error(line, GsiErrorKind::BadOption { keyword: "TYPE", message });
            word.map(|_| DropHeight::Absolute)
        }
    }
}
