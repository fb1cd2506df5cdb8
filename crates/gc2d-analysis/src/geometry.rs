//! Plane geometry the analyses share: axis-aligned test rectangles, convex hulls, polygon areas and clipping.

use gc2d_geometry::{DVec2, OverlapPolygon, cross, overlap_polygon};
use serde::Serialize;

/// An axis-aligned test area (reference §5.6, §5.7).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Rect {
    /// Lower-left corner, m.
    pub min: DVec2,
    /// Upper-right corner, m.
    pub max: DVec2,
}

impl Rect {
    /// The rectangle spanned by two corners (in any order).
    pub fn new(a: DVec2, b: DVec2) -> Self {
        Self { min: a.min(b), max: a.max(b) }
    }

    /// The rectangle of `size` centred on `center`.
    pub fn centered(center: DVec2, size: DVec2) -> Self {
        Self::new(center - 0.5 * size.abs(), center + 0.5 * size.abs())
    }

    /// The tight box around `points`; `None` when there are none or one is not finite.
    pub fn bounding(points: impl IntoIterator<Item = DVec2>) -> Option<Self> {
        let mut iter = points.into_iter();
        let first = iter.next()?;
        let (min, max) = iter.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p)));
        (min.is_finite() && max.is_finite()).then_some(Self { min, max })
    }

    /// Width and height, m.
    pub fn size(&self) -> DVec2 {
        self.max - self.min
    }

    /// Area, m².
    pub fn area(&self) -> f64 {
        let size = self.size();
        size.x * size.y
    }

    /// Centroid, m.
    pub fn center(&self) -> DVec2 {
        0.5 * (self.min + self.max)
    }

    /// True when `p` is inside or on the boundary.
    pub fn contains(&self, p: DVec2) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }

    /// The four corners, counter-clockwise from the lower left.
    pub fn corners(&self) -> [DVec2; 4] {
        [self.min, DVec2::new(self.max.x, self.min.y), self.max, DVec2::new(self.min.x, self.max.y)]
    }

    /// True when the rectangle has a positive, finite area.
    pub fn is_proper(&self) -> bool {
        let size = self.size();
        size.is_finite() && size.x > 0.0 && size.y > 0.0
    }
}

/// Area of a simple polygon given in order (shoelace); positive when counter-clockwise.
pub fn polygon_area(vertices: &[DVec2]) -> f64 {
    let n = vertices.len();
    if n < 3 {
        return 0.0;
    }
    0.5 * (0..n).map(|i| cross(vertices[i], vertices[(i + 1) % n])).sum::<f64>()
}

/// Convex hull of `points`, counter-clockwise without collinear points (Andrew's monotone chain). Non-finite
/// points are ignored. Fewer than three distinct non-collinear points give a degenerate hull (its area is 0).
pub fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut sorted: Vec<DVec2> = points.iter().copied().filter(|p| p.is_finite()).collect();
    sorted.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    sorted.dedup();
    if sorted.len() < 3 {
        return sorted;
    }
    let mut hull: Vec<DVec2> = Vec::with_capacity(2 * sorted.len());
    let turns_left = |hull: &[DVec2], p: DVec2| {
        let n = hull.len();
        cross(hull[n - 1] - hull[n - 2], p - hull[n - 2]) > 0.0
    };
    for &p in &sorted {
        while hull.len() >= 2 && !turns_left(&hull, p) {
            hull.pop();
        }
        hull.push(p);
    }
    let lower_len = hull.len() + 1;
    for &p in sorted.iter().rev().skip(1) {
        while hull.len() >= lower_len && !turns_left(&hull, p) {
            hull.pop();
        }
        hull.push(p);
    }
    hull.pop();
    hull
}

/// Area of the convex hull of `points`, m².
pub fn hull_area(points: &[DVec2]) -> f64 {
    polygon_area(&convex_hull(points)).max(0.0)
}

/// Writes the part of the convex polygon `polygon` inside `rect` into `out` (empty when they do not overlap or the
/// polygon is not admissible), using the engine's exact convex clipping.
pub fn clip_to_rect(polygon: &[DVec2], rect: &Rect, out: &mut OverlapPolygon) {
    if !rect.is_proper() {
        overlap_polygon(&[], &[], out);
        return;
    }
    overlap_polygon(polygon, &rect.corners(), out);
}

/// Highest point of the convex polygon's outline above `x` (the upper boundary), or `None` when `x` is outside its
/// horizontal extent.
pub fn upper_boundary_at(polygon: &[DVec2], x: f64) -> Option<f64> {
    let n = polygon.len();
    let mut top: Option<f64> = None;
    for i in 0..n {
        let (p, q) = (polygon[i], polygon[(i + 1) % n]);
        let (lo, hi) = if p.x <= q.x { (p, q) } else { (q, p) };
        if x < lo.x || x > hi.x {
            continue;
        }
        let y = if hi.x - lo.x > 0.0 { lo.y + (hi.y - lo.y) * (x - lo.x) / (hi.x - lo.x) } else { lo.y.max(hi.y) };
        if y.is_finite() {
            top = Some(top.map_or(y, |t: f64| t.max(y)));
        }
    }
    top
}
