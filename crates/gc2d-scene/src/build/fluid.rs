//! The scene's fluid: its checks (located at the field), the engine's [`EngineFluid`] it builds (loading VTK files
//! relative to the scene file's folder), and what `check` reports about it (terminal speeds, drag time scales).

use crate::checks::{finite_pair, non_negative, number, ordered_range, positive};
use crate::error::SceneError;
use crate::schema::{Drag, Field, Fluid, Ramp, Scene, VtkSnapshot};
use crate::spans::field_path;
use gc2d_engine::{Fluid as EngineFluid, MassModel};
use gc2d_fluid::drag::{ImmersedBody, drag_force};
use gc2d_fluid::sampled::MAX_NEIGHBOURS;
use gc2d_fluid::{
    DragCoefficient, FieldSnapshot, FluidField, FluidProperties, Interpolation, Poiseuille, SampledField,
    SnapshotSeries, TimeRamp, VtkFile,
};
use gc2d_geometry::DVec2;
use std::path::{Path, PathBuf};

/// Time steps per drag relaxation time below which `check` warns: Δt ≤ τ_drag/20 passes silently, so the drag
/// changes a particle's slip by at most about 5 % per step (docs/model.md, "Fluid": the time step and the drag).
pub const DRAG_STEPS_PER_RELAXATION_TIME: f64 = 20.0;

const PATH: &str = "fluid";

/// Checks the scene's fluid section, adding each problem to `errors` at its field. Files are read at build.
pub(crate) fn check(fluid: &Fluid, errors: &mut Vec<SceneError>) {
    let at = |field: &str| field_path(PATH, field);
    let mut push = |result: Result<(), SceneError>| {
        if let Err(error) = result {
            errors.push(error);
        }
    };
    push(non_negative(&at("density_kg_m3"), fluid.density_kg_m3).map(drop));
    push(positive(&at("viscosity_pa_s"), fluid.viscosity_pa_s).map(drop));
    if let Drag::Constant(c) = fluid.drag {
        push(non_negative(&field_path(&at("drag"), "0"), c).map(drop));
    }
    if let Some(ramp) = &fluid.ramp {
        push(ordered_range(&field_path(&at("ramp"), "window_s"), ramp.window_s, false).map(drop));
    }
    let field = at("field");
    match &fluid.field {
        Field::Uniform(u) => push(finite_pair(&field_path(&field, "0"), *u).map(drop)),
        Field::Poiseuille { .. } => push(poiseuille(&fluid.field, &field).map(drop)),
        Field::Vtk { file, snapshots, interpolation, .. } => {
            match (file, snapshots.is_empty()) {
                (Some(_), false) => push(Err(SceneError::value(
                    field_path(&field, "snapshots"),
                    "give either `file` (a steady field) or `snapshots` (a series), not both",
                ))),
                (None, true) => push(Err(SceneError::value(
                    field.clone(),
                    "a `Vtk` field needs `file` (a steady field) or `snapshots` (a series)",
                )
                .with_help("e.g. `field: Vtk(file: \"fields/riser.vtk\")`"))),
                _ => {}
            }
            push(snapshot_times(snapshots, &field_path(&field, "snapshots")));
            if let Interpolation::Shepard { power, neighbours } = *interpolation {
                let path = field_path(&field, "interpolation");
                push(positive(&field_path(&path, "power"), power).map(drop));
                if !(1..=MAX_NEIGHBOURS).contains(&neighbours) {
                    push(Err(SceneError::value(
                        field_path(&path, "neighbours"),
                        format!("{neighbours} neighbours: Shepard weighs between 1 and {MAX_NEIGHBOURS} nearest nodes"),
                    )));
                }
            }
        }
    }
}

/// FieldSnapshot times: finite and strictly increasing.
fn snapshot_times(snapshots: &[VtkSnapshot], path: &str) -> Result<(), SceneError> {
    for (i, snapshot) in snapshots.iter().enumerate() {
        crate::checks::finite(&field_path(&format!("{path}[{i}]"), "time_s"), snapshot.time_s)?;
    }
    for (i, pair) in snapshots.windows(2).enumerate() {
        if pair[1].time_s <= pair[0].time_s {
            return Err(SceneError::value(
                field_path(&format!("{path}[{}]", i + 1), "time_s"),
                format!(
                    "snapshot times must increase: {} s follows {} s",
                    number(pair[1].time_s),
                    number(pair[0].time_s)
                ),
            ));
        }
    }
    Ok(())
}

/// The Poiseuille channel of a `Poiseuille` field, checked.
fn poiseuille(field: &Field, path: &str) -> Result<Poiseuille, SceneError> {
    let Field::Poiseuille { axis_point_m, direction, half_width_m, centre_speed_m_s } = field else {
        unreachable!("called for Poiseuille fields only")
    };
    Poiseuille::new(DVec2::from_array(*axis_point_m), DVec2::from_array(*direction), *half_width_m, *centre_speed_m_s)
        .map_err(|e| SceneError::value(path, e.to_string()))
}

/// The engine's fluid of a checked scene, loading its VTK files relative to `folder` (the scene file's folder; the
/// working directory for scenes made in code).
pub(crate) fn plan(fluid: &Fluid, folder: &Path) -> Result<EngineFluid, SceneError> {
    let path = field_path(PATH, "field");
    let field = match &fluid.field {
        Field::Uniform(u) => FluidField::Uniform(DVec2::from_array(*u)),
        Field::Poiseuille { .. } => FluidField::Poiseuille(poiseuille(&fluid.field, &path)?),
        Field::Vtk { file, snapshots, time_interpolation, array, location, interpolation, outside } => {
            let load = |file: &str, at: &str| -> Result<SampledField, SceneError> {
                let resolved = folder.join(file);
                let located = |message: String| {
                    SceneError::value(at, message)
                        .with_help(format!("the file was looked for at {}", resolved.display()))
                };
                let vtk = VtkFile::read(&resolved).map_err(|e| located(e.to_string()))?;
                let samples = vtk.velocity_samples(array, *location).map_err(|e| located(e.to_string()))?;
                SampledField::new(&samples, *interpolation, *outside).map_err(|e| located(e.to_string()))
            };
            match file {
                Some(file) => FluidField::Sampled(Box::new(load(file, &field_path(&path, "file"))?)),
                None => {
                    let list = field_path(&path, "snapshots");
                    let loaded = snapshots
                        .iter()
                        .enumerate()
                        .map(|(i, s)| {
                            let at = field_path(&format!("{list}[{i}]"), "file");
                            Ok(FieldSnapshot { time_s: s.time_s, field: load(&s.file, &at)? })
                        })
                        .collect::<Result<Vec<_>, SceneError>>()?;
                    FluidField::Series(
                        SnapshotSeries::new(loaded, *time_interpolation)
                            .map_err(|e| SceneError::value(list, e.to_string()))?,
                    )
                }
            }
        }
    };
    let field = match fluid.ramp {
        Some(Ramp { window_s, shape }) => FluidField::Ramped {
            field: Box::new(field),
            ramp: TimeRamp { start_s: window_s[0], end_s: window_s[1], shape },
        },
        None => field,
    };
    Ok(EngineFluid {
        field,
        properties: FluidProperties {
            density_kg_m3: fluid.density_kg_m3,
            dynamic_viscosity_pa_s: fluid.viscosity_pa_s,
        },
        drag: match fluid.drag {
            Drag::Constant(c) => DragCoefficient::Constant(c),
            Drag::SchillerNaumann => DragCoefficient::SchillerNaumann,
        },
        buoyancy: fluid.buoyancy,
    })
}

impl Scene {
    /// The folder the scene's relative file names start from (a fluid's VTK files): the scene file's folder, or an
    /// empty path, the working directory, for a scene made in code.
    pub fn folder(&self) -> PathBuf {
        scene_folder(self)
    }

    /// Names the files the scene reads (a `Vtk` field's `file` and `snapshots`) by full paths: a relative name is
    /// taken from `folder` (the working directory where it is empty), and `..` and links are resolved where the file
    /// exists, so that one file always gets one name. For a copy of the scene written into another folder, such as a
    /// run directory's `scene.ron` or a sweep's point scenes, whose relative names would start from there. Fails only
    /// where the working directory cannot be found.
    pub fn anchor_file_names(&mut self, folder: &Path) -> std::io::Result<()> {
        let folder = if folder.as_os_str().is_empty() { std::env::current_dir()? } else { folder.to_path_buf() };
        if let Some(Fluid { field: Field::Vtk { file, snapshots, .. }, .. }) = &mut self.fluid {
            for name in file.iter_mut().chain(snapshots.iter_mut().map(|snapshot| &mut snapshot.file)) {
                let joined = folder.join(&*name);
                let full = std::fs::canonicalize(&joined).or_else(|_| std::path::absolute(&joined))?;
                *name = full.to_string_lossy().into_owned();
            }
        }
        Ok(())
    }
}

/// The folder a scene's relative file names start from: the scene file's folder, or the working directory.
pub(crate) fn scene_folder(scene: &Scene) -> PathBuf {
    scene
        .source
        .as_ref()
        .and_then(|source| Path::new(source.name()).parent().map(Path::to_path_buf))
        .unwrap_or_default()
}

/// A kind of particle the fluid acts on, as `check` reports it.
#[derive(Debug, Clone, PartialEq)]
pub struct DragScale {
    /// The scene entry the particles come from (`particles[0]`, `inlets[1]`, …).
    pub entry: String,
    /// The terminal speed in still fluid, m/s, downwards: negative for a particle lighter than the fluid it displaces,
    /// which rises, 0 for one as heavy, and infinite where the fluid exerts no drag (density or drag coefficient 0).
    pub terminal_speed_m_s: f64,
    /// The drag's relaxation time m/(∂F/∂w) at the reference slip, s: how fast the drag brings a particle to the
    /// fluid's speed.
    pub relaxation_time_s: f64,
}

/// What `check` says about a scene's fluid.
#[derive(Debug, Clone, PartialEq)]
pub struct FluidSummary {
    /// One line: density, drag law, buoyancy, field.
    pub description: String,
    /// Each particle kind's terminal speed and drag time, in scene order.
    pub scales: Vec<DragScale>,
}

impl FluidSummary {
    /// The entries whose drag relaxation time is shorter than [`DRAG_STEPS_PER_RELAXATION_TIME`] steps of `time_step`.
    pub fn too_fast_for(&self, time_step: f64) -> impl Iterator<Item = &DragScale> {
        self.scales.iter().filter(move |s| time_step * DRAG_STEPS_PER_RELAXATION_TIME > s.relaxation_time_s)
    }
}

/// A particle kind by its nominal radius (m) and mass (kg, or kg/m per unit thickness), for [`summary`].
pub(crate) struct NominalParticle {
    /// Its scene entry.
    pub entry: String,
    /// Its radius (a disk's) or equal-area radius, m.
    pub radius_m: f64,
    /// Its area, m² (what the per-unit-thickness model displaces).
    pub area_m2: f64,
    /// Its mass.
    pub mass: f64,
}

impl NominalParticle {
    /// A particle already in the World: its own radius (a disk's, or the equal-area radius), area and mass.
    pub(crate) fn of_body(bodies: &gc2d_engine::Bodies, id: gc2d_engine::BodyId, entry: &str) -> Self {
        let i = id.index();
        let area_m2 = bodies.area[i];
        let radius_m = if bodies.shape[i] == gc2d_engine::ShapeKind::Disk {
            bodies.radius[i]
        } else {
            gc2d_fluid::drag::equivalent_radius(area_m2)
        };
        Self { entry: entry.to_owned(), radius_m, area_m2, mass: bodies.mass[i] }
    }

    /// An inlet's particle at its recipe's nominal radius (a disk's radius, a polygon's larger semi-axis), taken as
    /// a disk: a scale, not the mass of each drawn particle.
    pub(crate) fn of_inlet(inlet: &gc2d_engine::Inlet, mass_model: MassModel, entry: &str) -> Self {
        let radius_m = inlet.nominal_radius();
        let area_m2 = std::f64::consts::PI * radius_m * radius_m;
        let mass = match mass_model {
            MassModel::PerUnitThickness => inlet.density * area_m2,
            MassModel::SphereEquivalent => inlet.density * 4.0 / 3.0 * area_m2 * radius_m,
        };
        Self { entry: entry.to_owned(), radius_m, area_m2, mass }
    }
}

/// The summary of `fluid` for the particle kinds `particles` under `mass_model` and gravity `g` (m/s²).
pub(crate) fn summary(
    fluid: &Fluid,
    engine: &EngineFluid,
    particles: &[NominalParticle],
    mass_model: MassModel,
    g: f64,
) -> FluidSummary {
    let drag = match fluid.drag {
        Drag::Constant(c) => format!("c_w = {}", number(c)),
        Drag::SchillerNaumann => format!("Schiller–Naumann, η = {} Pa·s", number(fluid.viscosity_pa_s)),
    };
    let field = match &fluid.field {
        Field::Uniform(u) => format!("uniform ({}, {}) m/s", number(u[0]), number(u[1])),
        Field::Poiseuille { centre_speed_m_s, half_width_m, .. } => {
            format!("Poiseuille, {} m/s on the axis, half width {} m", number(*centre_speed_m_s), number(*half_width_m))
        }
        Field::Vtk { file: Some(file), .. } => format!("loaded from {file}"),
        Field::Vtk { snapshots, .. } => format!("{} loaded snapshots", snapshots.len()),
    };
    let ramp = fluid
        .ramp
        .map_or(String::new(), |r| format!(", ramped up over {}–{} s", number(r.window_s[0]), number(r.window_s[1])));
    let description = format!(
        "ρ_f = {} kg/m³, drag {drag}, buoyancy {}, field {field}{ramp}",
        number(fluid.density_kg_m3),
        if fluid.buoyancy { "on" } else { "off" }
    );
    let speed_scale = match &fluid.field {
        Field::Uniform(u) => DVec2::from_array(*u).length(),
        Field::Poiseuille { centre_speed_m_s, .. } => centre_speed_m_s.abs(),
        Field::Vtk { .. } => 0.0,
    };
    let scales = particles
        .iter()
        .map(|p| {
            let body = match mass_model {
                MassModel::PerUnitThickness => ImmersedBody::per_unit_thickness(p.radius_m, p.area_m2),
                MassModel::SphereEquivalent => ImmersedBody::sphere_equivalent(p.radius_m),
            };
            let drag = |w: f64| drag_force(&engine.properties, engine.drag, &body, DVec2::new(w, 0.0)).x;
            // Where the drag balances the weight less buoyancy (if on); for a constant c_w this is
            // √(2·(m − ρ_f·V)·g/(ρ_f·c_w·A)), the thesis's w_t.
            let buoyancy = if fluid.buoyancy { fluid.density_kg_m3 * body.volume_m3 } else { 0.0 };
            // A particle lighter than the fluid it displaces rises at the speed where the drag balances its lift:
            // a negative terminal speed.
            let net_weight = (p.mass - buoyancy) * g;
            let terminal = speed_where(drag, net_weight.abs()).copysign(net_weight);
            let slip = terminal.abs().max(speed_scale).max(1e-3);
            // ∂F/∂w by a difference: the drag law's own stiffness at the reference slip.
            let step = slip * 1e-6;
            let stiffness = (drag(slip + step) - drag(slip)) / step;
            let relaxation_time_s = if stiffness > 0.0 { p.mass / stiffness } else { f64::INFINITY };
            DragScale { entry: p.entry.clone(), terminal_speed_m_s: terminal, relaxation_time_s }
        })
        .collect();
    FluidSummary { description, scales }
}

/// The slip speed at which the drag `drag(w)` (increasing in w) equals `force`, m/s, by bisection; 0 where the force
/// is not positive, infinite where no speed up to 1e12 m/s brakes that much (a fluid of density 0 or a drag
/// coefficient of 0: the particle falls freely).
fn speed_where(drag: impl Fn(f64) -> f64, force: f64) -> f64 {
    if force.is_nan() || force <= 0.0 {
        return 0.0;
    }
    let mut high = 1.0;
    while drag(high) < force && high < 1e12 {
        high *= 2.0;
    }
    if drag(high) < force {
        return f64::INFINITY;
    }
    let mut low = 0.0;
    for _ in 0..200 {
        let middle = 0.5 * (low + high);
        if drag(middle) < force { low = middle } else { high = middle }
    }
    0.5 * (low + high)
}
