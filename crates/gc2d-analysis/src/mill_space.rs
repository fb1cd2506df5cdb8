//! Where the balls of a mill are and where they collide (reference ballmill.md §7.6, "Spatial"): the radial
//! residence profile in rings one ball diameter wide, and sector maps of equal-area cells in radius and angle
//! (thesis §16.1) with the balls' share, their mean speed and the collisions that began in each cell.

use gc2d_geometry::DVec2;
use serde::Serialize;
use std::f64::consts::TAU;

/// The chamber the statistics refer to, and the width of their rings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ChamberFrame {
    /// Centre, m.
    pub centre_m: [f64; 2],
    /// Radius, m.
    pub radius_m: f64,
    /// Ball diameter, m (the rings' width).
    pub ball_diameter_m: f64,
}

impl ChamberFrame {
    /// Distance from the centre and angle CCW from +x in [0, 2π) of `point`.
    pub fn polar(&self, point: DVec2) -> (f64, f64) {
        let d = point - DVec2::from(self.centre_m);
        (d.length(), d.y.atan2(d.x).rem_euclid(TAU))
    }
}

/// One ring of the radial profile.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Ring {
    /// Inner radius, m.
    pub from_m: f64,
    /// Outer radius, m.
    pub to_m: f64,
    /// Share of the ball samples whose centre lies in the ring.
    pub share: f64,
    /// The ring's share of the chamber's area.
    pub area_share: f64,
}

/// The radial residence profile.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RadialProfile {
    /// Rings one ball diameter wide from the wall inwards (the innermost takes the rest), listed outwards.
    pub rings: Vec<Ring>,
    /// Share of the ball samples in the outermost ring of width two ball diameters (r > R − 2d).
    pub outer_ring_share: f64,
    /// That ring's share of the chamber's area.
    pub outer_ring_area_share: f64,
}

/// The radial profile of ball centres at distances `radii` from the centre (one per ball and dump).
pub fn radial_profile(chamber: &ChamberFrame, radii: &[f64]) -> RadialProfile {
    let (big_r, d) = (chamber.radius_m, chamber.ball_diameter_m);
    let count = ((big_r / d).ceil() as usize).max(1);
    let n = radii.len().max(1) as f64;
    let area = |from: f64, to: f64| (to * to - from * from) / (big_r * big_r);
    let rings = (0..count)
        .rev()
        .map(|k| {
            // Each edge from the same product, so that a ring's outer edge is its outer neighbour's inner edge to the
            // bit: `to − d` differed from it in the last bits, and a radius between the two was counted twice or not
            // at all.
            let to = big_r - k as f64 * d;
            let from = (big_r - (k + 1) as f64 * d).max(0.0);
            let inside = |r: f64| r > from && r <= to || (from == 0.0 && r == 0.0) || (k == 0 && r > big_r);
            Ring {
                from_m: from,
                to_m: to,
                share: radii.iter().filter(|&&r| inside(r)).count() as f64 / n,
                area_share: area(from, to),
            }
        })
        .collect();
    let outer = (big_r - 2.0 * d).max(0.0);
    RadialProfile {
        rings,
        outer_ring_share: radii.iter().filter(|&&r| r > outer).count() as f64 / n,
        outer_ring_area_share: area(outer, big_r),
    }
}

/// Rings of the sector maps (equal area: r_k = R √(k / rings)).
pub const SECTOR_RINGS: usize = 5;
/// Angular sectors of the sector maps.
pub const SECTOR_ANGLES: usize = 16;

/// One cell of the sector maps.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SectorCell {
    /// Ring index, 0 innermost.
    pub ring: usize,
    /// Sector index, 0 from +x counter-clockwise.
    pub sector: usize,
    /// Inner and outer radius, m.
    pub radii_m: [f64; 2],
    /// First and last angle, rad CCW from +x.
    pub angles_rad: [f64; 2],
    /// Share of the ball samples whose centre lies in the cell.
    pub ball_share: f64,
    /// Mean speed of those samples, m/s (NaN without samples).
    pub mean_speed_m_s: f64,
    /// Collisions that began in the cell (the contact point at first touch) in the window.
    pub collisions: usize,
    /// Those per second.
    pub collisions_per_second: f64,
}

/// The sector maps over [`SECTOR_RINGS`] × [`SECTOR_ANGLES`] equal-area cells of the chamber, from ball samples
/// (position, speed) and the begin points of collisions over a window of `span` s; points beyond the chamber's radius
/// count in the outer ring.
pub fn sector_map(chamber: &ChamberFrame, balls: &[(DVec2, f64)], collisions: &[DVec2], span: f64) -> Vec<SectorCell> {
    let cell_of = |point: DVec2| {
        let (r, angle) = chamber.polar(point);
        let ring = ((SECTOR_RINGS as f64 * (r / chamber.radius_m).powi(2)) as usize).min(SECTOR_RINGS - 1);
        let sector = ((angle / TAU * SECTOR_ANGLES as f64) as usize).min(SECTOR_ANGLES - 1);
        ring * SECTOR_ANGLES + sector
    };
    let cells = SECTOR_RINGS * SECTOR_ANGLES;
    let (mut samples, mut speed_sums, mut hits) = (vec![0usize; cells], vec![0.0; cells], vec![0usize; cells]);
    for &(point, speed) in balls {
        let c = cell_of(point);
        samples[c] += 1;
        speed_sums[c] += speed;
    }
    for &point in collisions {
        hits[cell_of(point)] += 1;
    }
    let radius = |k: usize| chamber.radius_m * (k as f64 / SECTOR_RINGS as f64).sqrt();
    let angle = |k: usize| TAU * k as f64 / SECTOR_ANGLES as f64;
    (0..cells)
        .map(|c| {
            let (ring, sector) = (c / SECTOR_ANGLES, c % SECTOR_ANGLES);
            SectorCell {
                ring,
                sector,
                radii_m: [radius(ring), radius(ring + 1)],
                angles_rad: [angle(sector), angle(sector + 1)],
                ball_share: samples[c] as f64 / balls.len().max(1) as f64,
                mean_speed_m_s: speed_sums[c] / samples[c] as f64,
                collisions: hits[c],
                collisions_per_second: hits[c] as f64 / span,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const CHAMBER: ChamberFrame = ChamberFrame { centre_m: [1.0, 2.0], radius_m: 0.01, ball_diameter_m: 0.003 };

    #[test]
    fn radial_rings_are_one_diameter_wide_from_the_wall_and_shares_add_up() {
        let radii = [0.0, 0.0005, 0.0015, 0.0075, 0.0085, 0.0095, 0.0099];
        let p = radial_profile(&CHAMBER, &radii);
        let edges: Vec<[f64; 2]> = p.rings.iter().map(|r| [r.from_m, r.to_m]).collect();
        assert_eq!(edges.len(), 4);
        assert_eq!(edges[0][0], 0.0);
        assert!((edges[0][1] - 0.001).abs() < 1e-15 && (edges[3][0] - 0.007).abs() < 1e-15 && edges[3][1] == 0.01);
        let shares: Vec<f64> = p.rings.iter().map(|r| r.share * 7.0).collect();
        assert_eq!(shares.iter().map(|s| s.round() as usize).collect::<Vec<_>>(), vec![2, 1, 0, 4]);
        assert!((p.rings.iter().map(|r| r.area_share).sum::<f64>() - 1.0).abs() < 1e-12);
        // r > R − 2d = 4 mm: four of seven; that ring is 1 − 0.4² = 84 % of the area.
        assert!((p.outer_ring_share - 4.0 / 7.0).abs() < 1e-15);
        assert!((p.outer_ring_area_share - 0.84).abs() < 1e-12);
    }

    /// QA outputs: 10 of 14 rings of a mill's profile had an outer edge a few bits off its neighbour's inner edge.
    #[test]
    fn neighbouring_rings_share_their_edge_to_the_bit_and_count_a_radius_on_it_once() {
        let chamber = ChamberFrame { centre_m: [0.0, 0.0], radius_m: 0.073, ball_diameter_m: 0.0051 };
        let edges: Vec<f64> = (1..15).map(|k| 0.073 - k as f64 * 0.0051).filter(|&e| e > 0.0).collect();
        let p = radial_profile(&chamber, &edges);
        for pair in p.rings.windows(2) {
            assert_eq!(pair[0].to_m.to_bits(), pair[1].from_m.to_bits(), "{:?}", pair);
        }
        let counted: f64 = p.rings.iter().map(|r| r.share).sum();
        assert!((counted - 1.0).abs() < 1e-12, "every radius on an edge counted once: {counted}");
    }

    #[test]
    fn sector_cells_have_equal_area_and_count_where_things_are() {
        let at = |r: f64, degrees: f64| DVec2::new(1.0, 2.0) + r * DVec2::from_angle(degrees.to_radians());
        // Ring 0 is r < R/√5 = 4.47 mm, ring 4 r > R √0.8 = 8.94 mm; sectors are 22.5° wide.
        let balls = [(at(0.001, 10.0), 1.0), (at(0.001, 20.0), 3.0), (at(0.0095, 100.0), 5.0), (at(0.02, 359.0), 7.0)];
        let collisions = [at(0.0095, 95.0), at(0.0095, 91.0), at(0.005, 200.0)];
        let cells = sector_map(&CHAMBER, &balls, &collisions, 0.5);
        assert_eq!(cells.len(), SECTOR_RINGS * SECTOR_ANGLES);
        let area = |c: &SectorCell| (c.radii_m[1].powi(2) - c.radii_m[0].powi(2)) * (c.angles_rad[1] - c.angles_rad[0]);
        assert!(cells.iter().all(|c| (area(c) - area(&cells[0])).abs() < 1e-18));
        let cell = |ring: usize, sector: usize| &cells[ring * SECTOR_ANGLES + sector];
        assert_eq!((cell(0, 0).ball_share, cell(0, 0).mean_speed_m_s), (0.5, 2.0));
        assert_eq!((cell(4, 4).ball_share, cell(4, 4).mean_speed_m_s, cell(4, 4).collisions), (0.25, 5.0, 2));
        assert_eq!(cell(4, 4).collisions_per_second, 4.0);
        assert_eq!(cell(4, 15).mean_speed_m_s, 7.0);
        assert_eq!(cell(1, 8).collisions, 1);
        assert!(cell(2, 2).mean_speed_m_s.is_nan());
    }
}
