//! Semantic checks after parsing: value ranges, material names and the interaction table, shapes and wall macros.
//! Every problem is reported with its field path; all found in one pass are returned together.

use crate::build::blocks::{Lattice, MAX_INITIAL_PARTICLES};
use crate::build::safety::MIN_TIME_STEP_S;
use crate::build::{shapes, walls};
use crate::checks::{finite, finite_pair, in_range, non_negative, number, ordered_range, positive, window};
use crate::error::{SceneError, suggest};
use crate::schema::{
    Area, Damping, FrictionStiffness, Gravity, GravityProfile, InteractionLaw, MassModel, Material, Particle, Scene,
    Source,
};
use crate::spans::field_path;
use gc2d_contact::{
    Cohesion, ContactLaw, CundallStrack, NormalDamping, NormalElastic, PenetrationLawError, RestitutionTable,
};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::borrow::Cow;

/// The scene's materials: the declared ones, or the single default material.
pub(crate) struct Materials<'a>(Cow<'a, [Material]>);

impl<'a> Materials<'a> {
    pub fn of(scene: &'a Scene) -> Self {
        if scene.materials.is_empty() {
            Self(Cow::Owned(vec![Material::implicit()]))
        } else {
            Self(Cow::Borrowed(&scene.materials))
        }
    }

    /// The first material: the material of bodies that name none.
    pub fn first(&self) -> &Material {
        &self.0[0]
    }

    /// All materials, in scene order (their index is the engine's material id).
    pub fn all(&self) -> &[Material] {
        &self.0
    }

    /// The density of `material` in the unit `mass_model` reads: `density_kg_m2` or `density_kg_m3` (whose
    /// presence validation checks).
    pub fn density(material: &Material, mass_model: MassModel) -> f64 {
        match mass_model {
            MassModel::PerUnitThickness => material.density_kg_m2,
            MassModel::SphereEquivalent => material.density_kg_m3.unwrap_or(f64::NAN),
        }
    }

    /// The index of the material `name` refers to (the first when `None`), or an error as [`Self::resolve`] gives.
    pub fn index_of(&self, name: Option<&str>, path: &str) -> Result<usize, SceneError> {
        let material = self.resolve(name, path)?;
        Ok(self.0.iter().position(|m| std::ptr::eq(m, material)).unwrap_or(0))
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

/// The overlap-area law of a pair of materials whose parameters are `youngs_modulus_n_m`, `gamma`, `mu` and
/// `cohesion_n_m`: E always, damping, friction and cohesion only where their coefficient is positive (a zero
/// sub-model is left out and costs nothing).
pub(crate) fn overlap_area_law(youngs_modulus_n_m: f64, gamma: f64, mu: f64, cohesion_n_m: f64) -> ContactLaw {
    ContactLaw {
        elastic: NormalElastic::thesis(youngs_modulus_n_m),
        damping: (gamma > 0.0).then_some(NormalDamping { gamma }),
        friction: (mu > 0.0).then_some(CundallStrack { mu }),
        cohesion: (cohesion_n_m > 0.0).then_some(Cohesion { k_coh: cohesion_n_m }),
    }
}

impl Scene {
    /// The names of the scene's materials in the order of their ids in the built World (the single `default` material
    /// when the scene declares none).
    pub fn material_names(&self) -> Vec<String> {
        Materials::of(self).names()
    }

    /// Checks every value that can be checked without building: ranges, names, shapes, wall macros. Returns all
    /// problems found, the first as the error and the others as its related errors, located in the source text
    /// when the scene was loaded from one.
    pub fn validate(&self) -> Result<(), SceneError> {
        let mut errors = Vec::new();
        check_run(self, &mut errors);
        check_gravity_and_heating(self, &mut errors);
        check_materials(self, &mut errors);
        let materials = Materials::of(self);
        check_interactions(self, &materials, &mut errors);
        let mut rng = ChaCha8Rng::seed_from_u64(self.run.seed);
        for (i, item) in self.walls.iter().enumerate() {
            collect(&mut errors, walls::expand(item, &format!("walls[{i}]"), &mut rng).map(drop));
        }
        for (i, particle) in self.particles.iter().enumerate() {
            check_particle(particle, &format!("particles[{i}]"), &materials, &mut rng, &mut errors);
        }
        // Where the start's particles come from: (field, count).
        let mut initial: Vec<(String, usize)> = vec![("particles".to_owned(), self.particles.len())];
        for (i, block) in self.blocks.iter().enumerate() {
            let path = format!("blocks[{i}]");
            collect(
                &mut errors,
                materials.resolve(block.material.as_deref(), &field_path(&path, "material")).map(drop),
            );
            collect(&mut errors, shapes::particle_recipe(&block.shape, &field_path(&path, "shape")).map(drop));
            collect(
                &mut errors,
                ordered_range(&field_path(&path, "speed_range_m_s"), block.speed_range_m_s, false).map(drop),
            );
            collect(
                &mut errors,
                ordered_range(&field_path(&path, "direction_range_rad"), block.direction_range_rad, false).map(drop),
            );
            match Lattice::of(block, &path) {
                Ok(lattice) => initial.push((path, lattice.len())),
                Err(error) => errors.push(error),
            }
        }
        if let Some(mill) = &self.mill {
            initial.push(("mill.balls.count".to_owned(), mill.balls.count));
            initial.extend(mill.ore.as_ref().map(|ore| ("mill.ore.count".to_owned(), ore.count)));
        }
        collect(&mut errors, initial_count_in_range(&initial));
        let (mut insertions, mut most) = (0.0, 0.0f64);
        for (i, source) in self.sources.iter().enumerate() {
            let planned = check_source(source, &format!("sources[{i}]"), self.run.end_time_s, &materials, &mut errors);
            insertions += planned;
            most = most.max(planned);
        }
        // Together (a source that plans too many on its own has been reported at its interval).
        if insertions > MAX_INITIAL_PARTICLES as f64 && most <= MAX_INITIAL_PARTICLES as f64 {
            errors.push(
                SceneError::value(
                    "sources",
                    format!(
                        "the sources would insert {} particles before the end time, more than the \
                         {MAX_INITIAL_PARTICLES} allowed",
                        number(insertions)
                    ),
                )
                .with_help("use longer intervals or shorter windows"),
            );
        }
        crate::build::inlets::check(self, &materials, &mut errors);
        if let Some(fluid) = &self.fluid {
            crate::build::fluid::check(fluid, &mut errors);
        }
        if let Some(mill) = &self.mill {
            collect(&mut errors, crate::build::mill::check(mill, "mill"));
            for (field, name) in [
                ("mill.chamber_material", &mill.chamber_material),
                ("mill.rotor_material", &mill.rotor_material),
                ("mill.balls.material", &mill.balls.material),
                ("mill.ore.material", &mill.ore.as_ref().and_then(|ore| ore.material.clone())),
            ] {
                collect(&mut errors, materials.resolve(name.as_deref(), field).map(drop));
            }
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

/// Refuses a start of more than [`MAX_INITIAL_PARTICLES`] particles, at the field of the entry that gives the most of
/// them and naming every entry that gives some; `sources` are `(field, count)`.
fn initial_count_in_range(sources: &[(String, usize)]) -> Result<(), SceneError> {
    let total = sources.iter().fold(0usize, |total, (_, count)| total.saturating_add(*count));
    if total <= MAX_INITIAL_PARTICLES {
        return Ok(());
    }
    let mut given: Vec<&(String, usize)> = sources.iter().filter(|(_, count)| *count > 0).collect();
    given.sort_by_key(|(_, count)| std::cmp::Reverse(*count));
    let parts: Vec<String> = given.iter().map(|(field, count)| format!("{count} from `{field}`")).collect();
    Err(SceneError::value(
        &given[0].0,
        format!(
            "the scene starts with {total} particles ({}), more than the {MAX_INITIAL_PARTICLES} allowed",
            parts.join(", ")
        ),
    )
    .with_label("too many"))
}

fn collect(errors: &mut Vec<SceneError>, result: Result<(), SceneError>) {
    if let Err(error) = result {
        errors.push(error);
    }
}

fn check_run(scene: &Scene, errors: &mut Vec<SceneError>) {
    if let Some(error) = invisible_character("name", &scene.name, "`check` and the recordings") {
        errors.push(error.with_help("use visible characters only; `description` may hold several lines"));
    }
    let run = &scene.run;
    if let Some(dt) = run.time_step_s
        && !(dt >= MIN_TIME_STEP_S && dt.is_finite())
    {
        errors.push(
            SceneError::value(
                "run.time_step_s",
                format!(
                    "{} s: the time step must be a finite time of at least {} s",
                    number(dt),
                    number(MIN_TIME_STEP_S)
                ),
            )
            .with_label("out of range")
            .with_help("a femtosecond is the step of molecular dynamics; no grain contact needs a finer one"),
        );
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
    if let Some(speed) = run.max_impact_speed_m_s {
        collect(errors, positive("run.max_impact_speed_m_s", speed).map(drop));
    }
}

fn check_area(area: &Area, path: &str, errors: &mut Vec<SceneError>) {
    collect(errors, ordered_range(&field_path(path, "x_range_m"), area.x_range_m, true).map(drop));
    collect(errors, ordered_range(&field_path(path, "y_range_m"), area.y_range_m, true).map(drop));
}

fn check_gravity_and_heating(scene: &Scene, errors: &mut Vec<SceneError>) {
    match scene.gravity {
        Gravity::Constant(g) => collect(errors, gravity_in_range("gravity", g)),
        Gravity::Varying { profile, from_m_s2, to_m_s2, window_s, steps, ramp_fraction } => {
            if steps == 0 && profile != GravityProfile::Linear {
                errors.push(
                    SceneError::value("gravity.steps", format!("0: a {profile:?} change of g needs at least one step"))
                        .with_help("`steps: 1` changes g in one jump"),
                );
            }
            collect(errors, gravity_in_range("gravity.from_m_s2", from_m_s2));
            collect(errors, gravity_in_range("gravity.to_m_s2", to_m_s2));
            collect(errors, window("gravity.window_s", window_s).map(drop));
            if !(0.0..=1.0).contains(&ramp_fraction) {
                errors.push(SceneError::value(
                    "gravity.ramp_fraction",
                    format!("{}: must lie in [0, 1]", number(ramp_fraction)),
                ));
            }
        }
    }
    if let Some(heating) = &scene.heating {
        collect(errors, window("heating.window_s", heating.window_s).map(drop));
        if !(heating.amplitude > -1.0 && heating.amplitude.is_finite()) {
            errors.push(SceneError::value(
                "heating.amplitude",
                format!(
                    "{}: must be a finite number above −1 (particles cannot shrink to nothing)",
                    number(heating.amplitude)
                ),
            ));
        }
        collect(errors, positive("heating.frequency_hz", heating.frequency_hz).map(drop));
        collect(errors, non_negative("heating.slope", heating.slope).map(drop));
    }
}

/// Area densities a `PerUnitThickness` material may have, kg/m²: ρ·(1 m) of solids from a millimetre of aerogel
/// (1e-3) to a few metres of osmium (1e5). Outside, masses underflow to 0 (NaN at the first step) or give an automatic
/// Δt of hours.
const AREA_DENSITY_RANGE: [f64; 2] = [1e-3, 1e5];

const AREA_DENSITY_HELP: &str = "per unit thickness, the density in kg/m² is ρ·(1 m): 1,000–22,590 for solids, 5000 \
                                 in gc2d; the range spans a millimetre of aerogel to metres of osmium";

/// Densities a `SphereEquivalent` material may have, kg/m³: the lightest aerogels (0.1) to beyond osmium (22,590).
const DENSITY_RANGE: [f64; 2] = [0.1, 1e5];

const DENSITY_HELP: &str =
    "solids lie between the lightest aerogels (about 0.2 kg/m³) and osmium (22,590 kg/m³); steel is 7850";

/// Largest magnitude of gravity, m/s²: about 10⁶ g, what an ultracentrifuge reaches (geotechnical centrifuges run
/// granular models at a few hundred g). Far above, the first steps overflow to NaN.
const MAX_GRAVITY_M_S2: f64 = 1e7;

fn gravity_in_range(path: &str, g: f64) -> Result<(), SceneError> {
    in_range(path, g, [-MAX_GRAVITY_M_S2, MAX_GRAVITY_M_S2], "m/s²", "gravity").map(drop).map_err(|e| {
        e.with_help("gravity acts along −y; Earth's is 9.81 m/s², and |g| may be at most 1e7 m/s² (about 10⁶ g)")
    })
}

/// Young's moduli (2D, per unit thickness) of the overlap-area law, N/m: E·(1 m) from soft gels (1 kPa·m) to ten
/// times diamond. Outside, the automatic Δt leaves the numbers the integrator can use (1e-320 N/m gave an infinite
/// step, 1e300 N/m one of 1e-151 s, both refused by the engine at `Scene(` with hundreds of digits).
const YOUNGS_MODULUS_N_M_RANGE: [f64; 2] = [1.0, 1e13];

/// Young's moduli (3D) of the Hertz and Mindlin laws, Pa: soft gels (1 kPa) to ten times diamond.
const YOUNGS_MODULUS_PA_RANGE: [f64; 2] = [1e3, 1e13];

const YOUNGS_MODULUS_PA_HELP: &str =
    "solids lie between soft gels (about 1e3 Pa) and diamond (1.2e12 Pa); steel is 2.1e11";

/// Checks an overlap-area law's E against [`YOUNGS_MODULUS_N_M_RANGE`].
fn youngs_modulus_in_range(path: &str, modulus: f64) -> Result<(), SceneError> {
    in_range(path, modulus, YOUNGS_MODULUS_N_M_RANGE, "N/m", "Young's modulus E").map(drop).map_err(|e| {
        e.with_help(
            "per unit thickness, E in N/m is E·(1 m): 1e6 for rubber to 1.2e12 for diamond, 1e7 in gc2d; the range \
             spans soft gels to ten times diamond",
        )
    })
}

/// True for the characters that turn the direction of the text after them (U+202A–U+202E, U+2066–U+2069): printed
/// in a name, they make a terminal show the rest of the line reversed.
fn is_direction_override(c: char) -> bool {
    matches!(c, '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}')
}

/// The refusal, at `path`, of a name holding a control character (a line break, a NUL) or one that reverses the text
/// after it: printed in `printed_in`, it would break or reverse their lines. `None` for a name of visible characters.
fn invisible_character(path: &str, name: &str, printed_in: &str) -> Option<SceneError> {
    let c = name.chars().find(|&c| c.is_control() || is_direction_override(c))?;
    let message = format!(
        "the name holds the invisible character U+{:04X}: it would break the lines of {printed_in} that print it",
        u32::from(c)
    );
    Some(SceneError::value(path, message).with_help("use visible characters only"))
}

/// Ranges of each material and unique names.
fn check_materials(scene: &Scene, errors: &mut Vec<SceneError>) {
    if scene.materials.is_empty() && scene.mass_model == MassModel::SphereEquivalent {
        errors.push(
            SceneError::value("mass_model", "the SphereEquivalent mass model needs materials with `density_kg_m3`")
                .with_help(
                    "declare the scene's materials, e.g. `materials: [(name: \"steel\", density_kg_m3: 7850.0)]`",
                ),
        );
    }
    for (i, material) in scene.materials.iter().enumerate() {
        let at = |field: &str| format!("materials[{i}].{field}");
        if material.name.is_empty() {
            errors.push(SceneError::value(at("name"), "a material needs a name"));
        } else if let Some(error) =
            invisible_character(&at("name"), &material.name, "`check`, the events and the dumps")
        {
            errors.push(error);
        } else if scene.materials[..i].iter().any(|m| m.name == material.name) {
            errors.push(SceneError::value(at("name"), format!("material `{}` is defined twice", material.name)));
        }
        collect(
            errors,
            in_range(&at("density_kg_m2"), material.density_kg_m2, AREA_DENSITY_RANGE, "kg/m²", "the area density")
                .map(drop)
                .map_err(|e| e.with_help(AREA_DENSITY_HELP)),
        );
        match (scene.mass_model, material.density_kg_m3) {
            (MassModel::SphereEquivalent, Some(density)) => collect(
                errors,
                in_range(&at("density_kg_m3"), density, DENSITY_RANGE, "kg/m³", "the density")
                    .map(drop)
                    .map_err(|e| e.with_help(DENSITY_HELP)),
            ),
            (MassModel::SphereEquivalent, None) => errors.push(
                SceneError::value(
                    at("name"),
                    format!(
                        "material `{}` needs `density_kg_m3`: the scene's mass model is SphereEquivalent",
                        material.name
                    ),
                )
                .with_help("give the density in kg/m³, e.g. `density_kg_m3: 7850.0` for steel"),
            ),
            (MassModel::PerUnitThickness, Some(_)) => errors.push(
                SceneError::value(
                    at("density_kg_m3"),
                    "`density_kg_m3` is read only by `mass_model: SphereEquivalent`; this scene uses PerUnitThickness \
                     (`density_kg_m2`)",
                )
                .with_help("remove it, or set `mass_model: SphereEquivalent` at the top of the scene"),
            ),
            (MassModel::PerUnitThickness, None) => {}
        }
        if !(material.youngs_modulus_n_m > 0.0 && material.youngs_modulus_n_m.is_finite()) {
            errors.push(SceneError::value(
                at("youngs_modulus_n_m"),
                format!(
                    "{}: Young's modulus E must be a positive finite number (N/m)",
                    number(material.youngs_modulus_n_m)
                ),
            ));
        } else {
            collect(errors, youngs_modulus_in_range(&at("youngs_modulus_n_m"), material.youngs_modulus_n_m));
        }
        if let Some(modulus) = material.youngs_modulus_pa {
            collect(
                errors,
                in_range(&at("youngs_modulus_pa"), modulus, YOUNGS_MODULUS_PA_RANGE, "Pa", "Young's modulus")
                    .map(drop)
                    .map_err(|e| e.with_help(YOUNGS_MODULUS_PA_HELP)),
            );
        }
        collect(errors, non_negative(&at("gamma"), material.gamma).map(drop));
        if !(material.mu >= 0.0 && material.mu.is_finite()) {
            errors.push(
                SceneError::value(
                    at("mu"),
                    format!("{}: the friction coefficient μ must be a finite number ≥ 0", number(material.mu)),
                )
                .with_help("μ = 0 switches friction off"),
            );
        }
        collect(errors, non_negative(&at("cohesion_n_m"), material.cohesion_n_m).map(drop));
        if !(material.poisson_ratio > -1.0 && material.poisson_ratio <= 0.5) {
            errors.push(
                SceneError::value(
                    at("poisson_ratio"),
                    format!(
                        "{}: Poisson's ratio ν of an isotropic solid lies in (−1, 0.5]",
                        number(material.poisson_ratio)
                    ),
                )
                .with_label("out of range")
                .with_help("steel and glass are about 0.3, rubber almost 0.5; at −1 the shear modulus is infinite"),
            );
        }
    }
}

/// The `interactions` entries: known material names, each pair once, parameters in range.
fn check_interactions(scene: &Scene, materials: &Materials, errors: &mut Vec<SceneError>) {
    let mut seen: Vec<[&str; 2]> = Vec::new();
    for (i, interaction) in scene.interactions.iter().enumerate() {
        let path = format!("interactions[{i}]");
        let mut known = true;
        for (k, name) in interaction.materials.iter().enumerate() {
            let at = format!("{path}.materials.{k}");
            if let Err(error) = materials.resolve(Some(name), &at) {
                errors.push(error);
                known = false;
            }
        }
        let [a, b] = [interaction.materials[0].as_str(), interaction.materials[1].as_str()];
        let pair = if a <= b { [a, b] } else { [b, a] };
        if known && seen.contains(&pair) {
            errors.push(
                SceneError::value(field_path(&path, "materials"), format!("the pair `{a}`–`{b}` is given a law twice"))
                    .with_help("give each pair of materials one entry; the later one would silently win")
                    .with_label("second entry for this pair"),
            );
        }
        seen.push(pair);
        let at = |field: &str| field_path(&field_path(&path, "law"), field);
        if let InteractionLaw::OverlapArea { youngs_modulus_n_m, gamma, mu, cohesion_n_m, .. } = &interaction.law {
            if let Some(e) = youngs_modulus_n_m {
                collect(errors, youngs_modulus_in_range(&at("youngs_modulus_n_m"), *e));
            }
            for (field, value) in [("gamma", gamma), ("mu", mu), ("cohesion_n_m", cohesion_n_m)] {
                if let Some(value) = value {
                    collect(errors, non_negative(&at(field), *value).map(drop));
                }
            }
            continue;
        }
        // The law's own numbers, each at its field; a law with a bad one, or between materials whose own moduli are
        // refused already, is not built (its errors would repeat the cause in the engine's terms).
        let before = errors.len();
        check_penetration_law(&interaction.law, &field_path(&path, "law"), errors);
        let resolved = (materials.resolve(Some(a), ""), materials.resolve(Some(b), ""));
        if errors.len() == before
            && let (Ok(a), Ok(b)) = resolved
            && usable_moduli(a)
            && usable_moduli(b)
            && let Err(message) = crate::build::interactions::listed_model(&interaction.law, a, b)
        {
            errors.push(SceneError::value(field_path(&path, "law"), message).with_label("cannot be used"));
        }
    }
}

/// The numbers of a `Linear` or `Hertz` law at their fields (`interactions[0].law.friction.mu`), in the ranges the
/// engine's law accepts.
fn check_penetration_law(law: &InteractionLaw, path: &str, errors: &mut Vec<SceneError>) {
    let (damping, friction, rolling) = match law {
        InteractionLaw::OverlapArea { .. } => return,
        InteractionLaw::Linear { stiffness_n_m, damping, friction, rolling, .. } => {
            collect(errors, positive(&field_path(path, "stiffness_n_m"), *stiffness_n_m).map(drop));
            (damping, friction, rolling)
        }
        InteractionLaw::Hertz { damping, friction, rolling, .. } => (damping, friction, rolling),
    };
    let at = |parent: &str, field: &str| field_path(&field_path(path, parent), field);
    match *damping {
        Damping::Ratio(ratio) => collect(errors, non_negative(&at("damping", "0"), ratio).map(drop)),
        Damping::Restitution(e) if !(0.0..=1.0).contains(&e) => errors.push(
            SceneError::value(
                at("damping", "0"),
                format!("{}: a coefficient of restitution lies in [0, 1]", number(e)),
            )
            .with_label("out of range"),
        ),
        Damping::PowerLaw { a, b, c } => {
            collect(errors, non_negative(&at("damping", "a"), a).map(drop));
            collect(errors, positive(&at("damping", "b"), b).map(drop));
            collect(errors, finite(&at("damping", "c"), c).map(drop));
        }
        Damping::Table(ref points) => {
            if let Err(error) = RestitutionTable::new(points) {
                // A bad point is named by its index in the list, a bad length at the list.
                let field = match error {
                    PenetrationLawError::TableSpeed { index, .. }
                    | PenetrationLawError::TableRestitution { index, .. } => format!("{}[{index}]", at("damping", "0")),
                    _ => at("damping", "0"),
                };
                errors.push(SceneError::value(field, format!("damping table: {error}")).with_label("out of range"));
            }
        }
        _ => {}
    }
    if let Some(friction) = friction {
        collect(errors, non_negative(&at("friction", "mu"), friction.mu).map(drop));
        collect(errors, non_negative(&at("friction", "damping_ratio"), friction.damping_ratio).map(drop));
        if let Some(FrictionStiffness::Ratio(ratio)) = friction.stiffness {
            collect(errors, non_negative(&field_path(&at("friction", "stiffness"), "0"), ratio).map(drop));
        }
    }
    if let Some(rolling) = rolling {
        for (field, value) in [
            ("mu_r", rolling.mu_r),
            ("stiffness_ratio", rolling.stiffness_ratio),
            ("damping_ratio", rolling.damping_ratio),
        ] {
            collect(errors, non_negative(&at("rolling", field), value).map(drop));
        }
    }
}

/// True when `material`'s Young's modulus (where given) and Poisson's ratio are ones its own checks accept, so that a
/// law built from them fails, if at all, for a reason of its own.
fn usable_moduli(material: &Material) -> bool {
    let modulus = material.youngs_modulus_pa.is_none_or(|e| e.is_finite() && e > 0.0);
    modulus && material.poisson_ratio > -1.0 && material.poisson_ratio <= 0.5
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
    collect(errors, shapes::particle_outline(&particle.shape, &at("shape"), rng).map(drop));
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

/// Shortest interval between a source's insertions, s. Far below any contact time step, and long enough that the
/// source's schedule moves on (t + interval > t in f64) up to t = 10⁷ s.
const MIN_SOURCE_INTERVAL_S: f64 = 1e-9;

/// Checks a source; returns the insertions it plans before `end_time` (0 when its times are unusable).
fn check_source(
    source: &Source,
    path: &str,
    end_time: f64,
    materials: &Materials,
    errors: &mut Vec<SceneError>,
) -> f64 {
    let at = |field: &str| field_path(path, field);
    collect(errors, materials.resolve(source.material.as_deref(), &at("material")).map(drop));
    collect(errors, shapes::particle_recipe(&source.shape, &at("shape")).map(drop));
    collect(errors, finite_pair(&at("position_m"), source.position_m).map(drop));
    collect(errors, non_negative(&at("width_m"), source.width_m).map(drop));
    let window_ok = window(&at("window_s"), source.window_s).map_err(|e| errors.push(e)).is_ok();
    let interval = source.interval_s;
    if !(interval >= MIN_SOURCE_INTERVAL_S && interval.is_finite()) {
        errors.push(
            SceneError::value(
                at("interval_s"),
                format!(
                    "{} s: the interval between insertions must be a finite time of at least {} s",
                    number(interval),
                    number(MIN_SOURCE_INTERVAL_S)
                ),
            )
            .with_label("too short")
            .with_help("check the units: `interval_s` is in seconds"),
        );
        return 0.0;
    }
    if !window_ok || !end_time.is_finite() {
        return 0.0;
    }
    let planned = planned_insertions(source, end_time);
    if planned > MAX_INITIAL_PARTICLES as f64 {
        errors.push(
            SceneError::value(
                at("interval_s"),
                format!(
                    "the source would insert {} particles before the end time {} s, more than the \
                     {MAX_INITIAL_PARTICLES} allowed",
                    number(planned),
                    number(end_time)
                ),
            )
            .with_label("too short")
            .with_help("use a longer interval or a shorter `window_s`; `interval_s` is in seconds"),
        );
    }
    planned
}

/// How many insertions a source attempts before `end_time`, as the build counts them (`planned_insertions` in
/// build/mod.rs): one at max(t1, 0) and one per interval while inside the window and not past the end time. In f64,
/// so that absurd values give a large number instead of overflowing; needs a checked window (no NaN), a finite
/// `end_time` and an interval > 0.
fn planned_insertions(source: &Source, end_time: f64) -> f64 {
    let first = source.window_s[0].max(0.0);
    let last = source.window_s[1].min(end_time);
    if last < first {
        return 0.0;
    }
    ((last - first) / source.interval_s).floor() + if first < source.window_s[1] { 1.0 } else { 0.0 }
}
