//! Sequential deposition: a dense, random, non-overlapping start for the polygon piles of the benchmarks.
//!
//! Particles are dropped one by one straight down onto the floor or the particles below (left to right, pass after
//! pass, each pass starting at a random offset) and left `DEPOSITION_GAP` above their support. Nothing overlaps at
//! the start; settling under gravity closes the gaps and loads the contacts, so the settling run sees no violent
//! impacts. ../shared/bench/lammps/make_scenes.py builds the LAMMPS comparison's piles the same way.

use gc2d_engine::World;
use gc2d_geometry::{ConvexPolygon, DVec2, Pose};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Clearance left between a deposited particle and what it rests on, m.
const DEPOSITION_GAP: f64 = 1e-6;
/// Orientations tried per deposited particle.
const ORIENTATIONS: usize = 12;
/// A new particle is tested against this many of the most recently deposited particles of every column it spans.
const SUPPORT_CANDIDATES: usize = 12;

/// Where and how the particles are laid down.
#[derive(Debug, Clone, Copy)]
pub struct DepositionPlan {
    /// Width of the floor, from x = 0, m.
    pub width: f64,
    /// Width of the columns that index the deposited particles, m: at least the largest particle's extent.
    pub column_width: f64,
    /// The orientations tried per particle are its drawn angle plus `ORIENTATIONS` even steps over this angle, rad
    /// (a full turn for irregular polygons, a quarter turn for squares); the one that rests lowest is taken, which
    /// lays particles on a flat side, as a settled pile would.
    pub turn_span: f64,
}

/// Adds the particles `shapes` (each with its drawn angle) to `world` by sequential deposition on a floor from x = 0
/// to x = `plan.width` with its top at y = 0, at rest, of area density `density`.
pub fn deposit(
    world: &mut World,
    shapes: &[(ConvexPolygon, f64)],
    plan: DepositionPlan,
    density: f64,
    rng: &mut ChaCha8Rng,
) {
    let mut deposition = Deposition::new(plan);
    for (shape, angle) in shapes {
        let pose = deposition.place(shape, *angle, rng);
        world.add_particle(shape, pose, density, DVec2::ZERO, 0.0).expect("deposited particles have finite poses");
    }
}

/// The state of a sequential deposition: the particles placed so far, indexed by vertical columns.
struct Deposition {
    width: f64,
    column_width: f64,
    turn_span: f64,
    placed: Vec<Vec<DVec2>>,
    columns: Vec<Vec<usize>>,
    cursor: f64,
}

impl Deposition {
    fn new(plan: DepositionPlan) -> Self {
        let DepositionPlan { width, column_width, turn_span } = plan;
        let column_count = (width / column_width).ceil() as usize + 1;
        let columns = vec![Vec::new(); column_count];
        Self { width, column_width, turn_span, placed: Vec::new(), columns, cursor: f64::MAX }
    }

    /// Finds the pose of the next particle and records it: of `ORIENTATIONS` turns of the drawn orientation, the
    /// one whose centroid comes to rest lowest.
    fn place(&mut self, shape: &ConvexPolygon, angle: f64, rng: &mut ChaCha8Rng) -> Pose {
        let start_new_pass = self.cursor > self.width;
        if start_new_pass {
            self.cursor = rng.random_range(0.0..self.column_width);
        }
        let mut best: Option<(Vec<DVec2>, Pose, f64)> = None;
        for turn in 0..ORIENTATIONS {
            let angle = angle + self.turn_span * turn as f64 / ORIENTATIONS as f64;
            let Some((outline, pose)) = self.drop(shape, angle) else { continue };
            if best.as_ref().is_none_or(|(_, best_pose, _)| pose.position.y < best_pose.position.y) {
                let right = x_extent(&outline).1;
                best = Some((outline, pose, right));
            }
        }
        let Some((outline, pose, right)) = best else {
            self.cursor = f64::MAX;
            return self.place(shape, angle, rng);
        };
        self.cursor = right;
        let (left, right) = x_extent(&outline);
        let index = self.placed.len();
        self.placed.push(outline);
        let (first, last) = (self.column(left), self.column(right));
        for column in &mut self.columns[first..=last] {
            column.push(index);
        }
        pose
    }

    /// The outline and pose of the particle turned by `angle`, put right of the cursor and dropped straight down
    /// onto the floor or the particles below; `None` if it does not fit before the right wall.
    fn drop(&self, shape: &ConvexPolygon, angle: f64) -> Option<(Vec<DVec2>, Pose)> {
        let mut outline: Vec<DVec2> = shape.vertices().to_vec();
        Pose::new(DVec2::ZERO, angle).transform_into(shape.vertices(), &mut outline);
        let (left, right) = x_extent(&outline);
        let x = self.cursor - left + DEPOSITION_GAP;
        if x + right > self.width - DEPOSITION_GAP {
            return None;
        }
        outline.iter_mut().for_each(|v| v.x += x);
        let floor_lift = -outline.iter().map(|v| v.y).fold(f64::INFINITY, f64::min);
        let (first, last) = (self.column(x + left), self.column(x + right));
        let lift = (first..=last)
            .flat_map(|c| self.columns[c].iter().rev().take(SUPPORT_CANDIDATES))
            .filter_map(|&k| rest_height(&outline, &self.placed[k]))
            .fold(floor_lift, f64::max)
            + DEPOSITION_GAP;
        outline.iter_mut().for_each(|v| v.y += lift);
        Some((outline, Pose::new(DVec2::new(x, lift), angle)))
    }

    fn column(&self, x: f64) -> usize {
        ((x / self.column_width).max(0.0) as usize).min(self.columns.len() - 1)
    }
}

/// Smallest and largest x of a point set.
fn x_extent(points: &[DVec2]) -> (f64, f64) {
    points.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v.x), hi.max(v.x)))
}

/// How far convex polygon `moving` must be lifted to lie on or above convex polygon `resting`; `None` when their x
/// ranges do not meet. The vertical gap between the lower outline of one and the upper outline of the other is
/// piecewise linear and concave in x, so its extreme is at a vertex x or at an end of the common range.
fn rest_height(moving: &[DVec2], resting: &[DVec2]) -> Option<f64> {
    let (moving_lo, moving_hi) = x_extent(moving);
    let (resting_lo, resting_hi) = x_extent(resting);
    let (lo, hi) = (moving_lo.max(resting_lo), moving_hi.min(resting_hi));
    if lo > hi {
        return None;
    }
    let lift_at = |x: f64| Some(y_range(resting, x)?.1 - y_range(moving, x)?.0);
    moving
        .iter()
        .chain(resting)
        .map(|v| v.x)
        .filter(|x| (lo..=hi).contains(x))
        .chain([lo, hi])
        .filter_map(lift_at)
        .reduce(f64::max)
}

/// Lowest and highest y of convex polygon `polygon` on the vertical line at `x`, `None` if the line misses it.
fn y_range(polygon: &[DVec2], x: f64) -> Option<(f64, f64)> {
    let mut range: Option<(f64, f64)> = None;
    for (k, &p) in polygon.iter().enumerate() {
        let q = polygon[(k + 1) % polygon.len()];
        let (lo, hi) = if p.x <= q.x { (p, q) } else { (q, p) };
        if !(lo.x <= x && x <= hi.x) {
            continue;
        }
        let ys = if hi.x > lo.x { [lo.y + (hi.y - lo.y) * (x - lo.x) / (hi.x - lo.x); 2] } else { [lo.y, hi.y] };
        for y in ys {
            range = Some(range.map_or((y, y), |(a, b)| (a.min(y), b.max(y))));
        }
    }
    range
}
