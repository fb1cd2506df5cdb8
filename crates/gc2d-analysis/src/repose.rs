//! Pile height, width and the angle of repose of both flanks (reference §5.4, Abb. 2.9; eq. 2.42).
//!
//! Fit method: the x-axis is cut into bins; in each bin the particle with the highest centre of mass marks the
//! surface; the points of one flank, without the rounded top and the foot, get a straight least-squares line whose
//! slope gives the angle. Area method (2.42): tan φ = 2a/b² for one flank of base b and area a under its surface;
//! for a symmetric pile of total base b this is tan φ = 4a/b².

use crate::geometry::upper_boundary_at;
use crate::snapshot::Snapshot;
use gc2d_geometry::DVec2;
use serde::Serialize;

/// The outline numbers of a pile, from the particle vertices.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PileShape {
    /// Lowest particle vertex, taken as the floor level, m.
    pub floor: f64,
    /// Highest particle vertex, m.
    pub top: f64,
    /// Leftmost particle vertex, m.
    pub left: f64,
    /// Rightmost particle vertex, m.
    pub right: f64,
    /// x of the top of the surface (the middle of the highest plateau of the surface envelope), m.
    pub apex_x: f64,
    /// top − floor, m.
    pub height: f64,
    /// right − left, m.
    pub width: f64,
}

/// How the surface is sampled and which part of each flank is fitted.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FlankOptions {
    /// Width of the x-bins, m; non-positive means one mean particle diameter.
    pub bin_width: f64,
    /// Fraction of the pile height at the top left out of the fit (the rounded apex). Default 0.2.
    pub exclude_top: f64,
    /// Fraction of the pile height at the bottom left out of the fit (the foot). Default 0.1.
    pub exclude_foot: f64,
}

impl Default for FlankOptions {
    fn default() -> Self {
        Self { bin_width: 0.0, exclude_top: 0.2, exclude_foot: 0.1 }
    }
}

/// A straight-line fit to one flank.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FlankFit {
    /// Angle of repose, degrees; positive when the flank rises towards the apex.
    pub angle_degrees: f64,
    /// dy/dx of the fitted line.
    pub slope: f64,
    /// y of the fitted line at x = 0, m.
    pub intercept: f64,
    /// Root-mean-square vertical distance of the points from the line, m.
    pub rms_residual: f64,
    /// The surface points (highest centroid per bin) used in the fit, m.
    pub points: Vec<DVec2>,
}

/// Both flanks by both methods.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Repose {
    /// Height, width and apex.
    pub shape: PileShape,
    /// Bin width used, m.
    pub bin_width: f64,
    /// Fit method, left flank (x < apex).
    pub left: Option<FlankFit>,
    /// Fit method, right flank (x > apex).
    pub right: Option<FlankFit>,
    /// Mean of the two fitted angles (or the one that exists), degrees (Abb. 4.18 averages both flanks).
    pub mean_degrees: Option<f64>,
    /// Area method (2.42) on the left flank: tan φ = 2a/b² with b = apex − left, degrees.
    pub area_left_degrees: Option<f64>,
    /// Area method (2.42) on the right flank, degrees.
    pub area_right_degrees: Option<f64>,
    /// Area method for the whole pile as a symmetric heap: tan φ = 4a/b², degrees.
    pub area_whole_degrees: Option<f64>,
    /// The surface envelope (x, highest particle outline above x) used by the area method, m.
    pub surface: Vec<DVec2>,
}

/// Number of envelope samples per bin width.
const SURFACE_SAMPLES_PER_BIN: f64 = 8.0;

/// No envelope has more samples than this; the spacing is widened instead.
const MAX_SURFACE_SAMPLES: usize = 200_000;

/// The pile's outline numbers; `None` without particles. The apex is found on `surface` (see [`surface_envelope`]).
pub fn pile_shape(snapshot: &Snapshot, surface: &[DVec2]) -> Option<PileShape> {
    let mut vertices = snapshot.particles.iter().flat_map(|p| p.vertices.iter().copied()).filter(|v| v.is_finite());
    let first = vertices.next()?;
    let (min, max) = vertices.fold((first, first), |(lo, hi), v| (lo.min(v), hi.max(v)));
    let top_y = surface.iter().map(|p| p.y).fold(f64::NEG_INFINITY, f64::max);
    let tolerance = 1e-9 * (max.y - min.y).max(f64::MIN_POSITIVE);
    let plateau = surface.iter().filter(|p| p.y >= top_y - tolerance).map(|p| p.x);
    let (lo, hi) = plateau.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| (lo.min(x), hi.max(x)));
    let apex_x = if lo <= hi { 0.5 * (lo + hi) } else { 0.5 * (min.x + max.x) };
    Some(PileShape {
        floor: min.y,
        top: max.y,
        left: min.x,
        right: max.x,
        apex_x,
        height: max.y - min.y,
        width: max.x - min.x,
    })
}

/// The upper outline of the union of all particles, sampled every `spacing` from the leftmost to the rightmost
/// vertex: (x, highest particle boundary above x). Samples above gaps between particles are left out.
pub fn surface_envelope(snapshot: &Snapshot, spacing: f64) -> Vec<DVec2> {
    let xs = snapshot.particles.iter().flat_map(|p| p.vertices.iter().map(|v| v.x)).filter(|x| x.is_finite());
    let (left, right) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| (lo.min(x), hi.max(x)));
    if !(left <= right && spacing > 0.0 && spacing.is_finite()) {
        return Vec::new();
    }
    let spacing = spacing.max((right - left) / MAX_SURFACE_SAMPLES as f64);
    let count = ((right - left) / spacing).floor() as usize + 1;
    let mut top = vec![f64::NEG_INFINITY; count];
    for particle in &snapshot.particles {
        let (lo, hi) =
            particle.vertices.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v.x), hi.max(v.x)));
        if lo.partial_cmp(&hi).is_none_or(|o| o.is_gt()) {
            continue;
        }
        let first = ((lo - left) / spacing).ceil().max(0.0) as usize;
        let last = (((hi - left) / spacing).floor().max(0.0) as usize).min(count - 1);
        for (k, slot) in top.iter_mut().enumerate().take(last + 1).skip(first) {
            if let Some(y) = upper_boundary_at(&particle.vertices, left + k as f64 * spacing) {
                *slot = slot.max(y);
            }
        }
    }
    top.iter()
        .enumerate()
        .filter(|(_, y)| y.is_finite())
        .map(|(k, &y)| DVec2::new(left + k as f64 * spacing, y))
        .collect()
}

/// Angle of repose of both flanks by the fit and the area method, with the pile's height and width; `None`
/// without particles.
pub fn angle_of_repose(snapshot: &Snapshot, options: &FlankOptions) -> Option<Repose> {
    let bin_width = if options.bin_width > 0.0 && options.bin_width.is_finite() {
        options.bin_width
    } else {
        snapshot.mean_particle_diameter()
    };
    if !(bin_width > 0.0 && bin_width.is_finite()) {
        return None;
    }
    let surface = surface_envelope(snapshot, bin_width / SURFACE_SAMPLES_PER_BIN);
    let shape = pile_shape(snapshot, &surface)?;
    let tops = highest_centroid_per_bin(snapshot, shape.left, bin_width);
    let low = shape.floor + options.exclude_foot.clamp(0.0, 1.0) * shape.height;
    let high = shape.top - options.exclude_top.clamp(0.0, 1.0) * shape.height;
    let in_band = |p: &DVec2| p.y >= low && p.y <= high;
    let left_points: Vec<DVec2> = tops.iter().copied().filter(|p| p.x < shape.apex_x && in_band(p)).collect();
    let right_points: Vec<DVec2> = tops.iter().copied().filter(|p| p.x > shape.apex_x && in_band(p)).collect();
    let left = fit_line(&left_points, 1.0);
    let right = fit_line(&right_points, -1.0);
    let mean_degrees = match (&left, &right) {
        (Some(l), Some(r)) => Some(0.5 * (l.angle_degrees + r.angle_degrees)),
        (Some(one), None) | (None, Some(one)) => Some(one.angle_degrees),
        (None, None) => None,
    };
    let left_area = area_under(&surface, shape.floor, shape.left, shape.apex_x);
    let right_area = area_under(&surface, shape.floor, shape.apex_x, shape.right);
    let angle = |tan: f64| tan.is_finite().then(|| tan.atan().to_degrees());
    let left_base = shape.apex_x - shape.left;
    let right_base = shape.right - shape.apex_x;
    Some(Repose {
        shape,
        bin_width,
        left,
        right,
        mean_degrees,
        area_left_degrees: (left_base > 0.0).then(|| angle(2.0 * left_area / (left_base * left_base))).flatten(),
        area_right_degrees: (right_base > 0.0).then(|| angle(2.0 * right_area / (right_base * right_base))).flatten(),
        area_whole_degrees: (shape.width > 0.0)
            .then(|| angle(4.0 * (left_area + right_area) / (shape.width * shape.width)))
            .flatten(),
        surface,
    })
}

/// Per x-bin of `bin_width` starting at `origin`, the centroid of the particle whose centroid is highest.
pub fn highest_centroid_per_bin(snapshot: &Snapshot, origin: f64, bin_width: f64) -> Vec<DVec2> {
    let mut bins: std::collections::BTreeMap<i64, DVec2> = std::collections::BTreeMap::new();
    for particle in &snapshot.particles {
        let c = particle.centroid;
        if !c.is_finite() {
            continue;
        }
        let bin = ((c.x - origin) / bin_width).floor() as i64;
        bins.entry(bin).and_modify(|best| *best = if c.y > best.y { c } else { *best }).or_insert(c);
    }
    bins.into_values().collect()
}

/// Least-squares line through `points`; `rising` is +1 for a left flank (angle from the slope) and −1 for a right
/// flank (angle from −slope). `None` with fewer than three points or no spread in x.
fn fit_line(points: &[DVec2], rising: f64) -> Option<FlankFit> {
    if points.len() < 3 {
        return None;
    }
    let n = points.len() as f64;
    let mean = points.iter().copied().sum::<DVec2>() / n;
    let sxx: f64 = points.iter().map(|p| (p.x - mean.x).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.x - mean.x) * (p.y - mean.y)).sum();
    if sxx.is_nan() || sxx <= 0.0 {
        return None;
    }
    let slope = sxy / sxx;
    let intercept = mean.y - slope * mean.x;
    let rms_residual = (points.iter().map(|p| (p.y - intercept - slope * p.x).powi(2)).sum::<f64>() / n).sqrt();
    Some(FlankFit {
        angle_degrees: (rising * slope).atan().to_degrees(),
        slope,
        intercept,
        rms_residual,
        points: points.to_vec(),
    })
}

/// ∫ (surface − floor) dx over [from, to] by the trapezoid rule on the envelope samples (gaps bridged linearly).
fn area_under(surface: &[DVec2], floor: f64, from: f64, to: f64) -> f64 {
    let height = |p: &DVec2| (p.y - floor).max(0.0);
    surface
        .windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let (lo, hi) = (a.x.max(from), b.x.min(to));
            if hi <= lo || b.x <= a.x {
                return 0.0;
            }
            let at = |x: f64| height(&a) + (height(&b) - height(&a)) * (x - a.x) / (b.x - a.x);
            0.5 * (at(lo) + at(hi)) * (hi - lo)
        })
        .sum()
}
