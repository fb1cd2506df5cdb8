//! Semantic checks after parsing: value ranges, material names and the one-contact-law rule, shapes and wall macros.
//! Every problem is reported with its field path; all found in one pass are returned together.

use crate::build::blocks::{Lattice, MAX_INITIAL_PARTICLES};
use crate::build::{shapes, walls};
use crate::checks::{finite, finite_pair, non_negative, ordered_range, positive, window};
use crate::error::{SceneError, suggest};
use crate::schema::{Area, Gravity, Material, Particle, Scene, Source, defaults};
use crate::spans::field_path;
use gc2d_contact::{Cohesion, ContactLaw, CundallStrack, NormalDamping, NormalElastic};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::borrow::Cow;

/// The scene's materials: the declared ones, or the single default material.
pub(crate) struct Materials<'a>(Cow<'a, [Material]>);

impl<'a> Materials<'a> {
    pub fn of(scene: &'a Scene) -> Self {
        if scene.materials.is_empty() {
            Self(Cow::Owned(vec![Material::named(defaults::MATERIAL)]))
        } else {
            Self(Cow::Borrowed(&scene.materials))
        }
    }

    /// The first material, which also carries the scene's contact law.
    pub fn first(&self) -> &Material {
        &self.0[0]
    }

    /// The names, in order.
    pub fn names(&self) -> Vec<String> {
        self.0.iter().map(|m| m.name.clone()).collect()
    }

    /// The material `name` refers to (the first when `None`), or an error at `path` suggesting the closest name.
    pub fn resolve(&self, name: Option<&str>, path: &str) -> Result<&Material, SceneError> {
        let Some(name) = name else { return Ok(self.first()) };
        if let Some(material) = self.0.iter().find(|m| m.name == name) {
            return Ok(material);
        }
        let names: Vec<&str> = self.0.iter().map(|m| m.name.as_str()).collect();
        let hint = suggest(name, &names).map_or(String::new(), |s| format!(", did you mean `{s}`?"));
        Err(SceneError::value(path, format!("unknown material `{name}`{hint}"))
            .with_help(format!(
                "the scene's materials are {}",
                names.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")
            ))
            .with_label("no such material"))
    }
}

/// The contact law of a material: E always, damping, friction and cohesion only where their coefficient is
/// positive (a zero sub-model is left out and costs nothing).
pub(crate) fn contact_law(material: &Material) -> ContactLaw {
    ContactLaw {
        elastic: NormalElastic { e_modulus: material.youngs_modulus_n_m },
        damping: (material.gamma > 0.0).then_some(NormalDamping { gamma: material.gamma }),
        friction: (material.mu > 0.0).then_some(CundallStrack { mu: material.mu }),
        cohesion: (material.cohesion_n_m > 0.0).then_some(Cohesion { k_coh: material.cohesion_n_m }),
    }
}

impl Scene {
    /// Checks every value that can be checked without building: ranges, names, shapes, wall macros. Returns all
    /// problems found, the first as the error and the others as its related errors, located in the source text
    /// when the scene was loaded from one.
    pub fn validate(&self) -> Result<(), SceneError> {
        let mut errors = Vec::new();
        check_run(self, &mut errors);
        check_gravity_and_heating(self, &mut errors);
        check_materials(self, &mut errors);
        let materials = Materials::of(self);
        let mut rng = ChaCha8Rng::seed_from_u64(self.run.seed);
        for (i, item) in self.walls.iter().enumerate() {
            collect(&mut errors, walls::expand(item, &format!("walls[{i}]"), &mut rng).map(drop));
        }
        for (i, particle) in self.particles.iter().enumerate() {
            check_particle(particle, &format!("particles[{i}]"), &materials, &mut rng, &mut errors);
        }
        let mut initial = self.particles.len();
        for (i, block) in self.blocks.iter().enumerate() {
            let path = format!("blocks[{i}]");
            collect(
                &mut errors,
                materials.resolve(block.material.as_deref(), &field_path(&path, "material")).map(drop),
            );
            collect(&mut errors, shapes::shape_recipe(&block.shape, &field_path(&path, "shape")).map(drop));
            collect(
                &mut errors,
                ordered_range(&field_path(&path, "speed_range_m_s"), block.speed_range_m_s, false).map(drop),
            );
            collect(
                &mut errors,
                ordered_range(&field_path(&path, "direction_range_rad"), block.direction_range_rad, false).map(drop),
            );
            match Lattice::of(block, &path) {
                Ok(lattice) => initial = initial.saturating_add(lattice.len()),
                Err(error) => errors.push(error),
            }
        }
        if initial > MAX_INITIAL_PARTICLES {
            errors.push(SceneError::value(
                "blocks",
                format!("the scene starts with {initial} particles, more than the {MAX_INITIAL_PARTICLES} allowed"),
            ));
        }
        for (i, source) in self.sources.iter().enumerate() {
            check_source(source, &format!("sources[{i}]"), &materials, &mut errors);
        }
        if let Some(view) = &self.view {
            check_area(view, "view", &mut errors);
        }
        match SceneError::combine(errors) {
            None => Ok(()),
            Some(error) => Err(error.located(self.source.as_ref())),
        }
    }

    /// The number of particles the scene starts with (explicit particles plus block lattice points), without
    /// building it; saturates instead of overflowing for absurd blocks (which validation refuses).
    pub fn initial_particle_count(&self) -> usize {
        self.blocks
            .iter()
            .enumerate()
            .filter_map(|(i, b)| Lattice::of(b, &format!("blocks[{i}]")).ok())
            .fold(self.particles.len(), |n, lattice| n.saturating_add(lattice.len()))
    }
}

fn collect(errors: &mut Vec<SceneError>, result: Result<(), SceneError>) {
    if let Err(error) = result {
        errors.push(error);
    }
}

fn check_run(scene: &Scene, errors: &mut Vec<SceneError>) {
    let run = &scene.run;
    if let Some(dt) = run.time_step_s {
        collect(errors, positive("run.time_step_s", dt).map(drop));
    }
    collect(errors, non_negative("run.end_time_s", run.end_time_s).map(drop));
    collect(errors, positive("run.frames_per_second", run.frames_per_second).map(drop));
    if let Some(interval) = run.checkpoint_interval_s {
        collect(errors, positive("run.checkpoint_interval_s", interval).map(drop));
    }
    if let Some(domain) = &run.domain {
        check_area(domain, "run.domain", errors);
    }
    collect(errors, positive("run.max_overlap_fraction", run.max_overlap_fraction).map(drop));
    collect(errors, positive("run.max_energy_gain_fraction", run.max_energy_gain_fraction).map(drop));
}

fn check_area(area: &Area, path: &str, errors: &mut Vec<SceneError>) {
    collect(errors, ordered_range(&field_path(path, "x_range_m"), area.x_range_m, true).map(drop));
    collect(errors, ordered_range(&field_path(path, "y_range_m"), area.y_range_m, true).map(drop));
}

fn check_gravity_and_heating(scene: &Scene, errors: &mut Vec<SceneError>) {
    match scene.gravity {
        Gravity::Constant(g) => collect(errors, finite("gravity", g).map(drop)),
        Gravity::Varying { from_m_s2, to_m_s2, window_s, ramp_fraction, .. } => {
            collect(errors, finite("gravity.from_m_s2", from_m_s2).map(drop));
            collect(errors, finite("gravity.to_m_s2", to_m_s2).map(drop));
            collect(errors, window("gravity.window_s", window_s).map(drop));
            if !(0.0..=1.0).contains(&ramp_fraction) {
                errors.push(SceneError::value("gravity.ramp_fraction", format!("{ramp_fraction}: must lie in [0, 1]")));
            }
        }
    }
    if let Some(heating) = &scene.heating {
        collect(errors, window("heating.window_s", heating.window_s).map(drop));
        if !(heating.amplitude > -1.0 && heating.amplitude.is_finite()) {
            errors.push(SceneError::value(
                "heating.amplitude",
                format!("{}: must be a finite number above −1 (particles cannot shrink to nothing)", heating.amplitude),
            ));
        }
        collect(errors, positive("heating.frequency_hz", heating.frequency_hz).map(drop));
        collect(errors, non_negative("heating.slope", heating.slope).map(drop));
    }
}

/// Ranges of each material, unique names, and one contact law for all (the engine has a single global law).
fn check_materials(scene: &Scene, errors: &mut Vec<SceneError>) {
    for (i, material) in scene.materials.iter().enumerate() {
        let at = |field: &str| format!("materials[{i}].{field}");
        if material.name.is_empty() {
            errors.push(SceneError::value(at("name"), "a material needs a name"));
        } else if scene.materials[..i].iter().any(|m| m.name == material.name) {
            errors.push(SceneError::value(at("name"), format!("material `{}` is defined twice", material.name)));
        }
        collect(errors, positive(&at("density_kg_m2"), material.density_kg_m2).map(drop));
        if !(material.youngs_modulus_n_m > 0.0 && material.youngs_modulus_n_m.is_finite()) {
            errors.push(SceneError::value(
                at("youngs_modulus_n_m"),
                format!("{}: Young's modulus E must be a positive finite number (N/m)", material.youngs_modulus_n_m),
            ));
        }
        collect(errors, non_negative(&at("gamma"), material.gamma).map(drop));
        if !(material.mu >= 0.0 && material.mu.is_finite()) {
            errors.push(
                SceneError::value(
                    at("mu"),
                    format!("{}: the friction coefficient μ must be a finite number ≥ 0", material.mu),
                )
                .with_help("μ = 0 switches friction off"),
            );
        }
        collect(errors, non_negative(&at("cohesion_n_m"), material.cohesion_n_m).map(drop));
    }
    let Some(first) = scene.materials.first() else { return };
    for (i, material) in scene.materials.iter().enumerate().skip(1) {
        let differences = [
            ("youngs_modulus_n_m", first.youngs_modulus_n_m, material.youngs_modulus_n_m),
            ("gamma", first.gamma, material.gamma),
            ("mu", first.mu, material.mu),
            ("cohesion_n_m", first.cohesion_n_m, material.cohesion_n_m),
        ];
        for (field, expected, found) in differences {
            if expected.to_bits() != found.to_bits() && !(expected.is_nan() || found.is_nan()) {
                errors.push(
                    SceneError::value(
                        format!("materials[{i}].{field}"),
                        format!(
                            "material `{}` has {field} = {found}, but `{}` has {expected}: all materials must share \
                             one contact law for now",
                            material.name, first.name
                        ),
                    )
                    .with_help("gc2d-rs has one contact law per scene; materials may differ only in density_kg_m2")
                    .with_label("differs from the first material"),
                );
            }
        }
    }
}

fn check_particle(
    particle: &Particle,
    path: &str,
    materials: &Materials,
    rng: &mut ChaCha8Rng,
    errors: &mut Vec<SceneError>,
) {
    let at = |field: &str| field_path(path, field);
    collect(errors, materials.resolve(particle.material.as_deref(), &at("material")).map(drop));
    collect(errors, shapes::outline(&particle.shape, &at("shape"), rng).map(drop));
    if let Some(position) = particle.position_m {
        collect(errors, finite_pair(&at("position_m"), position).map(drop));
    }
    collect(errors, finite(&at("angle_rad"), particle.angle_rad).map(drop));
    collect(errors, finite_pair(&at("velocity_m_s"), particle.velocity_m_s).map(drop));
    collect(errors, finite(&at("angular_velocity_rad_s"), particle.angular_velocity_rad_s).map(drop));
    if let Some(spring) = &particle.drag_spring {
        let at = |field: &str| field_path(&at("drag_spring"), field);
        collect(errors, non_negative(&at("stiffness_n_m"), spring.stiffness_n_m).map(drop));
        collect(errors, finite_pair(&at("fixing_point_m"), spring.fixing_point_m).map(drop));
        collect(errors, finite_pair(&at("pulling_start_m"), spring.pulling_start_m).map(drop));
        collect(errors, finite(&at("direction_rad"), spring.direction_rad).map(drop));
        collect(errors, finite(&at("speed_m_s"), spring.speed_m_s).map(drop));
        collect(errors, window(&at("window_s"), spring.window_s).map(drop));
    }
}

fn check_source(source: &Source, path: &str, materials: &Materials, errors: &mut Vec<SceneError>) {
    let at = |field: &str| field_path(path, field);
    collect(errors, materials.resolve(source.material.as_deref(), &at("material")).map(drop));
    collect(errors, shapes::shape_recipe(&source.shape, &at("shape")).map(drop));
    collect(errors, finite_pair(&at("position_m"), source.position_m).map(drop));
    collect(errors, non_negative(&at("width_m"), source.width_m).map(drop));
    collect(errors, window(&at("window_s"), source.window_s).map(drop));
    collect(errors, positive(&at("interval_s"), source.interval_s).map(drop));
}
