//! `gc2d-rs import-gsi`: a legacy gc2d input file (`.gsi`, reference §9) converted into a RON scene.
//!
//! The file is read with [`gc2d_scene::gsi::parse_gsi`] and converted with [`gc2d_scene::gsi::to_scene`]; the `$`
//! comments are printed as gc2d prints them, every warning is printed as `file:line: warning: …` and repeated in the
//! written scene's comment header, and the written scene is loaded back and built before the command succeeds.

use crate::failure::CommandFailure;
use gc2d_scene::Scene;
use gc2d_scene::gsi::{GsiWarning, PartSizeConvention, parse_gsi_bytes, to_scene};
use std::path::{Path, PathBuf};

/// How `--part-size` says PART_SIZE is read (see `docs/model.md`, D6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum PartSizeOption {
    /// Semi-axes, unless a GENERATE_BLOCK would start with its neighbours overlapping and full axes would not.
    #[default]
    Auto,
    /// PART_SIZE are the ellipse semi-axes (the thesis's particle "radius").
    SemiAxes,
    /// PART_SIZE are the full ellipse axes.
    FullAxes,
}

impl From<PartSizeOption> for PartSizeConvention {
    fn from(option: PartSizeOption) -> Self {
        match option {
            PartSizeOption::Auto => PartSizeConvention::Auto,
            PartSizeOption::SemiAxes => PartSizeConvention::SemiAxes,
            PartSizeOption::FullAxes => PartSizeConvention::FullAxes,
        }
    }
}

/// Converts `gsi` into a RON scene at `output` (default: `gsi` with the extension `.ron`), reading PART_SIZE as
/// `part_size` says; an existing `output` is replaced only with `force`. Returns the path written.
pub fn import_gsi(
    gsi: &Path,
    output: Option<&Path>,
    part_size: PartSizeOption,
    force: bool,
) -> Result<PathBuf, CommandFailure> {
    let output = output.map_or_else(|| gsi.with_extension("ron"), Path::to_path_buf);
    if output == gsi {
        return Err(CommandFailure::input(format!("the output {} would overwrite the input", output.display())));
    }
    if output.exists() && !force {
        return Err(CommandFailure::input(format!(
            "{} exists (perhaps a scene edited since an earlier import); write elsewhere with -o, or replace it with \
             --force",
            output.display()
        )));
    }
    let file = gsi.display().to_string();
    let bytes = std::fs::read(gsi).map_err(|e| CommandFailure::input(format!("cannot read {file}: {e}")))?;
    let located = |errors: gc2d_scene::gsi::GsiErrors| {
        let lines: Vec<String> = errors.0.iter().map(|error| error.located(&file)).collect();
        CommandFailure::input(lines.join("\n"))
    };
    let import =
        parse_gsi_bytes(&bytes, &gc2d_scene::gsi::ImportOptions { part_size: part_size.into() }).map_err(located)?;
    for note in &import.notes {
        // The comments are for reading along; a closed stdout does not stop the conversion.
        let _ = crate::console::out(&format!("{file}:{}: $ {}", note.line, note.text));
    }
    let name = output.file_stem().map_or_else(|| "imported".into(), |stem| stem.to_string_lossy().into_owned());
    let conversion = to_scene(&import, &name).map_err(located)?;
    for warning in &conversion.warnings {
        crate::console::err(&warning_line(&file, warning));
    }
    let ron = conversion.scene.to_ron_string().map_err(|e| CommandFailure::failed(format!("cannot write RON: {e}")))?;
    let written = format!("{}{ron}\n", header(&file, &name, &conversion.warnings));
    std::fs::write(&output, &written)
        .map_err(|e| CommandFailure::failed(format!("cannot write {}: {e}", output.display())))?;
    let output_name = output.display().to_string();
    let invalid = |error: gc2d_scene::SceneError| {
        CommandFailure::input(format!(
            "{output_name} was written but is not a valid scene:\n{:?}",
            miette::Report::new(error)
        ))
    };
    let summary = Scene::from_str(&written, &output_name).and_then(|scene| scene.summary()).map_err(invalid)?;
    crate::console::err(&format!(
        "Wrote {output_name}: {} walls, {} particles, {} sources, Δt = {} s{}.",
        summary.wall_bodies,
        summary.particles,
        summary.sources,
        gc2d_scene::significant_digits(summary.time_step_s, 4),
        if summary.time_step_is_automatic { " (automatic)" } else { "" }
    ));
    Ok(output)
}

/// A warning as `file:line: warning: message`.
fn warning_line(file: &str, warning: &GsiWarning) -> String {
    format!("{file}:{}: warning: {}", warning.line, warning.kind)
}

/// The comment header of the written scene: where it came from and every warning of the import.
fn header(file: &str, name: &str, warnings: &[GsiWarning]) -> String {
    let mut header = format!("// {name}.ron: imported from {file} with `gc2d-rs import-gsi`.\n");
    if !warnings.is_empty() {
        header.push_str("//\n// Warnings of the import:\n");
        for warning in warnings {
            header.push_str(&format!("// {}\n", warning_line(file, warning)));
        }
    }
    header
}
