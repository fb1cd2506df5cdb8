//! Inlets and outlets: their checks (located at the field), the start-phase warning, and the engine's inlets and
//! outlets they build.

use super::shapes;
use crate::build::blocks::MAX_INITIAL_PARTICLES;
use crate::checks::{finite, finite_pair, number, window};
use crate::error::SceneError;
use crate::schema::{Inlet, Scene};
use crate::spans::field_path;
use crate::validate::Materials;
use gc2d_engine::{Inlet as EngineInlet, MaterialId, Outlet as EngineOutlet};
use gc2d_geometry::DVec2;

/// The name an inlet's or outlet's counters go by: its own, or its index in the list.
fn counter_name(name: Option<&str>, index: usize) -> String {
    name.map_or_else(|| index.to_string(), str::to_owned)
}

/// Checks a name for a CSV column (letters, digits, `_` and `-`, not empty) and that the name the counters of entry
/// `index` go by ([`counter_name`]: its own, or its index) is not another entry's: two inlets named `1` and `1` by
/// default would give the time series the same columns twice.
fn check_name(name: Option<&str>, index: usize, path: &str, seen: &mut Vec<String>, errors: &mut Vec<SceneError>) {
    if let Some(name) = name
        && (name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-'))
    {
        errors.push(
            SceneError::value(field_path(path, "name"), format!("`{name}` is not a usable column name"))
                .with_help("use letters, digits, `_` and `-`"),
        );
        return;
    }
    let counters = counter_name(name, index);
    if !seen.contains(&counters) {
        seen.push(counters);
        return;
    }
    let error = match name {
        Some(name) => SceneError::value(field_path(path, "name"), format!("the name `{name}` is used twice")),
        None => SceneError::value(
            path,
            format!("without a name its counters go by its index, `{counters}`, which another one has as its name"),
        ),
    };
    errors.push(error.with_help("give each a name of its own (one without a name goes by its index in the list)"));
}

/// Checks a segment: finite end points that differ.
fn check_segment(from: [f64; 2], to: [f64; 2], path: &str, errors: &mut Vec<SceneError>) -> bool {
    let ends = [finite_pair(&field_path(path, "from_m"), from), finite_pair(&field_path(path, "to_m"), to)];
    let mut ok = true;
    for end in ends {
        if let Err(error) = end {
            errors.push(error);
            ok = false;
        }
    }
    if ok && from == to {
        errors.push(
            SceneError::value(
                field_path(path, "to_m"),
                format!("the segment has zero length: both ends are at ({}, {})", number(to[0]), number(to[1])),
            )
            .with_label("same as from_m"),
        );
        return false;
    }
    ok
}

/// The unit inward normal of the segment `from` → `to` (its direction turned 90° CCW).
fn inward_normal(from: [f64; 2], to: [f64; 2]) -> DVec2 {
    (DVec2::from_array(to) - DVec2::from_array(from)).perp().normalize_or_zero()
}

/// Checks the scene's inlets and outlets, adding each problem to `errors` at its field.
pub(crate) fn check(scene: &Scene, materials: &Materials, errors: &mut Vec<SceneError>) {
    let mut names = Vec::new();
    for (i, inlet) in scene.inlets.iter().enumerate() {
        let path = format!("inlets[{i}]");
        let at = |field: &str| field_path(&path, field);
        check_name(inlet.name.as_deref(), i, &path, &mut names, errors);
        let segment_ok = check_segment(inlet.from_m, inlet.to_m, &path, errors);
        if let Err(error) = materials.resolve(inlet.material.as_deref(), &at("material")) {
            errors.push(error);
        }
        if let Err(error) = shapes::particle_recipe(&inlet.shape, &at("shape")) {
            errors.push(error);
        }
        if let Err(error) = finite(&at("angular_velocity_rad_s"), inlet.angular_velocity_rad_s) {
            errors.push(error);
        }
        let mut window_ok = window(&at("window_s"), inlet.window_s).map_err(|e| errors.push(e)).is_ok();
        if window_ok && inlet.window_s[0] < 0.0 {
            // Particle k is due at t1 + k/rate: those due before the run's start would wait as a backlog.
            errors.push(
                SceneError::value(
                    at("window_s"),
                    format!(
                        "({}, {}) starts before the run does (t = 0): the particles due before 0 would wait as a \
                         backlog, fed as room clears",
                        number(inlet.window_s[0]),
                        number(inlet.window_s[1])
                    ),
                )
                .with_help("start the window at 0 or later"),
            );
            window_ok = false;
        }
        match finite_pair(&at("velocity_m_s"), inlet.velocity_m_s) {
            Err(error) => errors.push(error),
            Ok(velocity) if segment_ok => {
                let normal = inward_normal(inlet.from_m, inlet.to_m);
                if DVec2::from_array(velocity).dot(normal) <= 0.0 {
                    errors.push(
                        SceneError::value(
                            at("velocity_m_s"),
                            format!(
                                "the start velocity ({}, {}) m/s does not point into the domain, which lies on the \
                                 left of the segment from from_m to to_m (inward normal ({}, {}))",
                                number(velocity[0]),
                                number(velocity[1]),
                                number(normal.x + 0.0),
                                number(normal.y + 0.0)
                            ),
                        )
                        .with_label("points outward")
                        .with_help(
                            "give a velocity with a positive component along the inward normal, or swap from_m and to_m",
                        ),
                    );
                }
            }
            Ok(_) => {}
        }
        let rate = inlet.rate_per_s;
        if !(rate > 0.0 && rate.is_finite()) {
            errors.push(
                SceneError::value(
                    at("rate_per_s"),
                    format!("{}: the rate must be a positive number of particles per second", number(rate)),
                )
                .with_label("not positive"),
            );
        } else if window_ok && scene.run.end_time_s.is_finite() {
            let planned = planned_insertions(inlet, scene.run.end_time_s);
            if planned > MAX_INITIAL_PARTICLES as f64 {
                errors.push(
                    SceneError::value(
                        at("rate_per_s"),
                        format!(
                            "the inlet would feed {} particles before the end time {} s, more than the \
                             {MAX_INITIAL_PARTICLES} allowed",
                            number(planned),
                            number(scene.run.end_time_s)
                        ),
                    )
                    .with_label("too many")
                    .with_help("use a lower rate or a shorter `window_s`; `rate_per_s` is in particles per second"),
                );
            }
        }
    }
    let mut names = Vec::new();
    for (i, outlet) in scene.outlets.iter().enumerate() {
        let path = format!("outlets[{i}]");
        check_name(outlet.name.as_deref(), i, &path, &mut names, errors);
        check_segment(outlet.from_m, outlet.to_m, &path, errors);
    }
}

/// Particles an inlet feeds before `end_time` if none is postponed: those due in [t1, min(t2, end)). Needs a checked
/// window and a positive rate.
pub(crate) fn planned_insertions(inlet: &Inlet, end_time: f64) -> f64 {
    let first = inlet.window_s[0].max(0.0);
    let last = inlet.window_s[1].min(end_time);
    if last <= first { 0.0 } else { ((last - first) * inlet.rate_per_s).ceil() }
}

impl Scene {
    /// `path` prefixed with the file, line and column of its value where the scene was read from a text that holds
    /// it (`feed.ron:12:22: inlets[0].velocity_m_s`), else `path` alone.
    pub(crate) fn located_field(&self, path: &str) -> String {
        let place =
            self.source.as_ref().and_then(|source| Some(format!("{}: ", source.location(source.span_of(path)?.start))));
        format!("{}{path}", place.unwrap_or_default())
    }

    /// Warnings about the scene's inlets that do not stop it (feedpipe.md §2.12): an inlet whose start speed across
    /// the segment is below 2R·rate (R the recipe's nominal radius: a disk's radius, a polygon's larger semi-axis)
    /// lets a particle move less than one diameter before the next appears, so that particles may pile up at the
    /// inlet and insertions be postponed. Each names the file, line and column of the inlet's field where the scene
    /// was read from a text (`feed.ron:12:22: inlets[0].velocity_m_s: …`), else the field alone; empty for a scene
    /// without such an inlet.
    pub(crate) fn inlet_warnings(&self) -> Vec<String> {
        self.inlets
            .iter()
            .enumerate()
            .filter_map(|(i, inlet)| {
                let normal_speed = DVec2::from_array(inlet.velocity_m_s).dot(inward_normal(inlet.from_m, inlet.to_m));
                let radius = shapes::particle_recipe(&inlet.shape, "").ok().map(|recipe| match recipe {
                    gc2d_engine::ParticleRecipe::Disk(disk) => disk.radius,
                    gc2d_engine::ParticleRecipe::Polygon(polygon) => polygon.semi_axes.x.max(polygon.semi_axes.y),
                })?;
                let needed = 2.0 * radius * inlet.rate_per_s;
                (normal_speed < needed).then(|| {
                    format!(
                        "{}: the speed into the domain {} m/s is below 2R·rate = {} m/s: particles may pile up at \
                         the inlet (feedpipe.md §2.12)",
                        self.located_field(&format!("inlets[{i}].velocity_m_s")),
                        number(normal_speed),
                        number(needed)
                    )
                })
            })
            .collect()
    }
}

/// The engine's inlets and outlets of a validated scene.
pub(crate) fn plan(scene: &Scene, materials: &Materials) -> Result<(Vec<EngineInlet>, Vec<EngineOutlet>), SceneError> {
    let inlets = scene
        .inlets
        .iter()
        .enumerate()
        .map(|(i, inlet)| {
            let path = format!("inlets[{i}]");
            let material_path = field_path(&path, "material");
            let material = materials.resolve(inlet.material.as_deref(), &material_path)?;
            Ok(EngineInlet {
                name: counter_name(inlet.name.as_deref(), i),
                from: DVec2::from_array(inlet.from_m),
                to: DVec2::from_array(inlet.to_m),
                rate: inlet.rate_per_s,
                start: inlet.window_s[0],
                stop: inlet.window_s[1],
                velocity: DVec2::from_array(inlet.velocity_m_s),
                angular_velocity: inlet.angular_velocity_rad_s,
                recipe: shapes::particle_recipe(&inlet.shape, &field_path(&path, "shape"))?,
                density: Materials::density(material, scene.mass_model),
                material: MaterialId(materials.index_of(inlet.material.as_deref(), &material_path)? as u16),
            })
        })
        .collect::<Result<Vec<_>, SceneError>>()?;
    let outlets = scene
        .outlets
        .iter()
        .enumerate()
        .map(|(i, outlet)| EngineOutlet {
            name: counter_name(outlet.name.as_deref(), i),
            from: DVec2::from_array(outlet.from_m),
            to: DVec2::from_array(outlet.to_m),
        })
        .collect();
    Ok((inlets, outlets))
}
