//! The scene of every point, made and checked before anything runs: the base scene loaded, each parameter's path
//! checked against it (errors at the parameter in the sweep file, with the scene loader's "did you mean"), every
//! point's values put in, and the result loaded and built like `gc2d-rs check` does (errors name the point).

use super::apply::{PathProblem, Target, put, target};
use super::spec::{ParameterSpec, Point, Sweep};
use crate::analysis::AnalysisKind;
use crate::failure::CommandFailure;
use gc2d_scene::{ErrorKind, Material, Scene};
use rayon::prelude::*;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The path of the seed in a scene.
const SEED_PATH: &str = "run.seed";

/// The longest name of a file or directory most file systems take (ext4, XFS, btrfs, APFS, NTFS: 255 bytes).
const MAX_DIR_NAME: usize = 255;

/// Longest list of further failing points a report names.
const LISTED_FAILURES: usize = 10;

/// A point with its run directory and scene.
#[derive(Debug, Clone)]
pub struct PointScene {
    /// The point.
    pub point: Point,
    /// Its directory name (`rpm=1700_count=130_seed=1`).
    pub name: String,
    /// Its run directory.
    pub dir: PathBuf,
    /// The scene as RON text, as `scene.ron` holds it (fields at their defaults only where they are written out).
    pub text: String,
    /// The analysis its finished run gets before collecting: the sweep file's `analysis.kind`, else the mill's for a
    /// mill scene, else none.
    pub analysis: Option<AnalysisKind>,
    /// Its scene's end time, s.
    pub end_time_s: f64,
}

/// Makes and checks the scene of every point.
pub fn point_scenes(sweep: &Sweep) -> Result<Vec<PointScene>, CommandFailure> {
    let mut base = Scene::from_path(&sweep.scene).map_err(|e| {
        CommandFailure::input(format!(
            "the base scene of {} does not load:\n{}",
            sweep.path.display(),
            super::file::render(&e)
        ))
    })?;
    // The points' scenes are written into their run directories: file names relative to the base scene's folder (a
    // fluid's VTK files) would start from there.
    let base_folder = base.folder();
    base.anchor_file_names(&base_folder)
        .map_err(|e| CommandFailure::input(format!("cannot find the folder of {}: {e}", sweep.scene.display())))?;
    name_implicit_material(&mut base, sweep);
    let base_text =
        base.to_ron_string().map_err(|e| CommandFailure::failed(format!("cannot write the base scene: {e}")))?;
    // The sweep file's mistakes found against the scene, and its plots', are reported together, the parameters'
    // first: a misspelled path also names its parameter, so a plot's x spelled right would seem to be the mistake.
    let mut errors = Vec::new();
    let mut wrong_paths = Vec::new();
    for parameter in &sweep.parameters {
        if let Err(error) = check_path(sweep, &base_text, parameter) {
            errors.push(error);
            wrong_paths.push(parameter.index);
        }
    }
    errors.extend(check_analysis_kind(sweep, &base).err());
    errors.extend(sweep.plot_error(&wrong_paths));
    if !errors.is_empty() {
        let reports: Vec<String> = errors.into_iter().map(|e| e.report).collect();
        return Err(CommandFailure::input(reports.join("\n")));
    }
    let points = sweep.points(base.run.seed);
    check_dir_name_lengths(sweep, &points)?;
    let mut seen: HashMap<String, usize> = HashMap::new();
    for point in &points {
        let name = sweep.dir_name(point);
        if let Some(other) = seen.insert(name.clone(), point.index) {
            return Err(CommandFailure::input(format!(
                "points {other} and {} both get the directory name `{name}` (values that differ only in characters a \
                 directory name cannot hold): give different values",
                point.index
            )));
        }
    }
    let made: Vec<Result<PointScene, (String, String)>> =
        points.par_iter().map(|point| point_scene(sweep, &base_text, &base_folder, point)).collect();
    let mut scenes = Vec::with_capacity(made.len());
    let mut failures = Vec::new();
    for result in made {
        match result {
            Ok(scene) => scenes.push(scene),
            Err(failure) => failures.push(failure),
        }
    }
    if let Some((first, report)) = failures.first() {
        let mut message = format!(
            "the scene of point {first} is invalid (lines as in the scene.ron the sweep would write):\n{report}"
        );
        if failures.len() > 1 {
            let others: Vec<&str> = failures[1..].iter().take(LISTED_FAILURES).map(|(n, _)| n.as_str()).collect();
            let more = failures.len() - 1 - others.len();
            message.push_str(&format!(
                "\n{} of {} points fail; the others: {}{}",
                failures.len(),
                points.len(),
                others.join(", "),
                if more > 0 { format!(" and {more} more") } else { String::new() }
            ));
        }
        return Err(CommandFailure::input(message));
    }
    check_analysis_inputs(sweep, &scenes)?;
    Ok(scenes)
}

/// Writes the implicit material of a scene without `materials` (the one `check` prints) into `base`, where a
/// parameter's path leads into `materials[…]`: the written scene then has the `materials[0]` the path names, and
/// builds the same World. Other sweeps leave the scene as written (`materials: []`), so that their run directories'
/// `scene.ron` stay what earlier versions wrote.
fn name_implicit_material(base: &mut Scene, sweep: &Sweep) {
    let into_materials = sweep.parameters.iter().any(|p| p.path.starts_with("materials["));
    if base.materials.is_empty() && into_materials {
        base.materials.push(Material::implicit());
    }
}

/// Refuses points whose run directory names are longer than a file system allows ([`MAX_DIR_NAME`] bytes), before
/// anything is made: at the `name` (or `path`) of a parameter whose own part and the seed's are too long already,
/// else at `parameters` as a whole; the message names the longest directory and its length.
fn check_dir_name_lengths(sweep: &Sweep, points: &[Point]) -> Result<(), CommandFailure> {
    let Some((point, name)) =
        points.iter().map(|p| (p, sweep.dir_name(p))).max_by_key(|(p, name)| (name.len(), std::cmp::Reverse(p.index)))
    else {
        return Ok(());
    };
    if name.len() <= MAX_DIR_NAME {
        return Ok(());
    }
    let mut parts = sweep.dir_name_parts(point);
    // The seed's part, with the `_` that joins it.
    let seed_part = parts.pop().map_or(0, |seed| seed.len() + 1);
    let lengths = sweep.parameters.iter().zip(parts.iter().map(String::len));
    let alone = lengths.filter(|(_, len)| len + seed_part > MAX_DIR_NAME).max_by_key(|(_, len)| *len);
    let message = format!(
        "the point directory `{name}` is {} bytes long, more than the {MAX_DIR_NAME} a directory name may have",
        name.len()
    );
    Err(match alone {
        Some((parameter, _)) => {
            let own_name = parameter_has_name(sweep, parameter);
            sweep.field_error(
                &format!("parameters[{}].{}", parameter.index, if own_name { "name" } else { "path" }),
                format!("{message}: give the parameter a shorter `name`"),
            )
        }
        None => sweep.field_error("parameters", format!("{message}: give the parameters shorter `name`s")),
    })
}

/// Whether the sweep file gives `parameter` a `name` (else it is named after its path).
fn parameter_has_name(sweep: &Sweep, parameter: &ParameterSpec) -> bool {
    sweep.file.parameters.get(parameter.index).is_some_and(|p| p.name.is_some())
}

/// Refuses what would make every point's analysis fail after its run: a warm-up (`analysis.warm_up_s`) that is not
/// before a point's end, and a mill analysis of runs told not to write the contact events it reads.
fn check_analysis_inputs(sweep: &Sweep, scenes: &[PointScene]) -> Result<(), CommandFailure> {
    let analysed = |point: &PointScene, kinds: &[AnalysisKind]| point.analysis.is_some_and(|k| kinds.contains(&k));
    if let Some(warm_up) = sweep.file.analysis.warm_up_s {
        let windowed = [AnalysisKind::Mill, AnalysisKind::Feedpipe];
        if let Some(point) = scenes.iter().find(|s| analysed(s, &windowed) && warm_up >= s.end_time_s) {
            return Err(sweep.field_error(
                "analysis.warm_up_s",
                format!(
                    "{warm_up} s: point `{}` ends at {} s, so the warm-up would leave nothing to average",
                    point.name, point.end_time_s
                ),
            ));
        }
    }
    if sweep.file.run.events == Some(false)
        && let Some(point) = scenes.iter().find(|s| analysed(s, &[AnalysisKind::Mill]))
    {
        return Err(sweep.field_error(
            "run.events",
            format!(
                "the mill analysis of point `{}` reads the contact events (events.csv) this turns off: leave \
                 `events` out, and the mill's runs write them",
                point.name
            ),
        ));
    }
    Ok(())
}

/// The point's scene, loaded and built; on failure the point's name and values and the scene's error. File names a
/// parameter gives (a fluid's field) are taken from `base_folder`, the base scene's folder, as the base scene's own.
fn point_scene(
    sweep: &Sweep,
    base_text: &str,
    base_folder: &Path,
    point: &Point,
) -> Result<PointScene, (String, String)> {
    let name = sweep.dir_name(point);
    let dir = sweep.out.join(&name);
    let fail = |report: String| (format!("`{name}` ({})", sweep.describe(point)), report);
    let mut text = base_text.to_owned();
    let assignments = sweep.parameters.iter().map(|p| p.path.as_str()).zip(point.values.iter().cloned());
    for (path, value) in std::iter::once((SEED_PATH, point.seed.to_string())).chain(assignments) {
        let at = target(&text, path).map_err(|p| fail(format!("`{path}`: {}", p.message)))?;
        text = put(&text, &at, &value);
    }
    // Named as the point, not as its scene.ron: that file is written only once every point has passed.
    let mut scene = Scene::from_str(&text, &format!("point {name}")).map_err(|e| fail(super::file::render(&e)))?;
    scene.anchor_file_names(base_folder).map_err(|e| fail(format!("cannot find the working directory: {e}")))?;
    scene.summary().map_err(|e| fail(super::file::render(&e)))?;
    let text = scene.to_ron_string().map_err(|e| fail(format!("cannot write the scene: {e}")))?;
    let analysis = sweep.file.analysis.kind.or(scene.mill.is_some().then_some(AnalysisKind::Mill));
    Ok(PointScene { point: point.clone(), name, dir, text, analysis, end_time_s: scene.run.end_time_s })
}

/// Refuses an `analysis.kind` the base scene cannot give: a mill analysis without a `mill`, a feed pipe's without
/// `outlets` (its transit times come from them).
fn check_analysis_kind(sweep: &Sweep, base: &Scene) -> Result<(), CommandFailure> {
    let missing = match sweep.file.analysis.kind {
        Some(AnalysisKind::Mill) if base.mill.is_none() => "a `mill`",
        Some(AnalysisKind::Feedpipe) if base.outlets.is_empty() => "`outlets`",
        _ => return Ok(()),
    };
    Err(sweep.field_error(
        "analysis.kind",
        format!("this analysis needs a scene with {missing}, and {} has none", sweep.scene.display()),
    ))
}

/// Refuses a parameter whose path does not lead to a field of the base scene: located at the parameter in the sweep
/// file, with the loader's suggestion where the name is misspelled.
fn check_path(sweep: &Sweep, base_text: &str, parameter: &ParameterSpec) -> Result<(), CommandFailure> {
    let first = &parameter.values[0];
    let (probe, problem) = match target(base_text, &parameter.path) {
        Ok(Target::Value(_)) => return Ok(()),
        Ok(insert) => (Some((insert, first.as_str())), None),
        Err(problem) => (problem.probe.clone().map(|t| (t, "()")), Some(problem)),
    };
    if let Some((at, value)) = probe
        && let Err(error) = Scene::from_str(&put(base_text, &at, value), "probe")
        && error.kind() == ErrorKind::UnknownName
        && parameter.path.starts_with(error.path())
    {
        return Err(sweep.parameter_error(
            parameter,
            format!("`{}` is not a field of the scene: {}", parameter.path, error.message()),
            error.help_text().map(str::to_owned),
        ));
    }
    match problem {
        Some(PathProblem { message, help, .. }) => Err(sweep.parameter_error(parameter, message, help)),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The implicit material written out, as the sweep writes it for a path into `materials[…]`, is the one the
    /// scene had: the same name in `check`, and the same World, step for step.
    #[test]
    fn the_implicit_material_written_out_builds_the_same_world() {
        let text = "Scene(run: (end_time_s: 0.01, seed: 3), walls: [Wall(shape: Rectangle(width_m: 0.1, height_m: 0.01), \
                    position_m: (0, -0.005))], particles: [(shape: Regular(corners: 6, radius_m: 0.003), position_m: \
                    (0, 0.003), velocity_m_s: (0.1, -0.2)), (shape: Regular(corners: 5, radius_m: 0.002), position_m: \
                    (0.004, 0.008))])";
        let bare = Scene::from_str(text, "bare").unwrap();
        assert!(bare.materials.is_empty());
        assert_eq!(bare.summary().unwrap().materials, [Material::implicit().name]);
        let mut named = bare.clone();
        named.materials.push(Material::implicit());
        let named = Scene::from_str(&named.to_ron_string().unwrap(), "named").unwrap();
        assert_eq!(named.summary().unwrap().to_string(), bare.summary().unwrap().to_string());
        let end_state = |scene: &Scene| {
            let mut world = scene.build().unwrap();
            world.run_until(0.01).unwrap();
            let mut bytes = Vec::new();
            world.save_checkpoint(&mut bytes).unwrap();
            bytes
        };
        assert!(end_state(&bare) == end_state(&named));
    }
}
