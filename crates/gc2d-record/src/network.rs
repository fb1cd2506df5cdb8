//! The force network of a frame: one record per touching pair, read from the World's contact list.

use gc2d_engine::{BodyId, BodyKind, World};
use gc2d_geometry::DVec2;

/// One contact's force as drawn and counted: it acts at `point` on `a` (and oppositely on `b`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactForce {
    /// First body of the pair.
    pub a: BodyId,
    /// Second body of the pair.
    pub b: BodyId,
    /// Force application point (midpoint of the contact chord), m.
    pub point: DVec2,
    /// |F| of the total contact force (normal and tangential), N per unit thickness. The engine keeps the total
    /// force per pair, not its normal part; gc2d's force-network plots also scale with |F| (reference §5.5).
    pub magnitude: f64,
}

/// Replaces `out` with the World's touching pairs, in the World's pair order; returns the largest |F| (0 if none).
pub fn collect_contact_forces(world: &World, out: &mut Vec<ContactForce>) -> f64 {
    out.clear();
    out.extend(world.contacts().map(|(a, b, contact)| ContactForce {
        a,
        b,
        point: contact.point,
        magnitude: finite_or_zero(contact.force_on_a.length()),
    }));
    out.iter().map(|f| f.magnitude).fold(0.0, f64::max)
}

/// The line segments gc2d draws for one contact (reference §5.5): from each particle's centroid to the force point.
/// Walls get no segment: their centroid says nothing about where they were touched. Returns up to two (from, to).
pub fn contact_segments(world: &World, force: &ContactForce) -> [Option<(DVec2, DVec2)>; 2] {
    let bodies = world.bodies();
    let segment = |id: BodyId| {
        (bodies.kind[id.index()] == BodyKind::Particle).then(|| (bodies.pose[id.index()].position, force.point))
    };
    [segment(force.a), segment(force.b)]
}

/// Line width of a contact of force `magnitude` when the largest force of the frame, `max_force`, is drawn
/// `max_width` wide: proportional to |F|.
pub fn line_width(magnitude: f64, max_force: f64, max_width: f64) -> f64 {
    if max_force > 0.0 { max_width * (magnitude / max_force).clamp(0.0, 1.0) } else { 0.0 }
}

fn finite_or_zero(x: f64) -> f64 {
    if x.is_finite() { x } else { 0.0 }
}
