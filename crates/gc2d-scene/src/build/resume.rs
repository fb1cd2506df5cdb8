//! What a checkpoint's World must share with the scene a run is resumed with. A resumed run goes on with the
//! checkpoint's state, so a scene edited since (a material's friction, a wall, Δt) would be ignored without a word;
//! comparing the checkpoint with the World the scene builds catches that even where no copy of the original scene is
//! at hand (a checkpoint kept outside its run directory, or the run directory's own `scene.ron` edited by hand).

use super::{BuildOptions, StartOverlaps, build};
use crate::summary::interaction_lines;
use crate::{Scene, SceneError};
use gc2d_engine::motion::Piston;
use gc2d_engine::safety::SafetyLimits;
use gc2d_engine::{Bodies, BodyKind, GearC0, Integrator, WallMotion, World, WorldConfig};
use gc2d_geometry::{Aabb, DVec2};

/// A scene compared with a checkpoint's World ([`Scene::compare_with_checkpoint`]).
#[derive(Debug, Clone, PartialEq)]
pub struct CheckpointComparison {
    /// What the scene's World differs in from the checkpoint's, one line per difference naming the scene's field or
    /// object; empty where the scene can continue the checkpoint.
    pub differences: Vec<String>,
    /// The scene entry each body of the scene's World comes from ([`Scene::body_origins`]), built once with the
    /// comparison so that callers naming the bodies need not build the scene again.
    pub body_origins: Vec<String>,
}

impl Scene {
    /// Compares the World this scene builds with the checkpoint's `world`. The differences, one line each naming the
    /// scene's field or object (`run.time_step_s`, `walls[2]`, `blocks[0] #17`, …), cover the run's settings (Δt,
    /// corrector, contact laws, mass model, gravity, heating, safety limits, domain), the walls (shape, material, pose
    /// or motion), the particles of the start (shape, material, mass), sources, inlets, outlets and body forces (drag
    /// springs, a fluid). What a resumed run may change is not compared: the seed (the scene is built with the
    /// checkpoint's), the end time, output cadences, name, description and view. An error where the scene does not
    /// build.
    pub fn compare_with_checkpoint(&self, world: &World) -> Result<CheckpointComparison, SceneError> {
        let mut scene = self.clone();
        scene.run.seed = world.config().seed;
        scene.validate()?;
        let options = BuildOptions { start_overlaps: StartOverlaps::Refuse, origins: true };
        let built = build(&scene, options).map_err(|e| e.located(scene.source.as_ref()))?;
        let mut differences = config_differences(built.world.config(), world.config(), &built.summary.materials);
        differences.extend(body_differences(&built.world, world, &built.origins));
        differences.extend(feed_differences(&built.world, world));
        if self.run.time_step_s.is_none() {
            automatic_time_step_last(&mut differences);
        }
        Ok(CheckpointComparison { differences, body_origins: built.origins })
    }
}

/// The field a difference in Δt is named by.
const TIME_STEP_FIELD: &str = "run.time_step_s";

/// An automatic Δt follows from the materials and shapes: where it differs beside another difference, that one is the
/// edit and Δt its consequence, so Δt goes last (callers show the first: an edited Young's modulus was told as "Δt
/// differs"), and says that it is automatic.
fn automatic_time_step_last(differences: &mut Vec<String>) {
    if let Some(index) = differences.iter().position(|d| d.starts_with(TIME_STEP_FIELD)) {
        let time_step = differences.remove(index);
        differences.push(format!("{time_step} (automatic: it follows from the materials and shapes)"));
    }
}

fn config_differences(scene: &WorldConfig, checkpoint: &WorldConfig, materials: &[String]) -> Vec<String> {
    let mut differences = Vec::new();
    if scene.time_step != checkpoint.time_step {
        differences.push(format!(
            "{TIME_STEP_FIELD}: Δt is {:e} s with the scene, {:e} s in the checkpoint",
            scene.time_step, checkpoint.time_step
        ));
    }
    if scene.integrator != checkpoint.integrator {
        differences.push(format!(
            "run.corrector: {} with the scene, {} in the checkpoint",
            integrator_name(scene.integrator),
            integrator_name(checkpoint.integrator)
        ));
    }
    let (ours, theirs) = (&scene.interactions, &checkpoint.interactions);
    if ours.material_count() != theirs.material_count() {
        differences.push(format!(
            "materials: {} with the scene, {} in the checkpoint",
            ours.material_count(),
            theirs.material_count()
        ));
    } else if ours != theirs {
        // A checkpoint knows its materials by number only: its line names them so, not by the scene's names.
        let numbered: Vec<String> = (0..materials.len()).map(|i| format!("#{i}")).collect();
        let (ours, theirs_named) = (interaction_lines(materials, ours), interaction_lines(materials, theirs));
        if let Some(index) = ours.iter().zip(&theirs_named).position(|(a, b)| a != b) {
            differences.push(format!(
                "materials or interactions: `{}` with the scene, `{}` in the checkpoint (its materials by number)",
                ours[index],
                interaction_lines(&numbered, theirs)[index]
            ));
        } else {
            differences.push("materials or interactions: the contact laws differ".to_string());
        }
    }
    if scene.mass_model != checkpoint.mass_model {
        differences.push(format!(
            "mass_model: {:?} with the scene, {:?} in the checkpoint",
            scene.mass_model, checkpoint.mass_model
        ));
    }
    if scene.gravity != checkpoint.gravity {
        differences.push("gravity: the schedule differs".to_string());
    }
    if scene.heating != checkpoint.heating {
        differences.push("heating: the schedule differs".to_string());
    }
    differences.extend(safety_differences(&scene.safety, &checkpoint.safety));
    if scene.domain != checkpoint.domain {
        differences.push(format!(
            "run.domain: {} with the scene, {} in the checkpoint",
            domain_text(scene.domain),
            domain_text(checkpoint.domain)
        ));
    }
    differences
}

/// The integrator as the scene names it (`run.corrector`).
fn integrator_name(integrator: Integrator) -> String {
    match integrator {
        Integrator::Gear6(GearC0::VelocityDependent) => "VelocityDependent".to_string(),
        Integrator::Gear6(GearC0::PositionDependent) => "PositionDependent".to_string(),
        other => format!("{other:?}"),
    }
}

/// A domain as the scene writes it, or `none`.
fn domain_text(domain: Option<Aabb>) -> String {
    match domain {
        Some(d) => format!("x {} to {} m, y {} to {} m", d.min.x, d.max.x, d.min.y, d.max.y),
        None => "none".to_string(),
    }
}

fn safety_differences(scene: &SafetyLimits, checkpoint: &SafetyLimits) -> Vec<String> {
    let fields = [
        ("run.max_overlap_fraction", scene.max_overlap_fraction, checkpoint.max_overlap_fraction),
        ("run.max_energy_gain_fraction", scene.max_energy_gain_fraction, checkpoint.max_energy_gain_fraction),
        ("run.max_impact_speed_m_s", scene.max_impact_speed, checkpoint.max_impact_speed),
    ];
    let mut differences: Vec<String> = fields
        .iter()
        .filter(|(_, ours, theirs)| ours != theirs)
        .map(|(field, ours, theirs)| format!("{field}: {ours} with the scene, {theirs} in the checkpoint"))
        .collect();
    if scene.allow_unsafe_time_step != checkpoint.allow_unsafe_time_step {
        differences.push(format!(
            "run.allow_unsafe_time_step: {} with the scene, {} in the checkpoint",
            scene.allow_unsafe_time_step, checkpoint.allow_unsafe_time_step
        ));
    }
    if differences.is_empty() && scene != checkpoint {
        differences.push("the engine's safety limits differ (a checkpoint of another version?)".to_string());
    }
    differences
}

/// The walls and the particles of the start, body by body (bodies keep their slots for the whole run; particles a
/// source or inlet added later follow them in the checkpoint).
fn body_differences(scene: &World, checkpoint: &World, origins: &[String]) -> Vec<String> {
    let (ours, theirs) = (scene.bodies(), checkpoint.bodies());
    let walls = |bodies: &Bodies| bodies.kind.iter().filter(|&&k| k == BodyKind::Wall).count();
    if walls(ours) != walls(theirs) {
        return vec![format!("walls: {} wall bodies with the scene, {} in the checkpoint", walls(ours), walls(theirs))];
    }
    if ours.len() > theirs.len() {
        return vec![format!(
            "particles: {} at the start with the scene, the checkpoint has {} bodies in all",
            ours.len() - walls(ours),
            theirs.len() - walls(theirs)
        )];
    }
    let mut differences = Vec::new();
    for i in 0..ours.len() {
        let name = origins.get(i).map_or_else(|| format!("body {i}"), String::clone);
        let what = if ours.kind[i] != theirs.kind[i] {
            Some("a wall on one side, a particle on the other")
        } else if ours.shape[i] != theirs.shape[i]
            || ours.radius[i] != theirs.radius[i]
            || body_points(ours, i) != body_points(theirs, i)
        {
            Some("its shape differs")
        } else if ours.material[i] != theirs.material[i] {
            Some("its material differs")
        } else if ours.kind[i] == BodyKind::Particle && ours.mass[i] != theirs.mass[i] {
            Some("its mass differs (density or mass model)")
        } else {
            None
        };
        if let Some(what) = what {
            differences.push(format!("{name}: {what}"));
        }
    }
    let moving = |world: &World, i: usize| world.moving_walls().iter().find(|w| w.body.index() == i).cloned();
    for i in (0..ours.len()).filter(|&i| ours.kind[i] == BodyKind::Wall) {
        let name = origins.get(i).map_or_else(|| format!("body {i}"), String::clone);
        let moved = match (moving(scene, i), moving(checkpoint, i)) {
            (None, None) => ours.pose[i] != theirs.pose[i],
            (Some(a), Some(b)) => a.rest != b.rest || motion_law(a.motion) != motion_law(b.motion),
            _ => true,
        };
        if moved {
            differences.push(format!("{name}: its place or motion differs"));
        }
    }
    differences
}

/// A wall's motion without the state a piston integrates as it moves.
fn motion_law(motion: WallMotion) -> WallMotion {
    match motion {
        WallMotion::Piston(p) => WallMotion::Piston(Piston::new(p.direction_angle, p.target_force, p.v_max)),
        other => other,
    }
}

/// Body `i`'s points in its own frame.
fn body_points(bodies: &Bodies, i: usize) -> &[DVec2] {
    &bodies.body_vertices[bodies.vertices[i].range()]
}

/// Sources, inlets, outlets and body forces.
fn feed_differences(scene: &World, checkpoint: &World) -> Vec<String> {
    let mut differences = Vec::new();
    let sources = |world: &World| world.sources().cloned().collect::<Vec<_>>();
    let (ours, theirs) = (sources(scene), sources(checkpoint));
    if ours.len() != theirs.len() {
        differences.push(format!("sources: {} with the scene, {} in the checkpoint", ours.len(), theirs.len()));
    } else if let Some(i) = (0..ours.len()).find(|&i| ours[i] != theirs[i]) {
        differences.push(format!("sources[{i}]: it differs"));
    }
    let (ours, theirs) = (scene.inlets(), checkpoint.inlets());
    if ours.len() != theirs.len() {
        differences.push(format!("inlets: {} with the scene, {} in the checkpoint", ours.len(), theirs.len()));
    } else if let Some(i) = (0..ours.len()).find(|&i| ours[i].inlet() != theirs[i].inlet()) {
        differences.push(format!("inlets[{i}] ({}): it differs", ours[i].inlet().name));
    }
    let (ours, theirs) = (scene.outlets(), checkpoint.outlets());
    if ours.len() != theirs.len() {
        differences.push(format!("outlets: {} with the scene, {} in the checkpoint", ours.len(), theirs.len()));
    } else if let Some(i) = (0..ours.len()).find(|&i| ours[i].outlet() != theirs[i].outlet()) {
        differences.push(format!("outlets[{i}] ({}): it differs", ours[i].outlet().name));
    }
    let drag_springs = |world: &World| {
        world.body_forces().iter().find_map(|force| match force {
            gc2d_engine::BodyForce::DragSprings(springs) => Some(springs.clone()),
            _ => None,
        })
    };
    if drag_springs(scene) != drag_springs(checkpoint) {
        differences.push("particles' drag_spring: the drag springs differ".to_string());
    }
    let same_fluid = match (scene.fluid(), checkpoint.fluid()) {
        (Some(ours), Some(theirs)) => ours.same_fluid(theirs),
        (ours, theirs) => ours.is_none() && theirs.is_none(),
    };
    if !same_fluid {
        differences.push("fluid: the fluid differs".to_string());
    }
    differences
}
