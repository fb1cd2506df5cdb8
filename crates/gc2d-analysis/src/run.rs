//! `analyze_run`: one call that loads a run's final state, computes what applies to its scene, and writes the
//! analysis directory (CSV tables, SVG figures, `analysis.json`).

use crate::density::bulk_packing_fraction;
use crate::error::AnalysisError;
use crate::figures::{self, Labels};
use crate::output::OutputDir;
use crate::pressure::{Facing, WallSelection, wall_forces};
use crate::scene_pile::{PileReport, analyze_pile};
use crate::scene_silo::{SiloReport, analyze_silo};
use crate::snapshot::Snapshot;
use crate::statistics::{coordination, force_direction_histogram, force_magnitude_histogram};
use gc2d_engine::World;
use serde::Serialize;
use std::path::Path;

/// Which analyses to run; written in lower case (`"pile"`), as `analyze --kind` spells it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SceneKind {
    /// Decide from the wall forces: a silo when the side walls carry at least [`SILO_SIDE_FORCE_FRACTION`] of the
    /// floor's normal force, otherwise a pile.
    #[default]
    Auto,
    /// A free heap on a floor (Ch. 4).
    Pile,
    /// A filled column between two side walls (Ch. 3).
    Silo,
}

/// Side walls carrying this fraction of the floor force make a silo (under [`SceneKind::Auto`]). A pile that only
/// leans on a wall at its foot stays well below it; a silo in the Janssen regime is far above (its walls carry most
/// of the weight).
pub const SILO_SIDE_FORCE_FRACTION: f64 = 0.1;

/// Options of [`analyze_run`]; every `None` is chosen from the data.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct AnalyzeOptions {
    /// Pile, silo, or decide from the data.
    pub scene: SceneKind,
    /// Half-width b of the pressure window (2.38), m. Default: 15 wall contacts per window (§5.2 rule of thumb),
    /// at least half a mean particle diameter.
    pub window_half_width: Option<f64>,
    /// Side of the square test areas of the density and stress maps, m. Default: about
    /// [`PARTICLES_PER_TEST_AREA`] particles per cell (§5.7).
    pub grid_cell: Option<f64>,
}

/// Contacts per pressure window when b is chosen automatically (§5.2: 10–20).
pub const CONTACTS_PER_WINDOW: f64 = 15.0;

/// Particles per test area when the grid is chosen automatically (§5.7: 100–200 give very good results).
pub const PARTICLES_PER_TEST_AREA: f64 = 150.0;

/// Bins of the force-direction histogram (10° each).
pub const DIRECTION_BINS: usize = 36;

/// Bin width of P(F/⟨F⟩) in units of ⟨F⟩.
pub const MAGNITUDE_BIN_WIDTH: f64 = 0.1;

/// Everything [`analyze_run`] computed, as written to `analysis.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Simulated time of the analysed state, s.
    pub time: f64,
    /// g, m/s².
    pub gravity: f64,
    /// The scene analysed (never `Auto`).
    pub scene: SceneKind,
    /// The options as given.
    pub options: AnalyzeOptions,
    /// Living particles.
    pub particles: usize,
    /// Touching pairs.
    pub contacts: usize,
    /// Σm/Σa of the particles, kg/m².
    pub particle_area_density: f64,
    /// Σa over the convex hull of the analysed particles (the pile's group, or all in a silo): the bulk packing
    /// fraction ρ_rel (2.45 with a test area enclosing everything).
    pub packing_fraction: f64,
    /// Bulk density ρ = ρ_rel · ρ_particle (3.5), kg/m².
    pub bulk_density: f64,
    /// ⟨K⟩, contacts per particle (walls included, rattlers counted with 0).
    pub mean_coordination: f64,
    /// Particles without contact.
    pub rattlers: usize,
    /// `coordination_histogram[K]` = particles with K contacts.
    pub coordination_histogram: Vec<usize>,
    /// ⟨F⟩ over all contacts, N.
    pub mean_contact_force: f64,
    /// Pile results, when the scene is a pile.
    pub pile: Option<PileReport>,
    /// Silo results, when the scene is a silo.
    pub silo: Option<SiloReport>,
    /// Files written into the analysis directory.
    pub files: Vec<String>,
}

/// Loads `<run_dir>/final.ckpt`, analyses it and writes `<run_dir>/analysis/` (tables, figures, `analysis.json`).
pub fn analyze_run(run_dir: &Path, options: &AnalyzeOptions) -> Result<Report, AnalysisError> {
    let checkpoint = run_dir.join("final.ckpt");
    let world = World::load_checkpoint_file(&checkpoint)
        .map_err(|source| AnalysisError::Checkpoint { path: checkpoint.clone(), source })?;
    analyze_snapshot(&Snapshot::from_world(&world), options, &run_dir.join("analysis"))
}

/// The work of [`analyze_run`] on a snapshot, writing into `out_dir`.
pub fn analyze_snapshot(
    snapshot: &Snapshot,
    options: &AnalyzeOptions,
    out_dir: &Path,
) -> Result<Report, AnalysisError> {
    validate(options)?;
    if snapshot.particles.is_empty() {
        return Err(AnalysisError::NotEnoughData("the snapshot has no particles".into()));
    }
    let mut out = OutputDir::create(out_dir)?;
    let scene = match options.scene {
        SceneKind::Auto => detect_scene(snapshot),
        chosen => chosen,
    };
    // A pile is its largest contact-connected group; particles in flight or bounced away are not part of it.
    let pile = (scene != SceneKind::Silo).then(|| snapshot.restricted_to(&snapshot.largest_cluster()));
    let packing_fraction = bulk_packing_fraction(pile.as_ref().unwrap_or(snapshot));
    let particle_area_density = snapshot.particle_area_density();
    let coordination = coordination(snapshot);
    let directions = force_direction_histogram(snapshot, DIRECTION_BINS);
    let magnitudes = force_magnitude_histogram(snapshot, MAGNITUDE_BIN_WIDTH);
    write_statistics(&mut out, &coordination, &directions, &magnitudes)?;
    figures::force_network(&out.file("force_network.svg"), snapshot)?;
    let (pile, silo) = match &pile {
        Some(pile) => (Some(analyze_pile(pile, snapshot.particles.len(), options, &mut out)?), None),
        None => (None, Some(analyze_silo(snapshot, options, &mut out)?)),
    };
    let mut report = Report {
        time: snapshot.time,
        gravity: snapshot.gravity,
        scene,
        options: *options,
        particles: snapshot.particles.len(),
        contacts: snapshot.contacts.len(),
        particle_area_density,
        packing_fraction,
        bulk_density: packing_fraction * particle_area_density,
        mean_coordination: coordination.mean,
        rattlers: coordination.rattlers,
        coordination_histogram: coordination.histogram,
        mean_contact_force: magnitudes.mean_force,
        pile,
        silo,
        files: Vec::new(),
    };
    let json_path = out.file("analysis.json");
    report.files = out.written().to_vec();
    let json = serde_json::to_string_pretty(&report)?;
    std::fs::write(&json_path, json).map_err(|source| AnalysisError::Io { path: json_path, source })?;
    Ok(report)
}

/// Pile or silo, from the normal force the side walls carry relative to the floor.
pub fn detect_scene(snapshot: &Snapshot) -> SceneKind {
    let total =
        |facing| wall_forces(snapshot, WallSelection::facing(facing)).iter().map(|f| f.normal_force).sum::<f64>();
    let floor = total(Facing::Up);
    let sides = total(Facing::Left) + total(Facing::Right);
    if sides > 0.0 && sides >= SILO_SIDE_FORCE_FRACTION * floor { SceneKind::Silo } else { SceneKind::Pile }
}

fn validate(options: &AnalyzeOptions) -> Result<(), AnalysisError> {
    for (name, value) in [("window half-width", options.window_half_width), ("grid cell", options.grid_cell)] {
        if let Some(v) = value
            && !(v > 0.0 && v.is_finite())
        {
            return Err(AnalysisError::InvalidParameter(format!("{name} = {v} m must be positive and finite")));
        }
    }
    Ok(())
}

fn write_statistics(
    out: &mut OutputDir,
    coordination: &crate::statistics::Coordination,
    directions: &crate::statistics::DirectionHistogram,
    magnitudes: &crate::statistics::MagnitudeHistogram,
) -> Result<(), AnalysisError> {
    let particles = coordination.per_particle.len().max(1) as f64;
    let rows: Vec<Vec<f64>> = coordination
        .histogram
        .iter()
        .enumerate()
        .map(|(k, &n)| vec![k as f64, n as f64, n as f64 / particles])
        .collect();
    out.write_csv("coordination.csv", &["K", "particles", "fraction"], &rows)?;
    let bars: Vec<(f64, f64, f64)> = rows.iter().map(|r| (r[0] - 0.4, r[0] + 0.4, r[2])).collect();
    figures::bar_chart(
        &out.file("coordination.svg"),
        Labels { title: "coordination number P(K)", x: "K (contacts per particle)", y: "P(K)" },
        &bars,
    )?;
    let rows: Vec<Vec<f64>> =
        directions.centers_degrees.iter().zip(&directions.fraction).map(|(&a, &p)| vec![a, p]).collect();
    out.write_csv("force_directions.csv", &["alpha_deg", "fraction"], &rows)?;
    figures::polar_chart(
        &out.file("force_directions.svg"),
        "force directions P(α) (2.41)",
        &directions.centers_degrees,
        &directions.fraction,
    )?;
    let rows: Vec<Vec<f64>> = magnitudes.centers.iter().zip(&magnitudes.density).map(|(&f, &p)| vec![f, p]).collect();
    out.write_csv("force_magnitudes.csv", &["f_over_mean", "density"], &rows)?;
    let half = 0.5 * magnitudes.bin_width;
    let bars: Vec<(f64, f64, f64)> = rows.iter().map(|r| (r[0] - half, r[0] + half, r[1])).collect();
    figures::bar_chart(
        &out.file("force_magnitudes.svg"),
        Labels { title: "force magnitudes P(F/⟨F⟩)", x: "F/⟨F⟩", y: "probability density" },
        &bars,
    )
}
