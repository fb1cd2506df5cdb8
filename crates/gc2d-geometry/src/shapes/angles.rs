//! Where the corners of a polygon inscribed in an ellipse sit: the angle modes of gsi `PART_RANDOM_POS_CORNERS`
//! (reference §1.2) plus the minimum-gap rule that keeps every drawn polygon admissible.

use crate::MAX_VERTICES;
use crate::randomize::UnknownOptionValue;
use rand::Rng;
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, TAU};
use std::str::FromStr;

/// Smallest admissible angular gap between neighbouring corners, as a fraction of the regular spacing 2π/N.
///
/// Two corners drawn almost on top of each other give a near-zero edge and a near-collinear corner, which polygon
/// validation rejects. One hundredth of the regular spacing keeps the sine of every corner's turn above about
/// 10⁻³ times the ellipse's axis ratio at N = 64 (more for fewer corners; the collinearity tolerance is 10⁻⁹) while
/// conditioning away only a small part of each mode's distribution (see `docs/model.md`, "Shape generators").
pub const MIN_GAP_FRACTION: f64 = 0.01;

/// Draws RAND1 and RAND2 make before the last draw is spread out deterministically to satisfy the minimum gap.
/// RAND2 at N = 64 passes the gap rule with probability ≈ 0.72 per draw, so a fallback is about 10⁻⁵⁵ unlikely.
pub const MAX_REDRAWS: usize = 100;

/// How the corner angles φ_i of a polygon inscribed in an ellipse are chosen (gsi `PART_RANDOM_POS_CORNERS`,
/// reference §1.2). Every mode honours the minimum gap [`MIN_GAP_FRACTION`] · 2π/N between neighbouring corners.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum AngleMode {
    /// `REGULAR`: φ_i = i·2π/N.
    Regular,
    /// `RAND1`: φ_i uniform in [(i − ½)·2π/N, (i + ½)·2π/N[, redrawn until every gap is wide enough.
    Rand1,
    /// `RAND2`: φ_i uniform in [(i − 1)·2π/N, (i + 1)·2π/N[, redrawn until every gap is wide enough.
    Rand2,
    /// `FULL`: φ_i uniform in [0, 2π[, conditioned on every gap being wide enough (sampled exactly, no redraws).
    Full,
    /// `SPECIAL_RECTANGLE`: a rectangle with bevelled corners. The N corners are shared out over the four quadrants as
    /// evenly as possible (the N mod 4 extra corners go to quadrants 1, 3, 2, in that order, counted
    /// counter-clockwise from the first), and the k corners of a quadrant sit at the centres of k equal parts of the
    /// π/4-wide arc centred on its diagonal direction π/4 + qπ/2. N = 4 is the rectangle with corners on the
    /// diagonals, N = 8 an octagon with bevels spanning π/8, larger N round the corners.
    SpecialRectangle,
}

impl FromStr for AngleMode {
    type Err = UnknownOptionValue;

    /// Parses the gsi spelling `REGULAR`, `RAND1`, `RAND2`, `FULL` or `SPECIAL_RECTANGLE`, ignoring case.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_uppercase().as_str() {
            "REGULAR" => Ok(AngleMode::Regular),
            "RAND1" => Ok(AngleMode::Rand1),
            "RAND2" => Ok(AngleMode::Rand2),
            "FULL" => Ok(AngleMode::Full),
            "SPECIAL_RECTANGLE" => Ok(AngleMode::SpecialRectangle),
            _ => Err(UnknownOptionValue {
                option: "corner position mode",
                value: s.to_string(),
                expected: "SPECIAL_RECTANGLE, REGULAR, RAND1, RAND2, FULL",
            }),
        }
    }
}

/// Fills `angles` (one per corner, 3 to [`MAX_VERTICES`] of them) with ascending corner angles that span less than
/// one turn and whose circular gaps are all at least [`MIN_GAP_FRACTION`] · 2π/N.
pub(crate) fn corner_angles<R: Rng + ?Sized>(mode: AngleMode, rng: &mut R, angles: &mut [f64]) {
    let min_gap = min_gap(angles.len());
    match mode {
        AngleMode::Regular => regular(angles),
        AngleMode::Rand1 => redraw_until_spaced(0.5, min_gap, rng, angles),
        AngleMode::Rand2 => redraw_until_spaced(1.0, min_gap, rng, angles),
        AngleMode::Full => uniform_with_min_gap(min_gap, rng, angles),
        AngleMode::SpecialRectangle => special_rectangle(angles),
    }
}

/// The minimum gap for `n` corners.
fn min_gap(n: usize) -> f64 {
    MIN_GAP_FRACTION * TAU / n as f64
}

fn regular(angles: &mut [f64]) {
    let step = TAU / angles.len() as f64;
    for (i, angle) in angles.iter_mut().enumerate() {
        *angle = i as f64 * step;
    }
}

/// RAND1 (`half_width` ½) and RAND2 (`half_width` 1): independent draws in windows of ± `half_width` regular steps,
/// kept when every gap is at least `min_gap`. This samples the mode's distribution conditioned on the gap rule. If
/// [`MAX_REDRAWS`] draws all fail, the last one is spread out by [`spread_to_min_gap`].
fn redraw_until_spaced<R: Rng + ?Sized>(half_width: f64, min_gap: f64, rng: &mut R, angles: &mut [f64]) {
    for _ in 0..MAX_REDRAWS {
        draw_in_windows(half_width, rng, angles);
        sort_on_circle(angles);
        if min_circular_gap(angles) >= min_gap {
            return;
        }
    }
    spread_to_min_gap(min_gap, angles);
}

/// φ_i = (i + u_i)·2π/N with u_i uniform in [−`half_width`, `half_width`[, in index order (not sorted).
fn draw_in_windows<R: Rng + ?Sized>(half_width: f64, rng: &mut R, angles: &mut [f64]) {
    let step = TAU / angles.len() as f64;
    for (i, angle) in angles.iter_mut().enumerate() {
        let offset = half_width * (2.0 * rng.random::<f64>() - 1.0);
        *angle = (i as f64 + offset) * step;
    }
}

/// Reduces every angle into [0, 2π) and sorts ascending, so that the corners run counter-clockwise once around.
/// Sorting the raw values would not do: RAND2 can put φ_{N−1} past 2π or φ_0 below 0, out of circular order.
fn sort_on_circle(angles: &mut [f64]) {
    for angle in angles.iter_mut() {
        let reduced = angle.rem_euclid(TAU);
        // rem_euclid of a tiny negative number rounds up to exactly 2π.
        *angle = if reduced < TAU { reduced } else { 0.0 };
    }
    angles.sort_unstable_by(f64::total_cmp);
}

/// The smallest gap between circularly consecutive angles (ascending, spanning less than a turn), wrap-around included.
fn min_circular_gap(angles: &[f64]) -> f64 {
    let wrap = TAU - (angles[angles.len() - 1] - angles[0]);
    angles.windows(2).map(|pair| pair[1] - pair[0]).fold(wrap, f64::min)
}

/// The deterministic fallback: maps every gap g (wrap-around included, Σg = 2π) to `min_gap` + g·(1 − N·`min_gap`/2π),
/// keeping the first angle. The gaps again sum to 2π and each is at least `min_gap`; the order is kept.
fn spread_to_min_gap(min_gap: f64, angles: &mut [f64]) {
    let shrink = 1.0 - angles.len() as f64 * min_gap / TAU;
    let mut previous_old = angles[0];
    let mut previous_new = angles[0];
    for angle in angles[1..].iter_mut() {
        let gap = *angle - previous_old;
        previous_old = *angle;
        previous_new += min_gap + shrink * gap;
        *angle = previous_new;
    }
}

/// FULL conditioned on the gap rule, sampled exactly: for N independent uniform angles, the gaps read counter-clockwise
/// from a uniformly chosen start are 2π·Dirichlet(1, …, 1) and independent of the start angle, and conditioning that
/// Dirichlet on every gap ≥ δ gives δ + (2π − Nδ)·Dirichlet(1, …, 1). The Dirichlet gaps are the spacings of N − 1
/// sorted uniforms in [0, 1].
fn uniform_with_min_gap<R: Rng + ?Sized>(min_gap: f64, rng: &mut R, angles: &mut [f64]) {
    let free = TAU - angles.len() as f64 * min_gap;
    let start = TAU * rng.random::<f64>();
    let cuts = &mut angles[1..];
    for cut in cuts.iter_mut() {
        *cut = rng.random::<f64>();
    }
    cuts.sort_unstable_by(f64::total_cmp);
    angles[0] = start;
    let mut previous_cut = 0.0;
    for k in 1..angles.len() {
        let cut = angles[k];
        angles[k] = angles[k - 1] + min_gap + free * (cut - previous_cut);
        previous_cut = cut;
    }
}

/// The SPECIAL_RECTANGLE layout described on [`AngleMode::SpecialRectangle`].
fn special_rectangle(angles: &mut [f64]) {
    /// Quadrants that receive one of the N mod 4 extra corners, in order; two extras go to opposite corners.
    const EXTRA_CORNER_QUADRANTS: [usize; 3] = [0, 2, 1];
    let n = angles.len();
    debug_assert!(n <= MAX_VERTICES);
    let mut next = 0;
    for quadrant in 0..4 {
        let corners = n / 4 + usize::from(EXTRA_CORNER_QUADRANTS[..n % 4].contains(&quadrant));
        let diagonal = FRAC_PI_4 + quadrant as f64 * FRAC_PI_2;
        for j in 0..corners {
            angles[next] = diagonal + FRAC_PI_4 * (j as f64 + 0.5 - corners as f64 / 2.0) / corners as f64;
            next += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngCore, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use std::f64::consts::PI;

    /// A broken generator that repeats `values` forever.
    struct Cycle {
        values: [u64; 2],
        next: usize,
    }

    impl RngCore for Cycle {
        fn next_u64(&mut self) -> u64 {
            self.next += 1;
            self.values[(self.next - 1) % 2]
        }
        fn next_u32(&mut self) -> u32 {
            (self.next_u64() >> 32) as u32
        }
        fn fill_bytes(&mut self, dst: &mut [u8]) {
            for byte in dst {
                *byte = self.next_u32() as u8;
            }
        }
    }

    fn gaps(angles: &[f64]) -> Vec<f64> {
        let mut gaps: Vec<f64> = angles.windows(2).map(|p| p[1] - p[0]).collect();
        gaps.push(TAU - (angles[angles.len() - 1] - angles[0]));
        gaps
    }

    fn assert_ascending_within_a_turn(angles: &[f64]) {
        assert!(angles.windows(2).all(|p| p[0] < p[1]), "{angles:?}");
        assert!(angles[angles.len() - 1] - angles[0] < TAU);
    }

    #[test]
    fn regular_angles_are_evenly_spaced_from_zero() {
        let mut angles = [0.0; 7];
        corner_angles(AngleMode::Regular, &mut ChaCha8Rng::seed_from_u64(0), &mut angles);
        for (i, a) in angles.iter().enumerate() {
            assert_eq!(*a, i as f64 * TAU / 7.0);
        }
    }

    #[test]
    fn rand1_puts_exactly_one_corner_in_each_window() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for n in 3..=MAX_VERTICES {
            let step = TAU / n as f64;
            for _ in 0..200 {
                let mut angles = vec![0.0; n];
                corner_angles(AngleMode::Rand1, &mut rng, &mut angles);
                assert_ascending_within_a_turn(&angles);
                let mut hits = vec![0; n];
                for a in &angles {
                    let window = (a / step).round();
                    assert!((a - window * step).abs() <= 0.5 * step + 1e-12, "angle {a} outside its window");
                    hits[window as usize % n] += 1;
                }
                assert!(hits.iter().all(|h| *h == 1), "{hits:?}");
            }
        }
    }

    #[test]
    fn rand2_stays_within_one_step_of_the_regular_angles() {
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        for n in [3, 6, 12, 64] {
            let step = TAU / n as f64;
            for _ in 0..500 {
                let mut angles = vec![0.0; n];
                corner_angles(AngleMode::Rand2, &mut rng, &mut angles);
                assert_ascending_within_a_turn(&angles);
                assert!(angles.iter().all(|a| (0.0..TAU).contains(a)));
                // Every angle lies in the windows of at most two indices, so each regular angle i·step has a corner
                // within one step of it.
                for i in 0..n {
                    let nearest = angles
                        .iter()
                        .map(|a| ((a - i as f64 * step).rem_euclid(TAU)).min((i as f64 * step - a).rem_euclid(TAU)))
                        .fold(f64::INFINITY, f64::min);
                    assert!(nearest <= step + 1e-12);
                }
            }
        }
    }

    #[test]
    fn every_mode_keeps_the_minimum_gap() {
        let mut rng = ChaCha8Rng::seed_from_u64(13);
        for mode in
            [AngleMode::Regular, AngleMode::Rand1, AngleMode::Rand2, AngleMode::Full, AngleMode::SpecialRectangle]
        {
            for n in 3..=MAX_VERTICES {
                for _ in 0..50 {
                    let mut angles = vec![0.0; n];
                    corner_angles(mode, &mut rng, &mut angles);
                    assert_ascending_within_a_turn(&angles);
                    assert!(min_circular_gap(&angles) >= min_gap(n) * (1.0 - 1e-12), "{mode:?} n = {n}");
                }
            }
        }
    }

    #[test]
    fn full_is_uniform_on_the_circle_with_unbiased_gaps() {
        // For N = 3 each gap is δ + (2π − 3δ)·Beta(1, 2), so P(gap > π) = (1 − (π − δ)/(2π − 3δ))² ≈ 0.2484.
        let mut rng = ChaCha8Rng::seed_from_u64(14);
        let delta = min_gap(3);
        let expected = (1.0 - (PI - delta) / (TAU - 3.0 * delta)).powi(2);
        let draws = 60_000;
        let mut wide = [0usize; 3];
        let mut octants = [0usize; 8];
        for _ in 0..draws {
            let mut angles = [0.0; 3];
            corner_angles(AngleMode::Full, &mut rng, &mut angles);
            for (k, g) in gaps(&angles).iter().enumerate() {
                wide[k] += usize::from(*g > PI);
            }
            for a in angles {
                octants[((a.rem_euclid(TAU) / TAU * 8.0) as usize).min(7)] += 1;
            }
        }
        for count in wide {
            // Binomial σ ≈ 0.0018 of the fraction.
            assert!((count as f64 / draws as f64 - expected).abs() < 0.01, "{wide:?} vs {expected}");
        }
        for count in octants {
            // 22,500 expected per octant, σ ≈ 140.
            assert!((count as f64 - 22_500.0).abs() < 800.0, "{octants:?}");
        }
    }

    #[test]
    fn full_survives_a_constant_generator() {
        let mut angles = [0.0; 10];
        corner_angles(AngleMode::Full, &mut Cycle { values: [0, 0], next: 0 }, &mut angles);
        assert_ascending_within_a_turn(&angles);
        assert!(min_circular_gap(&angles) >= min_gap(10) * (1.0 - 1e-12));
    }

    #[test]
    fn rand1_falls_back_to_spreading_when_every_draw_is_too_tight() {
        // A generator alternating between the bottom and the top of [0, 1) puts corners 1 and 2 (and 3 and 4, …) on
        // the shared edge of their RAND1 windows in every draw, so all redraws fail.
        let mut rng = Cycle { values: [0, u64::MAX], next: 0 };
        let mut angles = [0.0; 6];
        corner_angles(AngleMode::Rand1, &mut rng, &mut angles);
        assert_ascending_within_a_turn(&angles);
        assert!(min_circular_gap(&angles) >= min_gap(6) * (1.0 - 1e-12));
    }

    #[test]
    fn spreading_keeps_order_and_total_and_widens_every_gap_to_the_minimum() {
        let mut angles = [0.1, 0.1 + 1e-9, 2.0, 2.0, 5.0];
        let delta = 0.05;
        spread_to_min_gap(delta, &mut angles);
        let gaps = gaps(&angles);
        assert_eq!(angles[0], 0.1);
        assert!(gaps.iter().all(|g| *g >= delta * (1.0 - 1e-12)), "{gaps:?}");
        assert!((gaps.iter().sum::<f64>() - TAU).abs() < 1e-12);
        // The wide gaps shrink by the factor 1 − 5δ/2π and gain δ.
        let shrink = 1.0 - 5.0 * delta / TAU;
        assert!((gaps[3] - (delta + shrink * 3.0)).abs() < 1e-12);
    }

    #[test]
    fn special_rectangle_clusters_corners_around_the_diagonals() {
        let mut angles = [0.0; 4];
        special_rectangle(&mut angles);
        assert_eq!(angles, [FRAC_PI_4, 3.0 * FRAC_PI_4, 5.0 * FRAC_PI_4, 7.0 * FRAC_PI_4]);
        let mut angles = [0.0; 8];
        special_rectangle(&mut angles);
        let bevel = PI / 16.0;
        for q in 0..4 {
            let diagonal = FRAC_PI_4 + q as f64 * FRAC_PI_2;
            assert!((angles[2 * q] - (diagonal - bevel)).abs() < 1e-15);
            assert!((angles[2 * q + 1] - (diagonal + bevel)).abs() < 1e-15);
        }
        // N = 6: the two extra corners go to opposite quadrants, giving a point-symmetric outline.
        let mut angles = [0.0; 6];
        special_rectangle(&mut angles);
        for k in 0..3 {
            assert!((angles[k + 3] - angles[k] - PI).abs() < 1e-12, "{angles:?}");
        }
    }

    #[test]
    fn gsi_spellings_parse_case_insensitively() {
        assert_eq!("REGULAR".parse(), Ok(AngleMode::Regular));
        assert_eq!("rand1".parse(), Ok(AngleMode::Rand1));
        assert_eq!("Rand2".parse(), Ok(AngleMode::Rand2));
        assert_eq!("FULL".parse(), Ok(AngleMode::Full));
        assert_eq!("Special_Rectangle".parse(), Ok(AngleMode::SpecialRectangle));
        assert!("RAND3".parse::<AngleMode>().is_err());
    }
}
