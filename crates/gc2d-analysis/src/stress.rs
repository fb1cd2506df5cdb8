//! Coarse-grained stress tensor in a test rectangle (reference §5.7, eq. 2.52) and its principal axes.
//!
//! The particles whose centre of mass lies in the rectangle form the test body. Summing x_i F_j over all forces on
//! them, with x relative to the rectangle's centroid, leaves only the boundary forces (internal pairs cancel):
//! σ_ij = −(1/2V) Σ (x_i F_j + x_j F_i). The sign makes compression positive, as the pressures of §5.2 and the
//! Janssen stresses of §7.1 are. V is the area of the convex hull of the force application points (§5.7).

use crate::density::Grid;
use crate::geometry::{Rect, hull_area};
use crate::snapshot::{BodyRef, Snapshot};
use gc2d_geometry::DVec2;
use serde::Serialize;

/// Which area V divides the force moments (§5.7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum StressVolume {
    /// Convex hull of the force application points (the thesis's choice).
    ForcePointHull,
    /// Convex hull of the selected particles' vertices (the thesis's alternative).
    ParticleHull,
}

/// A force-point hull smaller than this fraction of the particle hull is degenerate (e.g. a single-file column whose
/// force points are collinear); the particle hull is used instead and reported in [`LocalStress::volume_used`].
pub const DEGENERATE_HULL_FRACTION: f64 = 1e-6;

/// Options of the stress evaluation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StressOptions {
    /// The V of (2.52).
    pub volume: StressVolume,
}

impl Default for StressOptions {
    fn default() -> Self {
        Self { volume: StressVolume::ForcePointHull }
    }
}

/// A symmetric 2D stress tensor, N/m (2D), compression positive.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct StressTensor {
    /// σ_xx.
    pub xx: f64,
    /// σ_xy = σ_yx.
    pub xy: f64,
    /// σ_yy (the σ_zz of Ch. 3 and 4, z vertical).
    pub yy: f64,
}

/// Principal stresses and the angle of the major axis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PrincipalStress {
    /// Larger principal stress (most compressive), N/m.
    pub major: f64,
    /// Smaller principal stress, N/m.
    pub minor: f64,
    /// Ψ: angle of the major principal axis against the vertical, degrees, counter-clockwise positive, in
    /// (−90, 90] (§1.3, Abb. 4.24). An isotropic tensor has no axis and reports 0.
    pub psi_degrees: f64,
}

impl StressTensor {
    /// Eigenvalues and the major axis's angle from the vertical.
    pub fn principal(&self) -> PrincipalStress {
        let mean = 0.5 * (self.xx + self.yy);
        let radius = (0.25 * (self.xx - self.yy).powi(2) + self.xy * self.xy).sqrt();
        let isotropic = radius.is_nan() || radius <= 1e-12 * (mean.abs() + radius);
        let theta = if isotropic { 90f64 } else { 0.5 * (2.0 * self.xy).atan2(self.xx - self.yy).to_degrees() };
        let mut psi = theta - 90.0;
        if psi <= -90.0 {
            psi += 180.0;
        }
        if psi > 90.0 {
            psi -= 180.0;
        }
        PrincipalStress { major: mean + radius, minor: mean - radius, psi_degrees: psi }
    }
}

/// The stress in one test rectangle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LocalStress {
    /// The test rectangle; x in (2.52) is measured from its centroid.
    pub rect: Rect,
    /// Particles whose centre of mass is inside.
    pub particles: usize,
    /// Force records on these particles.
    pub forces: usize,
    /// V, m².
    pub volume: f64,
    /// Which hull gave V (the particle hull when the force-point hull is degenerate).
    pub volume_used: StressVolume,
    /// ⟨σ⟩ (2.52), compression positive.
    pub sigma: StressTensor,
    /// Principal stresses and Ψ.
    pub principal: PrincipalStress,
}

/// Force records per particle: (application point, force on that particle).
struct ForcesByParticle(Vec<Vec<(DVec2, DVec2)>>);

impl ForcesByParticle {
    fn new(snapshot: &Snapshot) -> Self {
        let mut lists = vec![Vec::new(); snapshot.particles.len()];
        for contact in &snapshot.contacts {
            if !(contact.point.is_finite() && contact.force_on_a.is_finite()) {
                continue;
            }
            for (side, force) in [(contact.a, contact.force_on_a), (contact.b, contact.force_on_b())] {
                if let BodyRef::Particle(i) = side
                    && let Some(list) = lists.get_mut(i)
                {
                    list.push((contact.point, force));
                }
            }
        }
        Self(lists)
    }
}

/// The stress (2.52) in `rect`; `None` when no particle's centre is inside or they carry no forces.
pub fn local_stress(snapshot: &Snapshot, rect: Rect, options: &StressOptions) -> Option<LocalStress> {
    stress_in(snapshot, &ForcesByParticle::new(snapshot), rect, options)
}

/// The stress in every cell of `grid` that has one, row by row from the bottom.
pub fn stress_grid(snapshot: &Snapshot, grid: &Grid, options: &StressOptions) -> Vec<LocalStress> {
    let forces = ForcesByParticle::new(snapshot);
    grid.cells().filter_map(|(_, _, rect)| stress_in(snapshot, &forces, rect, options)).collect()
}

fn stress_in(
    snapshot: &Snapshot,
    forces: &ForcesByParticle,
    rect: Rect,
    options: &StressOptions,
) -> Option<LocalStress> {
    let center = rect.center();
    let selected: Vec<usize> = (0..snapshot.particles.len())
        .filter(|&i| snapshot.particles[i].centroid.is_finite() && rect.contains(snapshot.particles[i].centroid))
        .collect();
    let mut moment = StressTensor::default();
    let mut points = Vec::new();
    for &i in &selected {
        for &(point, force) in &forces.0[i] {
            let x = point - center;
            moment.xx += x.x * force.x;
            moment.xy += 0.5 * (x.x * force.y + x.y * force.x);
            moment.yy += x.y * force.y;
            points.push(point);
        }
    }
    if points.is_empty() {
        return None;
    }
    let particle_hull = || {
        let vertices: Vec<DVec2> =
            selected.iter().flat_map(|&i| snapshot.particles[i].vertices.iter().copied()).collect();
        hull_area(&vertices)
    };
    let (volume, volume_used) = match options.volume {
        StressVolume::ParticleHull => (particle_hull(), StressVolume::ParticleHull),
        StressVolume::ForcePointHull => {
            let force_hull = hull_area(&points);
            let fallback = particle_hull();
            if force_hull > DEGENERATE_HULL_FRACTION * fallback {
                (force_hull, StressVolume::ForcePointHull)
            } else {
                (fallback, StressVolume::ParticleHull)
            }
        }
    };
    if !(volume > 0.0 && volume.is_finite()) {
        return None;
    }
    let sigma = StressTensor { xx: -moment.xx / volume, xy: -moment.xy / volume, yy: -moment.yy / volume };
    Some(LocalStress {
        rect,
        particles: selected.len(),
        forces: points.len(),
        volume,
        volume_used,
        sigma,
        principal: sigma.principal(),
    })
}
