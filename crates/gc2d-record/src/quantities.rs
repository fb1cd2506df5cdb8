//! Per-particle quantities that colour a frame, and the frame's scalar statistics.

use crate::colour::{Rgba, category, viridis};
use crate::network::ContactForce;
use gc2d_engine::{BodyKind, World};

/// What the particles' colour shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ColourBy {
    /// |v| of the centroid, m/s (viridis).
    #[default]
    Speed,
    /// Contact pressure p = Σ|F_c| / perimeter over the particle's contacts, N/m (viridis). A scalar stand-in for
    /// the particle stress (reference §5.7) that needs no tensor: how hard a particle is squeezed per unit of its
    /// surface.
    Pressure,
    /// Insertion order (gc2d colours by particle number, reference §5.5): the k-th particle slot of n maps to
    /// k / (n − 1) (viridis), so particles of the same age share a colour.
    Age,
    /// Material: particles of equal area density share a category colour (Okabe–Ito). The contact law is global,
    /// so density is the only per-particle material property.
    Material,
}

/// The values a scalar colour map spans.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum ColourRange {
    /// Speed and pressure: 0 to the largest value of the frame; age: the first to the last particle slot.
    #[default]
    Auto,
    /// A fixed range, the same for every frame (values outside are clamped).
    Fixed {
        /// Value drawn dark purple.
        min: f64,
        /// Value drawn yellow.
        max: f64,
    },
}

/// Working buffers for per-slot quantities, reused from frame to frame.
#[derive(Debug, Clone, Default)]
pub struct ParticleColours {
    values: Vec<f64>,
    densities: Vec<f64>,
    /// Colour of every body slot (walls and dead slots get an unused transparent entry).
    pub colours: Vec<Rgba>,
}

impl ParticleColours {
    /// Computes the colour of every particle slot of `world` for `colour_by` over `range`.
    pub fn update(&mut self, world: &World, colour_by: ColourBy, range: ColourRange, forces: &[ContactForce]) {
        let bodies = world.bodies();
        self.colours.clear();
        self.colours.resize(bodies.len(), Rgba::hex(0).with_alpha(0.0));
        match colour_by {
            ColourBy::Speed => {
                self.values.clear();
                self.values.extend(bodies.velocity.iter().map(|v| v.length()));
                self.apply_scalar(world, range, None);
            }
            ColourBy::Pressure => {
                contact_pressures(world, forces, &mut self.values);
                self.apply_scalar(world, range, None);
            }
            ColourBy::Age => {
                self.values.clear();
                self.values.resize(bodies.len(), 0.0);
                let mut ordinal = 0.0;
                for (i, kind) in bodies.kind.iter().enumerate() {
                    if *kind == BodyKind::Particle {
                        self.values[i] = ordinal;
                        ordinal += 1.0;
                    }
                }
                self.apply_scalar(world, range, Some((ordinal - 1.0).max(0.0)));
            }
            ColourBy::Material => {
                self.densities.clear();
                self.densities.extend(
                    (0..bodies.len()).filter(|&i| bodies.kind[i] == BodyKind::Particle).map(|i| area_density(world, i)),
                );
                self.densities.sort_by(f64::total_cmp);
                self.densities.dedup();
                for id in bodies.particles() {
                    let i = id.index();
                    let rank = self.densities.partition_point(|&d| d.total_cmp(&area_density(world, i)).is_lt());
                    self.colours[i] = category(rank);
                }
            }
        }
    }

    /// Maps `self.values` of the living particles through viridis. The automatic range starts at 0 and ends at
    /// `auto_max`, or at the frame's largest value when that is `None`.
    fn apply_scalar(&mut self, world: &World, range: ColourRange, auto_max: Option<f64>) {
        let bodies = world.bodies();
        let (min, max) = match range {
            ColourRange::Fixed { min, max } => (min, max),
            ColourRange::Auto => {
                let frame_max = bodies.particles().map(|id| self.values[id.index()]).fold(0.0, f64::max);
                (0.0, auto_max.unwrap_or(frame_max))
            }
        };
        let span = max - min;
        for id in bodies.particles() {
            let i = id.index();
            let t = if span > 0.0 { (self.values[i] - min) / span } else { 0.0 };
            self.colours[i] = viridis(t);
        }
    }
}

/// Mass per area at scale 1, kg/m².
fn area_density(world: &World, i: usize) -> f64 {
    let b = world.bodies();
    if b.area[i] > 0.0 { b.mass[i] / b.area[i] } else { 0.0 }
}

/// Replaces `out` with the contact pressure Σ|F_c| / perimeter of every body slot (0 for walls and dead slots), N/m.
pub fn contact_pressures(world: &World, forces: &[ContactForce], out: &mut Vec<f64>) {
    let bodies = world.bodies();
    out.clear();
    out.resize(bodies.len(), 0.0);
    for f in forces {
        out[f.a.index()] += f.magnitude;
        out[f.b.index()] += f.magnitude;
    }
    for (i, p) in out.iter_mut().enumerate() {
        let perimeter = body_perimeter(bodies, gc2d_engine::BodyId(i as u32));
        *p = if bodies.kind[i] == BodyKind::Particle && bodies.alive[i] && perimeter > 0.0 {
            *p / perimeter
        } else {
            0.0
        };
    }
}

/// Length of body `id`'s outline at its current pose and scale, m.
fn body_perimeter(bodies: &gc2d_engine::Bodies, id: gc2d_engine::BodyId) -> f64 {
    match bodies.shape_view(id) {
        gc2d_geometry::ShapeView::Polygon(vertices) => perimeter(vertices),
        gc2d_geometry::ShapeView::Disk { radius, .. } | gc2d_geometry::ShapeView::InnerCircle { radius, .. } => {
            std::f64::consts::TAU * radius
        }
        gc2d_geometry::ShapeView::Capsule { a, b, radius } => std::f64::consts::TAU * radius + 2.0 * a.distance(b),
    }
}

/// Perimeter of a closed polygon, m.
pub fn perimeter(vertices: &[gc2d_geometry::DVec2]) -> f64 {
    let n = vertices.len();
    (0..n).map(|k| vertices[k].distance(vertices[(k + 1) % n])).sum()
}

/// Mean number of contacts per living particle: each particle–particle contact counts for both particles, each
/// particle–wall contact for its particle. 0 when there are no particles.
pub fn mean_coordination(world: &World, forces: &[ContactForce]) -> f64 {
    let bodies = world.bodies();
    let particles = bodies.particles().count();
    if particles == 0 {
        return 0.0;
    }
    let ends: usize = forces
        .iter()
        .map(|f| {
            usize::from(bodies.kind[f.a.index()] == BodyKind::Particle)
                + usize::from(bodies.kind[f.b.index()] == BodyKind::Particle)
        })
        .sum();
    ends as f64 / particles as f64
}

/// The mean inscribed radius of the living particles at their current size, m; `None` without particles. The
/// recording's length scale: force-line widths and the small z offsets between layers are fractions of it.
pub fn mean_inscribed_radius(world: &World) -> Option<f64> {
    let b = world.bodies();
    let (sum, count) = b
        .particles()
        .fold((0.0, 0usize), |(s, n), id| (s + b.inscribed_radius[id.index()] * b.pose[id.index()].scale, n + 1));
    (count > 0 && sum > 0.0 && sum.is_finite()).then(|| sum / count as f64)
}
