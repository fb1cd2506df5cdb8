//! The legacy gc2d input reader: `.gsi` files (reference §9.1–§9.9) into a typed [`GsiScene`].
//!
//! The reader works in stages, one module each: `encoding` decodes the bytes (UTF-8, else Latin-1); `lexer` splits
//! the text into lines of words (header, line length, comments, END_OF_FILE); `syntax` groups them into objects
//! using the vocabulary in `keywords`, checking each command's value count; the object
//! modules (`general`, `bodies`, `generators`) turn each object into typed values with gc2d's defaults and gc2d-rs
//! conventions (SI units, counter-clockwise angles); `part_size` settles how PART_SIZE is read. Every value keeps
//! the line it came from ([`Sourced`]), so later stages can name `file:line`. `convert` ([`to_scene`]) turns the
//! result into a RON [`crate::Scene`], warning about every written command the scene cannot hold, and reports the
//! values the scene refuses at their gsi lines (`locate` maps a scene field back to its command).
//!
//! ```
//! use gc2d_scene::gsi::{ImportOptions, parse_gsi};
//!
//! let text = "PARAMETER v1.4\n\nDelta_T 1e-5\nG 0\nWALL\nCorners\n0 0\n1 0\n1 1\nEND\nEND_OF_FILE\n";
//! let import = parse_gsi(text, &ImportOptions::default()).unwrap();
//! assert_eq!(import.scene.general.time_step.value, 1e-5);
//! assert_eq!(import.scene.walls[0].corners.line(), 6);
//! ```

mod bodies;
mod convert;
mod diagnostics;
mod encoding;
mod general;
mod generators;
mod keywords;
mod lattice;
mod lexer;
mod locate;
mod part_size;
mod reader;
mod scene;
mod syntax;

#[cfg(test)]
mod tests;

pub use convert::{GsiConversion, IMPORTED_MATERIAL, to_scene};
pub use diagnostics::{GsiError, GsiErrorKind, GsiErrors, GsiWarning, GsiWarningKind, Note};
pub use encoding::decode_gsi;
pub use lattice::MAX_GRID_SITES;
pub use lexer::MAX_LINE_LENGTH;
pub use part_size::{ImportOptions, PartSizeConvention};
pub use scene::{
    BIG_NUMBER, Bounds, GsiBlock, GsiDisplay, GsiDrag, GsiDropSource, GsiGeneral, GsiGravity, GsiHeating, GsiParticle,
    GsiPiston, GsiScene, GsiShape, GsiVibration, GsiWall, GsiWallMotion, Origin, PartSizeReading, Sourced,
};

use diagnostics::Diagnostics;
use keywords::{ObjectKind, object_or_command_name};
use reader::ObjectReader;

/// A successfully read gsi file: the scene, the `$` comments to print, and the warnings.
#[derive(Debug, Clone, PartialEq)]
pub struct GsiImport {
    /// The scene.
    pub scene: GsiScene,
    /// The `$` comments, in file order; gc2d prints them when it reads the file.
    pub notes: Vec<Note>,
    /// Things read differently from what the file may intend, or ignored, in line order.
    pub warnings: Vec<GsiWarning>,
}

/// Reads a gsi file from its bytes: UTF-8, or Latin-1 with a warning (see [`decode_gsi`]), then as [`parse_gsi`]
/// does.
pub fn parse_gsi_bytes(bytes: &[u8], options: &ImportOptions) -> Result<GsiImport, GsiErrors> {
    let (text, encoding_warning) = decode_gsi(bytes);
    let mut import = parse_gsi(&text, options)?;
    if let Some(warning) = encoding_warning {
        import.warnings.push(warning);
        import.warnings.sort_by_key(|warning| warning.line);
    }
    Ok(import)
}

/// Reads a gsi file. On failure every error found is returned, in line order.
pub fn parse_gsi(text: &str, options: &ImportOptions) -> Result<GsiImport, GsiErrors> {
    let mut diagnostics = Diagnostics::default();
    let lexed = lexer::lex(text, &mut diagnostics).map_err(|error| GsiErrors(vec![error]))?;
    if let Some(keyword) = lexed.identification.split_ascii_whitespace().next().and_then(object_or_command_name) {
        diagnostics.warn(2, GsiWarningKind::IdentificationLooksLikeCommand { keyword });
    }
    let objects = syntax::parse_objects(&lexed.statements, &mut diagnostics);
    let mut scene = GsiScene {
        identification: lexed.identification.to_string(),
        general: general::read_general(&mut ObjectReader::new(objects.general, &mut diagnostics)),
        display: None,
        particles: Vec::new(),
        walls: Vec::new(),
        blocks: Vec::new(),
        drop_sources: Vec::new(),
        part_size_reading: PartSizeReading::SemiAxes,
    };
    for object in objects.named {
        let kind = object.kind;
        let mut reader = ObjectReader::new(object, &mut diagnostics);
        match kind {
            // `parse_objects` refuses the name GENERAL, so no named object is GENERAL.
            ObjectKind::General => {}
            ObjectKind::Display => {
                let display = general::read_display(&mut reader);
                if let Some(replaced) = scene.display.replace(display) {
                    let used = reader.line();
                    reader.diagnostics.warn(replaced.line, GsiWarningKind::DisplayReplaced { used });
                }
            }
            ObjectKind::Particle => scene.particles.extend(bodies::read_particle(&mut reader)),
            ObjectKind::Wall => scene.walls.extend(bodies::read_wall(&mut reader)),
            ObjectKind::GenerateBlock => scene.blocks.extend(generators::read_block(&mut reader)),
            ObjectKind::DropSource => scene.drop_sources.push(generators::read_drop_source(&mut reader)),
        }
    }
    part_size::settle_part_size(&mut scene, options.part_size, &mut diagnostics);
    if lexed.end_of_file.is_none() {
        let last_line = text.lines().count().max(1);
        diagnostics.warn(last_line, GsiWarningKind::MissingEndOfFile);
    }
    let Diagnostics { mut errors, mut warnings } = diagnostics;
    if errors.is_empty() {
        warnings.sort_by_key(|warning| warning.line);
        Ok(GsiImport { scene, notes: lexed.notes, warnings })
    } else {
        errors.sort_by_key(|error| error.line);
        Err(GsiErrors(errors))
    }
}
