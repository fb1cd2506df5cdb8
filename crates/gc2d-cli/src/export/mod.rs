//! `gc2d-rs export RUN [--at T]`: the state of a run at one of its checkpoints as tables for pandas, polars, DuckDB
//! and ParaView (docs/export.md): one row per particle and one per touching pair, as Parquet and CSV, and the
//! particles' outlines as VTK (`.vtu` with a `.pvd` collection).

pub mod rows;
pub mod vtk;

use crate::object_names::ObjectNames;
use crate::outputs::run_scene;
use crate::parquet_table::{NamedColumn, write_parquet};
use crate::resume::temporary_path;
use gc2d_analysis::particle_state::csv::quoted;
use gc2d_engine::World;
use rows::{ContactRow, ParticleRow, contact_rows, particle_rows};
use std::fmt::Write as _;
use std::fs::File;
use std::path::{Path, PathBuf};

/// The formats `export` and the dumps of `run --dump-every` write.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, clap::ValueEnum)]
pub enum ExportFormat {
    /// Apache Parquet tables (export: particles.parquet and contacts.parquet; dumps: particles_<k>.parquet).
    Parquet,
    /// CSV tables (export: particles.csv and contacts.csv; dumps: particles_<k>.csv).
    Csv,
    /// VTK outlines for ParaView, with particles.pvd (export: particles_<step>.vtu; dumps: particles_<k>.vtu).
    Vtk,
}

/// What `export` wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Exported {
    /// The checkpoint exported and its time.
    pub checkpoint: PathBuf,
    /// Its simulated time, s.
    pub time_s: f64,
    /// Particles written.
    pub particles: usize,
    /// Touching pairs written.
    pub contacts: usize,
    /// The files written.
    pub files: Vec<PathBuf>,
    /// What the user should know about the tables: why the particles are not named.
    pub warnings: Vec<String>,
}

/// Loads a checkpoint file, with a message naming it.
fn load(file: &Path) -> Result<World, String> {
    World::load_checkpoint_file(file).map_err(|e| format!("cannot read {}: {e}", file.display()))
}

/// The run's numbered checkpoints `checkpoints/checkpoint-<step>.ckpt`, by step.
fn numbered_checkpoints(run: &Path) -> Vec<(u64, PathBuf)> {
    let Ok(entries) = std::fs::read_dir(run.join("checkpoints")) else { return Vec::new() };
    let mut found: Vec<(u64, PathBuf)> = entries
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter_map(|path| {
            let name = path.file_name()?.to_str()?;
            let step = name.strip_prefix("checkpoint-")?.strip_suffix(".ckpt")?.parse().ok()?;
            Some((step, path))
        })
        .collect();
    found.sort();
    found
}

/// The checkpoint to export and its World: the last at or before `at` (within half a step), or the latest without
/// `at`. Loads final.ckpt (or, without it or where it is damaged, the newest numbered checkpoint, with a warning in
/// `warnings`) for the time step, and then only the chosen file: a numbered checkpoint's time is its step times Δt.
fn choose(run: &Path, at: Option<f64>, warnings: &mut Vec<String>) -> Result<(PathBuf, World), String> {
    let numbered = numbered_checkpoints(run);
    let final_path = run.join("final.ckpt");
    // A damaged final.ckpt leaves the periodic checkpoints intact: the newest of them gives the time step.
    let final_state = match final_path.is_file().then(|| load(&final_path)) {
        Some(Err(why)) if !numbered.is_empty() => {
            warnings.push(format!("{why}: it is left out; the periodic checkpoints give the time step and the states"));
            None
        }
        other => other.transpose()?,
    };
    let (reference_path, reference) = if let Some(world) = final_state {
        (final_path, world)
    } else if let Some((_, path)) = numbered.last() {
        (path.clone(), load(path)?)
    } else if let Some(running) = crate::run_lock::still_running_without_checkpoint(run) {
        return Err(format!("cannot export: {running}"));
    } else {
        return Err(format!(
            "{} holds no checkpoint (final.ckpt or checkpoints/checkpoint-<step>.ckpt): is it a run directory written \
             by `gc2d-rs run`?",
            run.display()
        ));
    };
    let dt = reference.time_step();
    // Every candidate with its step count: the reference's own, and the numbered ones'.
    let mut candidates: Vec<(u64, PathBuf)> = numbered.into_iter().filter(|(_, p)| *p != reference_path).collect();
    candidates.push((reference.steps(), reference_path.clone()));
    candidates.sort();
    let chosen = match at {
        None => candidates.last().cloned(),
        Some(at) => candidates.iter().rev().find(|(step, _)| *step as f64 * dt <= at + 0.5 * dt).cloned(),
    };
    match chosen {
        Some((_, path)) if path == reference_path => Ok((path, reference)),
        Some((_, path)) => Ok((path.clone(), load(&path)?)),
        None => {
            // final.ckpt and a periodic checkpoint of the same step are one time.
            let mut steps: Vec<u64> = candidates.iter().map(|(step, _)| *step).collect();
            steps.dedup();
            let times: Vec<String> = steps.iter().map(|step| crate::console::rounded(*step as f64 * dt)).collect();
            Err(format!(
                "{} has no checkpoint at or before t = {} s; its checkpoints are at {} s (write more with \
                 `run --checkpoint-every`)",
                run.display(),
                at.unwrap_or(f64::NAN),
                times.join(", ")
            ))
        }
    }
}

/// Exports the state of the run `run` at `at` (default: its latest checkpoint) into `out` in `formats`.
pub fn export(run: &Path, at: Option<f64>, formats: &[ExportFormat], out: &Path) -> Result<Exported, String> {
    if !run.is_dir() {
        return Err(format!("{} is not a run directory", run.display()));
    }
    let mut warnings = Vec::new();
    let (checkpoint, world) = choose(run, at, &mut warnings)?;
    let time_s = world.time();
    // Each format once, in the order given (`csv,parquet,csv` listed the CSV files twice in the manifest).
    let mut once: Vec<ExportFormat> = Vec::new();
    for format in formats {
        if !once.contains(format) {
            once.push(*format);
        }
    }
    let formats = once;
    refuse_to_replace_other_files(out, &planned_files(&formats, world.steps()))?;
    // The scene as run names the materials and the bodies' origins; without it, or where it is not the scene of the
    // checkpoint (edited, or copied from another run), the names are left empty rather than made up.
    let scene = match run_scene(run, &world, &checkpoint.display().to_string()) {
        Ok(scene) => Some(scene),
        Err(why) => {
            warnings.push(format!("{why}: the particles' origins and materials are left empty"));
            None
        }
    };
    let materials = scene.as_ref().map(|run| run.scene.material_names()).unwrap_or_default();
    let names = scene.map(|run| ObjectNames::from_origins(run.body_origins));
    let particles = particle_rows(&world, &materials, names.as_ref());
    let contacts = contact_rows(&world);
    std::fs::create_dir_all(out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    remove_earlier_export(out)?;
    let mut files = Vec::new();
    // Each file goes into the manifest before it is written, so that an export that fails half-way (a full disk) or
    // is killed is still replaced by the next one; each is written whole or not at all (see `write_whole`).
    let mut write = |name: &str, contents: &dyn Fn(&Path) -> Result<(), String>| -> Result<(), String> {
        let path = out.join(name);
        files.push(path.clone());
        write_manifest(out, &files)?;
        write_whole(&path, contents)
    };
    let text = |text: String| move |path: &Path| std::fs::write(path, &text).map_err(|e| e.to_string());
    for format in &formats {
        let [first, second] = file_names(*format, world.steps());
        match format {
            ExportFormat::Csv => {
                write(&first, &text(particles_csv(&particles)))?;
                write(&second, &text(contacts_csv(&contacts, time_s)))?;
            }
            ExportFormat::Vtk => {
                write(&first, &text(vtk::particles_vtu(&world, &particles)))?;
                write(&second, &text(vtk::collection(&[(time_s, Path::new(&first))])))?;
            }
            ExportFormat::Parquet => {
                let tables =
                    [("particles", particle_columns(&particles)), ("contacts", contact_columns(&contacts, time_s))];
                for ((table, columns), name) in tables.into_iter().zip([first, second]) {
                    write(&name, &|path| write_parquet(table, &columns, path).map_err(|e| e.to_string()))?;
                }
            }
        }
    }
    Ok(Exported { checkpoint, time_s, particles: particles.len(), contacts: contacts.len(), files, warnings })
}

/// The two files an export writes in `format` of a checkpoint after `steps` steps: the particles' and the contacts'
/// tables (CSV, Parquet), or the particles' outlines and their collection (VTK).
fn file_names(format: ExportFormat, steps: u64) -> [String; 2] {
    match format {
        ExportFormat::Csv => ["particles.csv".to_string(), "contacts.csv".to_string()],
        ExportFormat::Vtk => [format!("particles_{steps}.vtu"), "particles.pvd".to_string()],
        ExportFormat::Parquet => ["particles.parquet".to_string(), "contacts.parquet".to_string()],
    }
}

/// The names of the files an export in `formats` of a checkpoint after `steps` steps writes.
fn planned_files(formats: &[ExportFormat], steps: u64) -> Vec<String> {
    formats.iter().flat_map(|&format| file_names(format, steps)).collect()
}

/// Refuses an export that would overwrite a file in `out` that no earlier export there wrote (its
/// [`EXPORT_MANIFEST`] does not list it): `--out` pointed at a run's `dumps/` replaced the dumps' `particles.pvd`.
fn refuse_to_replace_other_files(out: &Path, planned: &[String]) -> Result<(), String> {
    let manifest = std::fs::read_to_string(out.join(EXPORT_MANIFEST)).unwrap_or_default();
    let exported: Vec<&str> = manifest.lines().collect();
    match planned.iter().find(|name| out.join(name).exists() && !exported.contains(&name.as_str())) {
        Some(name) => Err(format!(
            "{} holds {name}, which no export wrote: exporting there would replace it; choose another --out",
            out.display()
        )),
        None => Ok(()),
    }
}

/// The list of the files an export wrote, kept in its folder so that the next export there removes exactly those.
pub const EXPORT_MANIFEST: &str = ".gc2d-export";

/// Removes the files an earlier export in `out` wrote, as its [`EXPORT_MANIFEST`] lists them (plain names in `out`,
/// nothing else): exporting in other formats or at another time would otherwise leave them beside the new ones, a
/// Parquet table of one time next to a CSV of another, or outlines the new `particles.pvd` does not list. With each
/// file goes its `<name>.tmp`, which an export killed while writing it leaves. A file the list names that is gone
/// already is fine (an export that failed lists the file it could not write); a folder without the list (no export,
/// or one before the list existed) loses nothing.
fn remove_earlier_export(out: &Path) -> Result<(), String> {
    let Ok(manifest) = std::fs::read_to_string(out.join(EXPORT_MANIFEST)) else { return Ok(()) };
    for name in manifest.lines().filter(|name| is_plain_file_name(name)) {
        let path = out.join(name);
        for path in [temporary_path(&path), path] {
            match std::fs::remove_file(&path) {
                Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                    return Err(format!("cannot remove {} of an earlier export: {e}", path.display()));
                }
                _ => {}
            }
        }
    }
    Ok(())
}

/// True for a file name without a folder part (no separator, not `.` or `..`): what a manifest may name.
fn is_plain_file_name(name: &str) -> bool {
    let path = Path::new(name);
    !name.is_empty() && path.file_name().is_some_and(|file| file == path.as_os_str())
}

/// Writes the [`EXPORT_MANIFEST`] of the export that wrote `files` into `out`, whole or not at all: a manifest cut
/// short by a full disk would forget files of the export it lists.
fn write_manifest(out: &Path, files: &[PathBuf]) -> Result<(), String> {
    let names: Vec<String> =
        files.iter().filter_map(|f| f.file_name()).map(|name| name.to_string_lossy().into_owned()).collect();
    let text = names.join("\n") + "\n";
    write_whole(&out.join(EXPORT_MANIFEST), &|path| std::fs::write(path, &text).map_err(|e| e.to_string()))
}

/// Writes `path` whole or not at all, as the run writes its checkpoints and summary.json: `contents` writes
/// `<path>.tmp` ([`temporary_path`]), which is synced to disk and renamed over `path`. A write that fails (a full
/// disk) removes the temporary file and reports `path` with the reason, leaving no truncated file behind.
fn write_whole(path: &Path, contents: &dyn Fn(&Path) -> Result<(), String>) -> Result<(), String> {
    let temporary = temporary_path(path);
    let written = contents(&temporary)
        .and_then(|()| File::open(&temporary).and_then(|file| file.sync_all()).map_err(|e| e.to_string()))
        .and_then(|()| std::fs::rename(&temporary, path).map_err(|e| e.to_string()));
    written.map_err(|why| {
        let _ = std::fs::remove_file(&temporary);
        format!("cannot write {}: {why}", path.display())
    })
}

/// Column names of the particle table, in order.
pub const PARTICLE_COLUMNS: [&str; 18] = [
    "time_s",
    "id",
    "origin",
    "material",
    "shape",
    "corners",
    "radius_m",
    "x_m",
    "y_m",
    "phi_rad",
    "vx_m_s",
    "vy_m_s",
    "omega_rad_s",
    "fx_n",
    "fy_n",
    "torque_n_m",
    "contacts",
    "speed_m_s",
];

/// Column names of the contact table, in order.
pub const CONTACT_COLUMNS: [&str; 16] = [
    "time_s",
    "a",
    "b",
    "kind_a",
    "kind_b",
    "x_m",
    "y_m",
    "normal_x",
    "normal_y",
    "normal_force_n",
    "tangential_force_n",
    "fx_on_a_n",
    "fy_on_a_n",
    "overlap_fraction",
    "law",
    "force_n",
];

/// The Parquet columns of particle rows, in [`PARTICLE_COLUMNS`] order.
pub fn particle_columns(rows: &[ParticleRow]) -> Vec<NamedColumn> {
    let number = |name: &str, f: &dyn Fn(&ParticleRow) -> f64| NamedColumn::numbers(name, rows.iter().map(f));
    let text = |name: &str, f: &dyn Fn(&ParticleRow) -> String| NamedColumn::texts(name, rows.iter().map(f));
    let unsigned = |name: &str, f: &dyn Fn(&ParticleRow) -> u64| NamedColumn::unsigned(name, rows.iter().map(f));
    vec![
        number("time_s", &|r| r.state.time_s),
        unsigned("id", &|r| u64::from(r.state.id)),
        text("origin", &|r| r.origin.clone()),
        text("material", &|r| r.state.material.clone()),
        text("shape", &|r| r.state.shape.name().to_owned()),
        unsigned("corners", &|r| r.corners as u64),
        number("radius_m", &|r| r.radius_m),
        number("x_m", &|r| r.state.x_m),
        number("y_m", &|r| r.state.y_m),
        number("phi_rad", &|r| r.state.phi_rad),
        number("vx_m_s", &|r| r.state.vx_m_s),
        number("vy_m_s", &|r| r.state.vy_m_s),
        number("omega_rad_s", &|r| r.state.omega_rad_s),
        number("fx_n", &|r| r.state.fx_n),
        number("fy_n", &|r| r.state.fy_n),
        number("torque_n_m", &|r| r.state.torque_n_m),
        unsigned("contacts", &|r| u64::from(r.state.contacts)),
        number("speed_m_s", &|r| r.state.speed()),
    ]
}

fn contact_columns(rows: &[ContactRow], time_s: f64) -> Vec<NamedColumn> {
    let number = |name: &str, f: &dyn Fn(&ContactRow) -> f64| NamedColumn::numbers(name, rows.iter().map(f));
    let text = |name: &str, f: &dyn Fn(&ContactRow) -> String| NamedColumn::texts(name, rows.iter().map(f));
    let unsigned = |name: &str, f: &dyn Fn(&ContactRow) -> u64| NamedColumn::unsigned(name, rows.iter().map(f));
    vec![
        number("time_s", &|_| time_s),
        unsigned("a", &|r| u64::from(r.a)),
        unsigned("b", &|r| u64::from(r.b)),
        text("kind_a", &|r| r.kind_a.to_owned()),
        text("kind_b", &|r| r.kind_b.to_owned()),
        number("x_m", &|r| r.point.x),
        number("y_m", &|r| r.point.y),
        number("normal_x", &|r| r.normal.x),
        number("normal_y", &|r| r.normal.y),
        number("normal_force_n", &|r| r.normal_force_n),
        number("tangential_force_n", &|r| r.tangential_force_n),
        number("fx_on_a_n", &|r| r.force_on_a.x),
        number("fy_on_a_n", &|r| r.force_on_a.y),
        number("overlap_fraction", &|r| r.overlap_fraction),
        text("law", &|r| r.law.to_owned()),
        number("force_n", &|r| r.force_on_a.length()),
    ]
}

fn particles_csv(rows: &[ParticleRow]) -> String {
    let mut csv = format!("{}\n", PARTICLE_COLUMNS.join(","));
    for r in rows {
        let s = &r.state;
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{},{:e}",
            s.time_s,
            s.id,
            quoted(&r.origin),
            quoted(&s.material),
            s.shape.name(),
            r.corners,
            r.radius_m,
            s.x_m,
            s.y_m,
            s.phi_rad,
            s.vx_m_s,
            s.vy_m_s,
            s.omega_rad_s,
            s.fx_n,
            s.fy_n,
            s.torque_n_m,
            s.contacts,
            s.speed()
        );
    }
    csv
}

fn contacts_csv(rows: &[ContactRow], time_s: f64) -> String {
    let mut csv = format!("{}\n", CONTACT_COLUMNS.join(","));
    for r in rows {
        let _ = writeln!(
            csv,
            "{time_s},{},{},{},{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{},{:e}",
            r.a,
            r.b,
            r.kind_a,
            r.kind_b,
            r.point.x,
            r.point.y,
            r.normal.x,
            r.normal.y,
            r.normal_force_n,
            r.tangential_force_n,
            r.force_on_a.x,
            r.force_on_a.y,
            r.overlap_fraction,
            r.law,
            r.force_on_a.length()
        );
    }
    csv
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A manifest names files in its own folder only: an edited one cannot make an export remove anything elsewhere.
    #[test]
    fn manifests_name_plain_files_only() {
        assert!(is_plain_file_name("particles.csv") && is_plain_file_name("particles_12.vtu"));
        for name in ["", ".", "..", "../summary.json", "/etc/passwd", "sub/particles.csv", "./particles.csv"] {
            assert!(!is_plain_file_name(name), "{name}");
        }
    }
}
