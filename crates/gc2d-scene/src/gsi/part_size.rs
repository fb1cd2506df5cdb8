//! The PART_SIZE question (D6, erratum E29): gc2d's documentation does not say whether `PART_SIZE` gives the
//! semi-axes or the full axes of the ellipse a generated particle is inscribed in. The importer settles it once per
//! file, because one gc2d program reads every PART_SIZE of a file the same way, and reports what it did.

use std::str::FromStr;

use super::diagnostics::{Diagnostics, GsiWarningKind};
use super::scene::{GsiBlock, GsiScene, PartSizeReading, largest_semi_axis};

/// How the importer reads `PART_SIZE`, chosen by the caller (e.g. a command-line flag).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PartSizeConvention {
    /// Semi-axes (the thesis's "radius"), unless a GENERATE_BLOCK's particles would then overlap their grid
    /// neighbours while the full-axes reading leaves every block free of overlaps: then full axes. The thesis's own
    /// example (App. B.1.8, `Part_Size 0.003` on a 0.005 m FCC grid) is read as full axes this way.
    #[default]
    Auto,
    /// Always semi-axes.
    SemiAxes,
    /// Always full axes.
    FullAxes,
}

impl FromStr for PartSizeConvention {
    type Err = String;

    /// `auto`, `semi-axes` or `full-axes` (any case; `_` for `-` too).
    fn from_str(name: &str) -> Result<Self, Self::Err> {
        match name.to_ascii_lowercase().replace('_', "-").as_str() {
            "auto" => Ok(PartSizeConvention::Auto),
            "semi-axes" => Ok(PartSizeConvention::SemiAxes),
            "full-axes" => Ok(PartSizeConvention::FullAxes),
            _ => Err(format!("unknown PART_SIZE convention `{name}`; expected auto, semi-axes or full-axes")),
        }
    }
}

/// Options of the gsi import.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ImportOptions {
    /// How `PART_SIZE` is read.
    pub part_size: PartSizeConvention,
}

/// Relative allowance before two touching particles count as overlapping.
const TOUCH_TOLERANCE: f64 = 1e-9;

/// The largest particle size and the nearest site distance of `block` if, with PART_SIZE read as `reading`, its
/// largest possible particles reach past their nearest grid neighbour.
fn neighbour_overlap(block: &GsiBlock, reading: PartSizeReading) -> Option<(f64, f64)> {
    let spacing = block.nearest_site_distance()?;
    let diameter = 2.0 * largest_semi_axis(reading.semi_axes(block.shape.part_size.value), &block.shape);
    (diameter > spacing * (1.0 + TOUCH_TOLERANCE)).then_some((diameter, spacing))
}

/// Settles how PART_SIZE is read, applies it to every block and drop source, and warns about each block whose
/// particles overlap their grid neighbours (the run would start with strong repulsion).
pub(super) fn settle_part_size(scene: &mut GsiScene, convention: PartSizeConvention, diagnostics: &mut Diagnostics) {
    let reading = match convention {
        PartSizeConvention::SemiAxes => PartSizeReading::SemiAxes,
        PartSizeConvention::FullAxes => PartSizeReading::FullAxes,
        PartSizeConvention::Auto => {
            let overlapping_as_semi_axes: Vec<(usize, (f64, f64))> = scene
                .blocks
                .iter()
                .filter_map(|block| Some((block.line, neighbour_overlap(block, PartSizeReading::SemiAxes)?)))
                .collect();
            let full_axes_fit =
                scene.blocks.iter().all(|block| neighbour_overlap(block, PartSizeReading::FullAxes).is_none());
            if !overlapping_as_semi_axes.is_empty() && full_axes_fit {
                for (line, (semi_axes_diameter, spacing)) in overlapping_as_semi_axes {
                    diagnostics.warn(line, GsiWarningKind::PartSizeReadAsFullAxes { semi_axes_diameter, spacing });
                }
                PartSizeReading::FullAxes
            } else {
                PartSizeReading::SemiAxes
            }
        }
    };
    scene.part_size_reading = reading;
    for shape in
        scene.blocks.iter_mut().map(|b| &mut b.shape).chain(scene.drop_sources.iter_mut().map(|d| &mut d.shape))
    {
        shape.reading = reading;
    }
    for block in &scene.blocks {
        if let Some((diameter, spacing)) = neighbour_overlap(block, reading) {
            diagnostics.warn(block.line, GsiWarningKind::GridNeighboursOverlap { diameter, spacing, reading });
        }
    }
}
