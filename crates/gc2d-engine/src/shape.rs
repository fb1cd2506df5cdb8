//! The shape of a body in its body frame, and the mass model that turns a shape and a density into mass and inertia.
//!
//! Particles are convex polygons or exact disks; walls may also be capsules (a segment swept by a radius: rotor
//! blades, rounded wall ends) or an inner circle (the boundary of a circular chamber, solid outside the circle).
//! The body store keeps every shape as a few body-frame points in its flat vertex arrays (a polygon's vertices, a
//! disk's or an inner circle's centre, a capsule's two segment ends) plus a radius, so one transform pass moves them
//! all; [`ShapeKind`] says how to read them.

use gc2d_geometry::{ConvexPolygon, DVec2, MassProperties, Randomization, ShapeError, ShapeRecipe, ShapeView};
use rand::Rng;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// A body's outline in its body frame (centroid, or reference point for walls, at the origin).
#[derive(Debug, Clone, PartialEq)]
pub enum BodyShape {
    /// A convex polygon (particles and walls).
    Polygon(ConvexPolygon),
    /// An exact circle of this radius, m, centred on the body's origin (particles and walls).
    Disk {
        /// Radius, m.
        radius: f64,
    },
    /// The segment from −`half_length` to +`half_length` along the body's x axis, swept by `radius` (walls only).
    Capsule {
        /// Half the segment length, m (0 gives a disk-shaped wall).
        half_length: f64,
        /// Radius, m.
        radius: f64,
    },
    /// The circle of this radius about the body's origin, with the solid outside it (walls only): the boundary of a
    /// chamber or drum that particles stay inside.
    InnerCircle {
        /// Radius, m.
        radius: f64,
    },
}

/// Which [`BodyShape`] a body has: the tag the narrowphase dispatches on (the shape's numbers are in the store).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum ShapeKind {
    /// Vertices in the vertex arrays, no radius.
    Polygon,
    /// One point (the centre) and a radius.
    Disk,
    /// Two points (the segment ends) and a radius.
    Capsule,
    /// One point (the centre) and a radius; solid outside.
    InnerCircle,
}

impl From<&ConvexPolygon> for BodyShape {
    fn from(polygon: &ConvexPolygon) -> Self {
        BodyShape::Polygon(polygon.clone())
    }
}

impl From<ConvexPolygon> for BodyShape {
    fn from(polygon: ConvexPolygon) -> Self {
        BodyShape::Polygon(polygon)
    }
}

/// Why a shape cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BodyShapeError {
    /// A radius or length that is not a positive (for lengths: non-negative) finite number.
    #[error("{what} must be a positive finite number (m), got {value}")]
    Size {
        /// Which size.
        what: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// Capsules and inner circles are wall shapes (the shape named with its article: "an inner circle").
    #[error("{0} can only be a wall, not a particle")]
    WallOnly(&'static str),
}

impl BodyShape {
    /// The tag of this shape.
    pub fn kind(&self) -> ShapeKind {
        match self {
            BodyShape::Polygon(_) => ShapeKind::Polygon,
            BodyShape::Disk { .. } => ShapeKind::Disk,
            BodyShape::Capsule { .. } => ShapeKind::Capsule,
            BodyShape::InnerCircle { .. } => ShapeKind::InnerCircle,
        }
    }

    /// Checks the sizes, and that a particle has a particle shape (polygon or disk).
    pub fn validate(&self, particle: bool) -> Result<(), BodyShapeError> {
        let positive = |what, value: f64| {
            if value > 0.0 && value.is_finite() { Ok(()) } else { Err(BodyShapeError::Size { what, value }) }
        };
        match *self {
            BodyShape::Polygon(_) => Ok(()),
            BodyShape::Disk { radius } => positive("a disk's radius", radius),
            BodyShape::Capsule { half_length, radius } => {
                if particle {
                    return Err(BodyShapeError::WallOnly("a capsule"));
                }
                positive("a capsule's radius", radius)?;
                if half_length >= 0.0 && half_length.is_finite() {
                    Ok(())
                } else {
                    Err(BodyShapeError::Size { what: "a capsule's half length", value: half_length })
                }
            }
            BodyShape::InnerCircle { radius } => {
                if particle {
                    return Err(BodyShapeError::WallOnly("an inner circle"));
                }
                positive("an inner circle's radius", radius)
            }
        }
    }

    /// The body-frame points the store keeps for this shape (see the module docs).
    pub fn body_points(&self) -> Vec<DVec2> {
        match *self {
            BodyShape::Polygon(ref polygon) => polygon.vertices().to_vec(),
            BodyShape::Disk { .. } | BodyShape::InnerCircle { .. } => vec![DVec2::ZERO],
            BodyShape::Capsule { half_length, .. } => vec![DVec2::new(-half_length, 0.0), DVec2::new(half_length, 0.0)],
        }
    }

    /// The radius the store keeps: 0 for polygons.
    pub fn radius(&self) -> f64 {
        match *self {
            BodyShape::Polygon(_) => 0.0,
            BodyShape::Disk { radius } | BodyShape::Capsule { radius, .. } | BodyShape::InnerCircle { radius } => {
                radius
            }
        }
    }

    /// Area, m² (infinite for an inner circle, whose solid is unbounded).
    pub fn area(&self) -> f64 {
        match *self {
            BodyShape::Polygon(ref polygon) => polygon.area(),
            BodyShape::Disk { radius } => PI * radius * radius,
            BodyShape::Capsule { half_length, radius } => PI * radius * radius + 4.0 * half_length * radius,
            BodyShape::InnerCircle { .. } => f64::INFINITY,
        }
    }

    /// Radius of the largest circle about the origin inside the shape, m (the time-step bound's length).
    pub fn inscribed_radius(&self) -> f64 {
        match *self {
            BodyShape::Polygon(ref polygon) => polygon.inscribed_radius(),
            BodyShape::Disk { radius } | BodyShape::Capsule { radius, .. } => radius,
            BodyShape::InnerCircle { .. } => f64::INFINITY,
        }
    }

    /// κ = c/l of two copies of the shape pressed together face on along their flattest face
    /// ([`flat_contact_ratio`]); 0 for shapes without a face (disks and the wall shapes).
    pub fn flat_contact_ratio(&self) -> f64 {
        match *self {
            BodyShape::Polygon(ref polygon) => flat_contact_ratio(polygon.vertices(), DVec2::ZERO),
            _ => 0.0,
        }
    }

    /// Largest distance of a point of the shape from its origin, m: how far a point can travel per radian turned.
    pub fn reach(&self) -> f64 {
        match *self {
            BodyShape::Polygon(ref polygon) => polygon.bounding_radius(),
            BodyShape::Disk { radius } => radius,
            BodyShape::Capsule { half_length, radius } => half_length + radius,
            BodyShape::InnerCircle { .. } => f64::INFINITY,
        }
    }

    /// The radius of the equal-area circle, √(A/π), m: the size a sphere-equivalent mass model and drag use for a
    /// polygon (a disk's own radius).
    pub fn equivalent_radius(&self) -> f64 {
        match *self {
            BodyShape::Disk { radius } => radius,
            _ => (self.area() / PI).sqrt(),
        }
    }
}

/// How a source or a block draws each new particle: a random polygon or a disk of scattered radius.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum ParticleRecipe {
    /// A random convex polygon by gc2d's rules (reference §1.2).
    Polygon(ShapeRecipe),
    /// A disk.
    Disk(DiskRecipe),
}

/// A disk whose radius is drawn around `radius` with the size rule of gc2d's recipes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DiskRecipe {
    /// Nominal radius, m.
    pub radius: f64,
    /// How the radius scatters (`Const`, `Equal`, `Gauss`).
    pub size_randomization: Randomization,
    /// Relative spread of the radius, in [0, 1) when it scatters.
    pub size_variation: f64,
}

impl ParticleRecipe {
    /// Checks that every draw gives a valid shape.
    pub fn validate(&self) -> Result<(), ShapeError> {
        match self {
            ParticleRecipe::Polygon(recipe) => recipe.validate(),
            ParticleRecipe::Disk(disk) => {
                if !(disk.radius > 0.0 && disk.radius.is_finite()) {
                    return Err(ShapeError::InvalidValue {
                        parameter: "radius",
                        value: disk.radius,
                        reason: "must be a finite positive length",
                    });
                }
                if disk.size_randomization != Randomization::Const && !(0.0..1.0).contains(&disk.size_variation) {
                    return Err(ShapeError::InvalidValue {
                        parameter: "size_variation",
                        value: disk.size_variation,
                        reason: "the relative size spread must lie in [0, 1)",
                    });
                }
                Ok(())
            }
        }
    }

    /// Draws one shape and its orientation (radians CCW; 0 for disks) from `rng`. A polygon draws exactly what
    /// [`ShapeRecipe::draw`] draws; a disk draws its radius only when it scatters.
    pub fn draw<R: Rng + ?Sized>(&self, rng: &mut R) -> Result<(BodyShape, f64), ShapeError> {
        match self {
            ParticleRecipe::Polygon(recipe) => recipe.draw(rng).map(|(polygon, angle)| (polygon.into(), angle)),
            ParticleRecipe::Disk(disk) => {
                let radius = disk.size_randomization.draw_size(disk.radius, disk.size_variation, rng);
                Ok((BodyShape::Disk { radius }, 0.0))
            }
        }
    }
}

/// κ = 2·max over the edges of (edge length / distance of the edge's line from `centre`): the ratio c/l of the
/// overlap-area law when two copies of a convex polygon with centroid `centre` press on each other face on along
/// that edge (chord c = the edge, l = half the distance), its stiffest contact with the largest damping rate. 0 for
/// fewer than three points or an edge through the centre.
pub fn flat_contact_ratio(points: &[DVec2], centre: DVec2) -> f64 {
    if points.len() < 3 {
        return 0.0;
    }
    let mut largest: f64 = 0.0;
    for (k, &p) in points.iter().enumerate() {
        let edge = points[(k + 1) % points.len()] - p;
        let distance = edge.perp_dot(centre - p).abs() / edge.length();
        let ratio = edge.length() / distance;
        if !ratio.is_finite() {
            return 0.0;
        }
        largest = largest.max(ratio);
    }
    2.0 * largest
}

/// The world-frame outline of a body of kind `kind` whose world points are `points` (see the module docs) and whose
/// radius at its current scale is `radius`.
#[inline]
pub fn shape_view(kind: ShapeKind, points: &[DVec2], radius: f64) -> ShapeView<'_> {
    match kind {
        ShapeKind::Polygon => ShapeView::Polygon(points),
        ShapeKind::Disk => ShapeView::Disk { center: points[0], radius },
        ShapeKind::Capsule => ShapeView::Capsule { a: points[0], b: points[1], radius },
        ShapeKind::InnerCircle => ShapeView::InnerCircle { center: points[0], radius },
    }
}

/// How a particle's mass and moment of inertia follow from its shape and density (ARCHITECTURE.md, "2D units").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum MassModel {
    /// Per unit thickness (gc2d): m = ρ·A with ρ in kg/m², I = ρ·∫r²dA (a disk: ½·m·r²).
    #[default]
    PerUnitThickness,
    /// Spheres moving in a plane (the ball mill's and the feed pipe's theses): m = ρ·4/3·π·r³ with ρ in kg/m³ and
    /// I = 2/5·m·r², with r a disk's radius or a polygon's equal-area radius √(A/π).
    SphereEquivalent,
}

impl MassModel {
    /// Mass and moment of inertia of `shape` at `density` (kg/m² or kg/m³, see the variants).
    pub fn mass_properties(self, shape: &BodyShape, density: f64) -> MassProperties {
        match (self, shape) {
            (MassModel::PerUnitThickness, BodyShape::Polygon(polygon)) => polygon.mass_properties(density),
            (MassModel::PerUnitThickness, shape) => {
                let r = shape.radius();
                let mass = density * PI * r * r;
                MassProperties { mass, inertia: 0.5 * mass * r * r }
            }
            (MassModel::SphereEquivalent, shape) => {
                let r = shape.equivalent_radius();
                let mass = density * 4.0 / 3.0 * PI * r * r * r;
                MassProperties { mass, inertia: 0.4 * mass * r * r }
            }
        }
    }

    /// The unit of density this model reads, for messages.
    pub fn density_unit(self) -> &'static str {
        match self {
            MassModel::PerUnitThickness => "kg/m²",
            MassModel::SphereEquivalent => "kg/m³",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gc2d_geometry::square;

    #[test]
    fn disk_mass_per_unit_thickness_and_sphere_equivalent() {
        let disk = BodyShape::Disk { radius: 0.002 };
        let flat = MassModel::PerUnitThickness.mass_properties(&disk, 5000.0);
        assert!((flat.mass - 5000.0 * PI * 4e-6).abs() < 1e-15);
        assert!((flat.inertia - 0.5 * flat.mass * 4e-6).abs() < 1e-20);
        let sphere = MassModel::SphereEquivalent.mass_properties(&BodyShape::Disk { radius: 0.0025 }, 7850.0);
        // The mill thesis's 5 mm steel ball: 0.514 g.
        assert!((sphere.mass - 0.514e-3).abs() < 0.001e-3, "{}", sphere.mass);
        assert!((sphere.inertia - 0.4 * sphere.mass * 0.0025f64.powi(2)).abs() < 1e-20);
    }

    #[test]
    fn polygons_keep_their_mass_per_unit_thickness() {
        let polygon = square(0.01).unwrap();
        let shape = BodyShape::from(&polygon);
        assert_eq!(MassModel::PerUnitThickness.mass_properties(&shape, 5000.0), polygon.mass_properties(5000.0));
        let sphere = MassModel::SphereEquivalent.mass_properties(&shape, 1000.0);
        let r = (1e-4 / PI).sqrt();
        assert!((sphere.mass - 1000.0 * 4.0 / 3.0 * PI * r.powi(3)).abs() < 1e-15);
    }

    #[test]
    fn wall_shapes_are_refused_as_particles() {
        assert!(BodyShape::Capsule { half_length: 0.01, radius: 0.002 }.validate(true).is_err());
        assert!(BodyShape::InnerCircle { radius: 0.07 }.validate(true).is_err());
        assert!(BodyShape::InnerCircle { radius: 0.07 }.validate(false).is_ok());
        assert!(BodyShape::Disk { radius: -1.0 }.validate(true).is_err());
        assert!(BodyShape::Capsule { half_length: f64::NAN, radius: 0.002 }.validate(false).is_err());
    }
}
