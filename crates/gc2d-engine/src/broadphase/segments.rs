//! One long axis re-sorted in parallel, in segments, with the same swaps in the same order as one insertion sort.
//!
//! Between two updates an endpoint moves by its body's motion in one step, so it passes a few others at most, and
//! almost never from one stretch of thousands of endpoints into the stretch before it. The insertion sort over the
//! whole axis moves an endpoint left only while it precedes its left neighbour. So if every new value from some
//! position to the end of the axis is greater than every new value before that position, no endpoint crosses the
//! position in either direction, and the sort swaps on each side exactly what sorting that side alone swaps, in the
//! same order. The axis is cut into segments of at least [`ENDPOINTS_PER_SEGMENT`], and a group of segments starts
//! at every segment boundary where this holds; every group is sorted on its own (in parallel), and the pair-list
//! changes the groups found, read in group order, are the changes of the one sort, in its order. The pair list, and
//! so everything after it, is the same for any thread count and bit for bit what the single sort gave (docs/model.md,
//! "Broadphase (§4.2)").
//!
//! The test compares values only (equal values join the segments), so it needs no more than the least and greatest
//! value of each segment, taken while the values are refreshed. A boundary that fails it costs parallelism, never
//! correctness. On one thread the axis is one group and the values are not measured.

use super::bodies::{Bodies, Interval};
use super::{Endpoint, PairChange, insertion_sort, sort_refreshed};
use crate::bodies::vec_bytes;
use rayon::prelude::*;

/// Endpoints of a segment, at least; an axis shorter than two segments is one group. A segment of a settled pile
/// takes about 10 µs to refresh and sort on one core.
pub(super) const ENDPOINTS_PER_SEGMENT: usize = 4096;

/// The least and greatest value in one segment after the refresh (then, while the groups are found, the least value
/// from the segment to the end of the axis).
#[derive(Debug, Clone, Copy)]
struct ValueSpan {
    least: f64,
    greatest: f64,
}

/// Scratch for re-sorting an axis in segments, kept between updates so a warm update does not allocate.
#[derive(Debug, Clone, Default)]
pub(super) struct SegmentedSort {
    /// Per segment: its values' span.
    spans: Vec<ValueSpan>,
    /// The first endpoint of each group, then the axis's length.
    group_starts: Vec<usize>,
    /// Per group: the pair-list changes its sort found, in the order found. One buffer per segment (the most groups
    /// there can be), never shortened, so the buffers keep their room when the number of groups varies.
    changes: Vec<Vec<PairChange>>,
}

impl SegmentedSort {
    /// Refreshes the values of `endpoints` (one axis, `axis`) from the bodies' new intervals and re-sorts it, recording
    /// the changes of Table 2.3, which [`changes`](Self::changes) then gives in the order one insertion sort finds
    /// them. Returns the number of swaps.
    ///
    /// On one thread the axis is one segment: the same result without the cost of measuring the segments.
    pub(super) fn sort(&mut self, endpoints: &mut [Endpoint], axis: usize, bodies: &Bodies) -> u64 {
        let segment_len = if rayon::current_num_threads() > 1 { ENDPOINTS_PER_SEGMENT } else { usize::MAX };
        self.sort_in_segments(endpoints, axis, bodies, segment_len)
    }

    /// [`sort`](Self::sort) with segments of at least `segment_len` endpoints (the tests use short ones).
    fn sort_in_segments(
        &mut self,
        endpoints: &mut [Endpoint],
        axis: usize,
        bodies: &Bodies,
        segment_len: usize,
    ) -> u64 {
        let segments = (endpoints.len() / segment_len).max(1);
        if self.changes.len() < segments {
            self.changes.resize_with(segments, Vec::new);
        }
        if segments == 1 {
            // The whole-axis sort itself (its refresh in pieces of ENDPOINTS_PER_SEGMENT): a loop of its own here
            // made the broadphase of the 12,800 squares 5-10 % slower on one core.
            self.group_starts.clear();
            self.group_starts.extend([0, endpoints.len()]);
            self.changes[0].clear();
            return insertion_sort(endpoints, axis, bodies, &mut self.changes[0]);
        }
        let chunk = endpoints.len().div_ceil(segments);
        self.refresh(endpoints, bodies.intervals(axis), chunk);
        self.find_groups(chunk, endpoints.len());
        let groups = self.group_starts.len() - 1;
        sort_groups(endpoints, 0, &self.group_starts, &mut self.changes[..groups], axis, bodies)
    }

    /// Sets every endpoint's value to its body's new bound (the reads are scattered: the axis is in coordinate order,
    /// the intervals in body order), in parallel chunks of `chunk` endpoints, and records each chunk's span.
    fn refresh(&mut self, endpoints: &mut [Endpoint], intervals: &[Interval], chunk: usize) {
        self.spans.resize(endpoints.len().div_ceil(chunk), ValueSpan { least: 0.0, greatest: 0.0 });
        let refresh_chunk = |(endpoints, span): (&mut [Endpoint], &mut ValueSpan)| {
            *span = refresh_and_measure(endpoints, intervals);
        };
        endpoints.par_chunks_mut(chunk).zip(self.spans.par_iter_mut()).for_each(refresh_chunk);
    }

    /// Starts a group at the first segment and at every segment from which on every value is greater than every value
    /// before it (segments of `chunk` endpoints, `len` in all). The values after the segment count too: an endpoint
    /// of a later segment that belongs before the segment would move through it.
    fn find_groups(&mut self, chunk: usize, len: usize) {
        let mut least_after = f64::INFINITY;
        for span in self.spans.iter_mut().rev() {
            least_after = least_after.min(span.least);
            span.least = least_after;
        }
        self.group_starts.clear();
        self.group_starts.reserve(self.spans.len() + 1);
        self.group_starts.push(0);
        let mut greatest_before = f64::NEG_INFINITY;
        for (segment, span) in self.spans.iter().enumerate() {
            if segment > 0 && greatest_before < span.least {
                self.group_starts.push(segment * chunk);
            }
            greatest_before = greatest_before.max(span.greatest);
        }
        self.group_starts.push(len);
    }

    /// The changes of the last sort, group by group: the order one insertion sort of the whole axis finds them in.
    pub(super) fn changes(&mut self) -> impl Iterator<Item = PairChange> + '_ {
        let groups = self.group_starts.len().saturating_sub(1);
        self.changes[..groups].iter_mut().flat_map(|changes| changes.drain(..))
    }

    /// Bytes held on the heap.
    pub(super) fn heap_bytes(&self) -> usize {
        vec_bytes(&self.spans)
            + vec_bytes(&self.group_starts)
            + vec_bytes(&self.changes)
            + self.changes.iter().map(vec_bytes).sum::<usize>()
    }
}

/// Sets the values of `endpoints` to their bodies' new bounds and returns their span. Four running minima and maxima
/// instead of one, so that the comparisons do not wait for each other: with one of each, the broadphase of the 12,800
/// squares took 2.5 times as long as without them when forced onto one core in segments, with four 1.1 times.
fn refresh_and_measure(endpoints: &mut [Endpoint], intervals: &[Interval]) -> ValueSpan {
    let mut least = [f64::INFINITY; 4];
    let mut greatest = [f64::NEG_INFINITY; 4];
    let mut quads = endpoints.chunks_exact_mut(4);
    for quad in &mut quads {
        for (lane, e) in quad.iter_mut().enumerate() {
            e.refresh(intervals);
            least[lane] = if e.value < least[lane] { e.value } else { least[lane] };
            greatest[lane] = if e.value > greatest[lane] { e.value } else { greatest[lane] };
        }
    }
    for e in quads.into_remainder() {
        e.refresh(intervals);
        least[0] = least[0].min(e.value);
        greatest[0] = greatest[0].max(e.value);
    }
    ValueSpan {
        least: least.into_iter().fold(f64::INFINITY, f64::min),
        greatest: greatest.into_iter().fold(f64::NEG_INFINITY, f64::max),
    }
}

/// Sorts the groups that start at `starts` (the last entry is the end; `endpoints` begins at endpoint `offset` of the
/// axis), each on its own, halving the list of groups across rayon's threads; each group's changes go to its entry of
/// `changes`. Returns the number of swaps.
fn sort_groups(
    endpoints: &mut [Endpoint],
    offset: usize,
    starts: &[usize],
    changes: &mut [Vec<PairChange>],
    axis: usize,
    bodies: &Bodies,
) -> u64 {
    if let [_] = changes {
        changes[0].clear();
        return sort_refreshed(endpoints, axis, bodies, &mut changes[0]);
    }
    let middle = changes.len() / 2;
    let (low, high) = endpoints.split_at_mut(starts[middle] - offset);
    let (low_changes, high_changes) = changes.split_at_mut(middle);
    let (low_swaps, high_swaps) = rayon::join(
        || sort_groups(low, offset, &starts[..=middle], low_changes, axis, bodies),
        || sort_groups(high, starts[middle], &starts[middle..], high_changes, axis, bodies),
    );
    low_swaps + high_swaps
}

#[cfg(test)]
mod tests {
    use super::super::bodies::SlotState;
    use super::*;
    use crate::BodyKind;
    use gc2d_geometry::{Aabb, DVec2};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// `count` unit-high boxes in a row along x, of random widths, some apart and some overlapping.
    fn row_of_boxes(count: usize, rng: &mut ChaCha8Rng) -> Vec<Aabb> {
        (0..count)
            .map(|i| {
                let x = i as f64 + rng.random_range(-0.3..0.3);
                Aabb { min: DVec2::new(x, 0.0), max: DVec2::new(x + rng.random_range(0.2..1.6), 1.0) }
            })
            .collect()
    }

    fn sorted_axis(bodies: &Bodies) -> Vec<Endpoint> {
        let mut axis: Vec<Endpoint> = (0..bodies.len() as u32)
            .flat_map(|b| {
                let x = bodies.interval(0, b);
                [Endpoint::begin(b, x.lower), Endpoint::end(b, x.upper)]
            })
            .collect();
        axis.sort_unstable_by(Endpoint::order);
        axis
    }

    fn keys(axis: &[Endpoint]) -> Vec<u32> {
        axis.iter().map(|e| e.key).collect()
    }

    /// Moves of every size: most by a hundredth of a box, one in twenty by a few boxes (across segments of 16
    /// endpoints, so segments join), about one a round by up to half the row (which joins all segments it passes);
    /// then the segmented sort must end in the same order with the same changes in the same order as one insertion
    /// sort, for short and long segments on 1 to 4 threads.
    #[test]
    fn segments_swap_what_one_sort_swaps_in_the_same_order() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let count = 2_000;
        let mut boxes = row_of_boxes(count, &mut rng);
        let mut bodies = Bodies::default();
        for (body, aabb) in boxes.iter().enumerate() {
            bodies.make_pending(body as u32, BodyKind::Particle, aabb);
            bodies.set_state(body as u32, SlotState::Active);
        }
        let mut axis = sorted_axis(&bodies);
        let (mut several_groups, mut joined_segments) = (0, 0);
        for round in 0..20 {
            for aabb in &mut boxes {
                let shift = match rng.random_range(0..4000) {
                    0 => rng.random_range(-1000.0..1000.0),
                    1..200 => rng.random_range(-3.0..3.0),
                    _ => rng.random_range(-0.01..0.01),
                };
                *aabb = Aabb { min: aabb.min + DVec2::new(shift, 0.0), max: aabb.max + DVec2::new(shift, 0.0) };
            }
            bodies.take_boxes(&boxes);
            let mut expected_axis = axis.clone();
            let mut expected_changes = Vec::new();
            let expected_swaps = insertion_sort(&mut expected_axis, 0, &bodies, &mut expected_changes);
            for (segment_len, threads) in [(16, 4), (16, 1), (100, 3), (ENDPOINTS_PER_SEGMENT, 2)] {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let mut sorted = axis.clone();
                let mut segmented = SegmentedSort::default();
                let swaps = pool.install(|| segmented.sort_in_segments(&mut sorted, 0, &bodies, segment_len));
                if (segment_len, threads) == (16, 4) {
                    let groups = segmented.group_starts.len() - 1;
                    several_groups += usize::from(groups > 10);
                    joined_segments += sorted.len() / 16 - groups;
                }
                let changes: Vec<PairChange> = segmented.changes().collect();
                let case = format!("round {round}, segments of {segment_len} on {threads} threads");
                assert!(keys(&sorted) == keys(&expected_axis), "{case}: the order differs");
                assert!(changes == expected_changes, "{case}: the changes differ");
                assert_eq!(swaps, expected_swaps);
            }
            axis = expected_axis;
        }
        assert!(several_groups >= 5, "only {several_groups} rounds were sorted in more than ten groups");
        assert!(joined_segments > 100, "moves across segments should join them ({joined_segments} joined)");
    }

    /// An empty axis is one empty group and sorts to nothing.
    #[test]
    fn a_short_or_empty_axis_is_one_group() {
        let mut segmented = SegmentedSort::default();
        let bodies = Bodies::default();
        assert_eq!(segmented.sort(&mut [], 0, &bodies), 0);
        assert_eq!(segmented.group_starts, [0, 0]);
        assert_eq!(segmented.changes().count(), 0);
    }
}
