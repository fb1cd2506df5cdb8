//! The `/stats` message: per-frame scalars, JSON-encoded with a JSON schema, so Foxglove's Plot panel can plot
//! every field by path (`/stats.kinetic`) and any JSON reader can use the file without protobuf.

use crate::network::ContactForce;
use crate::quantities::mean_coordination;
use gc2d_engine::World;

/// Schema name of the `/stats` messages.
pub const STATS_SCHEMA_NAME: &str = "gc2d.FrameStats";

/// JSON schema of the `/stats` messages; energies in J per unit thickness.
pub const STATS_JSON_SCHEMA: &str = r#"{
  "$schema": "https://json-schema.org/draft/2020-12/schema",
  "title": "gc2d.FrameStats",
  "description": "Scalars of one gc2d-rs frame. Energies are J per unit thickness (2D).",
  "type": "object",
  "properties": {
    "time": {"type": "number", "description": "simulated time, s"},
    "steps": {"type": "integer", "description": "steps taken"},
    "particles": {"type": "integer", "description": "living particles"},
    "kinetic": {"type": "number", "description": "translational + rotational kinetic energy"},
    "kinetic_translational": {"type": "number"},
    "kinetic_rotational": {"type": "number"},
    "potential": {"type": "number", "description": "sum of m g y"},
    "elastic": {"type": "number", "description": "energy stored in the contacts"},
    "dissipated": {"type": "number", "description": "dissipated since the start"},
    "balance_error": {"type": "number", "description": "(E - E0) - (W_in - D - residual): integration error"},
    "contacts": {"type": "integer", "description": "touching pairs"},
    "max_overlap_fraction": {"type": "number", "description": "largest overlap area / smaller particle area"},
    "mean_coordination": {"type": "number", "description": "mean contacts per particle (wall contacts count once)"},
    "max_contact_force": {"type": "number", "description": "largest |F| of the frame, N/m; drawn at full line width"},
    "median_speed": {"type": "number", "description": "median |v| of the particles, m/s"},
    "rotor_power": {"type": "number", "description": "power the walls turning about pivots (a rotor) deliver to the particles, W"},
    "rotor_torque": {"type": "number", "description": "torque that drives the walls turning about pivots, N m"}
  },
  "required": ["time", "particles", "kinetic", "potential", "elastic", "dissipated", "contacts"]
}"#;

/// The scalars of one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameStats {
    /// Simulated time, s.
    pub time: f64,
    /// Steps taken.
    pub steps: u64,
    /// Living particles.
    pub particles: usize,
    /// Σ ½ m v², J.
    pub kinetic_translational: f64,
    /// Σ ½ I ω², J.
    pub kinetic_rotational: f64,
    /// Σ m g y, J.
    pub potential: f64,
    /// Energy stored in the contacts, J.
    pub elastic: f64,
    /// Energy dissipated since the start, J.
    pub dissipated: f64,
    /// The ledger's balance error, J.
    pub balance_error: f64,
    /// Touching pairs.
    pub contacts: usize,
    /// Largest overlap area as a fraction of the smaller particle's area.
    pub max_overlap_fraction: f64,
    /// Mean contacts per particle.
    pub mean_coordination: f64,
    /// Largest |F| of the frame, N per unit thickness.
    pub max_contact_force: f64,
    /// Median speed of the particles, m/s (0 without particles): the mill thesis's stationarity measure.
    pub median_speed: f64,
    /// Power the walls turning about pivots deliver to the particles, W (`World::rotor_power`).
    pub rotor_power: f64,
    /// Torque that drives them, N·m.
    pub rotor_torque: f64,
}

impl FrameStats {
    /// The statistics of `world` with its force network `forces` (largest force `max_force`).
    pub fn of(world: &World, forces: &[ContactForce], max_force: f64) -> Self {
        let ledger = world.ledger();
        let stats = world.stats();
        let rotor = world.rotor_power();
        Self {
            time: world.time(),
            steps: world.steps(),
            particles: world.bodies().particles().count(),
            kinetic_translational: ledger.kinetic_translational,
            kinetic_rotational: ledger.kinetic_rotational,
            potential: ledger.potential,
            elastic: ledger.contact_stored,
            dissipated: ledger.dissipated(),
            balance_error: ledger.balance_error(),
            contacts: forces.len(),
            max_overlap_fraction: stats.max_overlap_fraction,
            mean_coordination: mean_coordination(world, forces),
            max_contact_force: max_force,
            median_speed: median_speed(world),
            rotor_power: rotor.power_from_work,
            rotor_torque: rotor.torque,
        }
    }

    /// The JSON message. Non-finite numbers, which JSON cannot carry, are written as null.
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "time": self.time,
            "steps": self.steps,
            "particles": self.particles,
            "kinetic": self.kinetic_translational + self.kinetic_rotational,
            "kinetic_translational": self.kinetic_translational,
            "kinetic_rotational": self.kinetic_rotational,
            "potential": self.potential,
            "elastic": self.elastic,
            "dissipated": self.dissipated,
            "balance_error": self.balance_error,
            "contacts": self.contacts,
            "max_overlap_fraction": self.max_overlap_fraction,
            "mean_coordination": self.mean_coordination,
            "max_contact_force": self.max_contact_force,
            "median_speed": self.median_speed,
            "rotor_power": self.rotor_power,
            "rotor_torque": self.rotor_torque,
        })
    }
}

/// The median |v| of the living particles (the mean of the two middle ones for an even count), m/s; 0 without
/// particles.
pub fn median_speed(world: &World) -> f64 {
    let b = world.bodies();
    let mut speeds: Vec<f64> = b.particles().map(|id| b.velocity[id.index()].length()).collect();
    let n = speeds.len();
    if n == 0 {
        return 0.0;
    }
    let (_, upper, _) = speeds.select_nth_unstable_by(n / 2, f64::total_cmp);
    let upper = *upper;
    if n % 2 == 1 {
        upper
    } else {
        let lower = speeds[..n / 2].iter().copied().fold(f64::NEG_INFINITY, f64::max);
        0.5 * (lower + upper)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gc2d_contact::ContactLaw;
    use gc2d_engine::schedules::GravitySchedule;
    use gc2d_engine::{BodyShape, InteractionTable, MassModel, WorldConfig};
    use gc2d_geometry::{DVec2, Pose};

    /// A World without gravity holding disks that move at `speeds` along x, far apart.
    fn world_with_speeds(speeds: &[f64]) -> World {
        let config = WorldConfig {
            time_step: 1e-5,
            integrator: Default::default(),
            interactions: InteractionTable::uniform(ContactLaw::elastic(1e7)),
            mass_model: MassModel::PerUnitThickness,
            gravity: GravitySchedule::constant(0.0),
            heating: None,
            safety: Default::default(),
            domain: None,
            seed: 1,
        };
        let mut world = World::new(config).unwrap();
        for (k, &v) in speeds.iter().enumerate() {
            let pose = Pose::new(DVec2::new(k as f64, 0.0), 0.0);
            world.add_particle(BodyShape::Disk { radius: 0.01 }, pose, 1000.0, DVec2::new(v, 0.0), 0.0).unwrap();
        }
        world
    }

    #[test]
    fn median_speed_of_odd_even_and_no_particles() {
        assert_eq!(median_speed(&world_with_speeds(&[3.0, -1.0, 2.0])), 2.0);
        assert_eq!(median_speed(&world_with_speeds(&[4.0, 1.0, -2.0, 8.0])), 3.0);
        assert_eq!(median_speed(&world_with_speeds(&[])), 0.0);
    }
}
