//! The broadphase's per-body table: state flags and the current and previous box of every body slot.
//!
//! Boxes are kept per axis as compact (lower, upper) intervals, so the sort, which reads one axis of bodies in
//! scattered order, touches 16 bytes per body rather than a whole record.

use crate::bodies::vec_bytes;
use gc2d_geometry::Aabb;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Slots one task of [`Bodies::advance`] takes at least; below twice this the boxes are copied on one thread.
const SLOTS_PER_TASK: usize = 4096;

/// Whether a body moves. Two static bodies (walls) are never paired: their contact would exert no force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum BodyKind {
    /// A free particle.
    Dynamic,
    /// A wall: immovable or moved by a prescribed motion.
    Static,
}

/// Where a body slot stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub(super) enum SlotState {
    /// Not in the broadphase.
    Absent,
    /// Inserted; merged into the axes at the next update.
    Pending,
    /// In the axes.
    Active,
}

/// The flags of one body slot.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
struct Flags {
    state: SlotState,
    kind: BodyKind,
    /// Set while a newly merged body looks for its first pairs.
    fresh: bool,
}

/// One axis of a box, with `lower <= upper` and neither NaN.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
pub(super) struct Interval {
    pub(super) lower: f64,
    pub(super) upper: f64,
}

impl Interval {
    /// The interval of `min..max`, made safe to sort: a NaN lower bound becomes +∞, and an upper bound that is NaN
    /// or below the lower bound becomes the lower bound.
    pub(super) fn sanitised(min: f64, max: f64) -> Self {
        let lower = if min.is_nan() { f64::INFINITY } else { min };
        Self { lower, upper: if max >= lower { max } else { lower } }
    }

    /// Overlapping or touching.
    #[inline]
    fn meets(self, other: Interval) -> bool {
        self.lower <= other.upper && other.lower <= self.upper
    }
}

/// All body slots, indexed by body id.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub(super) struct Bodies {
    flags: Vec<Flags>,
    /// The box of the current update, x and y.
    current: [Vec<Interval>; 2],
    /// The box of the previous update (for bodies merged since, their first box).
    previous: [Vec<Interval>; 2],
}

impl Bodies {
    /// Number of slots (the largest id ever inserted plus one).
    #[inline]
    pub(super) fn len(&self) -> usize {
        self.flags.len()
    }

    /// Gives back the spare room of the flags and intervals.
    pub(super) fn shrink_to_fit(&mut self) {
        self.flags.shrink_to_fit();
        self.current.iter_mut().chain(&mut self.previous).for_each(Vec::shrink_to_fit);
    }

    /// Heap bytes of the flags and the current and previous intervals, from their capacities.
    pub(super) fn heap_bytes(&self) -> usize {
        vec_bytes(&self.flags) + self.current.iter().chain(&self.previous).map(vec_bytes).sum::<usize>()
    }

    /// The state of `body`; ids beyond the table are absent.
    #[inline]
    pub(super) fn state(&self, body: u32) -> SlotState {
        self.flags.get(body as usize).map_or(SlotState::Absent, |f| f.state)
    }

    #[inline]
    pub(super) fn set_state(&mut self, body: u32, state: SlotState) {
        self.flags[body as usize].state = state;
    }

    #[inline]
    pub(super) fn is_fresh(&self, body: u32) -> bool {
        self.flags[body as usize].fresh
    }

    #[inline]
    pub(super) fn set_fresh(&mut self, body: u32, fresh: bool) {
        self.flags[body as usize].fresh = fresh;
    }

    /// Makes `body` a pending slot of `kind` with box `aabb` (as current and previous box), growing the table.
    pub(super) fn make_pending(&mut self, body: u32, kind: BodyKind, aabb: &Aabb) {
        let index = body as usize;
        if index >= self.flags.len() {
            let absent = Flags { state: SlotState::Absent, kind: BodyKind::Dynamic, fresh: false };
            self.flags.resize(index + 1, absent);
            for axis in 0..2 {
                self.current[axis].resize(index + 1, Interval::default());
                self.previous[axis].resize(index + 1, Interval::default());
            }
        }
        self.flags[index] = Flags { state: SlotState::Pending, kind, fresh: false };
        for axis in 0..2 {
            let interval = Interval::sanitised(aabb.min[axis], aabb.max[axis]);
            self.current[axis][index] = interval;
            self.previous[axis][index] = interval;
        }
    }

    /// Starts an update: every box becomes the previous box, and bodies covered by `aabbs` take their new box.
    /// With `MEASURE_EXTENT`, returns the largest width and height of a dynamic body's new box (0 when there is
    /// none), which bounds how far before a query box a meeting box can begin (`box_query`): measured here, in the
    /// pass that reads every box anyway, so that a query needs no pass of its own. Without, returns +∞ (unknown).
    pub(super) fn advance<const MEASURE_EXTENT: bool>(&mut self, aabbs: &[Aabb]) -> [f64; 2] {
        std::mem::swap(&mut self.current, &mut self.previous);
        let mut extent = [f64::INFINITY; 2];
        for (axis, extent) in extent.iter_mut().enumerate() {
            let flags = &self.flags;
            // The new interval of slot `index`, and its width where it is measured (0 where not).
            let refresh = |(index, (current, previous)): (usize, (&mut Interval, &Interval))| {
                let f = flags[index];
                match aabbs.get(index) {
                    Some(aabb) if f.state != SlotState::Absent => {
                        *current = Interval::sanitised(aabb.min[axis], aabb.max[axis]);
                        if MEASURE_EXTENT && f.kind == BodyKind::Dynamic { current.upper - current.lower } else { 0.0 }
                    }
                    _ => {
                        *current = *previous;
                        0.0
                    }
                }
            };
            let (current, previous) = (&mut self.current[axis], &self.previous[axis]);
            // The maximum ignores NaN widths (from infinite boxes) in any order, so it is the same on any thread count.
            let widest = if current.len() >= 2 * SLOTS_PER_TASK {
                let slots = current.par_iter_mut().zip(previous.par_iter()).enumerate().with_min_len(SLOTS_PER_TASK);
                slots.map(refresh).reduce(|| 0.0, f64::max)
            } else {
                current.iter_mut().zip(previous).enumerate().map(refresh).fold(0.0, f64::max)
            };
            if MEASURE_EXTENT {
                *extent = widest;
            }
        }
        extent
    }

    /// Whether `body` moves; the kind it was inserted with.
    #[inline]
    pub(super) fn kind(&self, body: u32) -> BodyKind {
        self.flags[body as usize].kind
    }

    /// The static slots in the broadphase (pending or active), in id order.
    pub(super) fn static_slots(&self) -> Vec<u32> {
        let is_static = |f: &Flags| f.kind == BodyKind::Static && f.state != SlotState::Absent;
        (0..self.flags.len() as u32).filter(|&body| is_static(&self.flags[body as usize])).collect()
    }

    /// The current interval of `body` on `axis`.
    #[inline]
    pub(super) fn interval(&self, axis: usize, body: u32) -> Interval {
        self.current[axis][body as usize]
    }

    /// The current intervals of all bodies on `axis`.
    #[inline]
    pub(super) fn intervals(&self, axis: usize) -> &[Interval] {
        &self.current[axis]
    }

    /// True when the pair may exist: not two static bodies, and the current boxes overlap or touch.
    #[inline]
    pub(super) fn may_pair(&self, a: u32, b: u32) -> bool {
        let (a, b) = (a as usize, b as usize);
        (self.flags[a].kind == BodyKind::Dynamic || self.flags[b].kind == BodyKind::Dynamic)
            && self.current[0][a].meets(self.current[0][b])
            && self.current[1][a].meets(self.current[1][b])
    }

    /// True when the current box of `body` meets (overlaps or touches) the box `query` (x and y intervals).
    #[inline]
    pub(super) fn box_meets(&self, body: u32, query: [Interval; 2]) -> bool {
        let index = body as usize;
        self.current[0][index].meets(query[0]) && self.current[1][index].meets(query[1])
    }

    /// True when the pair could have existed before this update: the previous boxes overlapped or touched.
    #[inline]
    pub(super) fn met_before(&self, a: u32, b: u32) -> bool {
        let (a, b) = (a as usize, b as usize);
        self.previous[0][a].meets(self.previous[0][b]) && self.previous[1][a].meets(self.previous[1][b])
    }
}
