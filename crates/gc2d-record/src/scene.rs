//! Foxglove `SceneUpdate` messages for particles, walls and the force network (protobuf, from the foxglove SDK).
//!
//! Everything lies in the x-y plane of frame [`FRAME_ID`]; the 3D panel looks down the z axis. Layers sit a small
//! distance apart in z (walls below particles below outlines below force lines) so coplanar shapes do not flicker
//! in the depth test; seen from above the offset is invisible.

use crate::colour::{Rgba, WALL_GREY, force_colour};
use crate::fluid::FluidArrow;
use crate::network::{ContactForce, FORCE_WIDTH_CLASSES, class_width, contact_segments, width_class};
use foxglove::schemas::{
    Color, LinePrimitive, Point3, Pose, Quaternion, SceneEntity, SceneEntityDeletion, SceneUpdate, Timestamp,
    TriangleListPrimitive, Vector3, line_primitive, scene_entity_deletion,
};
use gc2d_engine::{BodyId, BodyKind, World};
use gc2d_geometry::{DVec2, TracedOutline};

/// The coordinate frame of every entity.
pub const FRAME_ID: &str = "world";

/// Body slots per `/particles` entity. Each entity is one triangle list and one line list (one mesh in Foxglove),
/// so a frame of n particles costs Foxglove about n/1024 meshes instead of n. Blocks this small keep a block's
/// fill and outline points (which repeat each other) within reach of zstd's match window, so the packed frames
/// compress as well as one entity per particle did, and keep the point indices short.
pub const PARTICLE_BLOCK_SLOTS: usize = 1024;

/// Id of the entity of `/contacts` that holds the force network.
pub const FORCES_ENTITY: &str = "forces";

/// Id of the entity of `/fluid` that holds the fluid's velocity arrows.
pub const FLUID_ENTITY: &str = "fluid";

/// Width of the fluid's arrows, screen pixels.
const FLUID_ARROW_PIXELS: f64 = 1.5;

/// Outline width of particles and walls, screen pixels.
const OUTLINE_PIXELS: f64 = 1.0;

/// Outline colour: translucent black, which over a fill darkens it to 45 % (as a fill colour darkened by 0.55
/// would), so one colour outlines bodies of every colour.
const OUTLINE_SHADE: Rgba = Rgba { r: 0.0, g: 0.0, b: 0.0, a: 0.55 };

/// Heights of the drawing layers, in units of the layer spacing.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Layer {
    Fluid = -2,
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
}

/// Outlines of many bodies packed into two primitives: one triangle list of every fill (fans of the convex outlines,
/// bands of the rings) with per-vertex colours, and one line list of every outline sharing its points. Foxglove draws
/// each triangle-list primitive as one mesh, so a frame of any size costs it one mesh and one line set.
#[derive(Debug, Default)]
struct PackedOutlines {
    points: Vec<Point3>,
    colours: Vec<Color>,
    triangles: Vec<u32>,
    outlines: Vec<u32>,
}

impl PackedOutlines {
    /// Adds one body's outline filled with `fill`.
    fn push(&mut self, outline: &TracedOutline, fill: Rgba) {
        let base = self.points.len() as u32;
        match outline {
            TracedOutline::Convex(vertices) => {
                self.points.extend(vertices.iter().map(|&v| point(v)));
                self.triangles.extend(fan_indices(vertices.len()).into_iter().map(|k| base + k));
                self.outlines.extend(loop_indices(base, vertices.len()));
            }
            TracedOutline::Ring { inner, outer } => {
                self.points.extend(inner.iter().chain(outer).map(|&v| point(v)));
                self.triangles.extend(band_indices(inner.len()).into_iter().map(|k| base + k));
                self.outlines.extend(loop_indices(base, inner.len()));
                self.outlines.extend(loop_indices(base + inner.len() as u32, outer.len()));
            }
        }
        self.colours.resize(self.points.len(), color(fill));
    }

    /// The entity `id` drawing the packed fills at `fill_layer` and the outlines one layer above it. `uniform`: one
    /// colour for every fill (written once instead of per vertex).
    fn into_entity(self, style: &SceneStyle, id: String, fill_layer: Layer, uniform: Option<Rgba>) -> SceneEntity {
        let fill_z = style.z(fill_layer);
        let outline_z = style.z(if matches!(fill_layer, Layer::Walls) { Layer::Fills } else { Layer::Outlines });
        let mut entity = style.entity(id);
        if self.points.is_empty() {
            return entity;
        }
        let (color_field, colors) = match uniform {
            Some(fill) => (Some(color(fill)), Vec::new()),
            None => (None, self.colours),
        };
        entity.lines.push(LinePrimitive {
            r#type: line_primitive::Type::LineList as i32,
            pose: Some(lifted_pose(outline_z)),
            thickness: OUTLINE_PIXELS,
            scale_invariant: true,
            points: self.points.clone(),
            color: Some(color(OUTLINE_SHADE)),
            colors: Vec::new(),
            indices: self.outlines,
        });
        entity.triangles.push(TriangleListPrimitive {
            pose: Some(lifted_pose(fill_z)),
            points: self.points,
            color: color_field,
            colors,
            indices: self.triangles,
        });
        entity
    }
}

/// `/particles`: every living particle filled with `colours[slot]` and outlined, packed by slot into blocks of
/// [`PARTICLE_BLOCK_SLOTS`]: the entity `particles/<k>` holds slots k·1024 … k·1024 + 1023 in slot order (see
/// [`particle_entity_id`]), so a particle stays in the same entity for the whole run.
pub(crate) fn particles_update(world: &World, colours: &[Rgba], style: &SceneStyle) -> SceneUpdate {
    let bodies = world.bodies();
    let mut entities = Vec::new();
    let mut block: Option<(usize, PackedOutlines)> = None;
    for id in bodies.particles() {
        let k = id.index() / PARTICLE_BLOCK_SLOTS;
        if block.as_ref().is_some_and(|(current, _)| *current != k) {
            let (current, packed) = block.take().expect("checked");
            entities.push(packed.into_entity(style, particle_entity_id(current), Layer::Fills, None));
        }
        let (_, packed) = block.get_or_insert_with(|| (k, PackedOutlines::default()));
        packed.push(&bodies.shape_view(id).traced_outline(), colours[id.index()]);
    }
    if let Some((current, packed)) = block {
        entities.push(packed.into_entity(style, particle_entity_id(current), Layer::Fills, None));
    }
    style.replacing_all(entities)
}

/// The id of the `/particles` entity holding block `block` of [`PARTICLE_BLOCK_SLOTS`] slots.
pub fn particle_entity_id(block: usize) -> String {
    format!("particles/{block}")
}

/// `/walls`: one grey entity per wall, id `w<slot>`.
pub(crate) fn walls_update(world: &World, style: &SceneStyle) -> SceneUpdate {
    let bodies = world.bodies();
    let entities = (0..bodies.len())
        .filter(|&i| bodies.kind[i] == BodyKind::Wall && bodies.alive[i])
        .map(|i| {
            let mut packed = PackedOutlines::default();
            packed.push(&bodies.shape_view(BodyId(i as u32)).traced_outline(), WALL_GREY);
            packed.into_entity(style, format!("w{i}"), Layer::Walls, Some(WALL_GREY))
        })
        .collect();
    style.replacing_all(entities)
}

/// `/contacts`: one entity [`FORCES_ENTITY`] with a line list per width class ([`width_class`]), holding the
/// segments from each particle centroid to the force point of every contact of that class, each segment in gc2d's
/// force colour of its contact. Widths are in metres (they scale with zoom), the largest force `max_width` wide.
pub(crate) fn contacts_update(
    world: &World,
    forces: &[ContactForce],
    max_force: f64,
    max_width: f64,
    style: &SceneStyle,
) -> SceneUpdate {
    let z = style.z(Layer::Forces);
    let mut entity = style.entity(FORCES_ENTITY.to_string());
    if max_width > 0.0 {
        let mut classes: Vec<LinePrimitive> = (1..=FORCE_WIDTH_CLASSES)
            .map(|class| LinePrimitive {
                r#type: line_primitive::Type::LineList as i32,
                pose: Some(lifted_pose(z)),
                thickness: class_width(class, max_width),
                scale_invariant: false,
                ..LinePrimitive::default()
            })
            .collect();
        for force in forces {
            let Some(class) = width_class(force.magnitude, max_force) else { continue };
            let line = &mut classes[class - 1];
            let shade = color(force_colour(force.magnitude / max_force));
            for (from, to) in contact_segments(world, force).into_iter().flatten() {
                line.points.extend([point(from), point(to)]);
                line.colors.extend([shade, shade]);
            }
        }
        entity.lines = classes.into_iter().filter(|line| !line.points.is_empty()).collect();
    }
    style.replacing_all(vec![entity])
}

/// `/fluid`: one entity [`FLUID_ENTITY`] with one line list of the arrows' segments, each in its arrow's colour,
/// under the walls and particles.
pub(crate) fn fluid_update(arrows: &[FluidArrow], style: &SceneStyle) -> SceneUpdate {
    let mut entity = style.entity(FLUID_ENTITY.to_string());
    let mut line = LinePrimitive {
        r#type: line_primitive::Type::LineList as i32,
        pose: Some(lifted_pose(style.z(Layer::Fluid))),
        thickness: FLUID_ARROW_PIXELS,
        scale_invariant: true,
        ..LinePrimitive::default()
    };
    for arrow in arrows {
        let shade = color(arrow.colour);
        for (from, to) in arrow.segments() {
            line.points.extend([point(from), point(to)]);
            line.colors.extend([shade, shade]);
        }
    }
    if !line.points.is_empty() {
        entity.lines.push(line);
    }
    style.replacing_all(vec![entity])
}

/// Line-list indices of the closed loop of `n` points starting at `base`: (base + k, base + (k+1) mod n).
fn loop_indices(base: u32, n: usize) -> impl Iterator<Item = u32> {
    let n = n as u32;
    (0..n).flat_map(move |k| [base + k, base + (k + 1) % n])
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

/// A Foxglove colour in 8-bit steps (k/255, what a display shows): colours of neighbouring particles then repeat
/// exactly, which the per-vertex colours of a packed frame compress by.
fn color(c: Rgba) -> Color {
    let q = |x: f64| (x * 255.0).round() / 255.0;
    Color { r: q(c.r), g: q(c.g), b: q(c.b), a: q(c.a) }
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
        let mut packed = PackedOutlines::default();
        packed.push(&chamber.traced_outline(), WALL_GREY);
        let entity = packed.into_entity(&style, "w0".into(), Layer::Walls, Some(WALL_GREY));
        assert_eq!(entity.triangles[0].points.len(), 2 * n);
        let outline = &entity.lines[0].indices;
        assert_eq!(outline.len(), 4 * n, "the ring is outlined on both edges");
        assert_eq!(&outline[2 * n - 2..2 * n + 2], &[95, 0, 96, 97], "inner loop closes, outer loop starts");
    }

    #[test]
    fn packed_bodies_keep_their_own_points_colours_and_closed_outlines() {
        let style = SceneStyle { timestamp: timestamp(0), layer_spacing: 1e-4 };
        let triangle = [DVec2::ZERO, DVec2::X, DVec2::Y];
        let square = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        let (red, blue) = (Rgba::hex(0xff0000), Rgba::hex(0x0000ff));
        let mut packed = PackedOutlines::default();
        packed.push(&TracedOutline::Convex(triangle.as_slice().into()), red);
        packed.push(&TracedOutline::Convex(square.as_slice().into()), blue);
        let entity = packed.into_entity(&style, "particles".into(), Layer::Fills, None);
        let (fills, lines) = (&entity.triangles[0], &entity.lines[0]);
        assert_eq!(fills.points.len(), 7);
        assert_eq!(fills.colors, [vec![color(red); 3], vec![color(blue); 4]].concat());
        assert_eq!(fills.indices, vec![0, 1, 2, 3, 4, 5, 3, 5, 6], "the square's fan starts at its own first point");
        assert_eq!(lines.points, fills.points, "outlines share the fills' points");
        assert_eq!(lines.indices, vec![0, 1, 1, 2, 2, 0, 3, 4, 4, 5, 5, 6, 6, 3]);
        assert!(lines.pose.unwrap().position.unwrap().z > fills.pose.unwrap().position.unwrap().z, "on top");
    }

    #[test]
    fn timestamps_split_nanoseconds_into_seconds() {
        let t = timestamp(2_500_000_001);
        assert_eq!(t, Timestamp::new(2, 500_000_001));
    }
}
