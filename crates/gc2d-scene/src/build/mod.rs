//! Building a World from a scene: walls (with the wall-builder macros expanded), particles, lattice blocks, drag
//! springs and sources, then the load-time safety checks (initial overlaps, time-step bound).
//!
//! Random draws are deterministic per `run.seed`: the shapes of `Random` particles and of blocks (and the block
//! scatter and velocities) come from ChaCha8 stream 1 of the seed, in scene order (particles, then blocks); the
//! World's own stream 0 drives the sources during the run; stream 2 samples source shapes for the time-step bound,
//! stream 3 inlet shapes for their start speed.

pub(crate) mod blocks;
mod feed_lines;
pub(crate) mod fluid;
pub(crate) mod inlets;
pub(crate) mod interactions;
pub(crate) mod mill;
mod resume;
pub use resume::CheckpointComparison;
pub(crate) mod safety;
pub(crate) mod shapes;
pub(crate) mod walls;

use crate::checks::number;
use crate::error::{ErrorKind, SceneError};
use crate::schema::{Corrector, DropHeight, Gravity, GravityProfile, Scene, Source};
use crate::spans::field_path;
use crate::summary::SceneSummary;
use crate::validate::Materials;
use blocks::Lattice;
use gc2d_engine::integrator::IntegratorError;
use gc2d_engine::schedules::{
    DragSpring as EngineDragSpring, GravityProfile as EngineProfile, GravitySchedule, HeatingSchedule,
};
use gc2d_engine::{
    BodyShape, DropSource, GearC0, Integrator, MaterialId, SafetyLimits, TimeWindow, World, WorldConfig, WorldError,
};
use gc2d_geometry::{DVec2, Pose};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use safety::{BlockGrid, PlacedBody, TimeStepBound};
use walls::PlacedWall;

/// ChaCha8 stream of the build's draws (the World uses stream 0 for its sources).
const BUILD_STREAM: u64 = 1;
/// ChaCha8 stream of the source samples for the time-step bound.
const SOURCE_SAMPLE_STREAM: u64 = 2;
/// ChaCha8 stream of the inlet samples for the start-speed check.
const INLET_SPEED_STREAM: u64 = 3;

/// A free particle ready for `World::add_particle`.
pub(crate) struct PlannedParticle {
    /// Its outline, centroid at the origin.
    pub shape: BodyShape,
    /// Where it starts.
    pub pose: Pose,
    /// Start velocity, m/s.
    pub velocity: DVec2,
    /// Start angular velocity, rad/s CCW.
    pub angular_velocity: f64,
    /// Density in the unit of the scene's mass model.
    pub density: f64,
    /// Its material.
    pub material: MaterialId,
    /// A drag spring pulling it, if any.
    pub drag_spring: Option<EngineDragSpring>,
    /// The field path of the scene entry it comes from.
    pub path: String,
}

/// A built scene and what the summary reports about it.
pub(crate) struct Built {
    pub world: World,
    pub summary: SceneSummary,
    /// The scene entry each body of the built World comes from, by body id ([`Scene::body_origins`]); named only
    /// when asked for ([`BuildOptions::origins`]), so a plain build allocates no name per body.
    pub origins: Vec<String>,
}

impl Scene {
    /// Builds the World the scene describes: validates it, expands wall macros, generates blocks, and checks that
    /// no two initial bodies overlap by more than `run.max_overlap_fraction` and that Δt is below the stable bound
    /// of every particle present at the start or inserted by a source (unless `run.allow_unsafe_time_step`).
    /// The same scene with the same seed gives a bitwise identical World.
    pub fn build(&self) -> Result<World, SceneError> {
        Ok(self.build_with_summary()?.world)
    }

    /// The scene entry each body of the built World comes from, by body id: `walls[0]` (with ` #k` for the k-th
    /// piece of a wall macro that makes several), `particles[3]`, `blocks[1] #17` (the 17th particle of the block,
    /// from 0), `mill.balls #4`, …: the names exports and messages give bodies. Bodies inserted later by sources and
    /// inlets are not in the list (their ids follow it).
    pub fn body_origins(&self) -> Result<Vec<String>, SceneError> {
        self.validate()?;
        let options = BuildOptions { start_overlaps: StartOverlaps::Refuse, origins: true };
        Ok(build(self, options).map_err(|e| e.located(self.source.as_ref()))?.origins)
    }

    /// What the scene contains once built: counts of walls, particles and sources, materials, Δt and its bound.
    pub fn summary(&self) -> Result<SceneSummary, SceneError> {
        Ok(self.build_with_summary()?.summary)
    }

    /// The highest normal impact speed the time-step bound of a Hertz contact is taken at, m/s:
    /// `run.max_impact_speed_m_s` where the scene gives it; else, for a mill, twice the rotor's tip speed (a ball a
    /// blade has thrown at up to (1 + e)·V meets the next blade head-on, ballmill.md §7.5), or the speed of a fall
    /// across the chamber where that is more (a slow rotor); else the engine's default (10 m/s).
    pub fn max_impact_speed(&self) -> f64 {
        self.run.max_impact_speed_m_s.unwrap_or_else(|| match &self.mill {
            Some(mill) => {
                let fall = (2.0 * self.gravity.largest_magnitude() * 2.0 * mill::outer_radius(mill)).sqrt();
                (2.0 * mill::tip_speed(mill)).max(fall)
            }
            None => gc2d_engine::safety::DEFAULT_MAX_IMPACT_SPEED,
        })
    }

    pub(crate) fn build_with_summary(&self) -> Result<Built, SceneError> {
        self.validate()?;
        let options = BuildOptions { start_overlaps: StartOverlaps::Refuse, origins: false };
        build(self, options).map_err(|e| e.located(self.source.as_ref()))
    }

    /// The summary of the scene built without the start-overlap check: for the gsi importer, which needs the
    /// time-step bound of a scene whose bodies may overlap (and then reports the overlap on loading it back).
    pub(crate) fn summary_ignoring_start_overlaps(&self) -> Result<SceneSummary, SceneError> {
        self.validate()?;
        let options = BuildOptions { start_overlaps: StartOverlaps::Ignore, origins: false };
        Ok(build(self, options).map_err(|e| e.located(self.source.as_ref()))?.summary)
    }
}

impl Scene {
    /// Warnings about the scene that do not stop it, each naming the file, line and column of the field where the
    /// scene was read from a text (`feed.ron:12:22: inlets[0].velocity_m_s: …`), else the field alone:
    /// - an inlet whose start speed across its segment is below 2R·rate: particles may pile up at it;
    /// - a source's drop line or an inlet's segment that lies partly inside a wall that does not move or outside
    ///   `run.domain`: it feeds only on the rest (one wholly there is refused by [`Scene::build`]);
    /// - an outlet wholly outside `run.domain`: the domain removes the particles first, so it counts none;
    /// - an outlet that every inlet lies behind (on its outer side): the particles fed cross it inward, and it
    ///   removes none;
    /// - a source or inlet with no insertion due before the run's end (an empty window, or one after the end);
    /// - a pair of materials the scene uses without an `interactions` entry where the entries give penetration laws:
    ///   it falls back to the overlap-area law;
    /// - an `interactions` entry with a penetration law (`Linear`, `Hertz`) in a scene whose masses are per unit
    ///   thickness: those laws are made for sphere-equivalent masses.
    ///
    /// Empty for a scene without such entries, or one that does not build (its errors say why).
    pub fn warnings(&self) -> Vec<String> {
        let mut warnings = self.inlet_warnings();
        let mut rng = ChaCha8Rng::seed_from_u64(self.run.seed);
        rng.set_stream(BUILD_STREAM);
        let Ok(mut walls) = scene_walls(self, &mut rng) else { return warnings };
        if let Some(mill) = &self.mill {
            let Ok(mill_walls) = mill::walls(mill, "mill") else { return warnings };
            walls.extend(mill_walls);
        }
        for line in feed_lines::covered_lines(self, &walls).into_iter().filter(|line| line.share < 1.0) {
            warnings.push(format!("{}: {}", self.located_field(&line.field), line.warning()));
        }
        for (field, planned) in self
            .sources
            .iter()
            .enumerate()
            .map(|(i, s)| (format!("sources[{i}].window_s"), planned_insertions(s, self.run.end_time_s) as f64))
            .chain(self.inlets.iter().enumerate().map(|(i, inlet)| {
                (format!("inlets[{i}].window_s"), inlets::planned_insertions(inlet, self.run.end_time_s))
            }))
        {
            if planned == 0.0 {
                warnings.push(format!(
                    "{}: no insertion is due between t = 0 and `run.end_time_s` = {} s (the window is empty, ends before \
                     the run starts, or starts at or after the end time): it feeds nothing, unless `--until` runs on \
                     into the window",
                    self.located_field(&field),
                    crate::checks::number(self.run.end_time_s)
                ));
            }
        }
        for [a, b] in interactions::unlisted_pairs(self) {
            warnings.push(format!(
                "{}: the pair `{a}`–`{b}` has no entry, so it takes the overlap-area law mixed from the two materials, \
                 unlike the penetration laws the entries give: add an entry for it if it should have one of those",
                self.located_field("interactions")
            ));
        }
        for (i, law) in interactions::penetration_laws_per_unit_thickness(self) {
            let [a, b] = &self.interactions[i].materials;
            warnings.push(format!(
                "{}: the {law} law of `{a}`–`{b}` meets masses per unit thickness (`mass_model` is `PerUnitThickness`, \
                 the default): a penetration law's force is that of a sphere, in N, while these masses are per metre \
                 of depth, hundreds of times a small ball's, so an impact overlaps far deeper than the law's time \
                 step and the overlap limit expect, and a run may stop at its first hard impact (\"blew up\", \
                 \"stiffen it\") though the material is stiff enough: set `mass_model: SphereEquivalent`, with the \
                 materials' `density_kg_m3`",
                self.located_field(&format!("interactions[{i}].law"))
            ));
        }
        for field in feed_lines::reversed_outlets(self) {
            warnings.push(format!(
                "{}: every inlet lies on the outlet's outer side (right of the way from `from_m` to `to_m`; the domain \
                 is on its left), so the particles fed reach it crossing inward and it removes none: swap `from_m` \
                 and `to_m` if they should leave there",
                self.located_field(&field)
            ));
        }
        for field in feed_lines::outlets_outside_domain(self) {
            warnings.push(format!(
                "{}: its segment lies entirely outside `run.domain`: the domain removes the particles before they \
                 reach it, and it counts none",
                self.located_field(&field)
            ));
        }
        warnings
    }
}

/// The walls of the scene's `walls` entries, wall macros expanded, drawing from `rng` (the build's stream, whose
/// first draws they are).
fn scene_walls(scene: &Scene, rng: &mut ChaCha8Rng) -> Result<Vec<PlacedWall>, SceneError> {
    let mut walls: Vec<PlacedWall> = Vec::new();
    for (i, item) in scene.walls.iter().enumerate() {
        walls.extend(walls::expand(item, &format!("walls[{i}]"), rng)?);
    }
    Ok(walls)
}

/// Whether the build refuses bodies that overlap at the start.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum StartOverlaps {
    /// As the engine would before its first step.
    Refuse,
    /// Not checked (the World is then not runnable; only its summary is used).
    Ignore,
}

/// What a build checks and keeps besides the World.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct BuildOptions {
    /// Whether bodies overlapping at the start are refused.
    start_overlaps: StartOverlaps,
    /// Whether the bodies' scene entries are named ([`Built::origins`]).
    origins: bool,
}

fn build(scene: &Scene, options: BuildOptions) -> Result<Built, SceneError> {
    let materials = Materials::of(scene);
    let table = interactions::interaction_table(scene, &materials)?;
    let models = table.models_per_material();
    let max_impact_speed = scene.max_impact_speed();
    let mut rng = ChaCha8Rng::seed_from_u64(scene.run.seed);
    rng.set_stream(BUILD_STREAM);

    let mut walls = scene_walls(scene, &mut rng)?;
    let mut particles = plan_particles(scene, &materials, &mut rng)?;
    if let Some(mill) = &scene.mill {
        let mill_walls = mill::walls(mill, "mill")?;
        let others: Vec<(&BodyShape, Pose)> =
            walls.iter().map(|w| (&w.shape, w.pose)).chain(particles.iter().map(|p| (&p.shape, p.pose))).collect();
        let mill_particles =
            mill::particles(mill, &mill_walls, &others, &materials, scene.mass_model, &mut rng, "mill")?;
        particles.extend(mill_particles);
        walls.extend(mill_walls);
    }
    let buried = feed_lines::covered_lines(scene, &walls).into_iter().filter(|line| line.share == 1.0);
    if let Some(error) = SceneError::combine(buried.map(|line| line.error()).collect()) {
        return Err(error);
    }
    if let Some(error) = SceneError::combine(safety::unusable_masses(&particles, scene.mass_model)) {
        return Err(error);
    }
    let domain = scene.run.domain.map(|d| d.aabb());
    if let Some(domain) = domain
        && let Some(error) = SceneError::combine(safety::outside_domain(&particles, domain))
    {
        return Err(error);
    }
    let sources = plan_sources(scene, &materials)?;
    let (inlets, outlets) = inlets::plan(scene, &materials)?;

    let mut bound = particles
        .iter()
        .filter_map(|p| {
            let models = &models[p.material.index()];
            TimeStepBound::of(&p.shape, p.density, scene.mass_model, models, max_impact_speed, &p.path)
        })
        .reduce(TimeStepBound::smaller);
    for p in particles.iter() {
        let Some(spring) = p.drag_spring else { continue };
        let mass = scene.mass_model.mass_properties(&p.shape, p.density);
        let path = field_path(&field_path(&p.path, "drag_spring"), "stiffness_n_m");
        let spring_bound = TimeStepBound::of_drag_spring(
            mass,
            spring.fixing_point,
            spring.stiffness,
            p.shape.inscribed_radius(),
            &path,
        );
        bound = TimeStepBound::min(bound, spring_bound);
    }
    let mut sample_rng = ChaCha8Rng::seed_from_u64(scene.run.seed);
    sample_rng.set_stream(SOURCE_SAMPLE_STREAM);
    for (i, source) in sources.iter().enumerate() {
        let path = format!("sources[{i}]");
        let source_bound = TimeStepBound::of_source(
            &source.recipe,
            source.density,
            scene.mass_model,
            &models[source.material.index()],
            max_impact_speed,
            &path,
            &mut sample_rng,
        );
        bound = TimeStepBound::min(bound, source_bound);
    }
    for (i, inlet) in inlets.iter().enumerate() {
        let path = format!("inlets[{i}]");
        let models = &models[inlet.material.index()];
        let inlet_bound = TimeStepBound::of_source(
            &inlet.recipe,
            inlet.density,
            scene.mass_model,
            models,
            max_impact_speed,
            &path,
            &mut sample_rng,
        );
        bound = TimeStepBound::min(bound, inlet_bound);
    }
    let time_step = safety::choose_time_step(scene.run.time_step_s, bound.as_ref(), scene.run.allow_unsafe_time_step)
        .map_err(|error| match &bound {
        Some(b) if error.kind() == ErrorKind::TimeStep => error.with_related(limiting_note(b)),
        _ => error,
    })?;
    if let Some(error) =
        safety::checkpoints_below_the_step(scene.run.checkpoint_interval_s, time_step, scene.run.time_step_s.is_none())
    {
        return Err(error);
    }

    // A scene that allows unsafe time steps experiments with instability: its particles may start as fast as it says,
    // and the engine stops the run where they outrun their step.
    let travel_limit = SafetyLimits::default().max_travel_fraction;
    if !scene.run.allow_unsafe_time_step {
        let mut errors = safety::too_fast_at_start(&particles, time_step, travel_limit);
        let mut inlet_rng = ChaCha8Rng::seed_from_u64(scene.run.seed);
        inlet_rng.set_stream(INLET_SPEED_STREAM);
        errors.extend(safety::inlets_too_fast(&inlets, time_step, travel_limit, &mut inlet_rng));
        if let Some(error) = SceneError::combine(errors) {
            return Err(error);
        }
    }

    let placed: Vec<PlacedBody> = walls
        .iter()
        .map(|w| PlacedBody { shape: &w.shape, pose: w.pose, is_wall: true, path: &w.path })
        .chain(particles.iter().map(|p| PlacedBody { shape: &p.shape, pose: p.pose, is_wall: false, path: &p.path }))
        .collect();
    // The rule the engine applies before its first step (`SafetyLimits::max_initial_overlap_fraction`), so that a
    // scene `check` passes is never refused by `run` for its start.
    let initial_tolerance = SafetyLimits::default().max_initial_overlap_fraction;
    if options.start_overlaps == StartOverlaps::Refuse {
        let blocks: Vec<BlockGrid> = scene
            .blocks
            .iter()
            .enumerate()
            .map(|(i, block)| BlockGrid {
                path: format!("blocks[{i}]"),
                spacing: block.grid_spacing_m,
                grid: block.grid,
            })
            .collect();
        let (errors, omitted) = safety::overlap_errors(&placed, initial_tolerance, &blocks);
        if let Some(error) = SceneError::combine(errors) {
            return Err(error.with_omitted(omitted));
        }
    }

    let config = WorldConfig {
        time_step,
        integrator: Integrator::Gear6(match scene.run.corrector {
            Corrector::VelocityDependent => GearC0::VelocityDependent,
            Corrector::PositionDependent => GearC0::PositionDependent,
        }),
        interactions: table,
        mass_model: scene.mass_model,
        gravity: gravity(&scene.gravity),
        heating: scene.heating.map(|h| HeatingSchedule {
            window: TimeWindow::new(h.window_s[0], h.window_s[1]),
            amplitude: h.amplitude,
            frequency: h.frequency_hz,
            slope: h.slope,
        }),
        safety: SafetyLimits {
            max_overlap_fraction: scene.run.max_overlap_fraction,
            max_energy_gain_fraction: scene.run.max_energy_gain_fraction,
            allow_unsafe_time_step: scene.run.allow_unsafe_time_step,
            max_impact_speed,
            ..SafetyLimits::default()
        },
        domain,
        seed: scene.run.seed,
    };
    let mut world = World::new(config).map_err(|e| world_error(&e, scene, bound.as_ref()))?;
    let moving_walls = walls.iter().filter(|w| !w.motion.is_static()).count();
    for wall in &walls {
        let id = world.add_wall(wall.shape.clone(), wall.pose, wall.surface_velocity, wall.motion);
        let material = materials.index_of(wall.material.as_deref(), &field_path(&wall.path, "material"))?;
        world.set_material(id, MaterialId(material as u16)).map_err(|e| engine_error(&e, &wall.path))?;
    }
    let mut drag_springs = 0;
    let mut kinds: Vec<fluid::NominalParticle> = Vec::new();
    for particle in &particles {
        let id = world
            .add_particle(
                particle.shape.clone(),
                particle.pose,
                particle.density,
                particle.velocity,
                particle.angular_velocity,
            )
            .map_err(|e| engine_error(&e, &particle.path))?;
        world.set_material(id, particle.material).map_err(|e| engine_error(&e, &particle.path))?;
        if kinds.last().is_none_or(|kind| kind.entry != particle.path) {
            let bodies = world.bodies();
            kinds.push(fluid::NominalParticle::of_body(bodies, id, &particle.path));
        }
        if let Some(spring) = particle.drag_spring {
            world.add_drag_spring(id, spring).map_err(|e| engine_error(&e, &particle.path))?;
            drag_springs += 1;
        }
    }
    for (i, source) in sources.into_iter().enumerate() {
        world.add_source(source).map_err(|e| engine_error(&e, &format!("sources[{i}]")))?;
    }
    for (i, inlet) in inlets.iter().enumerate() {
        kinds.push(fluid::NominalParticle::of_inlet(inlet, scene.mass_model, &format!("inlets[{i}]")));
    }
    for (i, inlet) in inlets.into_iter().enumerate() {
        world.add_inlet(inlet).map_err(|e| engine_error(&e, &format!("inlets[{i}]")))?;
    }
    for (i, outlet) in outlets.into_iter().enumerate() {
        world.add_outlet(outlet).map_err(|e| engine_error(&e, &format!("outlets[{i}]")))?;
    }
    let fluid = match &scene.fluid {
        Some(section) => {
            let engine = fluid::plan(section, &fluid::scene_folder(scene))?;
            let g = scene.gravity.largest_magnitude();
            let summary = fluid::summary(section, &engine, &kinds, scene.mass_model, g);
            world.set_fluid(engine).map_err(|e| engine_error(&e, "fluid"))?;
            Some(summary)
        }
        None => None,
    };
    world.check_time_step().map_err(|e| engine_error(&WorldError::Safety(e), "run.time_step_s"))?;
    world.shrink_to_fit();

    let summary = SceneSummary {
        name: scene.name.clone(),
        materials: materials.names(),
        interactions: crate::summary::interaction_lines(&materials.names(), &world.config().interactions),
        wall_bodies: walls.len(),
        moving_walls,
        mass_model: scene.mass_model,
        particles: particles.len(),
        particle_mass_kg_m: world
            .bodies()
            .particles()
            .map(|id| world.bodies().mass[id.index()])
            .fold(0.0, |a, m| a + m),
        drag_springs,
        sources: scene.sources.len(),
        inlets: scene.inlets.len(),
        planned_insertions: scene.sources.iter().map(|s| planned_insertions(s, scene.run.end_time_s)).sum::<u64>()
            + scene.inlets.iter().map(|i| inlets::planned_insertions(i, scene.run.end_time_s) as u64).sum::<u64>(),
        fluid,
        time_step_s: time_step,
        time_step_is_automatic: scene.run.time_step_s.is_none(),
        stable_time_step_s: bound.as_ref().map(|b| b.time_step),
        refusal_time_step_s: bound.as_ref().map(|b| b.refusal_time_step),
        limiting_entry: bound.map(|b| b.path),
        max_impact_speed_m_s: max_impact_speed,
        end_time_s: scene.run.end_time_s,
        heap_bytes_at_start: world.heap_bytes(),
    };
    let origins = if options.origins {
        numbered(walls.iter().map(|w| w.path.as_str()).chain(particles.iter().map(|p| p.path.as_str())))
    } else {
        Vec::new()
    };
    Ok(Built { world, summary, origins })
}

/// A note pointing at the scene entry whose particle sets the time-step bound.
fn limiting_note(bound: &TimeStepBound) -> SceneError {
    SceneError::new(
        ErrorKind::TimeStep,
        bound.path.clone(),
        format!(
            "the particle that limits the time step (inscribed radius {:.3e} m) comes from here",
            bound.inscribed_radius
        ),
    )
    .with_label("sets the bound")
}

/// An engine error while adding what `path` describes (validation catches these first; this is a backstop).
/// `World::new`'s refusal, located: a Δt the integrator cannot use is reported at `run.time_step_s` when the scene
/// gives one, else at the entry whose particle sets the automatic step (not at `Scene(`), its number in short form.
fn world_error(error: &WorldError, scene: &Scene, bound: Option<&TimeStepBound>) -> SceneError {
    let WorldError::TimeStep(IntegratorError::InvalidTimeStep(time_step)) = error else {
        return engine_error(error, "");
    };
    let path = match (scene.run.time_step_s, bound) {
        (Some(_), _) => "run.time_step_s".to_owned(),
        (None, Some(bound)) => bound.path.clone(),
        (None, None) => String::new(),
    };
    SceneError::new(
        ErrorKind::TimeStep,
        path,
        format!(
            "the time step {} s is not usable: the integrator needs a positive finite step with Δt⁵/120 a normal f64",
            number(*time_step)
        ),
    )
    .with_help("check the units of the materials' densities and Young's moduli, and of `run.time_step_s`")
}

fn engine_error(error: &WorldError, path: &str) -> SceneError {
    let kind = if matches!(error, WorldError::Safety(_)) { ErrorKind::TimeStep } else { ErrorKind::Value };
    SceneError::new(kind, path, error.to_string())
}

/// Explicit particles then block particles, with their materials, poses and drag springs.
fn plan_particles(
    scene: &Scene,
    materials: &Materials,
    rng: &mut ChaCha8Rng,
) -> Result<Vec<PlannedParticle>, SceneError> {
    let mut planned = Vec::new();
    for (i, particle) in scene.particles.iter().enumerate() {
        let path = format!("particles[{i}]");
        let material_path = field_path(&path, "material");
        let material = materials.resolve(particle.material.as_deref(), &material_path)?;
        let material_id = MaterialId(materials.index_of(particle.material.as_deref(), &material_path)? as u16);
        let shape = shapes::particle_outline(&particle.shape, &field_path(&path, "shape"), rng)?;
        let position = particle.position_m.map_or(shape.written_centroid, DVec2::from_array);
        planned.push(PlannedParticle {
            shape: shape.shape,
            pose: Pose::new(position, particle.angle_rad + shape.drawn_angle),
            velocity: DVec2::from_array(particle.velocity_m_s),
            angular_velocity: particle.angular_velocity_rad_s,
            density: Materials::density(material, scene.mass_model),
            material: material_id,
            drag_spring: particle.drag_spring.map(|s| EngineDragSpring {
                stiffness: s.stiffness_n_m,
                fixing_point: DVec2::from_array(s.fixing_point_m),
                pulling_start: DVec2::from_array(s.pulling_start_m),
                direction_angle: s.direction_rad,
                speed: s.speed_m_s,
                window: TimeWindow::new(s.window_s[0], s.window_s[1]),
            }),
            path,
        });
    }
    for (i, block) in scene.blocks.iter().enumerate() {
        let path = format!("blocks[{i}]");
        let material_path = field_path(&path, "material");
        let material = materials.resolve(block.material.as_deref(), &material_path)?;
        let material_id = MaterialId(materials.index_of(block.material.as_deref(), &material_path)? as u16);
        let lattice = Lattice::of(block, &path)?;
        let recipe = shapes::particle_recipe(&block.shape, &field_path(&path, "shape"))?;
        for particle in blocks::generate(block, &lattice, &recipe, rng, &path)? {
            planned.push(PlannedParticle {
                shape: particle.shape,
                pose: Pose::new(particle.position, particle.angle),
                velocity: particle.velocity,
                angular_velocity: 0.0,
                density: Materials::density(material, scene.mass_model),
                material: material_id,
                drag_spring: None,
                path: path.clone(),
            });
        }
    }
    Ok(planned)
}

fn plan_sources(scene: &Scene, materials: &Materials) -> Result<Vec<DropSource>, SceneError> {
    scene
        .sources
        .iter()
        .enumerate()
        .map(|(i, source)| {
            let path = format!("sources[{i}]");
            let material_path = field_path(&path, "material");
            let material = materials.resolve(source.material.as_deref(), &material_path)?;
            let material_id = MaterialId(materials.index_of(source.material.as_deref(), &material_path)? as u16);
            Ok(DropSource {
                position: DVec2::from_array(source.position_m),
                width: source.width_m,
                height: match source.height {
                    DropHeight::Absolute => gc2d_engine::DropHeight::Absolute,
                    DropHeight::AboveHighest => gc2d_engine::DropHeight::AboveHighest,
                },
                window: TimeWindow::new(source.window_s[0], source.window_s[1]),
                interval: source.interval_s,
                recipe: shapes::particle_recipe(&source.shape, &field_path(&path, "shape"))?,
                density: Materials::density(material, scene.mass_model),
                material: material_id,
            })
        })
        .collect()
}

fn gravity(gravity: &Gravity) -> GravitySchedule {
    match *gravity {
        Gravity::Constant(g) => GravitySchedule::constant(g),
        Gravity::Varying { profile, from_m_s2, to_m_s2, window_s, steps, ramp_fraction } => GravitySchedule {
            profile: match profile {
                GravityProfile::Linear => EngineProfile::Linear,
                GravityProfile::Step => EngineProfile::Step,
                GravityProfile::SmoothStep => EngineProfile::SmoothStep,
            },
            start_value: from_m_s2,
            end_value: to_m_s2,
            window: TimeWindow::new(window_s[0], window_s[1]),
            steps,
            ramp_fraction,
        },
    }
}

/// How many insertions a source attempts before the run ends: one at max(t1, 0) and one per interval while the time
/// is inside its window and not past the end time.
fn planned_insertions(source: &Source, end_time: f64) -> u64 {
    let first = source.window_s[0].max(0.0);
    let last = source.window_s[1].min(end_time);
    if !(last >= first && source.interval_s > 0.0) {
        return 0;
    }
    let span = (last - first) / source.interval_s;
    if span.is_finite() { span.floor() as u64 + u64::from(first < source.window_s[1]) } else { 0 }
}

/// Names for a list of entry paths: a path that occurs once as it is, one that occurs several times with ` #k`
/// (k from 0, in order).
fn numbered<'a>(paths: impl Iterator<Item = &'a str> + Clone) -> Vec<String> {
    let mut counts: std::collections::HashMap<&str, usize> = std::collections::HashMap::new();
    for path in paths.clone() {
        *counts.entry(path).or_default() += 1;
    }
    let mut seen: std::collections::HashMap<&str, usize> = std::collections::HashMap::new();
    paths
        .map(|path| {
            if counts[path] == 1 {
                return path.to_owned();
            }
            let k = seen.entry(path).or_default();
            *k += 1;
            format!("{path} #{}", *k - 1)
        })
        .collect()
}
