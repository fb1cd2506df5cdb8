//! Validated convex polygons in their body frame and their mass properties (reference §1.1, §1.3).

use crate::{DVec2, cross};
use thiserror::Error;

/// Most vertices a polygon may have: gc2d's `MAX_NUM_CORNERS`. Fixed so the contact routines can work in stack
/// buffers (an overlap of two polygons has at most `2 * MAX_VERTICES` vertices) and never allocate.
pub const MAX_VERTICES: usize = 64;

/// A turn at a vertex whose sine is below this (relative to the two edge lengths) counts as collinear.
/// 1e-9 rad is far below any shape a generator or a user means to make, and far above round-off.
pub const COLLINEAR_SIN_TOLERANCE: f64 = 1e-9;

/// An edge shorter than this fraction of the polygon's diameter counts as zero-length.
pub const MIN_EDGE_FRACTION: f64 = 1e-9;

/// Why a list of vertices is not an admissible particle or wall outline. Vertex indices refer to the caller's
/// input order (0-based).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PolygonError {
    /// Fewer than three vertices: segments and points have no overlap area and feel no force (reference §1.1).
    #[error("a polygon needs at least 3 vertices, got {0}")]
    TooFewVertices(usize),
    /// More than [`MAX_VERTICES`] vertices.
    #[error("a polygon may have at most {MAX_VERTICES} vertices, got {0}")]
    TooManyVertices(usize),
    /// A coordinate is NaN or infinite.
    #[error("vertex {0} has a coordinate that is not a finite number")]
    NotFinite(usize),
    /// Two consecutive vertices coincide (within [`MIN_EDGE_FRACTION`] of the diameter).
    #[error("vertices {0} and {1} coincide: the edge between them has zero length")]
    ZeroLengthEdge(usize, usize),
    /// A vertex lies on the line through its two neighbours (within [`COLLINEAR_SIN_TOLERANCE`]).
    #[error("vertex {0} is collinear with its neighbours; remove it")]
    Collinear(usize),
    /// The outline turns the wrong way at this vertex.
    #[error("the polygon is not convex at vertex {0}")]
    NotConvex(usize),
    /// Every turn has the same sense but the outline winds around more than once (a star such as a pentagram).
    #[error("the outline crosses itself (it winds around more than once)")]
    SelfIntersecting,
}

/// Mass and moment of inertia about the centroid of a polygon of homogeneous area density (per unit thickness).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// Mass in kg (per unit thickness: area density × area).
    pub mass: f64,
    /// Moment of inertia about the centroid in kg·m².
    pub inertia: f64,
}

/// A convex polygon in its body frame: counter-clockwise vertices with the centroid at the origin.
///
/// Construction validates the outline, so every `ConvexPolygon` is convex, has no zero-length edges, no collinear
/// vertices, and at most [`MAX_VERTICES`] vertices. Area and second moment are computed once here, by splitting the
/// polygon into triangles with one corner at the centroid (reference §1.3, eqs. 2.10–2.12).
#[derive(Debug, Clone, PartialEq)]
pub struct ConvexPolygon {
    vertices: Vec<DVec2>,
    area: f64,
    polar_second_moment: f64,
    bounding_radius: f64,
    inscribed_radius: f64,
}

impl ConvexPolygon {
    /// Validates `vertices` (either orientation; clockwise input is re-oriented) and moves the centroid to the origin.
    ///
    /// Returns the body-frame polygon and the centroid of the input vertices, i.e. where the body origin sits in the
    /// input's frame. A particle is then placed by its centroid; a wall keeps the returned centroid as its position.
    pub fn new(vertices: &[DVec2]) -> Result<(Self, DVec2), PolygonError> {
        let n = vertices.len();
        if n < 3 {
            return Err(PolygonError::TooFewVertices(n));
        }
        if n > MAX_VERTICES {
            return Err(PolygonError::TooManyVertices(n));
        }
        if let Some(i) = vertices.iter().position(|v| !v.is_finite()) {
            return Err(PolygonError::NotFinite(i));
        }
        // Work relative to the first vertex so that far-from-origin input loses no precision in the cross products.
        let origin = vertices[0];
        let local: Vec<DVec2> = vertices.iter().map(|&v| v - origin).collect();
        let diameter = local.iter().flat_map(|a| local.iter().map(move |b| (*a - *b).length())).fold(0.0, f64::max);
        for i in 0..n {
            let j = (i + 1) % n;
            if (local[j] - local[i]).length() <= MIN_EDGE_FRACTION * diameter {
                return Err(PolygonError::ZeroLengthEdge(i, j));
            }
        }
        let twice_area: f64 = (0..n).map(|i| cross(local[i], local[(i + 1) % n])).sum();
        // Map an index in counter-clockwise order back to the caller's index.
        let reversed = twice_area < 0.0;
        let input_index = |k: usize| if reversed { n - 1 - k } else { k };
        let ccw: Vec<DVec2> = if reversed { local.iter().rev().copied().collect() } else { local };
        let mut turning = 0.0;
        for k in 0..n {
            let before = ccw[k] - ccw[(k + n - 1) % n];
            let after = ccw[(k + 1) % n] - ccw[k];
            let sine = cross(before, after) / (before.length() * after.length());
            if sine.abs() <= COLLINEAR_SIN_TOLERANCE {
                return Err(PolygonError::Collinear(input_index(k)));
            }
            if sine < 0.0 {
                return Err(PolygonError::NotConvex(input_index(k)));
            }
            turning += cross(before, after).atan2(before.dot(after));
        }
        if turning > 3.0 * std::f64::consts::PI {
            return Err(PolygonError::SelfIntersecting);
        }
        let (area, centroid_local) = area_and_centroid(&ccw);
        let body: Vec<DVec2> = ccw.iter().map(|&v| v - centroid_local).collect();
        let polar_second_moment = polar_second_moment_about_origin(&body);
        let bounding_radius = body.iter().map(|v| v.length()).fold(0.0, f64::max);
        let inscribed_radius = (0..n)
            .map(|i| {
                let a = body[i];
                let edge = body[(i + 1) % n] - a;
                cross(edge, -a) / edge.length()
            })
            .fold(f64::INFINITY, f64::min);
        let polygon = Self { vertices: body, area, polar_second_moment, bounding_radius, inscribed_radius };
        Ok((polygon, origin + centroid_local))
    }

    /// Body-frame vertices, counter-clockwise, centroid at the origin.
    pub fn vertices(&self) -> &[DVec2] {
        &self.vertices
    }

    /// Number of vertices (equal to the number of edges).
    pub fn len(&self) -> usize {
        self.vertices.len()
    }

    /// Always false: a valid polygon has at least three vertices. Present because `len` is.
    pub fn is_empty(&self) -> bool {
        self.vertices.is_empty()
    }

    /// Area in m².
    pub fn area(&self) -> f64 {
        self.area
    }

    /// Polar second moment of area about the centroid, ∫ r² dA, in m⁴.
    pub fn polar_second_moment(&self) -> f64 {
        self.polar_second_moment
    }

    /// Largest distance from the centroid to a vertex: the radius of the smallest centred circle around the polygon.
    pub fn bounding_radius(&self) -> f64 {
        self.bounding_radius
    }

    /// Radius of the largest circle about the centroid that fits inside the polygon: the smallest distance from the
    /// centroid to an edge line. The time-step bound uses it for elongated particles (reference §3.6).
    pub fn inscribed_radius(&self) -> f64 {
        self.inscribed_radius
    }

    /// Mass and moment of inertia for a homogeneous area density in kg/m².
    pub fn mass_properties(&self, area_density: f64) -> MassProperties {
        MassProperties { mass: area_density * self.area, inertia: area_density * self.polar_second_moment }
    }
}

/// Area and centroid of a counter-clockwise polygon, from triangles (0, p_i, p_{i+1}) (reference eqs. 2.10, 2.11).
fn area_and_centroid(ccw: &[DVec2]) -> (f64, DVec2) {
    let n = ccw.len();
    let mut twice_area = 0.0;
    let mut weighted = DVec2::ZERO;
    for i in 0..n {
        let (p, q) = (ccw[i], ccw[(i + 1) % n]);
        let c = cross(p, q);
        twice_area += c;
        weighted += (p + q) * c;
    }
    (0.5 * twice_area, weighted / (3.0 * twice_area))
}

/// ∫ r² dA about the origin, summed over triangles (0, p, q): (p×q)/12 · (p·p + p·q + q·q) (reference eq. 2.12).
fn polar_second_moment_about_origin(ccw: &[DVec2]) -> f64 {
    let n = ccw.len();
    (0..n)
        .map(|i| {
            let (p, q) = (ccw[i], ccw[(i + 1) % n]);
            cross(p, q) / 12.0 * (p.dot(p) + p.dot(q) + q.dot(q))
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use std::f64::consts::PI;

    fn v(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    fn rectangle(w: f64, h: f64, at: DVec2) -> Vec<DVec2> {
        vec![at, at + v(w, 0.0), at + v(w, h), at + v(0.0, h)]
    }

    #[test]
    fn rectangle_mass_properties_match_closed_form() {
        let (w, h) = (0.3, 0.07);
        let (poly, centroid) = ConvexPolygon::new(&rectangle(w, h, v(5.0, -2.0))).unwrap();
        assert_relative_eq!(centroid, v(5.15, -1.965), max_relative = 1e-14);
        assert_relative_eq!(poly.area(), w * h, max_relative = 1e-12);
        assert_relative_eq!(poly.polar_second_moment(), w * h * (w * w + h * h) / 12.0, max_relative = 1e-12);
        let mp = poly.mass_properties(5000.0);
        assert_relative_eq!(mp.mass, 5000.0 * w * h, max_relative = 1e-12);
        assert_relative_eq!(mp.inertia, 5000.0 * w * h * (w * w + h * h) / 12.0, max_relative = 1e-12);
        assert_relative_eq!(poly.inscribed_radius(), h / 2.0, max_relative = 1e-12);
    }

    #[test]
    fn square_mass_properties_match_closed_form() {
        let a = 0.002;
        let (poly, _) = ConvexPolygon::new(&rectangle(a, a, v(0.1, 0.1))).unwrap();
        assert_relative_eq!(poly.area(), a * a, max_relative = 1e-12);
        assert_relative_eq!(poly.polar_second_moment(), a.powi(4) / 6.0, max_relative = 1e-12);
        assert_relative_eq!(poly.bounding_radius(), a / 2.0 * 2f64.sqrt(), max_relative = 1e-12);
    }

    #[test]
    fn triangle_mass_properties_match_closed_form() {
        // Right triangle with legs a (x) and b (y): centroid (a/3, b/3), J_c = ab(a² + b²)/36.
        let (a, b) = (0.4, 0.9);
        let (poly, centroid) = ConvexPolygon::new(&[v(0.0, 0.0), v(a, 0.0), v(0.0, b)]).unwrap();
        assert_relative_eq!(centroid, v(a / 3.0, b / 3.0), max_relative = 1e-14);
        assert_relative_eq!(poly.area(), a * b / 2.0, max_relative = 1e-12);
        assert_relative_eq!(poly.polar_second_moment(), a * b * (a * a + b * b) / 36.0, max_relative = 1e-12);
    }

    #[test]
    fn regular_polygon_mass_properties_match_closed_form() {
        for n in [3usize, 5, 7, 13, 64] {
            let r = 0.00175;
            let pts: Vec<DVec2> = (0..n)
                .map(|i| {
                    let phi = 2.0 * PI * i as f64 / n as f64;
                    v(1.0 + r * phi.cos(), 2.0 + r * phi.sin())
                })
                .collect();
            let (poly, centroid) = ConvexPolygon::new(&pts).unwrap();
            let nf = n as f64;
            let area = 0.5 * nf * r * r * (2.0 * PI / nf).sin();
            // J = (n r⁴ / 12) sin(2π/n) (2 + cos(2π/n)) for a regular n-gon of circumradius r.
            let j = nf * r.powi(4) / 12.0 * (2.0 * PI / nf).sin() * (2.0 + (2.0 * PI / nf).cos());
            assert_relative_eq!(poly.area(), area, max_relative = 1e-12);
            assert_relative_eq!(poly.polar_second_moment(), j, max_relative = 1e-12);
            assert_relative_eq!(centroid, v(1.0, 2.0), max_relative = 1e-14);
            assert_relative_eq!(poly.inscribed_radius(), r * (PI / nf).cos(), max_relative = 1e-12);
        }
    }

    #[test]
    fn clockwise_input_is_reoriented() {
        let mut pts = rectangle(1.0, 2.0, DVec2::ZERO);
        pts.reverse();
        let (poly, _) = ConvexPolygon::new(&pts).unwrap();
        assert!(poly.area() > 0.0);
        let vs = poly.vertices();
        let twice_area: f64 = (0..vs.len()).map(|i| cross(vs[i], vs[(i + 1) % vs.len()])).sum();
        assert_relative_eq!(twice_area, 4.0, max_relative = 1e-12);
    }

    #[test]
    fn invalid_outlines_are_named() {
        assert_eq!(ConvexPolygon::new(&[v(0.0, 0.0), v(1.0, 0.0)]).unwrap_err(), PolygonError::TooFewVertices(2));
        let dart = [v(0.0, 0.0), v(2.0, 0.0), v(1.0, 0.5), v(1.0, 2.0)];
        assert_eq!(ConvexPolygon::new(&dart).unwrap_err(), PolygonError::NotConvex(2));
        let collinear = [v(0.0, 0.0), v(1.0, 0.0), v(2.0, 0.0), v(2.0, 1.0)];
        assert_eq!(ConvexPolygon::new(&collinear).unwrap_err(), PolygonError::Collinear(1));
        let repeated = [v(0.0, 0.0), v(1.0, 0.0), v(1.0, 0.0), v(0.0, 1.0)];
        assert_eq!(ConvexPolygon::new(&repeated).unwrap_err(), PolygonError::ZeroLengthEdge(1, 2));
        let nan = [v(0.0, 0.0), v(f64::NAN, 0.0), v(0.0, 1.0)];
        assert_eq!(ConvexPolygon::new(&nan).unwrap_err(), PolygonError::NotFinite(1));
        let pentagram: Vec<DVec2> = (0..5)
            .map(|i| {
                let phi = 4.0 * PI * i as f64 / 5.0;
                v(phi.cos(), phi.sin())
            })
            .collect();
        assert_eq!(ConvexPolygon::new(&pentagram).unwrap_err(), PolygonError::SelfIntersecting);
        let too_many: Vec<DVec2> = (0..65).map(|i| v((i as f64 * 0.1).cos(), (i as f64 * 0.1).sin())).collect();
        assert_eq!(ConvexPolygon::new(&too_many).unwrap_err(), PolygonError::TooManyVertices(65));
    }

    #[test]
    fn non_convex_index_refers_to_clockwise_input_order() {
        let mut dart = vec![v(0.0, 0.0), v(2.0, 0.0), v(1.0, 0.5), v(1.0, 2.0)];
        dart.reverse(); // the dent is now input vertex 1
        assert_eq!(ConvexPolygon::new(&dart).unwrap_err(), PolygonError::NotConvex(1));
    }
}
