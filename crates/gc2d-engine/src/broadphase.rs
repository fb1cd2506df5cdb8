//! Incremental sort-and-sweep on both axes with a persistent pair list (reference §4.2, Tables 2.1–2.3; §10.1 item 12).
//!
//! Each axis keeps the begin and end values of every bounding box in one array, sorted by a strict total order
//! (value, then begins before ends, then body id). Every step the arrays are re-sorted by insertion sort, which is
//! O(N + swaps) and O(N) for the nearly sorted input of a time-stepped simulation. Every adjacent swap is one of the
//! four cases of Table 2.3; only two change the pair list:
//!
//! | swap | meaning | action |
//! |---|---|---|
//! | e_m b_n ⇒ b_n e_m | the intervals start to overlap on this axis | add (m, n) if the boxes now touch |
//! | b_m e_n ⇒ e_n b_m | the intervals stop overlapping on this axis | remove (m, n) if present |
//!
//! Because begins sort before ends at equal values, touching boxes count as overlapping, exactly as in
//! [`Aabb::overlaps`]. The pair list is therefore always exactly the set of touching-or-overlapping box pairs (minus
//! static–static pairs). The proof and the tie rules are in `docs/model.md`, "Broadphase (§4.2)".
//!
//! **The two axes are sorted in parallel, the pair list changed after** (the thesis ran the two sweeps on two threads,
//! §4.5, with a lock on the list): if both sorts wrote the one pair list as they swap, the order in which the two
//! threads reached it would decide the order of the list, so the pair order, and with it the narrowphase's summation
//! order, would change from run to run. Instead each sort only records the changes its swaps call for (the tests of
//! Table 2.3 read the boxes alone, never the list), and the changes are applied afterwards, the x axis's first, each
//! in the order found: the same sequence of insertions and removals as sorting x and then y with the list changed at
//! once, so the list is a pure function of the input and the same for any thread count.
//!
//! **In a scene much wider than high the y axis is split into bands of x** (`broadphase::bands`, docs/model.md "The y
//! axis in bands of x"): one y axis over the whole width would make every grain swap with endpoints across the whole
//! width.
//!
//! Bodies are inserted and removed at any time (drop sources, particles leaving the domain). Insertions are merged at
//! the next [`SortAndSweep::update`]: their endpoints are sorted (O(k log k)), merged into the axes in one pass, and
//! their pairs found with one sweep, so building the first state of N bodies costs O(N log N), never N² swaps.

mod bands;
mod bodies;
mod box_query;
mod pair_set;
mod segments;

pub use bodies::BoxWriter;
pub use pair_set::PairEntry;

use crate::bodies::{BodyKind, vec_bytes};
use crate::parallel::steps_in_parallel;
use bands::YBands;
use bodies::{Bodies, Interval, SlotState};
use box_query::PendingIndex;
use gc2d_geometry::Aabb;
use pair_set::PairSet;
use rayon::prelude::*;
use segments::{ENDPOINTS_PER_SEGMENT, SegmentedSort};
use serde::{Deserialize, Serialize};
use std::cmp::Ordering;

/// The largest body id plus one: one bit of an endpoint's key says whether it is a begin or an end.
pub const MAX_BODIES: u32 = 1 << 31;

/// Why a body could not be inserted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum BroadphaseError {
    /// The id is already in the broadphase (inserted and not removed since).
    #[error("body {0} is already in the broadphase")]
    AlreadyInserted(u32),
    /// The id does not fit the endpoint key.
    #[error("body id {0} exceeds the broadphase limit of 2^31 - 1")]
    IdTooLarge(u32),
}

/// Counters of one [`SortAndSweep::update`], for the statistics the engine logs.
///
/// Removals made with [`SortAndSweep::remove`] are counted in the next update's counters.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct BroadphaseStats {
    /// Adjacent swaps performed by the insertion sorts of both axes.
    pub swaps: u64,
    /// Pairs created.
    pub pairs_added: usize,
    /// Pairs ended, by separation or by removal of a body.
    pub pairs_removed: usize,
    /// Bodies merged into the axes.
    pub bodies_inserted: usize,
    /// Bodies removed.
    pub bodies_removed: usize,
}

/// Bit of [`Endpoint::key`] that marks an end value.
const END_BIT: u32 = 1 << 31;

/// One bound of one body's interval on one axis.
///
/// Packed to 12 bytes (4-byte aligned) instead of 16: the two axes hold four endpoints per body, so this is 16 bytes
/// per body less. The fields are only ever read and written by value, which the compiler does with unaligned loads
/// and stores: about 12 instructions per particle-step more in the sort, no measurable time (docs/performance.md,
/// "One box per body").
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[repr(C, packed(4))]
struct Endpoint {
    value: f64,
    /// Body id, with [`END_BIT`] set for an end. Comparing keys puts begins before ends, then orders by body.
    key: u32,
}

impl Endpoint {
    fn begin(body: u32, value: f64) -> Self {
        Self { value, key: body }
    }

    fn end(body: u32, value: f64) -> Self {
        Self { value, key: body | END_BIT }
    }

    #[inline]
    fn body(self) -> u32 {
        self.key & !END_BIT
    }

    #[inline]
    fn is_end(self) -> bool {
        self.key & END_BIT != 0
    }

    /// Sets the value to the body's bound in `intervals` (by body id): its lower bound for a begin, upper for an end.
    #[inline]
    fn refresh(&mut self, intervals: &[Interval]) {
        let interval = intervals[self.body() as usize];
        self.value = if self.is_end() { interval.upper } else { interval.lower };
    }

    /// The strict total order of the axis: value, then begin before end, then body id. Values are never NaN.
    #[inline]
    fn precedes(self, other: Endpoint) -> bool {
        self.value < other.value || (self.value == other.value && self.key < other.key)
    }

    /// [`precedes`](Self::precedes) as an `Ordering`, for `sort_unstable_by` (so −0.0 and +0.0 tie, as they do there).
    fn order(a: &Endpoint, b: &Endpoint) -> Ordering {
        if a.precedes(*b) {
            Ordering::Less
        } else if b.precedes(*a) {
            Ordering::Greater
        } else {
            Ordering::Equal
        }
    }
}

/// The incremental sort-and-sweep broadphase with a pair list carrying one `T` per pair.
///
/// Body ids are the engine's dense slots. Usage per step: [`update`](Self::update) with every body's box, then run
/// the narrowphase over [`pairs_mut`](Self::pairs_mut) (each pair writes only its own payload, so `par_iter_mut` is
/// safe), and read [`ended_pairs`](Self::ended_pairs) for the contacts that ended. Once the buffers have grown to the
/// scene's size, `update` does not allocate.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct SortAndSweep<T> {
    bodies: Bodies,
    /// Sorted endpoints of the x axis (index 0) and the y axis (index 1; empty where `bands` holds the y axis).
    axes: [Vec<Endpoint>; 2],
    /// The y axis split into bands of x, in a scene much wider than high (`broadphase::bands`); `None`: one y axis.
    bands: Option<YBands>,
    /// Bodies inserted since the last update, in insertion order.
    pending: Vec<u32>,
    /// Whether removed bodies still have endpoints in the axes.
    has_removed_endpoints: bool,
    pairs: PairSet<T>,
    /// Pairs reported by the last update (the first `reported`), then pairs ended by `remove` since.
    ended: Vec<PairEntry<T>>,
    reported: usize,
    stats: BroadphaseStats,
    /// Counters of `remove` calls since the last update.
    carried: BroadphaseStats,
    /// The static bodies in the broadphase (active or pending), for [`box_query`]; `None` until the first update
    /// after loading a checkpoint rebuilds it.
    #[serde(skip)]
    static_bodies: Option<Vec<u32>>,
    /// Largest width (x) and height (y) of a dynamic body's box at the last update, for [`box_query`]; +∞ until
    /// the first update after loading a checkpoint measures it.
    #[serde(skip, default = "box_query::unmeasured_extent")]
    dynamic_extent: [f64; 2],
    /// The dynamic bodies of `pending` ordered for [`box_query`]; `None` after loading a checkpoint until the next
    /// update has merged the pending bodies it held (a query then looks at each of them).
    #[serde(skip)]
    pending_index: Option<PendingIndex>,
    /// Scratch: the sorted endpoints of the bodies being merged.
    #[serde(skip)]
    merge_buffer: Vec<Endpoint>,
    /// Scratch for the sweep that finds new bodies' pairs.
    #[serde(skip)]
    sweep: SweepScratch,
    /// Scratch of each axis's sort, with the pair-list changes it found in the current update.
    #[serde(skip)]
    sorts: [SegmentedSort; 2],
}

/// A change of the pair list that a swap of the insertion sort calls for (Table 2.3), recorded by the sort and applied
/// after both axes are sorted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum PairChange {
    /// The boxes of the two bodies now touch: add the pair if it is not listed yet.
    Add(u32, u32),
    /// The intervals stopped overlapping on one axis: end the pair if it is listed.
    Remove(u32, u32),
}

impl<T: Default> Default for SortAndSweep<T> {
    fn default() -> Self {
        Self {
            bodies: Bodies::default(),
            axes: [Vec::new(), Vec::new()],
            bands: None,
            pending: Vec::new(),
            has_removed_endpoints: false,
            pairs: PairSet::default(),
            ended: Vec::new(),
            reported: 0,
            stats: BroadphaseStats::default(),
            carried: BroadphaseStats::default(),
            static_bodies: None,
            dynamic_extent: box_query::unmeasured_extent(),
            pending_index: Some(PendingIndex::default()),
            merge_buffer: Vec::new(),
            sweep: SweepScratch::default(),
            sorts: Default::default(),
        }
    }
}

impl<T: Default + Send> SortAndSweep<T> {
    /// An empty broadphase.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds `body` with its box. It joins the axes, and gets its pairs, at the next [`update`](Self::update), which
    /// also replaces the box given here if its slice covers `body`. Two walls are never paired: their contact would
    /// exert no force.
    pub fn insert(&mut self, body: u32, aabb: Aabb, kind: BodyKind) -> Result<(), BroadphaseError> {
        if body >= MAX_BODIES {
            return Err(BroadphaseError::IdTooLarge(body));
        }
        if self.bodies.state(body) != SlotState::Absent {
            return Err(BroadphaseError::AlreadyInserted(body));
        }
        self.bodies.make_pending(body, kind, &aabb);
        self.pending.push(body);
        match (kind, &mut self.static_bodies, &mut self.pending_index) {
            (BodyKind::Wall, Some(statics), _) => statics.push(body),
            (BodyKind::Particle, _, Some(index)) => index.insert(body, self.bodies.interval(0, body)),
            _ => {}
        }
        Ok(())
    }

    /// Removes `body` and ends all its pairs at once; they appear in the next update's
    /// [`ended_pairs`](Self::ended_pairs). Returns false if the body was not in the broadphase. The id may be
    /// inserted again right away.
    pub fn remove(&mut self, body: u32) -> bool {
        let state = self.bodies.state(body);
        if state == SlotState::Absent {
            return false;
        }
        if let (BodyKind::Wall, Some(statics)) = (self.bodies.kind(body), &mut self.static_bodies) {
            statics.retain(|&s| s != body);
        }
        match state {
            SlotState::Absent => {}
            SlotState::Pending => {
                self.pending.retain(|&p| p != body);
                if let Some(index) = &mut self.pending_index {
                    index.remove(body, self.bodies.interval(0, body));
                }
            }
            SlotState::Active => {
                self.carried.pairs_removed += self.pairs.remove_body(body, &mut self.ended);
                self.has_removed_endpoints = true;
            }
        }
        self.bodies.set_state(body, SlotState::Absent);
        self.carried.bodies_removed += 1;
        true
    }

    /// Moves every body to its new box (`aabbs[body]`; ids not in the broadphase are ignored, bodies beyond the slice
    /// keep their last box), re-sorts both axes, merges inserted bodies, and corrects the pair list.
    ///
    /// Box queries ([`any_box_meeting`](Self::any_box_meeting)) after this update walk a whole axis; use
    /// [`update_for_queries`](Self::update_for_queries) where they will be asked.
    pub fn update(&mut self, aabbs: &[Aabb]) {
        self.bodies.take_boxes(aabbs);
        self.update_measuring::<false>();
    }

    /// [`update`](Self::update), also measuring the widest dynamic box, which lets the box queries asked before the
    /// next update look at the bodies near the query box only. The measurement is one more pass over the boxes, so
    /// the engine asks for it only in steps of worlds with sources or inlets.
    pub fn update_for_queries(&mut self, aabbs: &[Aabb]) {
        self.bodies.take_boxes(aabbs);
        self.update_measuring::<true>();
    }

    /// A writer for the new boxes of body slots `0..len`, for a caller that computes the boxes itself (the engine's
    /// vertex transform): it writes them in place, with no box column of its own, then calls
    /// [`update_written`](Self::update_written). Slots it leaves alone keep their box. Between the writing and
    /// that update the broadphase holds the new boxes but the old order, so box queries wait for the update.
    pub fn box_writer(&mut self, len: usize) -> BoxWriter<'_> {
        self.bodies.box_writer(len)
    }

    /// [`update`](Self::update) with the boxes written through [`box_writer`](Self::box_writer) since the last one.
    pub fn update_written(&mut self) {
        self.update_measuring::<false>();
    }

    /// [`update_for_queries`](Self::update_for_queries) with the boxes written through
    /// [`box_writer`](Self::box_writer) since the last one.
    pub fn update_written_for_queries(&mut self) {
        self.update_measuring::<true>();
    }

    fn update_measuring<const MEASURE_EXTENT: bool>(&mut self) {
        self.ended.drain(..self.reported);
        self.stats = std::mem::take(&mut self.carried);
        if self.has_removed_endpoints {
            let bodies = &self.bodies;
            for axis in &mut self.axes {
                axis.retain(|e| bodies.state(e.body()) == SlotState::Active);
            }
            if let Some(bands) = &mut self.bands {
                bands.retain_active(bodies);
            }
            self.has_removed_endpoints = false;
        }
        self.dynamic_extent =
            if MEASURE_EXTENT { self.bodies.dynamic_extent() } else { box_query::unmeasured_extent() };
        if self.static_bodies.is_none() {
            self.static_bodies = Some(self.bodies.static_slots());
        }
        self.sort_axes();
        if !self.pending.is_empty() {
            self.merge_pending();
        }
        self.pairs.sort_if_disordered();
        self.reported = self.ended.len();
    }

    /// The current pairs: exactly the touching-or-overlapping box pairs that are not both static.
    #[inline]
    pub fn pairs(&self) -> &[PairEntry<T>] {
        self.pairs.entries()
    }

    /// The current pairs with mutable payloads, for the narrowphase.
    #[inline]
    pub fn pairs_mut(&mut self) -> &mut [PairEntry<T>] {
        self.pairs.entries_mut()
    }

    /// The record of the pair {a, b}, if their boxes touch.
    pub fn payload(&self, a: u32, b: u32) -> Option<&T> {
        self.pairs.get(a, b).map(|e| &e.payload)
    }

    /// The record of the pair {a, b}, mutable (e.g. to restore contact history at a restart).
    pub fn payload_mut(&mut self, a: u32, b: u32) -> Option<&mut T> {
        self.pairs.get_mut(a, b).map(|e| &mut e.payload)
    }

    /// The pairs that ended since the previous update, with their last payloads: those of bodies removed before
    /// this update, then those that separated in it. Each ended pair is reported by exactly one update.
    pub fn ended_pairs(&self) -> &[PairEntry<T>] {
        &self.ended[..self.reported]
    }

    /// Counters of the last update.
    pub fn stats(&self) -> &BroadphaseStats {
        &self.stats
    }

    /// Gives back the spare room of the sorted axes, the boxes and flags, and the pair list's entries. The scratch
    /// buffers keep theirs, which the next update would otherwise allocate again.
    pub fn shrink_to_fit(&mut self) {
        self.axes.iter_mut().for_each(Vec::shrink_to_fit);
        if let Some(bands) = &mut self.bands {
            bands.shrink_to_fit();
        }
        self.bodies.shrink_to_fit();
        self.pairs.shrink_to_fit();
    }

    /// Heap memory held by the broadphase, in bytes, counted from the capacities of its buffers: the sorted axes,
    /// the per-body boxes and flags, the pair list with its index table and payloads, the wall list, the entries of
    /// the index of bodies inserted since the last update, and the scratch buffers.
    pub fn heap_bytes(&self) -> usize {
        self.axes.iter().map(vec_bytes).sum::<usize>()
            + self.bands.as_ref().map_or(0, YBands::heap_bytes)
            + vec_bytes(&self.pending)
            + self.static_bodies.as_ref().map_or(0, vec_bytes)
            + self.pending_index.as_ref().map_or(0, PendingIndex::heap_bytes)
            + self.bodies.heap_bytes()
            + self.pairs.heap_bytes()
            + vec_bytes(&self.ended)
            + vec_bytes(&self.merge_buffer)
            + vec_bytes(&self.sweep.open)
            + vec_bytes(&self.sweep.open_fresh)
            + vec_bytes(&self.sweep.position)
            + self.sorts.iter().map(SegmentedSort::heap_bytes).sum::<usize>()
    }

    /// True if `body` is in the broadphase (active or waiting for the next update).
    pub fn contains(&self, body: u32) -> bool {
        self.bodies.state(body) != SlotState::Absent
    }

    /// Splits the y axis into bands of x where the dynamic bodies (active or pending) span at least four bands 64
    /// widest dynamic boxes wide (`broadphase::bands`, docs/model.md "The y axis in bands of x": in a scene much wider
    /// than high the single y axis costs time per body that grows with the width). Returns whether the y axis is in
    /// bands; a broadphase already in bands, or one too narrow, is left as it is. The engine asks once, before its
    /// first step; the bands stay for the life of the broadphase and change the order in which pairs are found, never
    /// which pairs there are.
    pub fn band_y_axis_if_wide(&mut self) -> bool {
        self.band_y_axis_by(YBands::for_wide_scene)
    }

    /// Splits the y axis into bands `width` wide over the x extent of the dynamic bodies (at most 65,536 of them;
    /// see [`band_y_axis_if_wide`](Self::band_y_axis_if_wide)). Returns whether the y axis is in bands now; an
    /// extent narrower than two bands keeps one axis.
    pub fn band_y_axis(&mut self, width: f64) -> bool {
        self.band_y_axis_by(|bodies, y_axis| YBands::with_width(bodies, y_axis, width))
    }

    /// The number of bands of the y axis: 1 where it is one axis.
    pub fn y_bands(&self) -> usize {
        self.bands.as_ref().map_or(1, YBands::count)
    }

    /// Splits the one y axis into the bands `choose` makes of it, if it makes any, and frees the axis; a broadphase
    /// already in bands is left as it is. Returns whether the y axis is in bands.
    fn band_y_axis_by(&mut self, choose: impl FnOnce(&Bodies, &[Endpoint]) -> Option<YBands>) -> bool {
        if self.bands.is_none() {
            self.bands = choose(&self.bodies, &self.axes[1]);
            if self.bands.is_some() {
                self.axes[1] = Vec::new();
            }
        }
        self.bands.is_some()
    }

    /// Re-sorts both axes (each on its own thread where the World steps in parallel, a long axis in segments:
    /// `broadphase::segments`), then applies the pair-list changes their swaps found: the x axis's, then the y axis's,
    /// each in the order one insertion sort finds them (with bands: each band's in band order, then the rechecks of the
    /// bodies that changed bands, `bands`), so the list is the same whichever thread sorted what.
    fn sort_axes(&mut self) {
        let bodies = &self.bodies;
        let ([x, y], [x_sort, y_sort]) = (&mut self.axes, &mut self.sorts);
        let (x_swaps, y_swaps) = match &mut self.bands {
            Some(bands) => rayon::join(|| x_sort.sort(x, 0, bodies), || bands.sort(bodies)),
            // From 512 bodies on, not only from the 8,192 endpoints of a segmented axis: sorting y beside x gives
            // the second thread a share of the update instead of leaving it idle until the narrowphase (two threads:
            // squares 3,200 and dense7 2,000 2–4 % faster, docs/performance.md "The predictor and corrector of small
            // Worlds in two").
            None if steps_in_parallel(x.len() / 2) => {
                rayon::join(|| x_sort.sort(x, 0, bodies), || y_sort.sort(y, 1, bodies))
            }
            None => (x_sort.sort(x, 0, bodies), y_sort.sort(y, 1, bodies)),
        };
        self.stats.swaps += x_swaps + y_swaps;
        let band_changes = self.bands.iter_mut().flat_map(YBands::changes);
        for change in x_sort.changes().chain(y_sort.changes()).chain(band_changes) {
            match change {
                PairChange::Add(m, n) => {
                    if self.pairs.insert(m, n) {
                        self.stats.pairs_added += 1;
                    }
                }
                PairChange::Remove(m, n) => {
                    if let Some(entry) = self.pairs.remove(m, n) {
                        self.ended.push(entry);
                        self.stats.pairs_removed += 1;
                    }
                }
            }
        }
    }

    /// Merges the pending bodies into both axes, then finds their pairs with one sweep along x.
    fn merge_pending(&mut self) {
        for &body in &self.pending {
            self.bodies.set_state(body, SlotState::Active);
            self.bodies.set_fresh(body, true);
        }
        for axis in 0..2 {
            for &body in &self.pending {
                let interval = self.bodies.interval(axis, body);
                if self.bodies.kind(body) == BodyKind::Particle {
                    self.dynamic_extent[axis] = self.dynamic_extent[axis].max(interval.upper - interval.lower);
                }
            }
            if axis == 1
                && let Some(bands) = &mut self.bands
            {
                bands.merge_pending(&self.pending, &self.bodies);
                continue;
            }
            self.merge_buffer.clear();
            for &body in &self.pending {
                let interval = self.bodies.interval(axis, body);
                self.merge_buffer.push(Endpoint::begin(body, interval.lower));
                self.merge_buffer.push(Endpoint::end(body, interval.upper));
            }
            self.merge_buffer.sort_unstable_by(Endpoint::order);
            merge_sorted(&mut self.axes[axis], &self.merge_buffer);
        }
        self.stats.pairs_added +=
            self.sweep.pair_fresh_bodies(&self.axes[0], &self.bodies, self.pending.len(), &mut self.pairs);
        for &body in &self.pending {
            self.bodies.set_fresh(body, false);
        }
        self.stats.bodies_inserted += self.pending.len();
        self.pending.clear();
        self.pending_index.get_or_insert_default().clear();
    }
}

/// Refreshes the values of one axis (or band) from the bodies' new boxes, then re-sorts it by insertion sort
/// ([`sort_refreshed`]); returns the number of swaps.
fn insertion_sort(endpoints: &mut [Endpoint], axis: usize, bodies: &Bodies, changes: &mut Vec<PairChange>) -> u64 {
    refresh_values(endpoints, bodies.intervals(axis));
    sort_refreshed(endpoints, axis, bodies, changes)
}

/// Re-sorts an axis whose values are the new ones by insertion sort, recording in `changes` the pair-list changes of
/// Table 2.3 at every adjacent swap; returns the number of swaps. The common case (element already in place) stays
/// a tight loop; moving an element is done out of line.
fn sort_refreshed(endpoints: &mut [Endpoint], axis: usize, bodies: &Bodies, changes: &mut Vec<PairChange>) -> u64 {
    let mut swaps = 0;
    for i in 1..endpoints.len() {
        let moving = endpoints[i];
        if moving.precedes(endpoints[i - 1]) {
            swaps += sink(&mut endpoints[..=i], moving, axis, bodies, changes);
        }
    }
    swaps
}

/// Sets every endpoint's value to its body's new bound on this axis (`intervals`, by body id), for an axis or a band
/// sorted whole (an axis sorted in segments is refreshed by `segments`, which also measures each segment). The axis
/// is in coordinate order, not body order, so these reads are scattered: on a 100,000-grain layer they were most of
/// the update's time on one thread. They are independent of each other, so a long axis runs them in parallel before
/// the sort, which then reads the array in order; the values, and so the sort, are the same for any thread count.
fn refresh_values(endpoints: &mut [Endpoint], intervals: &[Interval]) {
    let refresh = |e: &mut Endpoint| e.refresh(intervals);
    if endpoints.len() >= 2 * ENDPOINTS_PER_SEGMENT {
        endpoints.par_iter_mut().with_min_len(ENDPOINTS_PER_SEGMENT).for_each(refresh);
    } else {
        endpoints.iter_mut().for_each(refresh);
    }
}

/// Moves `moving` left from the end of `endpoints` to its place, recording the change of Table 2.3 that each element
/// it passes calls for; returns the number of elements passed.
///
/// An addition is recorded only if the boxes touch with their *new* values on both axes, so a pair is added only if
/// it exists at the end of the update; this keeps the list exact whichever axis's changes are applied first. A
/// removal is applied by looking the pair up in the list, and a pair that is not there (its boxes did not touch at
/// the previous update) is left alone. The previous boxes, which could tell those apart here, are not kept (32 bytes
/// per body), but the y axis skips the removals of pairs whose x intervals do not meet now: such a pair, if it was
/// listed, stopped meeting on x in this update too, and the x axis, which records every removal, ends it. In a wide
/// layer most y swaps are of bodies far apart in x, so this spares most lookups of pairs that never were
/// (docs/model.md, "Broadphase"). Either way the same removals take effect, in the same order.
#[inline(never)]
fn sink(
    endpoints: &mut [Endpoint],
    moving: Endpoint,
    axis: usize,
    bodies: &Bodies,
    changes: &mut Vec<PairChange>,
) -> u64 {
    let mut j = endpoints.len() - 1;
    let mut swaps = 0;
    while j > 0 && moving.precedes(endpoints[j - 1]) {
        let passed = endpoints[j - 1];
        swaps += 1;
        let (m, n) = (passed.body(), moving.body());
        if passed.is_end() && !moving.is_end() {
            // e_m b_n ⇒ b_n e_m: the intervals start to overlap on this axis.
            if bodies.may_pair(m, n) {
                changes.push(PairChange::Add(m, n));
            }
        } else if !passed.is_end() && moving.is_end() && (axis == 0 || bodies.meet_on(0, m, n)) {
            // b_m e_n ⇒ e_n b_m: the intervals stop overlapping on this axis.
            changes.push(PairChange::Remove(m, n));
        }
        endpoints[j] = passed;
        j -= 1;
    }
    endpoints[j] = moving;
    swaps
}

/// Merges the sorted `extra` into the sorted `axis` in place, from the back, in one pass.
fn merge_sorted(axis: &mut Vec<Endpoint>, extra: &[Endpoint]) {
    let old_len = axis.len();
    axis.resize(old_len + extra.len(), Endpoint::begin(0, 0.0));
    let (mut i, mut j, mut k) = (old_len, extra.len(), old_len + extra.len());
    while j > 0 {
        if i > 0 && extra[j - 1].precedes(axis[i - 1]) {
            axis[k - 1] = axis[i - 1];
            i -= 1;
        } else {
            axis[k - 1] = extra[j - 1];
            j -= 1;
        }
        k -= 1;
    }
}

/// The active lists of the sweep that pairs newly merged ("fresh") bodies.
#[derive(Debug, Clone, Default)]
struct SweepScratch {
    /// Bodies whose x interval is open at the sweep position.
    open: Vec<u32>,
    /// The fresh bodies among them.
    open_fresh: Vec<u32>,
    /// Per body, its index in `open` and in `open_fresh`.
    position: Vec<[u32; 2]>,
}

impl SweepScratch {
    /// Sweeps the sorted x axis once and adds every touching pair that has at least one fresh body. A fresh body is
    /// tested against all open intervals when it begins, an old body only against the open fresh ones. Returns the
    /// number of pairs added.
    fn pair_fresh_bodies<T: Default + Send>(
        &mut self,
        x_axis: &[Endpoint],
        bodies: &Bodies,
        fresh_count: usize,
        pairs: &mut PairSet<T>,
    ) -> usize {
        self.open.clear();
        self.open_fresh.clear();
        self.position.resize(bodies.len(), [0; 2]);
        let mut added = 0;
        let mut fresh_seen = 0;
        for e in x_axis {
            let body = e.body();
            let fresh = bodies.is_fresh(body);
            if e.is_end() {
                remove_open(&mut self.open, &mut self.position, body, 0);
                if fresh {
                    remove_open(&mut self.open_fresh, &mut self.position, body, 1);
                    if fresh_seen == fresh_count && self.open_fresh.is_empty() {
                        break;
                    }
                }
                continue;
            }
            let partners = if fresh { &self.open } else { &self.open_fresh };
            for &other in partners {
                if bodies.may_pair(other, body) && pairs.insert(other, body) {
                    added += 1;
                }
            }
            self.position[body as usize][0] = self.open.len() as u32;
            self.open.push(body);
            if fresh {
                self.position[body as usize][1] = self.open_fresh.len() as u32;
                self.open_fresh.push(body);
                fresh_seen += 1;
            }
        }
        added
    }
}

/// Removes `body` from an open list in O(1) by moving the last element into its place.
fn remove_open(open: &mut Vec<u32>, position: &mut [[u32; 2]], body: u32, list: usize) {
    let at = position[body as usize][list] as usize;
    if open.get(at) != Some(&body) {
        return;
    }
    open.swap_remove(at);
    if let Some(&moved) = open.get(at) {
        position[moved as usize][list] = at as u32;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gc2d_geometry::DVec2;

    fn interval_box(begin: f64, end: f64) -> Aabb {
        Aabb { min: DVec2::new(begin, 0.0), max: DVec2::new(end, 1.0) }
    }

    /// Four endpoints per body: packed, they take 48 bytes of it instead of 64 (docs/performance.md, "Memory per
    /// particle").
    #[test]
    fn an_endpoint_takes_12_bytes() {
        assert_eq!(std::mem::size_of::<Endpoint>(), 12);
    }

    fn x_order(sweep: &SortAndSweep<u32>) -> Vec<(bool, u32)> {
        sweep.axes[0].iter().map(|e| (e.is_end(), e.body())).collect()
    }

    /// Table 2.2 (Abb. 2.13) in 2D form: three boxes with equal y intervals, so only the x axis decides.
    #[test]
    fn table_2_2_worked_example() {
        let mut sweep = SortAndSweep::<u32>::new();
        // Old order b1 b2 e1 e2 b3 e3; K = {(1, 2)}.
        let old = [interval_box(0.0, 0.0), interval_box(0.0, 2.0), interval_box(1.0, 3.0), interval_box(4.0, 5.0)];
        for body in 1..4 {
            sweep.insert(body, old[body as usize], BodyKind::Particle).unwrap();
        }
        sweep.update(&old);
        let (b, e) = (false, true);
        assert_eq!(x_order(&sweep), [(b, 1), (b, 2), (e, 1), (e, 2), (b, 3), (e, 3)]);
        assert_eq!(sweep.pairs().iter().map(|p| (p.a(), p.b())).collect::<Vec<_>>(), [(1, 2)]);
        *sweep.payload_mut(1, 2).unwrap() = 42;

        // New order b2 b1 e1 b3 e2 e3: the swaps b1↔b2 (no change) and e2↔b3 (add (2;3)), nothing on y.
        let new = [interval_box(0.0, 0.0), interval_box(1.0, 2.0), interval_box(0.0, 4.0), interval_box(3.0, 5.0)];
        sweep.update(&new);
        assert_eq!(x_order(&sweep), [(b, 2), (b, 1), (e, 1), (b, 3), (e, 2), (e, 3)]);
        let pairs: Vec<_> = sweep.pairs().iter().map(|p| (p.a(), p.b(), p.payload)).collect();
        assert_eq!(pairs, [(1, 2, 42), (2, 3, 0)]);
        assert_eq!(
            *sweep.stats(),
            BroadphaseStats { swaps: 2, pairs_added: 1, pairs_removed: 0, bodies_inserted: 0, bodies_removed: 0 }
        );
        assert!(sweep.ended_pairs().is_empty());
    }

    #[test]
    fn touching_boxes_pair_and_a_gap_of_one_ulp_separates_them() {
        let mut sweep = SortAndSweep::<u32>::new();
        let touching = [interval_box(0.0, 1.0), interval_box(1.0, 2.0)];
        sweep.insert(0, touching[0], BodyKind::Particle).unwrap();
        sweep.insert(1, touching[1], BodyKind::Particle).unwrap();
        sweep.update(&touching);
        assert_eq!(sweep.pairs().len(), 1);
        let apart = [interval_box(0.0, 1.0), interval_box(1.0 + f64::EPSILON, 2.0)];
        sweep.update(&apart);
        assert!(sweep.pairs().is_empty());
        assert_eq!(sweep.ended_pairs().len(), 1);
        sweep.update(&touching);
        assert_eq!(sweep.pairs().len(), 1);
        assert!(sweep.ended_pairs().is_empty());
    }

    /// The y axis leaves the removal of a pair whose x intervals no longer meet to the x axis; a pair that stops
    /// meeting on both axes in one update must still end, exactly once, whichever way it leaves.
    #[test]
    fn a_pair_that_leaves_on_both_axes_in_one_update_ends() {
        let boxes = |x: f64, y: f64| {
            [
                Aabb { min: DVec2::ZERO, max: DVec2::ONE },
                Aabb { min: DVec2::new(x, y), max: DVec2::new(x + 1.0, y + 1.0) },
            ]
        };
        for (x, y) in [(2.0, 2.0), (-2.0, 2.0), (2.0, -2.0), (-2.0, -2.0), (2.0, 0.5), (0.5, 2.0)] {
            let mut sweep = SortAndSweep::<u32>::new();
            let overlapping = boxes(0.5, 0.5);
            sweep.insert(0, overlapping[0], BodyKind::Particle).unwrap();
            sweep.insert(1, overlapping[1], BodyKind::Particle).unwrap();
            sweep.update(&overlapping);
            assert_eq!(sweep.pairs().len(), 1);
            sweep.update(&boxes(x, y));
            assert!(sweep.pairs().is_empty(), "moved to ({x}, {y})");
            assert_eq!(sweep.ended_pairs().len(), 1, "moved to ({x}, {y})");
            assert_eq!(sweep.stats().pairs_removed, 1);
        }
    }

    #[test]
    fn negative_zero_touches_positive_zero_when_inserted_together() {
        let mut sweep = SortAndSweep::<u32>::new();
        let boxes = [interval_box(-1.0, -0.0), interval_box(0.0, 1.0)];
        sweep.insert(0, boxes[0], BodyKind::Particle).unwrap();
        sweep.insert(1, boxes[1], BodyKind::Particle).unwrap();
        sweep.update(&boxes);
        assert_eq!(sweep.pairs().len(), 1);
    }

    #[test]
    fn nan_and_inverted_boxes_are_parked_without_panicking() {
        let mut sweep = SortAndSweep::<u32>::new();
        let nan = Aabb { min: DVec2::NAN, max: DVec2::NAN };
        let boxes = [interval_box(0.0, 1.0), nan, Aabb::of_points(&[]), interval_box(3.0, 2.0)];
        for body in 0..4 {
            sweep.insert(body, boxes[body as usize], BodyKind::Particle).unwrap();
        }
        sweep.update(&boxes);
        // Bodies 1 and 2 both sit at (+∞, +∞); the inverted box 3 is the point interval x = 3.
        let pairs: Vec<_> = sweep.pairs().iter().map(|p| (p.a(), p.b())).collect();
        assert_eq!(pairs, [(1, 2)]);
        sweep.update(&[interval_box(0.0, 1.0), interval_box(0.5, 3.0), interval_box(9.0, 9.0), interval_box(3.0, 2.0)]);
        let mut pairs: Vec<_> = sweep.pairs().iter().map(|p| (p.a(), p.b())).collect();
        pairs.sort_unstable();
        assert_eq!(pairs, [(0, 1), (1, 3)]);
    }

    #[test]
    fn insert_rejects_duplicates_and_oversized_ids() {
        let mut sweep = SortAndSweep::<u32>::new();
        let unit = interval_box(0.0, 1.0);
        assert_eq!(sweep.insert(MAX_BODIES, unit, BodyKind::Particle), Err(BroadphaseError::IdTooLarge(MAX_BODIES)));
        sweep.insert(2, unit, BodyKind::Particle).unwrap();
        assert_eq!(sweep.insert(2, unit, BodyKind::Wall), Err(BroadphaseError::AlreadyInserted(2)));
        assert!(sweep.remove(2));
        assert!(!sweep.remove(2));
        assert!(!sweep.remove(7));
        assert!(sweep.insert(2, unit, BodyKind::Wall).is_ok());
    }
}
