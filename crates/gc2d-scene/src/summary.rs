//! What a built scene contains, for `gc2d-rs check` and for people reading a scene.

use crate::checks::number;
use gc2d_contact::{ImpactLaw, NormalSpring, PenetrationDamping, TangentialStiffness};
use gc2d_engine::{ContactModel, InteractionTable, MassModel, MaterialId};
use std::fmt;

/// One line per pair of materials (a ≤ b): `a–b: ` and the law with its parameters.
pub(crate) fn interaction_lines(names: &[String], table: &InteractionTable) -> Vec<String> {
    let mut lines = Vec::new();
    for a in 0..names.len() {
        for b in a..names.len() {
            let model = table.model(MaterialId(a as u16), MaterialId(b as u16));
            lines.push(format!("{}–{}: {}", names[a], names[b], describe(model)));
        }
    }
    lines
}

/// A contact model in words, with its parameters.
fn describe(model: &ContactModel) -> String {
    match model {
        ContactModel::OverlapArea(law) => {
            let mut text = format!("overlap area, E = {:e} N/m", law.elastic.e_modulus);
            if law.elastic.formulation == gc2d_contact::AreaFormulation::Conservative {
                text += ", conservative";
            }
            if let Some(damping) = law.damping {
                text += &format!(", γ = {}", number(damping.gamma));
            }
            if let Some(friction) = law.friction {
                text += &format!(", μ = {}", number(friction.mu));
            }
            if let Some(cohesion) = law.cohesion {
                text += &format!(", k_coh = {:e} N/m", cohesion.k_coh);
            }
            text
        }
        ContactModel::Penetration(law) => {
            let mut text = match law.normal {
                NormalSpring::Linear { stiffness_n_m } => format!("linear spring, k = {stiffness_n_m:e} N/m"),
                NormalSpring::Hertz { effective_modulus_pa } => format!("Hertz, E* = {effective_modulus_pa:e} Pa"),
            };
            text += &match law.damping {
                None => ", undamped".to_owned(),
                Some(PenetrationDamping::DampingRatio(ratio)) => format!(", damping ratio D = {}", number(ratio)),
                Some(PenetrationDamping::Restitution(e)) => format!(", restitution e = {}", number(e)),
                Some(PenetrationDamping::VelocityDependent(ImpactLaw::SteelReichardt)) => {
                    ", restitution e(v) of steel (Reichardt)".to_owned()
                }
                Some(PenetrationDamping::VelocityDependent(ImpactLaw::PowerLaw { a, b, c })) => {
                    format!(", restitution e(v) = {}/(v + {})^{}", number(a), number(b), number(c))
                }
                Some(PenetrationDamping::VelocityDependent(ImpactLaw::Table(table))) => {
                    format!(", restitution e(v) from {} points", table.points().len())
                }
            };
            if let Some(friction) = law.tangential {
                text += &match friction.stiffness {
                    TangentialStiffness::CundallStrack { stiffness_ratio } => {
                        format!(", μ = {}, k_t/k_n = {stiffness_ratio:.4}", number(friction.mu))
                    }
                    TangentialStiffness::Mindlin { .. } => format!(", μ = {}, Mindlin", number(friction.mu)),
                };
            }
            if let Some(rolling) = law.rolling {
                text += &format!(", rolling μ_r = {}", number(rolling.mu_r));
            }
            if law.tensile_clamp {
                text += ", no pull (clamped)";
            }
            text
        }
    }
}

/// Counts and time-step facts of a built scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// The scene's name.
    pub name: String,
    /// Material names, in order (the first is the material of bodies that name none).
    pub materials: Vec<String>,
    /// The contact law of every pair of materials, one line each (`a–b: law`).
    pub interactions: Vec<String>,
    /// Wall bodies after the wall macros are expanded.
    pub wall_bodies: usize,
    /// Walls that vibrate, rotate or act as pistons.
    pub moving_walls: usize,
    /// How masses follow from shape and density.
    pub mass_model: MassModel,
    /// Particles at the start (explicit and from blocks).
    pub particles: usize,
    /// Their total mass: kg per metre of thickness, or kg with sphere-equivalent masses.
    pub particle_mass_kg_m: f64,
    /// Particles with a drag spring.
    pub drag_springs: usize,
    /// Particle sources.
    pub sources: usize,
    /// Insertions the sources attempt before the end time (an insertion is skipped when no free spot is found).
    pub planned_insertions: u64,
    /// The Δt the World runs with, s.
    pub time_step_s: f64,
    /// True when Δt was chosen automatically (the scene left `time_step_s` out).
    pub time_step_is_automatic: bool,
    /// The stable bound of the particles present or to be inserted, each against its stiffest contact law, s.
    pub stable_time_step_s: Option<f64>,
    /// The scene entry that sets the bound.
    pub limiting_entry: Option<String>,
    /// The impact speed a Hertz contact's bound is taken at, m/s (`Scene::max_impact_speed`).
    pub max_impact_speed_m_s: f64,
    /// End time, s.
    pub end_time_s: f64,
}

impl Summary {
    /// Steps to reach the end time.
    pub fn steps(&self) -> u64 {
        let steps = (self.end_time_s / self.time_step_s).round();
        if steps.is_finite() && steps >= 0.0 { steps as u64 } else { 0 }
    }
}

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "scene `{}`", self.name)?;
        writeln!(f, "  materials: {}", self.materials.join(", "))?;
        for line in &self.interactions {
            writeln!(f, "    {line}")?;
        }
        writeln!(f, "  walls: {} bodies ({} moving)", self.wall_bodies, self.moving_walls)?;
        let (unit, model) = match self.mass_model {
            MassModel::PerUnitThickness => ("kg/m", "per unit thickness"),
            MassModel::SphereEquivalent => ("kg", "sphere-equivalent"),
        };
        writeln!(
            f,
            "  particles: {} at the start ({:.4} {unit}, masses {model}), {} with a drag spring",
            self.particles, self.particle_mass_kg_m, self.drag_springs
        )?;
        writeln!(f, "  sources: {} (up to {} insertions)", self.sources, self.planned_insertions)?;
        let how = if self.time_step_is_automatic { "automatic" } else { "given" };
        write!(f, "  time step: {:.3e} s ({how})", self.time_step_s)?;
        match (&self.stable_time_step_s, &self.limiting_entry) {
            (Some(bound), Some(entry)) => writeln!(f, ", stable bound {bound:.3e} s set by `{entry}`")?,
            _ => writeln!(f, ", no particles to bound it")?,
        }
        writeln!(
            f,
            "  impacts expected up to {:.3} m/s (where a Hertz contact's bound is taken)",
            self.max_impact_speed_m_s
        )?;
        write!(f, "  end time: {} s ({} steps)", number(self.end_time_s), self.steps())
    }
}
