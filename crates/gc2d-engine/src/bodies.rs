//! The body store: every particle and wall of a World as columns of a structure of arrays.
//!
//! Bodies are addressed by a dense slot index ([`BodyId`]) that never changes; removing a particle marks its slot dead
//! (its vertices stay in the arrays). Body-frame and world-frame vertices of all bodies sit in two flat arrays with
//! per-body offsets, so a step transforms them without allocating.

use crate::broadphase::BoxWriter;
use crate::force_ranges::BodyRanges;
use crate::home_threads::for_each_on_home_thread;
use crate::integrator::GearState;
use crate::interactions::MaterialId;
use crate::parallel::steps_in_parallel;
use crate::shape::{BodyShape, ShapeKind, shape_view};
use gc2d_geometry::{Aabb, DVec2, Pose, ShapeView};
use serde::{Deserialize, Serialize};

/// Index of a body in the World's store; stable for the life of the World.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub struct BodyId(pub u32);

impl BodyId {
    /// The slot as a `usize` index into the columns.
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// What moves a body.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum BodyKind {
    /// A free particle integrated by the Gear predictor-corrector.
    Particle,
    /// A wall: infinite mass, placed by its motion law (static unless the scene gives it one).
    Wall,
}

impl BodyKind {
    /// `particle` or `wall`, as the run's tables write it.
    pub fn name(self) -> &'static str {
        match self {
            BodyKind::Particle => "particle",
            BodyKind::Wall => "wall",
        }
    }
}

/// Range of a body's vertices in the flat vertex arrays.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct VertexRange {
    /// First vertex.
    pub start: u32,
    /// Number of vertices.
    pub len: u32,
}

impl VertexRange {
    /// As a `usize` range.
    #[inline]
    pub fn range(self) -> std::ops::Range<usize> {
        self.start as usize..(self.start + self.len) as usize
    }
}

/// Columns of per-body data. All `Vec`s have one entry per slot.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct Bodies {
    /// Particle or wall.
    pub kind: Vec<BodyKind>,
    /// False once a particle has been removed.
    pub alive: Vec<bool>,
    /// How to read the body's points and radius (see [`crate::shape`]).
    pub shape: Vec<ShapeKind>,
    /// Radius of a disk, capsule or inner circle at scale 1, m; 0 for polygons.
    pub radius: Vec<f64>,
    /// The body's material: with the other body's, it selects the pair's contact model.
    pub material: Vec<MaterialId>,
    /// Where the body's vertices are in `body_vertices` and `world_vertices`.
    pub vertices: Vec<VertexRange>,
    /// Body-frame points of all bodies (polygon vertices CCW, centroid at the origin; see [`crate::shape`]).
    pub body_vertices: Vec<DVec2>,
    /// World-frame vertices of all bodies at the current (predicted) pose.
    pub world_vertices: Vec<DVec2>,
    /// Pose of the centroid (particles: from the integrator; walls: from their motion law).
    pub pose: Vec<Pose>,
    /// Velocity of the centroid, m/s.
    pub velocity: Vec<DVec2>,
    /// Angular velocity, rad/s, CCW.
    pub angular_velocity: Vec<f64>,
    /// Gear scaled derivatives (meaningful for particles only).
    pub gear: Vec<GearState>,
    /// Mass, kg (per unit thickness); infinite for walls.
    pub mass: Vec<f64>,
    /// Moment of inertia about the centroid at scale 1, kg·m²; infinite for walls.
    pub inertia: Vec<f64>,
    /// 1/mass; 0 for walls.
    pub inverse_mass: Vec<f64>,
    /// 1/inertia at the current scale; 0 for walls.
    pub inverse_inertia: Vec<f64>,
    /// Area at scale 1, m².
    pub area: Vec<f64>,
    /// Radius of the largest circle about the centroid inside the body, at scale 1, m.
    pub inscribed_radius: Vec<f64>,
    /// Largest distance of a point of the body from its centroid, at scale 1, m.
    pub reach: Vec<f64>,
    /// How far any point of the body may have moved since the pose the last narrowphase saw, m, rounded up: the
    /// corrector's move of the last step plus this step's predictor's (`travel_bound`); infinite for walls, for a body
    /// not yet stepped or rescaled this step, and for every body while the World has no polygon particle. A pair apart
    /// by more than its two bodies' travel is still apart, so its closest-feature query can wait (docs/model.md, "Pairs
    /// apart by more than they moved"). Saved in checkpoints, so that a resumed run skips the same queries. Single
    /// precision: 4 bytes per body.
    pub travel: Vec<f32>,
    /// Virtual tangential surface velocity of the walls that have one (drums, §2.11), by body id. The column ends
    /// at the last such wall: every body beyond it has none, so the particles, added after the walls, do not carry
    /// 16 bytes each of a wall property. Read it with [`Bodies::surface_velocity_of`].
    pub(crate) surface_velocity: Vec<DVec2>,
    /// Force accumulated this step, N.
    pub force: Vec<DVec2>,
    /// Torque accumulated this step, N·m, CCW.
    pub torque: Vec<f64>,
}

impl Bodies {
    /// Number of slots (alive or not).
    pub fn len(&self) -> usize {
        self.kind.len()
    }

    /// True when the store has no slots.
    pub fn is_empty(&self) -> bool {
        self.kind.is_empty()
    }

    /// Appends a body of material 0 and returns its slot. `mass`/`inertia` are infinite for walls.
    pub(crate) fn push(&mut self, kind: BodyKind, shape: &BodyShape, pose: Pose, mass: f64, inertia: f64) -> BodyId {
        let id = BodyId(self.kind.len() as u32);
        let start = self.body_vertices.len() as u32;
        let points = shape.body_points();
        self.body_vertices.extend_from_slice(&points);
        self.world_vertices.extend(points.iter().map(|&v| pose.apply(v)));
        let range = VertexRange { start, len: points.len() as u32 };
        self.kind.push(kind);
        self.alive.push(true);
        self.shape.push(shape.kind());
        self.radius.push(shape.radius());
        self.material.push(MaterialId::default());
        self.vertices.push(range);
        self.pose.push(pose);
        self.velocity.push(DVec2::ZERO);
        self.angular_velocity.push(0.0);
        self.gear.push(GearState::default());
        self.mass.push(mass);
        self.inertia.push(inertia);
        self.inverse_mass.push(if mass.is_finite() { 1.0 / mass } else { 0.0 });
        self.inverse_inertia.push(if inertia.is_finite() { 1.0 / (inertia * pose.scale * pose.scale) } else { 0.0 });
        self.area.push(shape.area());
        self.inscribed_radius.push(shape.inscribed_radius());
        self.reach.push(shape.reach());
        self.travel.push(f32::INFINITY);
        self.force.push(DVec2::ZERO);
        self.torque.push(0.0);
        id
    }

    /// Gives back the spare room of every column (a `Vec` grows by doubling, so up to half of a column can be
    /// unused); the values stay as they are. The surface-velocity column is cut after its last wall with a surface
    /// velocity (checkpoints written before it stopped there hold one entry per body).
    pub fn shrink_to_fit(&mut self) {
        let kept = self.surface_velocity.iter().rposition(|&v| v != DVec2::ZERO).map_or(0, |last| last + 1);
        self.surface_velocity.truncate(kept);
        self.kind.shrink_to_fit();
        self.alive.shrink_to_fit();
        self.shape.shrink_to_fit();
        self.radius.shrink_to_fit();
        self.material.shrink_to_fit();
        self.reach.shrink_to_fit();
        self.travel.shrink_to_fit();
        self.vertices.shrink_to_fit();
        self.body_vertices.shrink_to_fit();
        self.world_vertices.shrink_to_fit();
        self.pose.shrink_to_fit();
        self.velocity.shrink_to_fit();
        self.angular_velocity.shrink_to_fit();
        self.gear.shrink_to_fit();
        self.mass.shrink_to_fit();
        self.inertia.shrink_to_fit();
        self.inverse_mass.shrink_to_fit();
        self.inverse_inertia.shrink_to_fit();
        self.area.shrink_to_fit();
        self.inscribed_radius.shrink_to_fit();
        self.surface_velocity.shrink_to_fit();
        self.force.shrink_to_fit();
        self.torque.shrink_to_fit();
    }

    /// Heap memory held by the columns, in bytes, counted from their capacities (not their lengths), so it is what
    /// the store really occupies, spare room of the growing `Vec`s included.
    pub fn heap_bytes(&self) -> usize {
        vec_bytes(&self.kind)
            + vec_bytes(&self.alive)
            + vec_bytes(&self.shape)
            + vec_bytes(&self.radius)
            + vec_bytes(&self.material)
            + vec_bytes(&self.reach)
            + vec_bytes(&self.travel)
            + vec_bytes(&self.vertices)
            + vec_bytes(&self.body_vertices)
            + vec_bytes(&self.world_vertices)
            + vec_bytes(&self.pose)
            + vec_bytes(&self.velocity)
            + vec_bytes(&self.angular_velocity)
            + vec_bytes(&self.gear)
            + vec_bytes(&self.mass)
            + vec_bytes(&self.inertia)
            + vec_bytes(&self.inverse_mass)
            + vec_bytes(&self.inverse_inertia)
            + vec_bytes(&self.area)
            + vec_bytes(&self.inscribed_radius)
            + vec_bytes(&self.surface_velocity)
            + vec_bytes(&self.force)
            + vec_bytes(&self.torque)
    }

    /// Virtual tangential surface velocity of body `i`, m/s: a wall's as given to `World::add_wall`, zero for every
    /// particle.
    #[inline]
    pub fn surface_velocity_of(&self, i: usize) -> DVec2 {
        self.surface_velocity.get(i).copied().unwrap_or(DVec2::ZERO)
    }

    /// Gives body `id` the surface velocity `velocity`, extending the column to it when it is not zero.
    pub(crate) fn set_surface_velocity(&mut self, id: BodyId, velocity: DVec2) {
        let i = id.index();
        if velocity != DVec2::ZERO && self.surface_velocity.len() <= i {
            self.surface_velocity.resize(i + 1, DVec2::ZERO);
        }
        if let Some(slot) = self.surface_velocity.get_mut(i) {
            *slot = velocity;
        }
    }

    /// World-frame vertices of one body.
    #[inline]
    pub fn world_vertices_of(&self, id: BodyId) -> &[DVec2] {
        &self.world_vertices[self.vertices[id.index()].range()]
    }

    /// Body `id`'s outline in the world frame at its current pose and scale, for the pair queries.
    #[inline]
    pub fn shape_view(&self, id: BodyId) -> ShapeView<'_> {
        let i = id.index();
        shape_view(self.shape[i], self.world_vertices_of(id), self.radius[i] * self.pose[i].scale)
    }

    /// Body-frame vertices of one body.
    #[inline]
    pub fn body_vertices_of(&self, id: BodyId) -> &[DVec2] {
        &self.body_vertices[self.vertices[id.index()].range()]
    }

    /// The columns the integrator writes (state, pose, velocities; with kind and liveness to read) and, beside them,
    /// the force columns and what the corrector and the closing pass read with them, borrowed apart so all can be
    /// used at once.
    pub(crate) fn split_for_integration(&mut self) -> IntegrationColumns<'_> {
        let StepColumns { kinematics, forces, inscribed_radius, .. } = self.split_for_step();
        IntegrationColumns { kinematics, forces, inscribed_radius }
    }

    /// Every column the passes of a step over the bodies write or read, borrowed apart.
    fn split_for_step(&mut self) -> StepColumns<'_> {
        StepColumns {
            kinematics: KinematicsColumns {
                gear: &mut self.gear,
                pose: &mut self.pose,
                velocity: &mut self.velocity,
                angular_velocity: &mut self.angular_velocity,
                travel: &mut self.travel,
                kind: &self.kind,
                alive: &self.alive,
                reach: &self.reach,
            },
            forces: ForceColumns {
                force: &mut self.force,
                torque: &mut self.torque,
                mass: &self.mass,
                inverse_mass: &self.inverse_mass,
                inverse_inertia: &self.inverse_inertia,
            },
            transform: TransformInputs {
                ranges: &self.vertices,
                body: &self.body_vertices,
                alive: &self.alive,
                radius: &self.radius,
            },
            world_vertices: &mut self.world_vertices,
            inscribed_radius: &self.inscribed_radius,
        }
    }

    /// Area of body `i` at its current scale for overlap fractions: a particle's area, infinite for a wall (an overlap
    /// is judged against the smaller particle, and a wall never is the smaller one).
    pub fn overlap_reference_area(&self, i: usize) -> f64 {
        match self.kind[i] {
            BodyKind::Particle => self.area[i] * self.pose[i].scale * self.pose[i].scale,
            BodyKind::Wall => f64::INFINITY,
        }
    }

    /// The radius penetration laws give body `i` at its current scale, m: a disk's radius, a polygon's equal-area
    /// radius √(A/π) (docs/model.md, "Penetration laws").
    #[inline]
    pub fn contact_radius(&self, i: usize) -> f64 {
        let radius = match self.shape[i] {
            ShapeKind::Polygon => (self.area[i] / std::f64::consts::PI).sqrt(),
            _ => self.radius[i],
        };
        radius * self.pose[i].scale
    }

    /// Ids of the living particles, in slot order.
    pub fn particles(&self) -> impl Iterator<Item = BodyId> + '_ {
        (0..self.len()).filter(|&i| self.alive[i] && self.kind[i] == BodyKind::Particle).map(|i| BodyId(i as u32))
    }

    /// Axis-aligned box around body `i`'s world vertices (grown by its scaled radius), computed from them: the
    /// bodies keep no box column, the broadphase keeps the boxes it sorts (`Bodies::update_world_vertices`).
    pub fn aabb(&self, i: usize) -> Aabb {
        body_aabb(Aabb::of_points(&self.world_vertices[self.vertices[i].range()]), self.radius[i] * self.pose[i].scale)
    }

    /// Recomputes the world vertices of every living body from its pose, and writes its box through `boxes` (the
    /// broadphase's, which must cover every slot): where the World steps in parallel ([`steps_in_parallel`]) each
    /// range of bodies on its home thread ([`for_each_on_home_thread`]), with the flat vertex array and the boxes
    /// split at the ranges' first bodies, so no allocation happens and each body's vertices are written by one task.
    pub(crate) fn update_world_vertices(&mut self, boxes: BoxWriter) {
        self.move_and_update_world_vertices(boxes, |_, _| {});
    }

    /// [`Self::update_world_vertices`], each range of bodies first moved by `move_range(first, rows)` (`first`: the
    /// range's first body) on the thread that then transforms it: the predictor and the vertex transform in one pass
    /// over the bodies (`World::predict_and_transform`). `move_range` may change poses, not vertices or liveness.
    pub(crate) fn move_and_update_world_vertices(
        &mut self,
        boxes: BoxWriter,
        move_range: impl Fn(usize, &mut KinematicsColumns) + Sync,
    ) {
        let count = self.len();
        debug_assert_eq!(boxes.len(), count, "the box writer covers every body slot");
        let StepColumns { kinematics: mut columns, transform: inputs, world_vertices, .. } = self.split_for_step();
        if !steps_in_parallel(count) {
            move_range(0, &mut columns);
            transform_range(0, count, &inputs, columns.pose, world_vertices, boxes);
            return;
        }
        let per_range = BodyRanges::of_pool(count).per_range();
        let vertex_count = world_vertices.len();
        let first_vertex = |body: usize| inputs.ranges.get(body).map_or(vertex_count, |range| range.start as usize);
        let (mut world, mut boxes) = (world_vertices, Some(boxes));
        let mut first = 0;
        let ranges = columns.ranges(per_range).map_while(|rows| {
            let remaining_boxes = boxes.take()?;
            let last = first + rows.len();
            let vertices = first_vertex(last) - first_vertex(first);
            let (range_world, rest_world) = std::mem::take(&mut world).split_at_mut(vertices);
            let (range_boxes, rest_boxes) = remaining_boxes.split_at(last - first);
            (world, boxes) = (rest_world, (last < count).then_some(rest_boxes));
            let range = (first, last, rows, range_world, range_boxes);
            first = last;
            Some(range)
        });
        for_each_on_home_thread(ranges, |_, (first, last, mut rows, world, boxes)| {
            move_range(first, &mut rows);
            transform_range(first, last, &inputs, rows.pose, world, boxes);
        });
    }
}

/// A body's box from `tight`, the box of its world points, grown by its scaled radius (disks, capsules, inner circles;
/// a polygon's radius is 0 and its box is the points' own).
#[inline]
fn body_aabb(tight: Aabb, scaled_radius: f64) -> Aabb {
    if scaled_radius > 0.0 { tight.expanded(scaled_radius) } else { tight }
}

/// An upper bound on how far any point of a body reaching `reach` (m, at its scale) from its centroid moves from pose
/// `from` to pose `to` of the same scale, m, in single precision: the centroid's move plus the arc of the farthest
/// point, |Δx| + |Δy| + R·|Δφ| (a turn by Δφ moves a point at distance r by 2r·sin(|Δφ|/2) ≤ r·|Δφ|; the sum of
/// the two components bounds the length of the move without a square root). Raised by 2⁻²² of itself and 10⁻³⁰ m
/// before it is rounded to single precision, which changes a number by at most 2⁻²⁴ of itself in the normal range,
/// so the rounded bound is never below the exact one.
#[inline]
pub(crate) fn travel_bound(from: &Pose, to: &Pose, reach: f64) -> f32 {
    let moved = (to.position - from.position).abs();
    let bound = moved.x + moved.y + reach * (to.angle - from.angle).abs();
    (bound * TRAVEL_ROUNDING_UP + 1e-30) as f32
}

/// The factor that lifts a travel bound above the rounding to single precision: 1 + 2⁻²².
const TRAVEL_ROUNDING_UP: f64 = 1.0 + 1.0 / (1u64 << 22) as f64;

/// Heap bytes of a `Vec`'s buffer: capacity times element size.
pub(crate) fn vec_bytes<T>(v: &Vec<T>) -> usize {
    v.capacity() * std::mem::size_of::<T>()
}

/// Per-body columns the predictor and corrector update (Gear state, pose, velocities, travel) and read (kind,
/// liveness, reach), one slice each over the same bodies.
pub(crate) struct KinematicsColumns<'a> {
    pub gear: &'a mut [GearState],
    pub pose: &'a mut [Pose],
    pub velocity: &'a mut [DVec2],
    pub angular_velocity: &'a mut [f64],
    pub travel: &'a mut [f32],
    pub kind: &'a [BodyKind],
    pub alive: &'a [bool],
    pub reach: &'a [f64],
}

impl<'a> KinematicsColumns<'a> {
    /// Number of bodies.
    pub fn len(&self) -> usize {
        self.gear.len()
    }

    /// The columns cut into ranges of `per_range` bodies (the last one shorter), in body order; one empty range
    /// where there are no bodies.
    pub fn ranges(self, per_range: usize) -> impl Iterator<Item = Self> {
        let mut rest = Some(self);
        std::iter::from_fn(move || {
            let columns = rest.take()?;
            if columns.len() <= per_range {
                return Some(columns);
            }
            let (range, others) = columns.split_at(per_range);
            rest = Some(others);
            Some(range)
        })
    }

    /// The first `mid` bodies and the rest.
    fn split_at(self, mid: usize) -> (Self, Self) {
        let (gear, gear_rest) = self.gear.split_at_mut(mid);
        let (pose, pose_rest) = self.pose.split_at_mut(mid);
        let (velocity, velocity_rest) = self.velocity.split_at_mut(mid);
        let (angular_velocity, angular_velocity_rest) = self.angular_velocity.split_at_mut(mid);
        let (travel, travel_rest) = self.travel.split_at_mut(mid);
        let (kind, kind_rest) = self.kind.split_at(mid);
        let (alive, alive_rest) = self.alive.split_at(mid);
        let (reach, reach_rest) = self.reach.split_at(mid);
        (
            Self { gear, pose, velocity, angular_velocity, travel, kind, alive, reach },
            Self {
                gear: gear_rest,
                pose: pose_rest,
                velocity: velocity_rest,
                angular_velocity: angular_velocity_rest,
                travel: travel_rest,
                kind: kind_rest,
                alive: alive_rest,
                reach: reach_rest,
            },
        )
    }
}

/// Per-body columns of the forces on the bodies (written by the force accumulation and the body forces) and what
/// turns them into accelerations (read by gravity and the corrector), one slice each over the same bodies.
pub(crate) struct ForceColumns<'a> {
    pub force: &'a mut [DVec2],
    pub torque: &'a mut [f64],
    pub mass: &'a [f64],
    pub inverse_mass: &'a [f64],
    pub inverse_inertia: &'a [f64],
}

/// The columns of [`Bodies::split_for_integration`]: the kinematics, the forces, and the inscribed radii that the
/// closing pass's travel check reads where it runs in the corrector's pass.
pub(crate) struct IntegrationColumns<'a> {
    pub kinematics: KinematicsColumns<'a>,
    pub forces: ForceColumns<'a>,
    /// Each body's inscribed radius at scale 1, m.
    pub inscribed_radius: &'a [f64],
}

/// Every column the passes of a step over the bodies write or read, borrowed apart ([`Bodies::split_for_step`]).
struct StepColumns<'a> {
    kinematics: KinematicsColumns<'a>,
    forces: ForceColumns<'a>,
    transform: TransformInputs<'a>,
    world_vertices: &'a mut [DVec2],
    inscribed_radius: &'a [f64],
}

/// The columns [`transform_range`] reads besides the poses, over all bodies.
struct TransformInputs<'a> {
    ranges: &'a [VertexRange],
    body: &'a [DVec2],
    alive: &'a [bool],
    radius: &'a [f64],
}

/// Transforms bodies `first..last`, whose poses are `poses`; `world` starts at body `first`'s first vertex, `boxes`
/// at body `first`.
fn transform_range(
    first: usize,
    last: usize,
    inputs: &TransformInputs,
    poses: &[Pose],
    world: &mut [DVec2],
    mut boxes: BoxWriter,
) {
    let ranges = inputs.ranges;
    let offset = if first < ranges.len() { ranges[first].start as usize } else { 0 };
    for (slot, i) in (first..last).enumerate() {
        if !inputs.alive[i] {
            continue;
        }
        let r = ranges[i].range();
        let local = r.start - offset..r.end - offset;
        let pose = &poses[slot];
        let tight = pose.transform_into(&inputs.body[r], &mut world[local]);
        boxes.set(slot, &body_aabb(tight, inputs.radius[i] * pose.scale));
    }
}
