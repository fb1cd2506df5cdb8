//! The exported tables' rows: one per particle (the dumps' [`ParticleState`] plus where it came from and its outline's
//! corner count) and one per touching pair of bodies (point, normal, normal and tangential force, overlap).

use crate::object_names::ObjectNames;
use gc2d_analysis::{ParticleState, particle_states};
use gc2d_engine::{ContactModel, World};
use gc2d_geometry::DVec2;

/// One particle.
#[derive(Debug, Clone, PartialEq)]
pub struct ParticleRow {
    /// Its state (id, material, shape, pose, velocities, force, torque, contacts).
    pub state: ParticleState,
    /// The scene entry it came from (`particles[3]`, `blocks[1] #17`, `inlets[0]`, `sources`); empty when unknown.
    pub origin: String,
    /// Corners of its outline; 0 for a disk.
    pub corners: usize,
    /// A disk's radius, or a polygon's equal-area radius √(area/π), m.
    pub radius_m: f64,
}

/// One touching pair.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactRow {
    /// Body ids, a < b.
    pub a: u32,
    /// Body ids, a < b.
    pub b: u32,
    /// `particle` or `wall`.
    pub kind_a: &'static str,
    /// `particle` or `wall`.
    pub kind_b: &'static str,
    /// The force point, m.
    pub point: DVec2,
    /// Unit contact normal, pointing from b into a (the direction of the normal force on a).
    pub normal: DVec2,
    /// Normal force on a (positive: pushing a away from b), N (N/m per unit thickness).
    pub normal_force_n: f64,
    /// Tangential force on a along the normal turned 90° CCW, N.
    pub tangential_force_n: f64,
    /// Force on a, N.
    pub force_on_a: DVec2,
    /// The overlap: for the overlap-area law the area as a fraction of the smaller particle's area, for penetration
    /// laws the depth as a fraction of the smaller particle's diameter.
    pub overlap_fraction: f64,
    /// `overlap_area` or `penetration`: which of the two `overlap_fraction` is.
    pub law: &'static str,
}

/// The particle rows of `world`; `materials` names the material ids, `names` the bodies (none: the `origin` column
/// is left empty).
pub fn particle_rows(world: &World, materials: &[String], names: Option<&ObjectNames>) -> Vec<ParticleRow> {
    let bodies = world.bodies();
    particle_states(world, materials)
        .into_iter()
        .map(|state| {
            let i = state.id as usize;
            let origin = names.map_or_else(String::new, |names| names.name(world, gc2d_engine::BodyId(state.id)));
            let disk = bodies.shape[i] == gc2d_engine::ShapeKind::Disk;
            let corners = if disk { 0 } else { bodies.vertices[i].len as usize };
            let radius_m = if disk { bodies.radius[i] } else { (bodies.area[i] / std::f64::consts::PI).sqrt() };
            ParticleRow { state, origin, corners, radius_m }
        })
        .collect()
}

/// The contact rows of `world`, in pair order.
pub fn contact_rows(world: &World) -> Vec<ContactRow> {
    let bodies = world.bodies();
    let kind = |i: usize| bodies.kind[i].name();
    world
        .contacts()
        .map(|(a, b, contact)| {
            let normal = world.contact_normal(a, b).unwrap_or(DVec2::NAN);
            let law = match world.config().interactions.model(bodies.material[a.index()], bodies.material[b.index()]) {
                ContactModel::OverlapArea(_) => "overlap_area",
                ContactModel::Penetration(_) => "penetration",
            };
            let force = contact.force_on_a;
            ContactRow {
                a: a.0,
                b: b.0,
                kind_a: kind(a.index()),
                kind_b: kind(b.index()),
                point: contact.point,
                normal,
                normal_force_n: force.dot(normal),
                tangential_force_n: force.dot(normal.perp()),
                force_on_a: force,
                overlap_fraction: world.overlap_fraction(a, b, contact),
                law,
            }
        })
        .collect()
}
