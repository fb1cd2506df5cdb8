//! The broadphase's per-body table: state flags and the current box of every body slot.
//!
//! Boxes are kept per axis as compact (lower, upper) intervals, so the sort, which reads one axis of bodies in
//! scattered order, touches 16 bytes per body rather than a whole record. The box of the previous update is not
//! kept (32 bytes per body): the sort's removals are checked against the pair list instead (`sink`).

use crate::bodies::{BodyKind, vec_bytes};
use gc2d_geometry::Aabb;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Slots one task of [`Bodies::advance`] takes at least; below twice this the boxes are copied on one thread.
const SLOTS_PER_TASK: usize = 4096;

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

/// Where the vertex transform writes the bodies' new boxes for the next update, straight into the broadphase's
/// intervals (the bodies keep no box column of their own: 32 bytes per body less). It covers a run of body slots
/// and splits like a slice, so parallel tasks write disjoint runs. Get one from
/// [`SortAndSweep::box_writer`](super::SortAndSweep::box_writer).
pub struct BoxWriter<'a> {
    x: &'a mut [Interval],
    y: &'a mut [Interval],
}

impl BoxWriter<'_> {
    /// Number of body slots covered.
    #[inline]
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// True when no slot is covered.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// The writers of slots `..mid` and `mid..` of this one (indices restart at 0 in the second).
    #[inline]
    pub fn split_at(self, mid: usize) -> (Self, Self) {
        let (x_low, x_high) = self.x.split_at_mut(mid);
        let (y_low, y_high) = self.y.split_at_mut(mid);
        (BoxWriter { x: x_low, y: y_low }, BoxWriter { x: x_high, y: y_high })
    }

    /// Sets the box of slot `index` (of this writer's run); NaN bounds are made safe to sort as at insertion.
    #[inline]
    pub fn set(&mut self, index: usize, aabb: &Aabb) {
        self.x[index] = Interval::sanitised(aabb.min.x, aabb.max.x);
        self.y[index] = Interval::sanitised(aabb.min.y, aabb.max.y);
    }
}

/// All body slots, indexed by body id.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub(super) struct Bodies {
    flags: Vec<Flags>,
    /// The box of the current update, x and y (for bodies inserted since, their first box).
    current: [Vec<Interval>; 2],
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
        self.current.iter_mut().for_each(Vec::shrink_to_fit);
    }

    /// Heap bytes of the flags and the intervals, from their capacities.
    pub(super) fn heap_bytes(&self) -> usize {
        vec_bytes(&self.flags) + self.current.iter().map(vec_bytes).sum::<usize>()
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

    /// Grows the table to `len` slots; the new ones are absent.
    fn grow_to(&mut self, len: usize) {
        if len > self.flags.len() {
            let absent = Flags { state: SlotState::Absent, kind: BodyKind::Particle, fresh: false };
            self.flags.resize(len, absent);
            for axis in &mut self.current {
                axis.resize(len, Interval::default());
            }
        }
    }

    /// Makes `body` a pending slot of `kind` with box `aabb`, growing the table.
    pub(super) fn make_pending(&mut self, body: u32, kind: BodyKind, aabb: &Aabb) {
        let index = body as usize;
        self.grow_to(index + 1);
        self.flags[index] = Flags { state: SlotState::Pending, kind, fresh: false };
        for (axis, intervals) in self.current.iter_mut().enumerate() {
            intervals[index] = Interval::sanitised(aabb.min[axis], aabb.max[axis]);
        }
    }

    /// A writer for the boxes of slots `0..len` (the table grows to `len` slots if it is shorter).
    pub(super) fn box_writer(&mut self, len: usize) -> BoxWriter<'_> {
        self.grow_to(len);
        let [x, y] = &mut self.current;
        BoxWriter { x: &mut x[..len], y: &mut y[..len] }
    }

    /// Bodies covered by `aabbs` take their new box, the others keep theirs.
    pub(super) fn take_boxes(&mut self, aabbs: &[Aabb]) {
        let flags = &self.flags;
        for (axis, current) in self.current.iter_mut().enumerate() {
            let take = |(index, (current, aabb)): (usize, (&mut Interval, &Aabb))| {
                if flags[index].state != SlotState::Absent {
                    *current = Interval::sanitised(aabb.min[axis], aabb.max[axis]);
                }
            };
            if current.len().min(aabbs.len()) >= 2 * SLOTS_PER_TASK {
                current.par_iter_mut().zip(aabbs).enumerate().with_min_len(SLOTS_PER_TASK).for_each(take);
            } else {
                current.iter_mut().zip(aabbs).enumerate().for_each(take);
            }
        }
    }

    /// The largest width and height of a dynamic body's box (0 when there is none), which bounds how far before a
    /// query box a meeting box can begin (`box_query`). The maximum ignores NaN widths (from infinite boxes) in any
    /// order, so it is the same on any thread count.
    pub(super) fn dynamic_extent(&self) -> [f64; 2] {
        let flags = &self.flags;
        [0, 1].map(|axis| {
            let width = |(index, interval): (usize, &Interval)| {
                let f = flags[index];
                let measured = f.state != SlotState::Absent && f.kind == BodyKind::Particle;
                if measured { interval.upper - interval.lower } else { 0.0 }
            };
            let current = &self.current[axis];
            if current.len() >= 2 * SLOTS_PER_TASK {
                current.par_iter().enumerate().with_min_len(SLOTS_PER_TASK).map(width).reduce(|| 0.0, f64::max)
            } else {
                current.iter().enumerate().map(width).fold(0.0, f64::max)
            }
        })
    }

    /// Whether `body` moves; the kind it was inserted with.
    #[inline]
    pub(super) fn kind(&self, body: u32) -> BodyKind {
        self.flags[body as usize].kind
    }

    /// The static slots in the broadphase (pending or active), in id order.
    pub(super) fn static_slots(&self) -> Vec<u32> {
        let is_static = |f: &Flags| f.kind == BodyKind::Wall && f.state != SlotState::Absent;
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
        (self.flags[a].kind == BodyKind::Particle || self.flags[b].kind == BodyKind::Particle)
            && self.current[0][a].meets(self.current[0][b])
            && self.current[1][a].meets(self.current[1][b])
    }

    /// True when the current intervals of `a` and `b` on `axis` overlap or touch.
    #[inline]
    pub(super) fn meet_on(&self, axis: usize, a: u32, b: u32) -> bool {
        self.current[axis][a as usize].meets(self.current[axis][b as usize])
    }

    /// True when the current box of `body` meets (overlaps or touches) the box `query` (x and y intervals).
    #[inline]
    pub(super) fn box_meets(&self, body: u32, query: [Interval; 2]) -> bool {
        let index = body as usize;
        self.current[0][index].meets(query[0]) && self.current[1][index].meets(query[1])
    }
}
