//! The y axis split into bands of x, for scenes much wider than high.
//!
//! One y axis over a layer 300 m wide and 1 cm deep (10⁶ grains) orders 2·10⁶ endpoints within 1 cm, so a grain that
//! moves up by δ passes every endpoint in that height across the whole width: its swaps, and the box reads each swap
//! makes, grow with the width, i.e. with N. Split into bands, each band keeps the y endpoints of the bodies whose x
//! interval reaches into it, and a grain only passes the endpoints of its own band(s): the work per grain no longer
//! depends on the width (docs/performance.md, "The y axis in bands").
//!
//! **Why the pair list stays exact.** Bodies whose x intervals meet share a band (a point of both intervals lies in
//! some band, and both reach into it). A pair whose boxes start or stop meeting either changes its x overlap (the x
//! axis, still one axis over the whole width, sees the swap) or keeps its x overlap and changes its y overlap. In the
//! latter case the two share a band now, and, if neither body changed its bands in this update, they shared that
//! band before: its insertion sort swaps their endpoints (it swaps exactly the endpoint pairs whose order changed)
//! and records the change of Table 2.3, as the single axis did. A body that changed its bands ("mover") is checked
//! against every body of its bands once the bands are sorted ([`YBands::sort`], the recheck): a pair whose boxes
//! meet is added, one whose x intervals meet and y intervals do not is ended. Every recorded change is true of the
//! new boxes, and adding or ending a pair twice does nothing, so bodies in two bands do no harm.
//!
//! The bands are fixed once chosen (origin, width and count are saved in checkpoints); bodies beyond the outer
//! bands' edges belong to the outer bands. The changes are applied in a fixed order (the x axis's, then each band's
//! in band order, then the rechecks in body order), so the pair list is the same for any thread count.

use super::bodies::{Bodies, Interval, SlotState};
use super::{Endpoint, PairChange, insertion_sort, merge_sorted};
use crate::BodyKind;
use crate::bodies::vec_bytes;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// A band is this many times as wide as the widest dynamic box when [`YBands::for_wide_scene`] chooses the bands: wide
/// enough that few bodies straddle two bands or change bands in a step, narrow enough that a band of a shallow layer
/// holds some hundreds of bodies (about 270 in the benchmark layer, 1 cm deep).
const BAND_WIDTH_IN_BOXES: f64 = 64.0;

/// [`YBands::for_wide_scene`] splits the y axis only where the dynamic bodies span at least this many bands.
const MIN_BANDS: usize = 4;

/// The most bands; a wider scene gets wider bands. Bounds the copies of a wall that spans the whole scene.
const MAX_BANDS: usize = 1 << 16;

/// Room the arrivals buffer keeps after a merge of new bodies: plenty for a step's movers, far less than the first
/// merge of a large scene needed.
const ARRIVALS_KEPT: usize = 4096;

/// Bands below this many per task are sorted on one thread.
const BANDS_PER_TASK: usize = 4;

/// Bodies per piece of the parallel search for the bodies that changed bands ([`YBands::find_movers`]).
const BODIES_PER_SEARCH: usize = 4096;

/// The bands a body's x interval reaches into: `first..=last`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
struct BandRange {
    first: u32,
    last: u32,
}

impl BandRange {
    fn bands(self) -> std::ops::RangeInclusive<usize> {
        self.first as usize..=self.last as usize
    }

    fn contains(self, band: usize) -> bool {
        self.bands().contains(&band)
    }
}

/// A body whose bands changed in the current update, with the bands it had before.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Mover {
    body: u32,
    before: BandRange,
}

/// An endpoint to be merged into a band.
#[derive(Debug, Clone, Copy)]
struct Arrival {
    band: u32,
    endpoint: Endpoint,
}

impl Arrival {
    /// Adds both y endpoints of `body` (its interval `y`) for `band` to `arrivals`.
    fn push_both(arrivals: &mut Vec<Arrival>, band: usize, body: u32, y: Interval) {
        let band = band as u32;
        arrivals.push(Arrival { band, endpoint: Endpoint::begin(body, y.lower) });
        arrivals.push(Arrival { band, endpoint: Endpoint::end(body, y.upper) });
    }
}

/// The y axis as bands of x: per band the sorted y endpoints of the bodies reaching into it.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub(super) struct YBands {
    /// x of the left edge of band 0.
    origin: f64,
    /// Width of a band, m.
    width: f64,
    /// Per band, its sorted y endpoints.
    axes: Vec<Vec<Endpoint>>,
    /// Per body slot, the bands it is in (for bodies in the axes).
    ranges: Vec<BandRange>,
    /// Scratch: per band, the pair-list changes its sort found in the current update.
    #[serde(skip)]
    changes: Vec<Vec<PairChange>>,
    /// Scratch: the changes the recheck of the movers found.
    #[serde(skip)]
    rechecks: Vec<PairChange>,
    /// Scratch: the bodies whose bands changed in the current update, in body order.
    #[serde(skip)]
    movers: Vec<Mover>,
    /// Scratch: per piece of [`BODIES_PER_SEARCH`] body slots, whether it holds a mover (the parallel search).
    #[serde(skip)]
    pieces_with_movers: Vec<bool>,
    /// Scratch: the bands a mover left, to be cleaned.
    #[serde(skip)]
    left: Vec<u32>,
    /// Scratch: endpoints to merge into the bands.
    #[serde(skip)]
    arrivals: Vec<Arrival>,
    /// Scratch: one band's sorted arrivals.
    #[serde(skip)]
    merge_buffer: Vec<Endpoint>,
}

impl YBands {
    /// Bands of `width` starting at `origin`, `count` of them, holding the endpoints of `y_axis` (the sorted y axis of
    /// the bodies in the axes).
    fn new(bodies: &Bodies, y_axis: &[Endpoint], origin: f64, width: f64, count: usize) -> Self {
        let mut bands = Self {
            origin,
            width,
            axes: vec![Vec::new(); count],
            ranges: vec![BandRange::default(); bodies.len()],
            changes: Vec::new(),
            rechecks: Vec::new(),
            movers: Vec::new(),
            pieces_with_movers: Vec::new(),
            left: Vec::new(),
            arrivals: Vec::new(),
            merge_buffer: Vec::new(),
        };
        for body in 0..bodies.len() as u32 {
            if bodies.state(body) == SlotState::Active {
                bands.ranges[body as usize] = bands.range_of(bodies.interval(0, body));
            }
        }
        // Each band takes its bodies' endpoints in axis order, so it is sorted too.
        for &endpoint in y_axis {
            for band in bands.ranges[endpoint.body() as usize].bands() {
                bands.axes[band].push(endpoint);
            }
        }
        bands
    }

    /// Bands of `width` over the x extent of the dynamic bodies (active or pending), or `None` where that extent is
    /// not finite or holds fewer than two bands.
    pub(super) fn with_width(bodies: &Bodies, y_axis: &[Endpoint], width: f64) -> Option<Self> {
        Self::over(bodies, y_axis, dynamic_x_extent(bodies)?, width)
    }

    /// Bands [`BAND_WIDTH_IN_BOXES`] widest dynamic boxes wide, where the dynamic bodies span at least [`MIN_BANDS`]
    /// of them; `None` for a scene that is not that wide (its one y axis passes few endpoints of bodies far away).
    pub(super) fn for_wide_scene(bodies: &Bodies, y_axis: &[Endpoint]) -> Option<Self> {
        let [widest, _] = bodies.dynamic_extent();
        let width = BAND_WIDTH_IN_BOXES * widest;
        let extent = dynamic_x_extent(bodies)?;
        let wide = (extent.upper - extent.lower) >= MIN_BANDS as f64 * width;
        if wide { Self::over(bodies, y_axis, extent, width) } else { None }
    }

    /// Bands of `width` over `extent` (at most [`MAX_BANDS`]: then as wide as it takes), or `None` where it holds
    /// fewer than two.
    fn over(bodies: &Bodies, y_axis: &[Endpoint], extent: Interval, width: f64) -> Option<Self> {
        let count = ((extent.upper - extent.lower) / width).ceil();
        if !(width > 0.0 && count >= 2.0) {
            return None;
        }
        let count = (count as usize).min(MAX_BANDS);
        let width = width.max((extent.upper - extent.lower) / count as f64);
        Some(Self::new(bodies, y_axis, extent.lower, width, count))
    }

    /// Number of bands.
    pub(super) fn count(&self) -> usize {
        self.axes.len()
    }

    /// The band holding x (the outer bands hold everything beyond their edges).
    fn band_of(&self, x: f64) -> u32 {
        // Clamped to [0, last] first, so `as` (which truncates) floors; without a call to libm's `floor` (0.6 % of a
        // 100,000-grain layer's step). NaN (not possible for sanitised intervals) goes to band 0.
        ((x - self.origin) / self.width).clamp(0.0, (self.axes.len() - 1) as f64) as u32
    }

    fn range_of(&self, x: Interval) -> BandRange {
        BandRange { first: self.band_of(x.lower), last: self.band_of(x.upper) }
    }

    /// Drops the endpoints of bodies no longer in the broadphase.
    pub(super) fn retain_active(&mut self, bodies: &Bodies) {
        for axis in &mut self.axes {
            axis.retain(|e| bodies.state(e.body()) == SlotState::Active);
        }
    }

    /// Moves the bodies that changed bands, re-sorts every band (in parallel), and rechecks the movers; the changes
    /// found are then read with [`changes`](Self::changes). Returns the number of swaps.
    pub(super) fn sort(&mut self, bodies: &Bodies) -> u64 {
        self.find_movers(bodies);
        self.leave_bands();
        self.changes.resize_with(self.axes.len(), Vec::new);
        let sort_band = |(axis, changes): (&mut Vec<Endpoint>, &mut Vec<PairChange>)| {
            changes.clear();
            insertion_sort(axis, 1, bodies, changes)
        };
        let swaps = if self.axes.len() >= 2 * BANDS_PER_TASK {
            self.axes.par_iter_mut().zip(self.changes.par_iter_mut()).with_min_len(BANDS_PER_TASK).map(sort_band).sum()
        } else {
            self.axes.iter_mut().zip(self.changes.iter_mut()).map(sort_band).sum()
        };
        self.join_bands(bodies);
        self.recheck_movers(bodies);
        swaps
    }

    /// The changes of the last [`sort`](Self::sort): each band's in band order, then the rechecks.
    pub(super) fn changes(&mut self) -> impl Iterator<Item = PairChange> + '_ {
        self.changes.iter_mut().flat_map(|changes| changes.drain(..)).chain(self.rechecks.drain(..))
    }

    /// Records the bodies in the axes whose x interval now reaches into other bands, in body order, and gives them
    /// their new bands.
    ///
    /// Few bodies change bands in a step (5 in 200 steps of the 100,000-grain layer), but every body's bands are
    /// computed to find them: 3.8 ns a body on one thread, a third of that layer's broadphase, and on 16 threads the
    /// part of it that did not shrink with threads. So in a pool of several threads the body slots are looked at in
    /// parallel, in pieces of [`BODIES_PER_SEARCH`], only to mark the pieces that hold a mover; the marked pieces are
    /// then gone through in order, which records the same movers in the same order as one pass (docs/performance.md,
    /// "The layer's broadphase on many threads").
    fn find_movers(&mut self, bodies: &Bodies) {
        let piece_len = if rayon::current_num_threads() > 1 { BODIES_PER_SEARCH } else { usize::MAX };
        self.find_movers_in_pieces(bodies, piece_len);
    }

    /// [`find_movers`](Self::find_movers) with pieces of `piece_len` body slots (the tests use short ones); one
    /// piece is looked at in one pass.
    fn find_movers_in_pieces(&mut self, bodies: &Bodies, piece_len: usize) {
        self.movers.clear();
        self.ranges.resize(bodies.len(), BandRange::default());
        let slots = bodies.intervals(0).len();
        let piece = |index: usize| index * piece_len..slots.min((index + 1).saturating_mul(piece_len));
        let pieces = slots.div_ceil(piece_len);
        if pieces < 2 {
            self.record_movers(bodies, 0..slots);
            return;
        }
        let mut holds_a_mover = std::mem::take(&mut self.pieces_with_movers);
        holds_a_mover.resize(pieces, false);
        let this = &*self;
        holds_a_mover.par_iter_mut().enumerate().for_each(|(index, marked)| {
            *marked = piece(index).any(|body| this.new_range(bodies, body).is_some());
        });
        for (index, _) in holds_a_mover.iter().enumerate().filter(|(_, marked)| **marked) {
            self.record_movers(bodies, piece(index));
        }
        self.pieces_with_movers = holds_a_mover;
    }

    /// Records the movers among `slots` (body slots, in order) and gives them their new bands.
    fn record_movers(&mut self, bodies: &Bodies, slots: std::ops::Range<usize>) {
        for body in slots {
            if let Some(now) = self.new_range(bodies, body) {
                self.movers.push(Mover { body: body as u32, before: self.ranges[body] });
                self.ranges[body] = now;
            }
        }
    }

    /// The bands of body slot `body` where it is in the axes and they are not those it had; else `None`.
    #[inline]
    fn new_range(&self, bodies: &Bodies, body: usize) -> Option<BandRange> {
        if bodies.state(body as u32) != SlotState::Active {
            return None;
        }
        let now = self.range_of(bodies.intervals(0)[body]);
        (now != self.ranges[body]).then_some(now)
    }

    /// Takes the movers' endpoints out of the bands they left.
    fn leave_bands(&mut self) {
        self.left.clear();
        for mover in &self.movers {
            let now = self.ranges[mover.body as usize];
            self.left.extend(mover.before.bands().filter(|&band| !now.contains(band)).map(|band| band as u32));
        }
        self.left.sort_unstable();
        self.left.dedup();
        for &band in &self.left {
            let band = band as usize;
            let ranges = &self.ranges;
            self.axes[band].retain(|e| ranges[e.body() as usize].contains(band));
        }
    }

    /// Merges the movers' endpoints into the bands they joined.
    fn join_bands(&mut self, bodies: &Bodies) {
        self.arrivals.clear();
        for mover in &self.movers {
            let now = self.ranges[mover.body as usize];
            let y = bodies.interval(1, mover.body);
            for band in now.bands().filter(|&band| !mover.before.contains(band)) {
                Arrival::push_both(&mut self.arrivals, band, mover.body, y);
            }
        }
        self.merge_arrivals();
    }

    /// Puts the bodies being merged into the broadphase (`pending`, in the axes from now on) into their bands.
    pub(super) fn merge_pending(&mut self, pending: &[u32], bodies: &Bodies) {
        self.ranges.resize(bodies.len(), BandRange::default());
        self.arrivals.clear();
        for &body in pending {
            let range = self.range_of(bodies.interval(0, body));
            self.ranges[body as usize] = range;
            let y = bodies.interval(1, body);
            for band in range.bands() {
                Arrival::push_both(&mut self.arrivals, band, body, y);
            }
        }
        self.merge_arrivals();
        // The first merge of a scene holds every body (32 bytes per grain); the movers of a step need far less.
        self.arrivals.clear();
        self.arrivals.shrink_to(ARRIVALS_KEPT);
    }

    /// Merges `arrivals` into their bands, band by band.
    fn merge_arrivals(&mut self) {
        self.arrivals
            .sort_unstable_by(|a, b| a.band.cmp(&b.band).then_with(|| Endpoint::order(&a.endpoint, &b.endpoint)));
        let mut start = 0;
        while let Some(first) = self.arrivals.get(start) {
            let band = first.band;
            let end = start + self.arrivals[start..].partition_point(|a| a.band == band);
            self.merge_buffer.clear();
            self.merge_buffer.extend(self.arrivals[start..end].iter().map(|a| a.endpoint));
            let axis = &mut self.axes[band as usize];
            if axis.capacity() - axis.len() < self.merge_buffer.len() {
                // A sixteenth to spare, not `Vec`'s doubling, which would leave every band a body moved into half
                // empty (24 bytes per grain of a layer).
                axis.reserve_exact(self.merge_buffer.len() + axis.len() / 16);
            }
            merge_sorted(axis, &self.merge_buffer);
            start = end;
        }
    }

    /// Checks every mover against every body of its bands: adds the pairs whose boxes meet, ends those whose x
    /// intervals meet and y intervals do not (those whose x intervals do not meet are the x axis's to end).
    fn recheck_movers(&mut self, bodies: &Bodies) {
        self.rechecks.clear();
        for mover in &self.movers {
            let m = mover.body;
            for band in self.ranges[m as usize].bands() {
                for other in self.axes[band].iter().filter(|e| !e.is_end() && e.body() != m) {
                    let n = other.body();
                    if bodies.may_pair(m, n) {
                        self.rechecks.push(PairChange::Add(m, n));
                    } else if bodies.meet_on(0, m, n) {
                        self.rechecks.push(PairChange::Remove(m, n));
                    }
                }
            }
        }
    }

    /// The endpoints of the bands that `x` reaches into, from the highest down (value, then the axis order), each
    /// once: among them those of every body whose x interval meets `x`.
    pub(super) fn endpoints_from_top(&self, x: Interval) -> FromTop<'_> {
        let axes = &self.axes[self.range_of(x).bands()];
        FromTop { axes, cursors: axes.iter().map(Vec::len).collect(), last: None }
    }

    /// Gives back the spare room of the bands and the per-body ranges.
    pub(super) fn shrink_to_fit(&mut self) {
        self.axes.iter_mut().for_each(Vec::shrink_to_fit);
        self.axes.shrink_to_fit();
        self.ranges.shrink_to_fit();
    }

    /// Heap bytes of the bands, the ranges and the scratch buffers.
    pub(super) fn heap_bytes(&self) -> usize {
        vec_bytes(&self.axes)
            + self.axes.iter().map(vec_bytes).sum::<usize>()
            + vec_bytes(&self.ranges)
            + vec_bytes(&self.changes)
            + self.changes.iter().map(vec_bytes).sum::<usize>()
            + vec_bytes(&self.rechecks)
            + vec_bytes(&self.movers)
            + vec_bytes(&self.pieces_with_movers)
            + vec_bytes(&self.left)
            + vec_bytes(&self.arrivals)
            + vec_bytes(&self.merge_buffer)
    }
}

/// The x extent (lowest lower, highest upper bound) of the dynamic bodies in the broadphase, active or pending;
/// `None` when there are none or it is not finite.
fn dynamic_x_extent(bodies: &Bodies) -> Option<Interval> {
    let mut extent = Interval { lower: f64::INFINITY, upper: f64::NEG_INFINITY };
    let dynamic = |&body: &u32| bodies.state(body) != SlotState::Absent && bodies.kind(body) == BodyKind::Particle;
    for body in (0..bodies.len() as u32).filter(dynamic) {
        let x = bodies.interval(0, body);
        extent.lower = extent.lower.min(x.lower);
        extent.upper = extent.upper.max(x.upper);
    }
    (extent.lower.is_finite() && extent.upper.is_finite()).then_some(extent)
}

/// The endpoints of all bands merged from the highest down; an endpoint held by two bands (a body in both) comes
/// once. Each step looks at every band's next endpoint, so it is meant for walks that stop after a few (the sources'
/// highest-particle search), not for a whole axis.
pub(super) struct FromTop<'a> {
    axes: &'a [Vec<Endpoint>],
    /// Per band, how many of its endpoints are still to come.
    cursors: Vec<usize>,
    /// The last endpoint given, to skip its copies in other bands.
    last: Option<Endpoint>,
}

impl Iterator for FromTop<'_> {
    type Item = Endpoint;

    fn next(&mut self) -> Option<Endpoint> {
        loop {
            let mut highest: Option<(usize, Endpoint)> = None;
            for (band, (&cursor, axis)) in self.cursors.iter().zip(self.axes).enumerate() {
                if let Some(&candidate) = cursor.checked_sub(1).and_then(|k| axis.get(k))
                    && highest.is_none_or(|(_, best)| best.precedes(candidate))
                {
                    highest = Some((band, candidate));
                }
            }
            let (band, endpoint) = highest?;
            self.cursors[band] -= 1;
            let repeated = self.last.is_some_and(|last| !last.precedes(endpoint) && !endpoint.precedes(last));
            if !repeated {
                self.last = Some(endpoint);
                return Some(endpoint);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gc2d_geometry::{Aabb, DVec2};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The search for the bodies that changed bands, in pieces on several threads, records the same movers in the
    /// same order, and gives them the same bands, as one pass: 3,000 slots (some pending, some absent, so skipped) in
    /// bands of two boxes' width, most bodies moving a little and some far, over 20 updates, pieces of 64 and 1,000
    /// slots on 1 to 4 threads.
    #[test]
    fn the_search_in_pieces_finds_the_movers_of_one_pass_in_the_same_order() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let count = 3_000_u32;
        let mut boxes: Vec<Aabb> = (0..count)
            .map(|i| {
                let x = f64::from(i) * 0.5;
                Aabb { min: DVec2::new(x, 0.0), max: DVec2::new(x + 1.0, 1.0) }
            })
            .collect();
        let mut bodies = Bodies::default();
        for (body, aabb) in boxes.iter().enumerate() {
            let body = body as u32;
            bodies.make_pending(body, BodyKind::Particle, aabb);
            if body % 97 != 5 {
                bodies.set_state(body, SlotState::Active);
            }
        }
        bodies.set_state(2_500, SlotState::Absent);
        let mut y_axis: Vec<Endpoint> = (0..count)
            .filter(|&body| bodies.state(body) == SlotState::Active)
            .flat_map(|body| {
                let y = bodies.interval(1, body);
                [Endpoint::begin(body, y.lower), Endpoint::end(body, y.upper)]
            })
            .collect();
        y_axis.sort_unstable_by(Endpoint::order);
        let mut one_pass = YBands::with_width(&bodies, &y_axis, 2.0).expect("bands");
        let mut movers_seen = 0;
        for round in 0..20 {
            for aabb in &mut boxes {
                let shift =
                    if rng.random_bool(0.01) { rng.random_range(-50.0..50.0) } else { rng.random_range(-0.1..0.1) };
                *aabb = Aabb { min: aabb.min + DVec2::new(shift, 0.0), max: aabb.max + DVec2::new(shift, 0.0) };
            }
            bodies.take_boxes(&boxes);
            let before = one_pass.clone();
            one_pass.find_movers_in_pieces(&bodies, usize::MAX);
            movers_seen += one_pass.movers.len();
            for (piece_len, threads) in [(64, 4), (64, 1), (1_000, 3), (BODIES_PER_SEARCH, 2)] {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let mut in_pieces = before.clone();
                pool.install(|| in_pieces.find_movers_in_pieces(&bodies, piece_len));
                let case = format!("round {round}, pieces of {piece_len} on {threads} threads");
                assert_eq!(in_pieces.movers, one_pass.movers, "{case}: the movers differ");
                assert_eq!(in_pieces.ranges, one_pass.ranges, "{case}: the bands differ");
            }
        }
        assert!(movers_seen > 1_000, "the moves must change bands, saw {movers_seen} movers");
    }
}
