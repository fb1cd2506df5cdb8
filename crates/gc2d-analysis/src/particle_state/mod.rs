//! Per-particle state: one [`ParticleState`] row per living particle of a World, the table `gc2d-rs run --dump-every`
//! writes (and the analysis of a mill reads back). The row is separate from its file formats: [`csv`] writes and
//! reads it; other formats (Parquet, VTK) are further writers of the same rows.

pub mod csv;

use gc2d_engine::{ShapeKind, World};
use serde::{Deserialize, Serialize};

/// The outline kind of a particle, as the tables spell it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ParticleShape {
    /// An exact disk.
    Disk,
    /// A convex polygon.
    Polygon,
}

impl ParticleShape {
    /// `disk` or `polygon`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Disk => "disk",
            Self::Polygon => "polygon",
        }
    }

    /// The shape named `name` (`disk` or `polygon`).
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "disk" => Some(Self::Disk),
            "polygon" => Some(Self::Polygon),
            _ => None,
        }
    }
}

/// The state of one living particle at one time: where it is, how it moves, what the last step's forces on it were
/// and how many bodies it touches. SI units; angles in radians, counter-clockwise.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ParticleState {
    /// Simulated time, s.
    pub time_s: f64,
    /// The particle's body id (its slot in the World; stable over the run, never reused). The scene format gives
    /// particles no names of their own, so the id is also the particle's name.
    pub id: u32,
    /// The name of its material, as the scene spells it.
    pub material: String,
    /// Disk or polygon.
    pub shape: ParticleShape,
    /// Centroid, m.
    pub x_m: f64,
    /// Centroid, m.
    pub y_m: f64,
    /// Orientation, rad.
    pub phi_rad: f64,
    /// Velocity of the centroid, m/s.
    pub vx_m_s: f64,
    /// Velocity of the centroid, m/s.
    pub vy_m_s: f64,
    /// Angular velocity, rad/s.
    pub omega_rad_s: f64,
    /// Net force of the last step (contacts and body forces such as gravity), N (per unit thickness in a
    /// per-unit-thickness scene).
    pub fx_n: f64,
    /// Net force of the last step, N.
    pub fy_n: f64,
    /// Net torque about the centroid of the last step, N·m.
    pub torque_n_m: f64,
    /// Bodies (particles and walls) it overlapped in the last step.
    pub contacts: u32,
}

impl ParticleState {
    /// Speed of the centroid, m/s.
    pub fn speed(&self) -> f64 {
        self.vx_m_s.hypot(self.vy_m_s)
    }
}

/// The rows of every living particle of `world`, in id order; `materials` names the material ids (a missing name is
/// written as `?`).
pub fn particle_states(world: &World, materials: &[String]) -> Vec<ParticleState> {
    let bodies = world.bodies();
    let mut contacts = vec![0u32; bodies.len()];
    for (a, b, _) in world.contacts() {
        contacts[a.index()] += 1;
        contacts[b.index()] += 1;
    }
    bodies
        .particles()
        .map(|id| {
            let i = id.index();
            let pose = bodies.pose[i];
            ParticleState {
                time_s: world.time(),
                id: id.0,
                material: materials.get(bodies.material[i].index()).cloned().unwrap_or_default(),
                shape: if bodies.shape[i] == ShapeKind::Disk { ParticleShape::Disk } else { ParticleShape::Polygon },
                x_m: pose.position.x,
                y_m: pose.position.y,
                phi_rad: pose.angle,
                vx_m_s: bodies.velocity[i].x,
                vy_m_s: bodies.velocity[i].y,
                omega_rad_s: bodies.angular_velocity[i],
                fx_n: bodies.force[i].x,
                fy_n: bodies.force[i].y,
                torque_n_m: bodies.torque[i],
                contacts: contacts[i],
            }
        })
        .collect()
}
