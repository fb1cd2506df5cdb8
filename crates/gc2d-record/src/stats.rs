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
    "max_contact_force": {"type": "number", "description": "largest |F| of the frame, N/m; drawn at full line width"}
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
}

impl FrameStats {
    /// The statistics of `world` with its force network `forces` (largest force `max_force`).
    pub fn of(world: &World, forces: &[ContactForce], max_force: f64) -> Self {
        let ledger = world.ledger();
        let stats = world.stats();
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
        })
    }
}
