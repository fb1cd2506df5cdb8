//! Builders of synthetic snapshots whose analysis results are known in closed form.

#![allow(dead_code)]

use gc2d_analysis::{BodyRef, Contact, ParticleOutline, Snapshot, Wall};
use gc2d_geometry::DVec2;

/// Counter-clockwise square of side `side` centred on `center`.
pub fn square(center: DVec2, side: f64) -> Vec<DVec2> {
    let h = 0.5 * side;
    vec![center + DVec2::new(-h, -h), center + DVec2::new(h, -h), center + DVec2::new(h, h), center + DVec2::new(-h, h)]
}

/// Counter-clockwise axis-aligned rectangle.
pub fn rectangle(min: DVec2, max: DVec2) -> Vec<DVec2> {
    vec![min, DVec2::new(max.x, min.y), max, DVec2::new(min.x, max.y)]
}

/// A square particle of side `side` and area density `density`.
pub fn square_particle(id: u32, center: DVec2, side: f64, density: f64) -> ParticleOutline {
    ParticleOutline {
        id,
        centroid: center,
        vertices: square(center, side),
        area: side * side,
        mass: density * side * side,
        is_disk: false,
    }
}

/// A wall body.
pub fn wall(id: u32, vertices: Vec<DVec2>) -> Wall {
    Wall { id, vertices }
}

/// A contact record.
pub fn contact(a: BodyRef, b: BodyRef, force_on_a: DVec2, point: DVec2) -> Contact {
    Contact { a, b, force_on_a, point }
}

/// Area density of the test particles, kg/m² (the thesis's 5000 kg/m², reference §7.1).
pub const DENSITY: f64 = 5000.0;

/// g, m/s².
pub const G: f64 = 9.81;

/// A single-file column of `n` squares of side `d` standing on a floor (the wall `[-half_floor, half_floor] × [-d, 0]`,
/// body id 0) in static equilibrium under gravity, without friction: the floor carries the whole weight at x = 0 and
/// each square carries the weight of those above it.
pub fn column_on_floor(n: usize, d: f64, half_floor: f64) -> Snapshot {
    let particles: Vec<ParticleOutline> =
        (0..n).map(|i| square_particle(i as u32 + 1, DVec2::new(0.0, d * (i as f64 + 0.5)), d, DENSITY)).collect();
    let weight = DENSITY * d * d * G;
    let mut contacts =
        vec![contact(BodyRef::Particle(0), BodyRef::Wall(0), DVec2::new(0.0, n as f64 * weight), DVec2::ZERO)];
    for i in 0..n.saturating_sub(1) {
        let above = (n - 1 - i) as f64 * weight;
        contacts.push(contact(
            BodyRef::Particle(i + 1),
            BodyRef::Particle(i),
            DVec2::new(0.0, above),
            DVec2::new(0.0, d * (i + 1) as f64),
        ));
    }
    Snapshot {
        time: 1.0,
        gravity: G,
        particles,
        walls: vec![wall(0, rectangle(DVec2::new(-half_floor, -d), DVec2::new(half_floor, 0.0)))],
        contacts,
    }
}

/// A block of `nx` × `ny` touching squares of side `d` filling `[x0, x0 + nx d] × [0, ny d]`, without contacts.
pub fn block_of_squares(nx: usize, ny: usize, d: f64, x0: f64) -> Snapshot {
    let particles = (0..ny)
        .flat_map(|j| (0..nx).map(move |i| (i, j)))
        .enumerate()
        .map(|(k, (i, j))| {
            square_particle(k as u32, DVec2::new(x0 + d * (i as f64 + 0.5), d * (j as f64 + 0.5)), d, DENSITY)
        })
        .collect();
    Snapshot { time: 0.0, gravity: G, particles, walls: Vec::new(), contacts: Vec::new() }
}
