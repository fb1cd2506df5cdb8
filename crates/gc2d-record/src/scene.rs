//! Foxglove `SceneUpdate` messages for particles, walls and the force network (protobuf, from the foxglove SDK).
//!
//! Everything lies in the x-y plane of frame [`FRAME_ID`]; the 3D panel looks down the z axis. Layers sit a small
//! distance apart in z (walls below particles below outlines below force lines) so coplanar shapes do not flicker
//! in the depth test; seen from above the offset is invisible.

use crate::colour::{Rgba, WALL_GREY, force_colour};
use crate::network::{ContactForce, contact_segments, line_width};
use foxglove::schemas::{
    Color, LinePrimitive, Point3, Pose, Quaternion, SceneEntity, SceneEntityDeletion, SceneUpdate, Timestamp,
    TriangleListPrimitive, Vector3, line_primitive, scene_entity_deletion,
};
use gc2d_engine::{BodyId, BodyKind, World};
use gc2d_geometry::{DVec2, TracedOutline};

/// The coordinate frame of every entity.
pub const FRAME_ID: &str = "world";

/// Outline width of particles and walls, screen pixels.
const OUTLINE_PIXELS: f64 = 1.0;

/// Heights of the drawing layers, in units of the layer spacing.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Layer {
    Walls = -1,
    Fills = 0,
    Outlines = 1,
    Forces = 2,
}

/// Shared settings of the scene messages of one frame.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SceneStyle {
    /// Simulated time as a Foxglove timestamp.
    pub timestamp: Timestamp,
    /// z distance between layers, m.
    pub layer_spacing: f64,
}

impl SceneStyle {
    fn z(&self, layer: Layer) -> f64 {
        layer as i32 as f64 * self.layer_spacing
    }

    fn entity(&self, id: String) -> SceneEntity {
        SceneEntity { timestamp: Some(self.timestamp), frame_id: FRAME_ID.to_string(), id, ..SceneEntity::default() }
    }

    /// A message that first clears every entity of its topic, so bodies that disappeared do not linger.
    fn replacing_all(&self, entities: Vec<SceneEntity>) -> SceneUpdate {
        let clear = SceneEntityDeletion {
            timestamp: Some(self.timestamp),
            r#type: scene_entity_deletion::Type::All as i32,
            id: String::new(),
        };
        SceneUpdate { deletions: vec![clear], entities }
    }

    /// One body as a filled shape with a thin outline: a convex outline as a fan of triangles, a ring (an inner
    /// circle's wall) as the band of triangles between its two circles.
    fn body_entity(&self, id: String, outline: &TracedOutline, fill: Rgba, fill_layer: Layer) -> SceneEntity {
        let fill_z = self.z(fill_layer);
        let outline_z = self.z(if matches!(fill_layer, Layer::Walls) { Layer::Fills } else { Layer::Outlines });
        let mut entity = self.entity(id);
        let (points, indices, loops): (Vec<Point3>, Vec<u32>, Vec<&[DVec2]>) = match outline {
            TracedOutline::Convex(vertices) => {
                (vertices.iter().map(|&v| point(v)).collect(), fan_indices(vertices.len()), vec![vertices.as_ref()])
            }
            TracedOutline::Ring { inner, outer } => {
                let points = inner.iter().chain(outer).map(|&v| point(v)).collect();
                (points, band_indices(inner.len()), vec![inner.as_slice(), outer.as_slice()])
            }
        };
        entity.triangles.push(TriangleListPrimitive {
            pose: Some(lifted_pose(fill_z)),
            points,
            color: Some(color(fill)),
            colors: Vec::new(),
            indices,
        });
        for outline_points in loops {
            entity.lines.push(LinePrimitive {
                r#type: line_primitive::Type::LineLoop as i32,
                pose: Some(lifted_pose(outline_z)),
                thickness: OUTLINE_PIXELS,
                scale_invariant: true,
                points: outline_points.iter().map(|&v| point(v)).collect(),
                color: Some(color(fill.darkened(0.55))),
                colors: Vec::new(),
                indices: Vec::new(),
            });
        }
        entity
    }
}

/// `/particles`: one entity per living particle, id `p<slot>`, coloured by `colours[slot]`.
pub(crate) fn particles_update(world: &World, colours: &[Rgba], style: &SceneStyle) -> SceneUpdate {
    let bodies = world.bodies();
    let entities = bodies
        .particles()
        .map(|id| {
            style.body_entity(
                format!("p{}", id.0),
                &bodies.shape_view(id).traced_outline(),
                colours[id.index()],
                Layer::Fills,
            )
        })
        .collect();
    style.replacing_all(entities)
}

/// `/walls`: one grey entity per wall, id `w<slot>`.
pub(crate) fn walls_update(world: &World, style: &SceneStyle) -> SceneUpdate {
    let bodies = world.bodies();
    let entities = (0..bodies.len())
        .filter(|&i| bodies.kind[i] == BodyKind::Wall && bodies.alive[i])
        .map(|i| {
            let id = BodyId(i as u32);
            style.body_entity(format!("w{i}"), &bodies.shape_view(id).traced_outline(), WALL_GREY, Layer::Walls)
        })
        .collect();
    style.replacing_all(entities)
}

/// `/contacts`: one entity `forces` with a line list per contact, from each particle centroid to the force point,
/// width `max_width`·|F|/F_max (in metres, so it scales with zoom) and gc2d's force colour.
pub(crate) fn contacts_update(
    world: &World,
    forces: &[ContactForce],
    max_force: f64,
    max_width: f64,
    style: &SceneStyle,
) -> SceneUpdate {
    let z = style.z(Layer::Forces);
    let mut entity = style.entity("forces".to_string());
    for force in forces {
        let width = line_width(force.magnitude, max_force, max_width);
        if width <= 0.0 {
            continue;
        }
        let points: Vec<Point3> = contact_segments(world, force)
            .into_iter()
            .flatten()
            .flat_map(|(from, to)| [point(from), point(to)])
            .collect();
        if points.is_empty() {
            continue;
        }
        entity.lines.push(LinePrimitive {
            r#type: line_primitive::Type::LineList as i32,
            pose: Some(lifted_pose(z)),
            thickness: width,
            scale_invariant: false,
            points,
            color: Some(color(force_colour(force.magnitude / max_force))),
            colors: Vec::new(),
            indices: Vec::new(),
        });
    }
    style.replacing_all(vec![entity])
}

/// Triangle indices of the band between two closed loops of `n` points each, stored one after the other (inner
/// then outer): two triangles per corner.
pub(crate) fn band_indices(n: usize) -> Vec<u32> {
    let n32 = n as u32;
    (0..n32)
        .flat_map(|k| {
            let next = (k + 1) % n32;
            [k, n32 + k, n32 + next, k, n32 + next, next]
        })
        .collect()
}

/// Indices of a fan triangulation of a convex polygon with `n` vertices: (0, k, k+1) for k = 1 … n−2.
pub(crate) fn fan_indices(n: usize) -> Vec<u32> {
    (1..n.saturating_sub(1)).flat_map(|k| [0, k as u32, k as u32 + 1]).collect()
}

/// A Foxglove timestamp from simulated nanoseconds.
pub(crate) fn timestamp(nanoseconds: u64) -> Timestamp {
    let sec = (nanoseconds / 1_000_000_000).min(u32::MAX as u64) as u32;
    Timestamp::new(sec, (nanoseconds % 1_000_000_000) as u32)
}

/// A point of the x-y plane; the layer height goes into the primitive's pose, so it is written once per primitive.
fn point(v: DVec2) -> Point3 {
    Point3 { x: v.x, y: v.y, z: 0.0 }
}

fn color(c: Rgba) -> Color {
    Color { r: c.r, g: c.g, b: c.b, a: c.a }
}

/// Primitives are given in world coordinates, shifted by `z` to their layer; the orientation is written out
/// (identity) so that no reader has to guess a default for a missing quaternion.
fn lifted_pose(z: f64) -> Pose {
    Pose {
        position: Some(Vector3 { x: 0.0, y: 0.0, z }),
        orientation: Some(Quaternion { x: 0.0, y: 0.0, z: 0.0, w: 1.0 }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fan_of_a_heptagon_has_five_triangles_sharing_vertex_zero() {
        let indices = fan_indices(7);
        assert_eq!(indices.len(), 15);
        assert_eq!(&indices[..3], &[0, 1, 2]);
        assert_eq!(&indices[12..], &[0, 5, 6]);
        assert!(fan_indices(2).is_empty());
    }

    #[test]
    fn a_ring_band_covers_every_corner_with_two_triangles_inside_its_points() {
        let n = 96;
        let indices = band_indices(n);
        assert_eq!(indices.len(), 6 * n);
        assert!(indices.iter().all(|&k| (k as usize) < 2 * n));
        // The last quad closes the ring: inner 95, outer 95, outer 0 (index 96), inner 0.
        assert_eq!(&indices[6 * (n - 1)..], &[95, 191, 96, 95, 96, 0]);
        let style = SceneStyle { timestamp: timestamp(0), layer_spacing: 1e-4 };
        let chamber = gc2d_geometry::ShapeView::InnerCircle { center: DVec2::ZERO, radius: 0.07 };
        let entity = style.body_entity("w0".into(), &chamber.traced_outline(), WALL_GREY, Layer::Walls);
        assert_eq!(entity.triangles[0].points.len(), 2 * n);
        assert_eq!(entity.lines.len(), 2, "the ring is outlined on both edges");
    }

    #[test]
    fn timestamps_split_nanoseconds_into_seconds() {
        let t = timestamp(2_500_000_001);
        assert_eq!(t, Timestamp::new(2, 500_000_001));
    }
}
