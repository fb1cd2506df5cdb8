//! What a built scene contains, for `gc2d-rs check` and for people reading a scene.

use std::fmt;

/// Counts and time-step facts of a built scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// The scene's name.
    pub name: String,
    /// Material names, in order (the first carries the contact law).
    pub materials: Vec<String>,
    /// Wall polygons after the wall macros are expanded.
    pub wall_polygons: usize,
    /// Walls that vibrate, rotate or act as pistons.
    pub moving_walls: usize,
    /// Particles at the start (explicit and from blocks).
    pub particles: usize,
    /// Their total mass, kg per metre of thickness.
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
    /// The stable bound (π/10)·sqrt(m/E) of the lightest particle present or to be inserted, s.
    pub stable_time_step_s: Option<f64>,
    /// The scene entry that sets the bound.
    pub limiting_entry: Option<String>,
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
        writeln!(f, "  walls: {} polygons ({} moving)", self.wall_polygons, self.moving_walls)?;
        writeln!(
            f,
            "  particles: {} at the start ({:.4} kg/m), {} with a drag spring",
            self.particles, self.particle_mass_kg_m, self.drag_springs
        )?;
        writeln!(f, "  sources: {} (up to {} insertions)", self.sources, self.planned_insertions)?;
        let how = if self.time_step_is_automatic { "automatic" } else { "given" };
        write!(f, "  time step: {:.3e} s ({how})", self.time_step_s)?;
        match (&self.stable_time_step_s, &self.limiting_entry) {
            (Some(bound), Some(entry)) => writeln!(f, ", stable bound {bound:.3e} s set by `{entry}`")?,
            _ => writeln!(f, ", no particles to bound it")?,
        }
        write!(f, "  end time: {} s ({} steps)", self.end_time_s, self.steps())
    }
}
