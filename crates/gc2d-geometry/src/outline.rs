//! A body's outline traced as polygons, for pictures and for analyses that read boundaries as vertices: a polygon as
//! it is, disks and capsules as fine polygons (visually exact circles), and an inner circle (a chamber wall, solid
//! outside) as a ring around the chamber.

use crate::{DVec2, ShapeView};
use std::borrow::Cow;
use std::f64::consts::{PI, TAU};

/// Corners of a drawn full circle: at 48 the chord error is 0.2 % of the radius, below a pixel for a disk 200
/// pixels across.
pub const CIRCLE_SEGMENTS: usize = 48;

/// Width of the ring drawn for an inner circle, as a fraction of its radius.
const RING_WIDTH_FRACTION: f64 = 0.06;

/// A traced outline.
#[derive(Debug, Clone, PartialEq)]
pub enum TracedOutline<'a> {
    /// A convex polygon, counter-clockwise (a polygon's own vertices, or a disk or capsule traced finely).
    Convex(Cow<'a, [DVec2]>),
    /// The band between two concentric circles traced with the same number of corners: an inner circle's wall.
    Ring {
        /// The chamber's circle.
        inner: Vec<DVec2>,
        /// The ring's outer edge.
        outer: Vec<DVec2>,
    },
}

impl<'a> ShapeView<'a> {
    /// The outline traced as polygons.
    pub fn traced_outline(&self) -> TracedOutline<'a> {
        match *self {
            ShapeView::Polygon(vertices) => TracedOutline::Convex(Cow::Borrowed(vertices)),
            ShapeView::Disk { center, radius } => {
                TracedOutline::Convex(Cow::Owned(arc(center, radius, 0.0, TAU, CIRCLE_SEGMENTS)))
            }
            ShapeView::Capsule { a, b, radius } => {
                let axis = b - a;
                let angle = if axis.length_squared() > 0.0 { axis.y.atan2(axis.x) } else { 0.0 };
                let half = CIRCLE_SEGMENTS / 2;
                let mut points = arc(b, radius, angle - 0.5 * PI, PI, half + 1);
                points.extend(arc(a, radius, angle + 0.5 * PI, PI, half + 1));
                TracedOutline::Convex(Cow::Owned(points))
            }
            ShapeView::InnerCircle { center, radius } => TracedOutline::Ring {
                inner: arc(center, radius, 0.0, TAU, 2 * CIRCLE_SEGMENTS),
                outer: arc(center, radius * (1.0 + RING_WIDTH_FRACTION), 0.0, TAU, 2 * CIRCLE_SEGMENTS),
            },
        }
    }
}

impl TracedOutline<'_> {
    /// The outline as one loop of vertices: a convex outline's own, a ring's inner circle (the boundary particles
    /// touch).
    pub fn boundary(&self) -> &[DVec2] {
        match self {
            TracedOutline::Convex(vertices) => vertices,
            TracedOutline::Ring { inner, .. } => inner,
        }
    }
}

/// `count` points on the circle about `center` of radius `radius`, counter-clockwise from angle `start` over
/// `sweep` radians (a full turn leaves out the end point, which is the start point).
fn arc(center: DVec2, radius: f64, start: f64, sweep: f64, count: usize) -> Vec<DVec2> {
    let full_turn = (sweep - TAU).abs() < 1e-12;
    let steps = if full_turn { count } else { count.saturating_sub(1).max(1) };
    (0..count).map(|k| center + radius * DVec2::from_angle(start + sweep * k as f64 / steps as f64)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn perimeter(vertices: &[DVec2]) -> f64 {
        let n = vertices.len();
        (0..n).map(|k| vertices[k].distance(vertices[(k + 1) % n])).sum()
    }

    #[test]
    fn arcs_close_full_turns_and_reach_their_ends() {
        let circle = arc(DVec2::ZERO, 2.0, 0.0, TAU, 4);
        assert_eq!(circle.len(), 4);
        assert!((circle[1] - DVec2::new(0.0, 2.0)).length() < 1e-12);
        let half = arc(DVec2::ZERO, 1.0, 0.0, PI, 3);
        assert!((half[2] - DVec2::new(-1.0, 0.0)).length() < 1e-12);
        let traced = perimeter(&arc(DVec2::ZERO, 1.0, 0.0, TAU, CIRCLE_SEGMENTS));
        assert!((traced - TAU).abs() < 0.003 * TAU, "{traced}");
    }
}
