//! What heating (the particles' size factor s(t), reference §1.6) does besides resizing the particles: it keeps each
//! particle's angular momentum I·ω while I grows with s², and it works on the contacts whose overlap the expansion
//! deepens. Both are the energy ledger's `work_heating` (docs/model.md, "Spin under heating", "Heating's work on the
//! contacts").
//!
//! The work on a contact follows from the expansion's displacement field: growing particle i by ds/s about its
//! centroid c_i moves its material point x by (ds/s)·(x − c_i). Over the overlap this changes the overlap-area law's
//! area by (ds/s)·(c·n·(r_j − r_i) + 2A) (chord c, normal n from j to i, arms r from the centroids to the chord's
//! midpoint, A the area; the 2A because the field spreads: its divergence is 2 ds/s), that is its approach ΔA/c by
//! (ds/s)·(n·(r_j − r_i) + 2A/c), and a penetration law's depth by (ds/s)·(n·(r_j − r_i) + δ) (two disks:
//! (ds/s)·(R_i + R_j)). A wall does not grow: its arm and its part of the spread drop out. The normal force times
//! that approach per unit of ln s is the pair's expansion virial; the step's work is the trapezoid rule over the
//! step, ln(s_new/s_old) times the mean of the last and this step's sums over the pairs.

use crate::bodies::Bodies;
use crate::schedules::HeatingSchedule;
use gc2d_contact::{ContactGeometry, PenetrationGeometry};
use glam::DVec2;
use serde::{Deserialize, Serialize};

/// Keeps particle `i`'s angular momentum as its size factor changes from `old_scale` to `new_scale`: its angular
/// velocity and the higher derivatives of its angle are scaled by I_old/I_new = (s_old/s_new)², as for a skater who
/// spreads their arms. Returns the change of its rotational energy, ½I_old·ω²·(I_old/I_new − 1), J: the heating's work
/// on its spin. A body of infinite inertia (it cannot turn) is left alone.
pub(crate) fn keep_angular_momentum(bodies: &mut Bodies, i: usize, old_scale: f64, new_scale: f64) -> f64 {
    let inertia = bodies.inertia[i];
    if !inertia.is_finite() {
        return 0.0;
    }
    let old_inertia = inertia * HeatingSchedule::inertia_factor(old_scale);
    let ratio = HeatingSchedule::inertia_factor(old_scale) / HeatingSchedule::inertia_factor(new_scale);
    let angular_velocity = bodies.angular_velocity[i];
    bodies.angular_velocity[i] = angular_velocity * ratio;
    for derivative in &mut bodies.gear[i].angular[1..] {
        *derivative *= ratio;
    }
    0.5 * old_inertia * angular_velocity * angular_velocity * (ratio - 1.0)
}

/// The expansion virial of an overlap-area contact: its normal force `normal_force` (N, repulsive positive) times
/// the approach ΔA/c one unit of ln s gives, J (module docs). `j_grows` is false where body j is a wall.
#[inline]
pub(crate) fn area_contact_virial(normal_force: f64, geometry: &ContactGeometry, j_grows: bool) -> f64 {
    let arm_j = if j_grows { geometry.arm_j } else { DVec2::ZERO };
    let spread = if geometry.chord_length > 0.0 { 2.0 * geometry.area / geometry.chord_length } else { 0.0 };
    normal_force * (geometry.normal.dot(arm_j - geometry.arm_i) + spread)
}

/// The expansion virial of a penetration contact: its elastic normal force `elastic_force` (N; the dashpot's force
/// sees only the bodies' velocities, not the expansion) times the depth one unit of ln s adds, J (module docs).
/// `j_grows` is false where body j is a wall, which adds only body i's half of the depth.
#[inline]
pub(crate) fn penetration_virial(elastic_force: f64, geometry: &PenetrationGeometry, j_grows: bool) -> f64 {
    let (arm_j, spread) = if j_grows { (geometry.arm_j, geometry.depth) } else { (DVec2::ZERO, 0.5 * geometry.depth) };
    elastic_force * (geometry.normal.dot(arm_j - geometry.arm_i) + spread)
}

/// The heating's work on the contacts, step by step: the trapezoid rule over the expansion virials of the step's
/// start and end. Saved in checkpoints, so that a resumed run books the step after the split as the whole run does.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub(crate) struct ContactExpansion {
    /// The sum of the pairs' expansion virials after the last step, J.
    last_virial: f64,
}

impl ContactExpansion {
    /// The work on the contacts of a step over which ln s changed by `log_change` and after which the pairs'
    /// expansion virials sum to `virial`, J; `virial` becomes the next step's start.
    pub fn step_work(&mut self, log_change: f64, virial: f64) -> f64 {
        let work = log_change * 0.5 * (self.last_virial + virial);
        self.last_virial = virial;
        work
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two disks of radii 1 and 2 at distance 2.9 (depth 0.1): growing both by ds/s deepens the contact by
    /// (R_i + R_j)·ds/s, whatever the contact point; a wall adds only the disk's part.
    #[test]
    fn a_penetration_contact_deepens_by_the_sum_of_the_radii() {
        // Disk i at x = 2.9, disk j at 0; the contact point midway between the surfaces, at x = 1.95.
        let (arm_i, arm_j) = (DVec2::new(1.95 - 2.9, 0.0), DVec2::new(1.95, 0.0));
        let geometry = PenetrationGeometry { depth: 0.1, normal: DVec2::X, arm_i, arm_j };
        assert!((penetration_virial(1.0, &geometry, true) - 3.0).abs() < 1e-15);
        // A wall whose surface is at x = 2, into which disk i (radius 1) reaches 0.1: the contact point at 1.95, the
        // disk adds R_i.
        assert!((penetration_virial(2.0, &geometry, false) - 2.0).abs() < 1e-15);
    }

    /// A square of side 2 centred at the origin pressed 0.1 deep into a wall whose surface is at y = −0.9 (chord 2 at
    /// y = −0.9, area 0.2): grown to size factor s the overlap is 2s·(s − 0.9), so dA/ds = 2.2 at s = 1 and the
    /// approach dA/c is 1.1 per unit of ln s: 0.9 from the chord's move, 0.2 from the spread.
    #[test]
    fn an_area_contact_counts_the_chord_and_the_spread() {
        let geometry = ContactGeometry {
            area: 0.2,
            normal: DVec2::Y,
            chord_length: 2.0,
            arm_i: DVec2::new(0.0, -0.9),
            ..ContactGeometry::SEPARATED
        };
        let virial = area_contact_virial(3.0, &geometry, false);
        assert!((virial - 3.0 * 1.1).abs() < 1e-14, "{virial}");
    }

    #[test]
    fn the_step_work_is_the_trapezoid_rule_and_nothing_without_a_change() {
        let mut expansion = ContactExpansion::default();
        assert_eq!(expansion.step_work(0.0, 4.0), 0.0);
        assert_eq!(expansion.step_work(0.5, 2.0), 0.5 * 3.0);
        assert_eq!(expansion.step_work(0.0, 7.0), 0.0);
        assert_eq!(expansion.last_virial, 7.0);
    }
}
