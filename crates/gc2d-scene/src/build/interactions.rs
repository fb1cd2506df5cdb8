//! The scene's materials and `interactions` to the engine's interaction table: the listed law for a listed pair,
//! and the overlap-area law mixed from the two materials for every other pair (docs/model.md, "Materials and mixing
//! rules").

use crate::error::SceneError;
use crate::schema::{Damping, Friction, FrictionStiffness, InteractionLaw, MassModel, Material, Rolling, Scene};
use crate::validate::{Materials, overlap_area_law};
use gc2d_contact::penetration::{effective_modulus, effective_shear_modulus};
use gc2d_contact::{
    CundallStrack, ImpactLaw, NormalSpring, PenetrationDamping, PenetrationLaw, RestitutionTable, RollingResistance,
    TangentialSpring, TangentialStiffness,
};
use gc2d_engine::{ContactModel, InteractionTable, MaterialId, MaterialPair};

/// The contact model of every pair of the scene's materials, material ids in scene order.
pub(crate) fn interaction_table(scene: &Scene, materials: &Materials) -> Result<InteractionTable, SceneError> {
    let all = materials.all();
    let mut pairs = Vec::with_capacity(all.len() * (all.len() + 1) / 2);
    for a in 0..all.len() {
        for b in a..all.len() {
            let model = match listed_entry(scene, &all[a].name, &all[b].name) {
                Some(entry) => listed_model(&entry.law, &all[a], &all[b])
                    .map_err(|message| SceneError::value(interaction_path(scene, entry), message))?,
                None => mixed_model(&all[a], &all[b]),
            };
            pairs.push(MaterialPair { a: MaterialId(a as u16), b: MaterialId(b as u16), model });
        }
    }
    InteractionTable::new(all.len(), &pairs).map_err(|e| SceneError::value("interactions", e.to_string()))
}

/// The `interactions` entry of the materials named `a` and `b`, in either order.
fn listed_entry<'a>(scene: &'a Scene, a: &str, b: &str) -> Option<&'a crate::schema::Interaction> {
    scene.interactions.iter().find(|entry| {
        let [x, y] = [entry.materials[0].as_str(), entry.materials[1].as_str()];
        (x == a && y == b) || (x == b && y == a)
    })
}

/// The `interactions` entries that give a penetration law (`Linear`, `Hertz`) in a scene whose masses are per unit
/// thickness: each entry's index and its law's name. Those laws are made for spheres moving in a plane (a force in N
/// against a sphere's mass), so with masses per metre of depth an impact overlaps far deeper than the law's time-step
/// bound and the overlap limit expect (docs/model.md, "Mass models"). Empty for a sphere-equivalent scene.
pub(crate) fn penetration_laws_per_unit_thickness(scene: &Scene) -> Vec<(usize, &'static str)> {
    if scene.mass_model != MassModel::PerUnitThickness {
        return Vec::new();
    }
    let laws = scene.interactions.iter().enumerate();
    laws.filter_map(|(i, entry)| match entry.law {
        InteractionLaw::OverlapArea { .. } => None,
        InteractionLaw::Linear { .. } => Some((i, "Linear")),
        InteractionLaw::Hertz { .. } => Some((i, "Hertz")),
    })
    .collect()
}

/// The pairs of materials that can meet in the scene (two materials of its particles, or one of its particles' and one
/// of its walls'; an entry without a material uses the first) and have no `interactions` entry, in a scene whose
/// entries give some pair a penetration law (`Linear`, `Hertz`): such a pair falls back to the overlap-area law mixed
/// from the two materials, which in a Hertz scene is almost certainly a forgotten entry. Empty otherwise.
pub(crate) fn unlisted_pairs(scene: &Scene) -> Vec<[String; 2]> {
    let penetration = scene.interactions.iter().any(|entry| !matches!(entry.law, InteractionLaw::OverlapArea { .. }));
    if !penetration || scene.materials.is_empty() {
        return Vec::new();
    }
    let first = scene.materials[0].name.as_str();
    fn or_first<'a>(material: &'a Option<String>, first: &'a str) -> &'a str {
        material.as_deref().unwrap_or(first)
    }
    let named = |material| or_first(material, first);
    // Particles: their entries, sources, inlets, and a mill's balls and ore; walls: theirs and a mill's chamber and
    // rotor.
    // Materials of many particles (blocks, sources, inlets, a mill's balls and ore), and one per single particle.
    let mut many: Vec<&str> = Vec::new();
    many.extend(scene.blocks.iter().map(|b| named(&b.material)));
    many.extend(scene.sources.iter().map(|s| named(&s.material)));
    many.extend(scene.inlets.iter().map(|i| named(&i.material)));
    let singles: Vec<&str> = scene.particles.iter().map(|p| named(&p.material)).collect();
    let mut walls: Vec<&str> = scene.walls.iter().map(|wall| wall.material().unwrap_or(first)).collect();
    if let Some(mill) = &scene.mill {
        many.push(named(&mill.balls.material));
        many.extend(mill.ore.iter().map(|ore| named(&ore.material)));
        walls.extend([named(&mill.chamber_material), named(&mill.rotor_material)]);
    }
    let particles: Vec<&str> = many.iter().chain(&singles).copied().collect();
    // Two particles of one material meet only where there are two.
    let two_of = |m: &str| many.contains(&m) || singles.iter().filter(|&&s| s == m).count() >= 2;
    // In the scene's order of materials, each pair once.
    let names: Vec<&str> = scene.materials.iter().map(|m| m.name.as_str()).collect();
    let mut pairs = Vec::new();
    for (i, a) in names.iter().enumerate() {
        for b in &names[i..] {
            let (a_moves, b_moves) = (particles.contains(a), particles.contains(b));
            let particles_meet = if a == b { two_of(a) } else { a_moves && b_moves };
            let meet = particles_meet || (a_moves && walls.contains(b)) || (b_moves && walls.contains(a));
            if meet && listed_entry(scene, a, b).is_none() {
                pairs.push([a.to_string(), b.to_string()]);
            }
        }
    }
    pairs
}

/// The overlap-area law of two materials with no entry of their own: each parameter mixed by [`mix`], the
/// modulus by [`mix_stiffness`].
fn mixed_model(a: &Material, b: &Material) -> ContactModel {
    ContactModel::OverlapArea(overlap_area_law(
        mix_stiffness(a.youngs_modulus_n_m, b.youngs_modulus_n_m),
        mix(a.gamma, b.gamma),
        mix(a.mu, b.mu),
        mix(a.cohesion_n_m, b.cohesion_n_m),
    ))
}

/// The field path of an `interactions` entry, for errors.
fn interaction_path(scene: &Scene, entry: &crate::schema::Interaction) -> String {
    let index = scene.interactions.iter().position(|e| std::ptr::eq(e, entry)).unwrap_or(0);
    format!("interactions[{index}].law")
}

/// The law of a listed pair, its left-out parameters mixed; an error says what the materials lack or which
/// parameter is out of range.
pub(crate) fn listed_model(law: &InteractionLaw, a: &Material, b: &Material) -> Result<ContactModel, String> {
    let model = match law {
        InteractionLaw::OverlapArea { youngs_modulus_n_m, gamma, mu, cohesion_n_m, formulation } => {
            let mut law = overlap_area_law(
                youngs_modulus_n_m.unwrap_or_else(|| mix_stiffness(a.youngs_modulus_n_m, b.youngs_modulus_n_m)),
                gamma.unwrap_or_else(|| mix(a.gamma, b.gamma)),
                mu.unwrap_or_else(|| mix(a.mu, b.mu)),
                cohesion_n_m.unwrap_or_else(|| mix(a.cohesion_n_m, b.cohesion_n_m)),
            );
            law.elastic.formulation = *formulation;
            ContactModel::OverlapArea(law)
        }
        InteractionLaw::Linear { stiffness_n_m, damping, friction, rolling, tensile_clamp } => {
            ContactModel::Penetration(PenetrationLaw {
                normal: NormalSpring::Linear { stiffness_n_m: *stiffness_n_m },
                damping: penetration_damping(damping)?,
                tangential: friction.map(|f| tangential(&f, false, a, b)).transpose()?,
                rolling: rolling.map(|r| rolling_resistance(&r)),
                tensile_clamp: *tensile_clamp,
            })
        }
        InteractionLaw::Hertz { damping, friction, rolling, tensile_clamp } => {
            let (e_a, e_b) = (hertz_modulus(a)?, hertz_modulus(b)?);
            ContactModel::Penetration(PenetrationLaw {
                normal: NormalSpring::Hertz {
                    effective_modulus_pa: effective_modulus(e_a, a.poisson_ratio, e_b, b.poisson_ratio),
                },
                damping: penetration_damping(damping)?,
                tangential: friction.map(|f| tangential(&f, true, a, b)).transpose()?,
                rolling: rolling.map(|r| rolling_resistance(&r)),
                tensile_clamp: *tensile_clamp,
            })
        }
    };
    model.validate().map_err(|e| e.to_string())?;
    Ok(model)
}

/// A material's 3D Young's modulus, which Hertz and Mindlin need.
fn hertz_modulus(material: &Material) -> Result<f64, String> {
    material.youngs_modulus_pa.ok_or_else(|| {
        format!(
            "material `{}` has no `youngs_modulus_pa`, which this law needs (with `poisson_ratio`, default 0.3)",
            material.name
        )
    })
}

/// The engine's damping of a scene `Damping`.
fn penetration_damping(damping: &Damping) -> Result<Option<PenetrationDamping>, String> {
    Ok(match damping {
        Damping::None => None,
        Damping::Ratio(ratio) => Some(PenetrationDamping::DampingRatio(*ratio)),
        Damping::Restitution(e) => Some(PenetrationDamping::Restitution(*e)),
        Damping::SteelReichardt => Some(PenetrationDamping::VelocityDependent(ImpactLaw::SteelReichardt)),
        &Damping::PowerLaw { a, b, c } => Some(PenetrationDamping::VelocityDependent(ImpactLaw::PowerLaw { a, b, c })),
        Damping::Table(points) => {
            let table = RestitutionTable::new(points).map_err(|e| format!("damping table: {e}"))?;
            Some(PenetrationDamping::VelocityDependent(ImpactLaw::Table(table)))
        }
    })
}

/// The engine's tangential spring of a scene `Friction`; the stiffness defaults to Mindlin under Hertz and to the
/// area law's ratio 2/7 under the linear spring.
fn tangential(friction: &Friction, hertz: bool, a: &Material, b: &Material) -> Result<TangentialSpring, String> {
    let stiffness = match friction.stiffness {
        Some(FrictionStiffness::Ratio(stiffness_ratio)) => TangentialStiffness::CundallStrack { stiffness_ratio },
        Some(FrictionStiffness::Mindlin) => mindlin(a, b)?,
        None if hertz => mindlin(a, b)?,
        None => TangentialStiffness::CundallStrack { stiffness_ratio: CundallStrack::STIFFNESS_FACTOR },
    };
    Ok(TangentialSpring { mu: friction.mu, stiffness, damping_ratio: friction.damping_ratio })
}

/// Mindlin's stiffness with G* of the two materials.
fn mindlin(a: &Material, b: &Material) -> Result<TangentialStiffness, String> {
    let (e_a, e_b) = (hertz_modulus(a)?, hertz_modulus(b)?);
    Ok(TangentialStiffness::Mindlin {
        effective_shear_modulus_pa: effective_shear_modulus(e_a, a.poisson_ratio, e_b, b.poisson_ratio),
    })
}

/// The engine's rolling resistance of a scene `Rolling`.
fn rolling_resistance(rolling: &Rolling) -> RollingResistance {
    RollingResistance {
        mu_r: rolling.mu_r,
        stiffness_ratio: rolling.stiffness_ratio,
        damping_ratio: rolling.damping_ratio,
    }
}

/// A coefficient of a pair of materials: the common value when both agree (bit for bit, so a one-material scene
/// keeps its law exactly), else the arithmetic mean.
pub(crate) fn mix(a: f64, b: f64) -> f64 {
    if a == b { a } else { 0.5 * (a + b) }
}

/// A stiffness of a pair of materials: the common value when both agree, else the harmonic mean 2·E_a·E_b/(E_a +
/// E_b) (two half-contacts in series, each as stiff as its own material).
pub(crate) fn mix_stiffness(a: f64, b: f64) -> f64 {
    if a == b { a } else { 2.0 * a * b / (a + b) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_values_mix_to_themselves_and_unequal_ones_to_their_means() {
        assert_eq!(mix(0.3, 0.3), 0.3);
        assert_eq!(mix(0.2, 0.6), 0.4);
        assert_eq!(mix_stiffness(1e7, 1e7), 1e7);
        assert!((mix_stiffness(1e7, 3e7) - 1.5e7).abs() < 1e-6);
    }
}
