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

/// Width classes of the recording's force network: Foxglove gives a line primitive one thickness, so the contacts
/// are drawn in this many line lists, the k-th (k = 1 … 16) `k/16` of the largest width wide.
pub const FORCE_WIDTH_CLASSES: usize = 16;

/// The width class (1 … [`FORCE_WIDTH_CLASSES`]) of a contact of force `magnitude` when the frame's largest force is
/// `max_force`: the smallest class at least as wide as [`line_width`], so a line is at most 1/16 of the largest
/// width wider than its exact width and the largest force is drawn exactly. `None` for a zero (or non-finite)
/// force, which is not drawn.
pub fn width_class(magnitude: f64, max_force: f64) -> Option<usize> {
    let t = if max_force > 0.0 { magnitude / max_force } else { 0.0 };
    (t > 0.0 && t.is_finite()).then(|| ((t.min(1.0) * FORCE_WIDTH_CLASSES as f64).ceil() as usize).max(1))
}

/// The line width of width class `class` when the largest force is drawn `max_width` wide.
pub fn class_width(class: usize, max_width: f64) -> f64 {
    max_width * class as f64 / FORCE_WIDTH_CLASSES as f64
}

fn finite_or_zero(x: f64) -> f64 {
    if x.is_finite() { x } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn width_classes_round_up_to_sixteenths_and_skip_zero_forces() {
        assert_eq!(width_class(1.0, 1.0), Some(16));
        assert_eq!(width_class(0.5, 1.0), Some(8));
        assert_eq!(width_class(0.501, 1.0), Some(9));
        assert_eq!(width_class(1e-12, 1.0), Some(1));
        assert_eq!(width_class(0.0, 1.0), None);
        assert_eq!(width_class(1.0, 0.0), None);
        assert_eq!(width_class(f64::NAN, 1.0), None);
        assert_eq!(class_width(16, 0.004), 0.004);
        for magnitude in [0.01, 0.3, 0.77, 1.0] {
            let class = width_class(magnitude, 1.0).unwrap();
            let (drawn, exact) = (class_width(class, 1.0), line_width(magnitude, 1.0, 1.0));
            assert!(drawn >= exact && drawn - exact < 1.0 / 16.0, "{magnitude}: {drawn} vs {exact}");
        }
    }
}
