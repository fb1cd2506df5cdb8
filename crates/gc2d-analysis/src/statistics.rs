//! Force statistics (reference §5.3): coordination numbers, the force-direction distribution P(α) (2.41) and the
//! force-magnitude distribution P(F/⟨F⟩). Every contact (particle–particle and particle–wall) is one force record.

use crate::snapshot::{BodyRef, Snapshot};
use serde::Serialize;
use std::f64::consts::TAU;

/// Contacts per particle.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Coordination {
    /// K for each particle (contacts with particles and walls), in snapshot order.
    pub per_particle: Vec<usize>,
    /// `histogram[K]` = number of particles with K contacts (rattlers at K = 0 included).
    pub histogram: Vec<usize>,
    /// ⟨K⟩ over all particles, 0 without particles.
    pub mean: f64,
    /// Particles without any contact.
    pub rattlers: usize,
}

/// Counts the contacts of every particle.
pub fn coordination(snapshot: &Snapshot) -> Coordination {
    let mut per_particle = vec![0usize; snapshot.particles.len()];
    for contact in &snapshot.contacts {
        for side in [contact.a, contact.b] {
            if let BodyRef::Particle(i) = side
                && let Some(k) = per_particle.get_mut(i)
            {
                *k += 1;
            }
        }
    }
    let max = per_particle.iter().copied().max().unwrap_or(0);
    let mut histogram = vec![0usize; if per_particle.is_empty() { 0 } else { max + 1 }];
    for &k in &per_particle {
        histogram[k] += 1;
    }
    let mean = if per_particle.is_empty() {
        0.0
    } else {
        per_particle.iter().sum::<usize>() as f64 / per_particle.len() as f64
    };
    let rattlers = histogram.first().copied().unwrap_or(0);
    Coordination { per_particle, histogram, mean, rattlers }
}

/// P(α), α the direction of a contact force (2.41), counter-clockwise from +x.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DirectionHistogram {
    /// Bin width, degrees. Bin k is centred on k · width.
    pub bin_width_degrees: f64,
    /// Bin centres, degrees, in [0, 360).
    pub centers_degrees: Vec<f64>,
    /// Fraction of force vectors in each bin (sums to 1 when there are forces).
    pub fraction: Vec<f64>,
    /// Number of force vectors counted (two per contact with a non-zero force).
    pub forces: usize,
}

/// Histogram of the directions of all contact forces in `bins` bins over the full circle. Each contact adds the force
/// on both of its bodies, α and α + π, so P(α) = P(α + π) (§5.3). Zero forces have no direction and are skipped.
pub fn force_direction_histogram(snapshot: &Snapshot, bins: usize) -> DirectionHistogram {
    let bins = bins.max(1);
    let width = TAU / bins as f64;
    let mut counts = vec![0usize; bins];
    for contact in &snapshot.contacts {
        let f = contact.force_on_a;
        if !f.is_finite() || f.length_squared() == 0.0 {
            continue;
        }
        for force in [f, -f] {
            let alpha = force.y.atan2(force.x).rem_euclid(TAU);
            let k = (alpha / width).round() as usize % bins;
            counts[k] += 1;
        }
    }
    let forces: usize = counts.iter().sum();
    DirectionHistogram {
        bin_width_degrees: width.to_degrees(),
        centers_degrees: (0..bins).map(|k| (k as f64 * width).to_degrees()).collect(),
        fraction: counts.iter().map(|&c| if forces > 0 { c as f64 / forces as f64 } else { 0.0 }).collect(),
        forces,
    }
}

/// P(F/⟨F⟩) as a probability density over bins of the normalised force magnitude.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MagnitudeHistogram {
    /// ⟨F⟩, mean contact force magnitude, N.
    pub mean_force: f64,
    /// Bin width in units of ⟨F⟩.
    pub bin_width: f64,
    /// Bin centres in units of ⟨F⟩, from bin_width/2.
    pub centers: Vec<f64>,
    /// Probability density: Σ density · bin_width = 1 when there are forces.
    pub density: Vec<f64>,
    /// Contacts counted (one magnitude per contact).
    pub contacts: usize,
}

/// No magnitude histogram has more bins than this; larger ratios land in the last bin.
pub const MAX_MAGNITUDE_BINS: usize = 10_000;

/// Histogram of |F|/⟨F⟩ over all contacts, bins of `bin_width` (≤ 0 means 0.1) from 0 up to the largest ratio.
pub fn force_magnitude_histogram(snapshot: &Snapshot, bin_width: f64) -> MagnitudeHistogram {
    let bin_width = if bin_width > 0.0 && bin_width.is_finite() { bin_width } else { 0.1 };
    let magnitudes: Vec<f64> =
        snapshot.contacts.iter().map(|c| c.force_on_a.length()).filter(|f| f.is_finite()).collect();
    let mean_force = if magnitudes.is_empty() { 0.0 } else { magnitudes.iter().sum::<f64>() / magnitudes.len() as f64 };
    if mean_force.is_nan() || mean_force <= 0.0 {
        return MagnitudeHistogram {
            mean_force,
            bin_width,
            centers: Vec::new(),
            density: Vec::new(),
            contacts: magnitudes.len(),
        };
    }
    let largest = magnitudes.iter().fold(0.0f64, |m, &f| m.max(f / mean_force));
    let bins = ((largest / bin_width).floor() as usize + 1).min(MAX_MAGNITUDE_BINS);
    let mut counts = vec![0usize; bins];
    for &f in &magnitudes {
        let k = ((f / mean_force / bin_width).floor() as usize).min(bins - 1);
        counts[k] += 1;
    }
    let norm = magnitudes.len() as f64 * bin_width;
    MagnitudeHistogram {
        mean_force,
        bin_width,
        centers: (0..bins).map(|k| (k as f64 + 0.5) * bin_width).collect(),
        density: counts.iter().map(|&c| c as f64 / norm).collect(),
        contacts: magnitudes.len(),
    }
}
