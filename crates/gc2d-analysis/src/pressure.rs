//! Pressure on floors and walls (reference §5.2, eqs. 2.36–2.40 with erratum E7 fixed).
//!
//! The forces that particles exert on chosen wall faces are summed in a window of width 2b sliding along the face:
//! along x for a floor (2.39) and along y for a side wall (2.40). The printed equations test the wrong coordinate
//! (E7); here the window always runs along the face. Pressure is the force component into the wall per unit length,
//! N/m (2D), positive in compression.

use crate::snapshot::{BodyRef, Snapshot};
use gc2d_geometry::DVec2;
use serde::Serialize;

/// A face of a wall whose outward normal is within this angle of the chosen direction counts as facing it.
pub const FACING_TOLERANCE_DEGREES: f64 = 30.0;

/// Direction of a wall face's outward normal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Facing {
    /// +y: a floor.
    Up,
    /// −y: a ceiling or piston.
    Down,
    /// −x: the right-hand side wall of a silo.
    Left,
    /// +x: the left-hand side wall of a silo.
    Right,
}

impl Facing {
    /// The outward unit normal n.
    pub fn normal(self) -> DVec2 {
        match self {
            Facing::Up => DVec2::Y,
            Facing::Down => DVec2::NEG_Y,
            Facing::Left => DVec2::NEG_X,
            Facing::Right => DVec2::X,
        }
    }

    /// The coordinate along the face, the one the window slides along (E7): x for floors, y for side walls.
    pub fn along(self, point: DVec2) -> f64 {
        match self {
            Facing::Up | Facing::Down => point.x,
            Facing::Left | Facing::Right => point.y,
        }
    }
}

/// Which wall forces to use: faces with outward normal `facing`, optionally of one wall body only.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct WallSelection {
    /// The face direction.
    pub facing: Facing,
    /// Engine body id of one wall, or `None` for every wall.
    pub wall: Option<u32>,
}

impl WallSelection {
    /// Every wall face with outward normal `facing`.
    pub fn facing(facing: Facing) -> Self {
        Self { facing, wall: None }
    }
}

/// One particle–wall force on a selected face.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WallForce {
    /// Application point, m.
    pub point: DVec2,
    /// Force the particle exerts on the wall, N.
    pub force_on_wall: DVec2,
    /// Pressure contribution −n·F_wall = n·F_particle, N (positive when the particle pushes into the wall).
    pub normal_force: f64,
    /// Position along the face (x for floors, y for side walls), m.
    pub along: f64,
}

/// The particle–wall forces acting on the faces chosen by `selection`. A contact belongs to the wall edge nearest
/// its application point; it is kept when that edge's outward normal is within [`FACING_TOLERANCE_DEGREES`] of the
/// chosen direction.
pub fn wall_forces(snapshot: &Snapshot, selection: WallSelection) -> Vec<WallForce> {
    let normal = selection.facing.normal();
    let min_cos = FACING_TOLERANCE_DEGREES.to_radians().cos();
    let mut forces = Vec::new();
    for contact in &snapshot.contacts {
        let (wall_index, force_on_wall) = match (contact.a, contact.b) {
            (BodyRef::Wall(w), BodyRef::Particle(_)) => (w, contact.force_on_a),
            (BodyRef::Particle(_), BodyRef::Wall(w)) => (w, contact.force_on_b()),
            _ => continue,
        };
        let Some(wall) = snapshot.walls.get(wall_index) else { continue };
        if selection.wall.is_some_and(|id| id != wall.id) {
            continue;
        }
        let Some(face_normal) = nearest_edge_normal(&wall.vertices, contact.point) else { continue };
        if face_normal.dot(normal) < min_cos || !force_on_wall.is_finite() || !contact.point.is_finite() {
            continue;
        }
        forces.push(WallForce {
            point: contact.point,
            force_on_wall,
            normal_force: -normal.dot(force_on_wall),
            along: selection.facing.along(contact.point),
        });
    }
    forces
}

/// Total length of the wall edges matching `selection`, m: the l of (2.36)/(2.37).
pub fn face_length(snapshot: &Snapshot, selection: WallSelection) -> f64 {
    let normal = selection.facing.normal();
    let min_cos = FACING_TOLERANCE_DEGREES.to_radians().cos();
    snapshot
        .walls
        .iter()
        .filter(|w| selection.wall.is_none_or(|id| id == w.id))
        .flat_map(|w| edges(&w.vertices))
        .filter(|&(p, q)| outward_normal(p, q).is_some_and(|n| n.dot(normal) >= min_cos))
        .map(|(p, q)| (q - p).length())
        .sum()
}

/// Mean pressure over a face of length `length` (2.36)/(2.37): Σ n·F / l, N/m; 0 for a non-positive length.
pub fn mean_pressure(forces: &[WallForce], length: f64) -> f64 {
    if length > 0.0 && length.is_finite() { forces.iter().map(|f| f.normal_force).sum::<f64>() / length } else { 0.0 }
}

/// How to build a windowed profile.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ProfileOptions {
    /// Half-width b of the window (2.38), m. Rule of thumb (§5.2): 10–20 contacts per window.
    pub half_width: f64,
    /// Distance between window centres, m; windows overlap when it is below 2b. Non-positive means b/2.
    pub step: f64,
    /// Number of samples in the centred moving average drawn beside the raw profile (lattice spikes, §5.2);
    /// even numbers are rounded up to the next odd one, 0 or 1 means no smoothing.
    pub moving_average: usize,
}

/// No profile has more samples than this; the step is widened instead.
pub const MAX_PROFILE_SAMPLES: usize = 100_000;

/// A pressure profile p(s) along a face (2.39)/(2.40).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PressureProfile {
    /// Window half-width b, m.
    pub half_width: f64,
    /// Distance between samples, m.
    pub step: f64,
    /// Window centres, m (x for floors, y for side walls).
    pub positions: Vec<f64>,
    /// p(s) = (1/2b) Σ n·F_i Θ(s, s_i), N/m.
    pub pressure: Vec<f64>,
    /// Centred moving average of `pressure`, N/m.
    pub smoothed: Vec<f64>,
    /// Σ n·F_i over the selected forces, N.
    pub total_normal_force: f64,
    /// Number of forces.
    pub force_count: usize,
}

impl PressureProfile {
    /// ∫ p ds by the rectangle rule over the samples, N. Equals `total_normal_force` up to a relative error of about
    /// step/(2b) when the profile covers every window (the default range does).
    pub fn integral(&self) -> f64 {
        self.pressure.iter().sum::<f64>() * self.step
    }

    /// The profile in the scaled form of Ch. 4 (§5.2): s' = (s − origin)/length and p' = p/(ρ g h).
    /// Returns `(s', p', smoothed p')`; empty when `length` or ρ g h is not positive.
    pub fn scaled(&self, origin: f64, length: f64, rho_g_h: f64) -> Vec<(f64, f64, f64)> {
        if !(length > 0.0 && rho_g_h > 0.0 && length.is_finite() && rho_g_h.is_finite()) {
            return Vec::new();
        }
        self.positions
            .iter()
            .zip(&self.pressure)
            .zip(&self.smoothed)
            .map(|((&s, &p), &m)| ((s - origin) / length, p / rho_g_h, m / rho_g_h))
            .collect()
    }
}

/// The windowed profile of `forces` (2.39)/(2.40) at window centres from `range.0` to `range.1`. Without a range the
/// profile runs from the first force − b to the last + b, so that every force lies in full windows.
pub fn pressure_profile(forces: &[WallForce], options: &ProfileOptions, range: Option<(f64, f64)>) -> PressureProfile {
    let b = if options.half_width > 0.0 && options.half_width.is_finite() { options.half_width } else { 0.0 };
    let total_normal_force = forces.iter().map(|f| f.normal_force).sum();
    let empty = PressureProfile {
        half_width: b,
        step: 0.0,
        positions: Vec::new(),
        pressure: Vec::new(),
        smoothed: Vec::new(),
        total_normal_force,
        force_count: forces.len(),
    };
    let span = range.or_else(|| {
        let lo = forces.iter().map(|f| f.along).fold(f64::INFINITY, f64::min);
        let hi = forces.iter().map(|f| f.along).fold(f64::NEG_INFINITY, f64::max);
        (lo <= hi).then_some((lo - b, hi + b))
    });
    let Some((start, end)) = span.filter(|(s, e)| s.is_finite() && e.is_finite() && s <= e) else { return empty };
    if b <= 0.0 {
        return empty;
    }
    let requested = if options.step > 0.0 && options.step.is_finite() { options.step } else { 0.5 * b };
    let step = requested.max((end - start) / MAX_PROFILE_SAMPLES as f64);
    let count = ((end - start) / step).floor() as usize + 1;
    let mut sorted: Vec<(f64, f64)> = forces.iter().map(|f| (f.along, f.normal_force)).collect();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut prefix = Vec::with_capacity(sorted.len() + 1);
    prefix.push(0.0);
    for &(_, f) in &sorted {
        prefix.push(prefix.last().copied().unwrap_or(0.0) + f);
    }
    let positions: Vec<f64> = (0..count).map(|k| start + k as f64 * step).collect();
    let pressure: Vec<f64> = positions
        .iter()
        .map(|&s| {
            let first = sorted.partition_point(|&(x, _)| x < s - b);
            let past = sorted.partition_point(|&(x, _)| x <= s + b);
            (prefix[past] - prefix[first]) / (2.0 * b)
        })
        .collect();
    let smoothed = moving_average(&pressure, options.moving_average);
    PressureProfile {
        half_width: b,
        step,
        positions,
        pressure,
        smoothed,
        total_normal_force,
        force_count: forces.len(),
    }
}

/// Centred moving average over `window` samples (rounded up to odd), shrinking at the ends.
pub fn moving_average(values: &[f64], window: usize) -> Vec<f64> {
    let half = window / 2;
    let mut prefix = Vec::with_capacity(values.len() + 1);
    prefix.push(0.0);
    for &v in values {
        prefix.push(prefix.last().copied().unwrap_or(0.0) + v);
    }
    (0..values.len())
        .map(|i| {
            let (lo, hi) = (i.saturating_sub(half), (i + half + 1).min(values.len()));
            (prefix[hi] - prefix[lo]) / (hi - lo) as f64
        })
        .collect()
}

/// The edges (p, q) of a closed polygon.
fn edges(vertices: &[DVec2]) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
    let n = vertices.len();
    (0..n).map(move |i| (vertices[i], vertices[(i + 1) % n]))
}

/// Outward unit normal of the counter-clockwise edge p → q.
fn outward_normal(p: DVec2, q: DVec2) -> Option<DVec2> {
    let d = q - p;
    DVec2::new(d.y, -d.x).try_normalize()
}

/// Outward normal of the polygon edge nearest to `point`.
fn nearest_edge_normal(vertices: &[DVec2], point: DVec2) -> Option<DVec2> {
    let mut best: Option<(f64, DVec2)> = None;
    for (p, q) in edges(vertices) {
        let Some(normal) = outward_normal(p, q) else { continue };
        let d = q - p;
        let t = ((point - p).dot(d) / d.length_squared()).clamp(0.0, 1.0);
        let distance = (p + t * d - point).length_squared();
        if best.is_none_or(|(b, _)| distance < b) {
            best = Some((distance, normal));
        }
    }
    best.map(|(_, n)| n)
}
