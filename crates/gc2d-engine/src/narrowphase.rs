//! The narrowphase: for one broadphase pair, closest features (warm-started; skipped while the pair keeps touching),
//! then the overlap and its contact chord, then the contact law (reference §2.15). Each pair writes only its own record, so all pairs run in parallel;
//! the engine adds the forces to the bodies afterwards in pair order, which keeps results independent of threads.

use crate::bodies::{Bodies, BodyId, BodyKind};
use gc2d_contact::{BodyMotion, ContactLaw, ContactState, EnergyTerms};
use gc2d_geometry::{ContactGeometry, DVec2, FeaturePair, closest_features, contact_geometry};
use serde::{Deserialize, Serialize};

/// Everything the World keeps about one pair of bodies whose boxes touch: the contact history and this step's result.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct PairContact {
    /// Closest features of the last closest-feature query, the warm start of the next one.
    pub warm_start: Option<FeaturePair>,
    /// The contact law's history (old area, tangential spring, frozen l, m⊥, m∥).
    pub state: ContactState,
    /// True when the bodies overlapped this step.
    pub touching: bool,
    /// Force on body `a` of the pair (body `b` receives the opposite), N.
    pub force_on_a: DVec2,
    /// Torque on body `a`, N·m.
    pub torque_on_a: f64,
    /// Torque on body `b`, N·m.
    pub torque_on_b: f64,
    /// Force application point (midpoint of the contact chord), m.
    pub point: DVec2,
    /// Overlap area as a fraction of the smaller particle's area.
    pub overlap_fraction: f64,
    /// Energy stored and dissipated by the contact this step.
    pub energy: EnergyTerms,
    /// Work the real motion of a wall did on the particle this step, J.
    pub wall_work: f64,
    /// Passes the closest-feature walk needed this step; 0 when the pair was still touching and no query ran.
    pub passes: u32,
    /// `force_on_a` of the two steps before this one, newest first: the history of the force-alternation
    /// diagnostic ([`World::force_alternation`](crate::World::force_alternation)). Not saved in checkpoints, so that
    /// the format stays; a resumed World measures the diagnostic again after two steps.
    #[serde(skip)]
    pub earlier_forces: [DVec2; 2],
}

/// The overlap of polygons `i` and `j` this step, or `None`.
///
/// A pair that touched in the last step almost always still touches, so the overlap computation itself decides; a
/// closest-feature query first would only repeat its answer. Every other pair (approaching, or just separated) asks
/// the warm-started closest-feature walk first (reference §4.3), which settles the common "apart" case without
/// building an overlap polygon, and keeps the warm start fresh for the step the pair comes into contact.
#[inline]
fn overlap_of(vertices_i: &[DVec2], vertices_j: &[DVec2], contact: &mut PairContact) -> Option<ContactGeometry> {
    if contact.touching
        && let Some(overlap) = contact_geometry(vertices_i, vertices_j)
    {
        contact.passes = 0;
        return Some(overlap);
    }
    let separation = closest_features(vertices_i, vertices_j, contact.warm_start);
    contact.warm_start = Some(separation.features);
    contact.passes = separation.passes;
    if separation.distance > 0.0 || contact.touching { None } else { contact_geometry(vertices_i, vertices_j) }
}

/// What a pair evaluation reads: the body store as it is after the predictor.
pub(crate) struct PairContext<'a> {
    pub bodies: &'a Bodies,
    pub law: &'a ContactLaw,
    pub dt: f64,
}

impl PairContext<'_> {
    /// The contact law's view of body `id` at the predicted state.
    fn motion(&self, id: BodyId) -> BodyMotion {
        let i = id.index();
        let b = self.bodies;
        BodyMotion {
            velocity: b.velocity[i],
            angular_velocity: b.angular_velocity[i],
            inv_mass: b.inverse_mass[i],
            inv_inertia: b.inverse_inertia[i],
            surface_velocity: b.surface_velocity[i],
        }
    }

    /// Evaluates the pair {a, b} (a < b) for this step and stores the result in `contact`.
    ///
    /// When one body is a wall, the contact law sees the particle as body i; the stored result is always expressed
    /// for `a`, so that accumulation does not need to know.
    pub fn evaluate(&self, a: u32, b: u32, contact: &mut PairContact) {
        let bodies = self.bodies;
        let wall_first = bodies.kind[a as usize] == BodyKind::Wall;
        let (i, j) = if wall_first { (BodyId(b), BodyId(a)) } else { (BodyId(a), BodyId(b)) };
        let (vertices_i, vertices_j) = (bodies.world_vertices_of(i), bodies.world_vertices_of(j));
        let overlap = overlap_of(vertices_i, vertices_j, contact);
        let (position_i, position_j) = (bodies.pose[i.index()].position, bodies.pose[j.index()].position);
        let geometry = overlap.map_or(gc2d_contact::ContactGeometry::SEPARATED, |g| gc2d_contact::ContactGeometry {
            area: g.area,
            normal: g.normal,
            chord_length: g.chord_length,
            arm_i: g.point - position_i,
            arm_j: g.point - position_j,
        });
        let (motion_i, motion_j) = (self.motion(i), self.motion(j));
        let response = self.law.evaluate(&geometry, &motion_i, &motion_j, &contact.state, self.dt);
        contact.state = response.state;
        contact.energy = response.energy;
        contact.touching = overlap.is_some();
        contact.point = overlap.map_or(DVec2::ZERO, |g| g.point);
        contact.overlap_fraction = overlap.map_or(0.0, |g| g.area / self.smaller_particle_area(i, j));
        contact.wall_work = if motion_j.inv_mass == 0.0 {
            let wall_point_velocity = motion_j.velocity + motion_j.angular_velocity * geometry.arm_j.perp();
            response.force_on_i.dot(wall_point_velocity) * self.dt
        } else {
            0.0
        };
        let (sign, torque_a, torque_b) = if wall_first {
            (-1.0, response.torque_on_j, response.torque_on_i)
        } else {
            (1.0, response.torque_on_i, response.torque_on_j)
        };
        contact.earlier_forces = [contact.force_on_a, contact.earlier_forces[0]];
        contact.force_on_a = sign * response.force_on_i;
        contact.torque_on_a = torque_a;
        contact.torque_on_b = torque_b;
    }

    /// Area of the smaller particle of the pair at its current scale (walls do not count).
    fn smaller_particle_area(&self, i: BodyId, j: BodyId) -> f64 {
        self.bodies.overlap_reference_area(i.index()).min(self.bodies.overlap_reference_area(j.index()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gc2d_geometry::{Pose, square};

    /// Two unit squares, the second `gap` above the first (negative: overlapping).
    fn stacked(gap: f64) -> Bodies {
        let mut bodies = Bodies::default();
        let shape = square(1.0).unwrap();
        for y in [0.0, 1.0 + gap] {
            bodies.push(BodyKind::Particle, &shape, Pose::new(DVec2::new(0.0, y), 0.0), 1.0, 1.0 / 6.0);
        }
        bodies.update_world_vertices();
        bodies
    }

    /// The closest-feature query runs for pairs apart or just meeting, and is skipped while a pair keeps touching:
    /// then the overlap alone decides (`passes` = 0), with the same geometry the query would have led to.
    #[test]
    fn a_touching_pair_skips_the_closest_feature_query() {
        let law = ContactLaw::elastic(1e7);
        let mut contact = PairContact::default();
        let apart = stacked(0.1);
        PairContext { bodies: &apart, law: &law, dt: 1e-6 }.evaluate(0, 1, &mut contact);
        assert!(!contact.touching);
        assert!(contact.passes >= 1 && contact.warm_start.is_some());

        let overlapping = stacked(-0.01);
        PairContext { bodies: &overlapping, law: &law, dt: 1e-6 }.evaluate(0, 1, &mut contact);
        assert!(contact.touching && contact.passes >= 1);
        let first_force = contact.force_on_a;

        PairContext { bodies: &overlapping, law: &law, dt: 1e-6 }.evaluate(0, 1, &mut contact);
        assert!(contact.touching);
        assert_eq!(contact.passes, 0);
        assert_eq!(contact.force_on_a, first_force, "same overlap, same elastic force");
        assert!(contact.point.x == 0.0 && (0.49..=0.5).contains(&contact.point.y), "{:?}", contact.point);
        assert!((contact.overlap_fraction - 0.01).abs() < 1e-12);

        PairContext { bodies: &apart, law: &law, dt: 1e-6 }.evaluate(0, 1, &mut contact);
        assert!(!contact.touching && contact.passes >= 1, "a pair that separated asks the query again");
        assert_eq!(contact.force_on_a, DVec2::ZERO);
    }
}
