//! The fluid's velocity u(x, t) drawn under the particles (issue 15 item 6): arrows on a regular grid over the
//! scene, each pointing along u at its grid point, as long as the grid spacing (× 0.9) at the largest speed in the
//! frame and proportionally shorter below it, coloured by speed with viridis (dark: slow, yellow: the frame's
//! largest). The same arrows go to Foxglove (`/fluid`) and into PNG pictures. A World without a fluid draws nothing
//! and pays nothing.

use crate::colour::{Rgba, viridis};
use gc2d_engine::World;
use gc2d_geometry::{Aabb, DVec2};

/// Grid points along the longer side of the drawn region; the shorter side gets as many as keep the cells square
/// (at least [`MIN_ARROWS_ACROSS`]).
pub const ARROWS_ALONG_LONGER_SIDE: usize = 40;

/// Grid points along the shorter side at least, so that a narrow pipe still shows its profile.
pub const MIN_ARROWS_ACROSS: usize = 5;

/// The longest arrow, as a fraction of the grid spacing (arrows of neighbouring points do not touch).
const LONGEST_ARROW_SPACINGS: f64 = 0.9;

/// An arrow head's barbs: their length as a fraction of the arrow's, and their angle to the shaft.
const HEAD_FRACTION: f64 = 0.3;
const HEAD_ANGLE_RAD: f64 = 0.45;

/// One arrow of the drawing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FluidArrow {
    /// The grid point, m.
    pub tail: DVec2,
    /// Where the arrow ends, m.
    pub head: DVec2,
    /// |u| at the grid point, m/s.
    pub speed: f64,
    /// Its colour.
    pub colour: Rgba,
}

impl FluidArrow {
    /// The arrow as line segments: the shaft, then the two barbs of its head (none for a zero arrow).
    pub fn segments(&self) -> Vec<(DVec2, DVec2)> {
        let shaft = self.head - self.tail;
        if shaft == DVec2::ZERO {
            return Vec::new();
        }
        let back = -shaft * HEAD_FRACTION;
        let barb = |angle: f64| self.head + DVec2::from_angle(angle).rotate(back);
        vec![(self.tail, self.head), (self.head, barb(HEAD_ANGLE_RAD)), (self.head, barb(-HEAD_ANGLE_RAD))]
    }
}

/// The arrows of `world`'s fluid at its current time over `region`; `None` without a fluid. Grid points off a
/// loaded field's mesh (where the field would give an error) get no arrow.
pub fn fluid_arrows(world: &World, region: Aabb) -> Option<Vec<FluidArrow>> {
    let fluid = world.fluid()?;
    let size = region.max - region.min;
    if !(size.x > 0.0 && size.y > 0.0 && size.is_finite()) {
        return Some(Vec::new());
    }
    let spacing = size.max_element() / ARROWS_ALONG_LONGER_SIDE as f64;
    let count = |length: f64| ((length / spacing).round() as usize).max(MIN_ARROWS_ACROSS);
    let (nx, ny) = (count(size.x), count(size.y));
    let (dx, dy) = (size.x / nx as f64, size.y / ny as f64);
    let time = world.time();
    let samples: Vec<(DVec2, DVec2)> = (0..ny)
        .flat_map(|j| (0..nx).map(move |i| region.min + DVec2::new((i as f64 + 0.5) * dx, (j as f64 + 0.5) * dy)))
        .filter_map(|x| fluid.field.velocity(x, time).ok().map(|u| (x, u)))
        .collect();
    let max_speed = samples.iter().map(|(_, u)| u.length()).fold(0.0, f64::max);
    let scale = if max_speed > 0.0 { LONGEST_ARROW_SPACINGS * dx.min(dy) / max_speed } else { 0.0 };
    Some(
        samples
            .into_iter()
            .map(|(x, u)| {
                let speed = u.length();
                let shade = if max_speed > 0.0 { speed / max_speed } else { 0.0 };
                FluidArrow { tail: x, head: x + u * scale, speed, colour: viridis(shade) }
            })
            .collect(),
    )
}

/// The region the fluid is drawn over: the bounding box of the World's bodies (walls included), without margin;
/// `None` for an empty World.
pub fn drawn_region(world: &World) -> Option<Aabb> {
    let b = world.bodies();
    (0..b.len())
        .filter(|&i| b.alive[i])
        .map(|i| b.aabb(i))
        .reduce(|x, y| Aabb { min: x.min.min(y.min), max: x.max.max(y.max) })
}
