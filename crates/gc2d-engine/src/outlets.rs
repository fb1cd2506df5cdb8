//! Particle outlets (feedpipe.md §2.12, §4.9.2): a segment of the boundary that removes every particle whose centre
//! crosses it outward. Outlets are not walls: particles feel no force from them.
//!
//! Orientation as for inlets: walking from `from` to `to`, the domain lies on the **left**. A particle is removed when
//! its centre was on the segment's line or on its inner side at the start of a step, is strictly on the outer side at
//! the end, and the straight path between the two positions meets the segment within its extent (ends included). A
//! particle crossing inward, or passing beside the segment, stays.

use gc2d_geometry::{DVec2, cross};
use serde::{Deserialize, Serialize};

/// A particle outlet: the segment from `from` to `to`, the domain on its left.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outlet {
    /// The name its counter goes by (in time series and summaries).
    pub name: String,
    /// First end of the segment, m.
    pub from: DVec2,
    /// Second end of the segment, m.
    pub to: DVec2,
}

impl Outlet {
    /// True when a centre moving from `before` to `after` crosses the segment from the inner (left) side to the outer
    /// side.
    pub fn crossed_outward(&self, before: DVec2, after: DVec2) -> bool {
        let edge = self.to - self.from;
        // Positive on the inner side (left of the edge), negative outside.
        let side_before = cross(edge, before - self.from);
        let side_after = cross(edge, after - self.from);
        if !(side_before >= 0.0 && side_after < 0.0) {
            return false;
        }
        // Where the path meets the edge's line, as a fraction of the edge, 0 at `from` and 1 at `to`.
        let fraction = side_before / (side_before - side_after);
        let hit = before + (after - before) * fraction;
        let along = (hit - self.from).dot(edge) / edge.length_squared();
        (0.0..=1.0).contains(&along)
    }
}

/// What an outlet did since the start.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct OutletCounters {
    /// Particles removed.
    pub removed: u64,
}

/// An outlet and its counters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OutletState {
    outlet: Outlet,
    counters: OutletCounters,
}

impl OutletState {
    /// An outlet that has removed nothing yet.
    pub(crate) fn new(outlet: Outlet) -> Self {
        Self { outlet, counters: OutletCounters::default() }
    }

    /// The outlet.
    pub fn outlet(&self) -> &Outlet {
        &self.outlet
    }

    /// Its counters.
    pub fn counters(&self) -> OutletCounters {
        self.counters
    }

    /// Books one removed particle.
    pub(crate) fn removed(&mut self) {
        self.counters.removed += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_an_outward_crossing_within_the_segment_counts() {
        // A floor outlet from (1, 0) to (0, 0): the domain is below it (left walking in −x), outside is above.
        let outlet = Outlet { name: "top".into(), from: DVec2::new(1.0, 0.0), to: DVec2::new(0.0, 0.0) };
        let below = DVec2::new(0.5, -0.01);
        let above = DVec2::new(0.5, 0.01);
        assert!(outlet.crossed_outward(below, above));
        assert!(!outlet.crossed_outward(above, below), "inward");
        assert!(!outlet.crossed_outward(DVec2::new(1.5, -0.01), DVec2::new(1.5, 0.01)), "beside");
        assert!(!outlet.crossed_outward(below, DVec2::new(0.5, -0.001)), "stays inside");
        assert!(outlet.crossed_outward(DVec2::new(1.0, -0.01), DVec2::new(1.0, 0.01)), "at an end");
        assert!(outlet.crossed_outward(DVec2::new(0.5, 0.0), above), "from the line");
    }
}
