//! Which bodies' boxes meet a given box: the spatial query of the free-spot test of sources and inlets, answered
//! from the sorted axes instead of a scan over every body, so that inserting a particle costs the same at 100 and at
//! 1,000,000 bodies (issue 18, item 4).
//!
//! A box that meets the query box `[a, b]` on an axis begins at or before `b` and ends at or after `a`, so it begins
//! at or after `a − w`, with `w` the widest box on that axis. The walls are few but can be as wide as the scene (a
//! floor), so they are kept in a list of their own and `w` is the widest *dynamic* box, measured by
//! [`SortAndSweep::update_for_queries`] in the pass that reads the boxes anyway (after a plain update `w` is
//! unknown and a query walks a whole axis). A query then binary-searches both axes for the endpoints in the window
//! `[a − w, b]`, walks the axis whose window holds fewer (above a pile a source's box meets few falling particles on
//! y; a wide flood of falling particles is sparse on x; with the y axis in bands, `broadphase::bands`, the x axis),
//! and tests the walls one by one. The bodies inserted since
//! the last update are not in the axes yet; a source can insert thousands in one step, so they are kept ordered by
//! the left ends of their boxes ([`PendingIndex`]) and queried the same way.
//!
//! The boxes are those of the last [`SortAndSweep::update`] (a body inserted since: the box it was inserted with).
//! The engine's per-body boxes (`Bodies::aabb`) change only in the same place, just before the update, so the query
//! finds exactly the bodies whose box a scan over `Bodies::aabb` would find.

use super::bands::FromTop;
use super::bodies::Interval;
use super::{Endpoint, SlotState, SortAndSweep};
use crate::BodyKind;
use gc2d_geometry::Aabb;
use std::collections::BTreeSet;

/// The extent a broadphase has before it has measured its boxes (after loading a checkpoint): unbounded, so that a
/// query then walks a whole axis rather than miss a box.
pub(super) fn unmeasured_extent() -> [f64; 2] {
    [f64::INFINITY; 2]
}

/// Relative widening of a query window against rounding in `a − w` (boxes' widths are differences of two rounded
/// numbers); a wider window only costs a few more candidates, never a wrong answer.
const WINDOW_SLACK: f64 = 1e-9;

impl<T: Default> SortAndSweep<T> {
    /// Calls `hit` with each body whose box meets (overlaps or touches) `query`, until `hit` returns true, and says
    /// whether one did. Each such body is offered at least once; others may be offered too, so `hit` does its own
    /// exact test. Walls come first, then bodies inserted since the last update, then the dynamic bodies of the
    /// axes.
    pub fn any_box_meeting(&self, query: &Aabb, mut hit: impl FnMut(u32) -> bool) -> bool {
        let query = [0, 1].map(|axis| Interval::sanitised(query.min[axis], query.max[axis]));
        let meets = |body: u32| self.bodies.box_meets(body, query);
        let offered = |body: u32, hit: &mut dyn FnMut(u32) -> bool| meets(body) && hit(body);
        let walls_hit = match &self.static_bodies {
            Some(statics) => statics.iter().any(|&body| offered(body, &mut hit)),
            None => (0..self.bodies.len() as u32)
                .filter(|&body| self.bodies.state(body) != SlotState::Absent)
                .filter(|&body| self.bodies.kind(body) == BodyKind::Wall)
                .any(|body| offered(body, &mut hit)),
        };
        if walls_hit {
            return true;
        }
        let pending_hit = match &self.pending_index {
            Some(index) => index.candidates(query[0]).any(|body| offered(body, &mut hit)),
            None => self
                .pending
                .iter()
                .filter(|&&body| self.bodies.kind(body) == BodyKind::Particle)
                .any(|&body| offered(body, &mut hit)),
        };
        if pending_hit {
            return true;
        }
        let x_window = self.window(0, query[0]);
        let (axis, window) = match &self.bands {
            // In bands (`broadphase::bands`) the y axis is no one sorted array to search.
            Some(_) => (0, x_window),
            None => {
                let y_window = self.window(1, query[1]);
                if x_window.len() <= y_window.len() { (0, x_window) } else { (1, y_window) }
            }
        };
        self.axes[axis][window]
            .iter()
            .filter(|e| !e.is_end())
            .map(|e| e.body())
            .filter(|&body| {
                self.bodies.state(body) == SlotState::Active && self.bodies.kind(body) == BodyKind::Particle
            })
            .any(|body| offered(body, &mut hit))
    }

    /// The dynamic bodies of the axes from the highest box top down, each with its top (y), as of the last update:
    /// every one whose box meets `x_min..=x_max` in x, and possibly others (the caller tests them). Bodies inserted
    /// since are not among them (see [`pending`](Self::pending)). Walks the sorted y axis from its end, so a caller
    /// looking for the highest body that passes a test stops after the first few; with the y axis in bands
    /// (`broadphase::bands`) it merges the ends of the bands that `x_min..=x_max` reaches into, looking at each of
    /// them for every body.
    pub fn dynamic_bodies_from_top(&self, x_min: f64, x_max: f64) -> impl Iterator<Item = (u32, f64)> + '_ {
        let endpoints = match &self.bands {
            None => YFromTop::Axis(self.axes[1].iter().rev()),
            Some(bands) => YFromTop::Bands(bands.endpoints_from_top(Interval::sanitised(x_min, x_max))),
        };
        endpoints
            .filter(|e| e.is_end())
            .filter(|e| {
                self.bodies.state(e.body()) == SlotState::Active && self.bodies.kind(e.body()) == BodyKind::Particle
            })
            .map(|e| (e.body(), e.value))
    }

    /// Bodies inserted since the last update, in insertion order: not yet in the axes.
    pub fn pending(&self) -> &[u32] {
        &self.pending
    }

    /// The index range of the endpoints of `axis` whose values lie in `[a − w − slack, b]`: every begin of a dynamic
    /// box meeting `[a, b]` is in it.
    fn window(&self, axis: usize, query: Interval) -> std::ops::Range<usize> {
        let extent = self.dynamic_extent[axis];
        let low = query.lower - extent - WINDOW_SLACK * (extent + query.lower.abs());
        let endpoints = &self.axes[axis];
        let start = endpoints.partition_point(|e: &Endpoint| e.value < low);
        let end = start + endpoints[start..].partition_point(|e: &Endpoint| e.value <= query.upper);
        start..end
    }
}

/// The y endpoints from the highest down: of the one y axis, or merged from its bands.
enum YFromTop<'a> {
    Axis(std::iter::Rev<std::slice::Iter<'a, Endpoint>>),
    Bands(FromTop<'a>),
}

impl Iterator for YFromTop<'_> {
    type Item = Endpoint;

    fn next(&mut self) -> Option<Endpoint> {
        match self {
            Self::Axis(endpoints) => endpoints.next().copied(),
            Self::Bands(endpoints) => endpoints.next(),
        }
    }
}

/// The dynamic bodies inserted since the last update, ordered by the left ends (x) of their boxes, so that a query
/// finds those near it without a pass over all of them.
#[derive(Debug, Clone, Default)]
pub(super) struct PendingIndex {
    /// (left end as [`ordered_bits`], body).
    by_left_end: BTreeSet<(u64, u32)>,
    /// The widest of their boxes (x); bounds how far left of a query a meeting box can begin.
    widest: f64,
}

impl PendingIndex {
    /// Adds `body` with the x interval of its box.
    pub(super) fn insert(&mut self, body: u32, x: Interval) {
        self.by_left_end.insert((ordered_bits(x.lower), body));
        self.widest = self.widest.max(x.upper - x.lower);
    }

    /// Removes `body`, inserted with the x interval `x`.
    pub(super) fn remove(&mut self, body: u32, x: Interval) {
        self.by_left_end.remove(&(ordered_bits(x.lower), body));
    }

    /// Heap bytes of its entries (the tree's node overhead is not counted).
    pub(super) fn heap_bytes(&self) -> usize {
        self.by_left_end.len() * std::mem::size_of::<(u64, u32)>()
    }

    /// Forgets every body (they have joined the axes).
    pub(super) fn clear(&mut self) {
        self.by_left_end.clear();
        self.widest = 0.0;
    }

    /// The bodies whose boxes begin in `[a − w − slack, b]` for the query interval `[a, b]` on x: all that can meet
    /// it.
    fn candidates(&self, x: Interval) -> impl Iterator<Item = u32> + '_ {
        let low = x.lower - self.widest - WINDOW_SLACK * (self.widest + x.lower.abs());
        self.by_left_end.range((ordered_bits(low), 0)..=(ordered_bits(x.upper), u32::MAX)).map(|&(_, body)| body)
    }
}

/// The bits of `x` as an integer that orders as the numbers do (−∞ first, −0 just before +0).
fn ordered_bits(x: f64) -> u64 {
    let bits = x.to_bits();
    if bits >> 63 == 1 { !bits } else { bits | 1 << 63 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gc2d_geometry::DVec2;
    use proptest::prelude::*;

    fn aabb(x: f64, y: f64, w: f64, h: f64) -> Aabb {
        Aabb { min: DVec2::new(x, y), max: DVec2::new(x + w, y + h) }
    }

    /// Bodies whose box meets `query`, found by asking the broadphase for every one (the query stops at the first
    /// hit, so a hit that always says no collects them all).
    fn offered(sweep: &SortAndSweep<()>, query: &Aabb) -> Vec<u32> {
        let mut bodies = Vec::new();
        sweep.any_box_meeting(query, |body| {
            bodies.push(body);
            false
        });
        bodies
    }

    proptest! {
        /// Every body whose box (as the broadphase holds it) meets the query is offered, for walls wider than the
        /// scene, bodies inserted or removed since the last update, and a broadphase read back from a checkpoint
        /// (no wall list and no measured extent until its next update).
        #[test]
        fn every_meeting_box_is_offered(
            boxes in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64, 0.0..0.1f64, 0.0..0.1f64), 1..60),
            walls in prop::collection::vec(0usize..60, 0..4),
            removed in prop::collection::vec(0usize..60, 0..6),
            late in 0usize..10,
            queries in prop::collection::vec((-1.2..1.2f64, -1.2..1.2f64, 0.0..0.2f64, 0.0..0.2f64), 1..20),
            reload in any::<bool>(),
            banded in any::<bool>(),
        ) {
            let mut aabbs: Vec<Aabb> = boxes.iter().map(|&(x, y, w, h)| aabb(x, y, w, h)).collect();
            let is_wall = |i: usize| walls.contains(&i);
            for &i in &walls {
                if i < aabbs.len() {
                    aabbs[i] = aabb(-5.0, aabbs[i].min.y, 10.0, 0.01); // a floor as wide as everything
                }
            }
            let kind = |i: usize| if is_wall(i) { BodyKind::Wall } else { BodyKind::Particle };
            let settled = aabbs.len().saturating_sub(late);
            let mut sweep = SortAndSweep::<()>::new();
            for (i, b) in aabbs.iter().enumerate().take(settled) {
                sweep.insert(i as u32, *b, kind(i)).unwrap();
            }
            if banded {
                sweep.band_y_axis(0.3);
            }
            sweep.update_for_queries(&aabbs);
            // The particles move (and turn, changing their boxes' sizes) before the next update.
            for (i, b) in aabbs.iter_mut().enumerate().filter(|(i, _)| !is_wall(*i)) {
                let (shift, grow) = (DVec2::new(0.3 * (i as f64).sin(), 0.2 * (i as f64).cos()), 0.05 * (i % 3) as f64);
                *b = Aabb { min: b.min + shift, max: b.max + shift + DVec2::splat(grow) };
            }
            sweep.update_for_queries(&aabbs);
            if reload {
                let bytes = postcard::to_allocvec(&sweep).unwrap();
                sweep = postcard::from_bytes(&bytes).unwrap();
            }
            for (i, b) in aabbs.iter().enumerate().skip(settled) {
                sweep.insert(i as u32, *b, kind(i)).unwrap();
            }
            for &i in &removed {
                sweep.remove(i as u32);
            }
            for &(x, y, w, h) in &queries {
                let query = aabb(x, y, w, h);
                let mut found = offered(&sweep, &query);
                found.sort_unstable();
                found.dedup();
                let expected: Vec<u32> = (0..aabbs.len())
                    .filter(|&i| sweep.contains(i as u32) && aabbs[i].overlaps(&query))
                    .map(|i| i as u32)
                    .collect();
                prop_assert_eq!(found, expected);
            }
        }
    }

    #[test]
    fn a_query_stops_at_the_first_hit() {
        let mut sweep = SortAndSweep::<()>::new();
        let boxes: Vec<Aabb> = (0..5).map(|i| aabb(i as f64 * 0.1, 0.0, 0.05, 0.05)).collect();
        for (i, b) in boxes.iter().enumerate() {
            sweep.insert(i as u32, *b, BodyKind::Particle).unwrap();
        }
        sweep.update(&boxes);
        let mut asked = 0;
        assert!(sweep.any_box_meeting(&aabb(-1.0, -1.0, 2.0, 2.0), |_| {
            asked += 1;
            true
        }));
        assert_eq!(asked, 1);
    }

    #[test]
    fn dynamic_bodies_come_from_the_highest_top_down_without_walls() {
        let mut sweep = SortAndSweep::<()>::new();
        let boxes =
            [aabb(0.0, 0.0, 1.0, 0.3), aabb(0.0, 0.5, 1.0, 0.1), aabb(-5.0, 2.0, 10.0, 1.0), aabb(0.0, -1.0, 0.1, 0.1)];
        let kinds = [BodyKind::Particle, BodyKind::Particle, BodyKind::Wall, BodyKind::Particle];
        for (i, (b, kind)) in boxes.iter().zip(kinds).enumerate() {
            sweep.insert(i as u32, *b, kind).unwrap();
        }
        sweep.update(&boxes);
        let order: Vec<u32> = sweep.dynamic_bodies_from_top(-1.0, 1.0).map(|(body, _)| body).collect();
        assert_eq!(order, [1, 0, 3]);
    }

    /// With the y axis in bands the bands' ends are merged: every dynamic body once (body 1 lies in two bands), from
    /// the highest top down, with its top, exactly as from one axis (bodies 2 and 5 tie at 0.6: the larger id first);
    /// a walk over part of the width merges only the bands it reaches into.
    #[test]
    fn dynamic_bodies_come_from_the_top_down_out_of_bands() {
        let boxes = [
            aabb(0.0, 0.0, 0.1, 0.3),
            aabb(0.95, 0.2, 0.1, 0.2),
            aabb(2.5, 0.1, 0.1, 0.5),
            aabb(-5.0, 0.4, 10.0, 0.1),
            aabb(3.9, 0.6, 0.1, 0.05),
            aabb(1.5, 0.4, 0.1, 0.2),
        ];
        let kinds = |i: usize| if i == 3 { BodyKind::Wall } else { BodyKind::Particle };
        let order = |banded: bool| {
            let mut sweep = SortAndSweep::<()>::new();
            for (i, b) in boxes.iter().enumerate() {
                sweep.insert(i as u32, *b, kinds(i)).unwrap();
            }
            if banded {
                assert!(sweep.band_y_axis(1.0));
                assert_eq!(sweep.y_bands(), 4);
            }
            sweep.update(&boxes);
            let all = sweep.dynamic_bodies_from_top(0.0, 4.0).collect::<Vec<_>>();
            // Over x in [1.2, 1.6] (band 1 of 4): the bodies of band 1 only when in bands, body 5 among them.
            let near = sweep.dynamic_bodies_from_top(1.2, 1.6).map(|(body, _)| body).collect::<Vec<_>>();
            (all, near)
        };
        let ((banded, near_banded), (single, near_single)) = (order(true), order(false));
        assert_eq!(banded, single);
        assert_eq!(banded.iter().map(|&(body, _)| body).collect::<Vec<_>>(), [4, 5, 2, 1, 0]);
        assert_eq!(near_banded, [5, 1]);
        assert_eq!(near_single, [4, 5, 2, 1, 0]);
    }
}
