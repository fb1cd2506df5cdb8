//! A frozen copy of what the analysis needs from a World (reference §5.1): particle outlines, walls, contact forces.
//!
//! Every analysis function reads a [`Snapshot`], never a World, so each can be tested on hand-made configurations
//! whose answer is known.

use gc2d_engine::{BodyKind, ShapeKind, World};
use gc2d_geometry::DVec2;
use serde::Serialize;

/// One particle at the instant of the snapshot.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParticleOutline {
    /// The engine's body id (stable slot number; ascending with insertion, i.e. with "age", §5.5).
    pub id: u32,
    /// Centre of mass, m.
    pub centroid: DVec2,
    /// World-frame vertices, counter-clockwise (a disk traced as a fine polygon).
    pub vertices: Vec<DVec2>,
    /// Current area (scaled by the pose's size factor), m².
    pub area: f64,
    /// Mass per unit thickness, kg.
    pub mass: f64,
    /// True for a disk: its `vertices` are a fine polygon inscribed in its circle.
    pub is_disk: bool,
}

/// One wall (immovable or driven body of infinite mass).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Wall {
    /// The engine's body id.
    pub id: u32,
    /// World-frame vertices, counter-clockwise.
    pub vertices: Vec<DVec2>,
}

/// Which body of the snapshot a contact side refers to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum BodyRef {
    /// Index into [`Snapshot::particles`].
    Particle(usize),
    /// Index into [`Snapshot::walls`].
    Wall(usize),
}

/// One force record (the gff line of §5.1): a contact between bodies `a` and `b`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Contact {
    /// First body.
    pub a: BodyRef,
    /// Second body.
    pub b: BodyRef,
    /// Force on `a`, N (per unit thickness); `b` receives the opposite.
    pub force_on_a: DVec2,
    /// Application point (midpoint of the contact chord), m.
    pub point: DVec2,
}

impl Contact {
    /// Force on `b`: −`force_on_a` (each contact carries two opposite forces, §5.3).
    pub fn force_on_b(&self) -> DVec2 {
        -self.force_on_a
    }

    /// The force this contact exerts on `body`, or `None` if `body` is not one of its two sides.
    pub fn force_on(&self, body: BodyRef) -> Option<DVec2> {
        if self.a == body {
            Some(self.force_on_a)
        } else if self.b == body {
            Some(self.force_on_b())
        } else {
            None
        }
    }
}

/// Particles, walls and contact forces at one instant, plus g.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Snapshot {
    /// Simulated time, s.
    pub time: f64,
    /// Magnitude of gravity, m/s²; gravity points along −y.
    pub gravity: f64,
    /// Living particles in slot order.
    pub particles: Vec<ParticleOutline>,
    /// Walls in slot order.
    pub walls: Vec<Wall>,
    /// Touching pairs with their forces.
    pub contacts: Vec<Contact>,
}

impl Snapshot {
    /// Copies the living particles, the walls and the touching pairs of `world`.
    pub fn from_world(world: &World) -> Self {
        let bodies = world.bodies();
        let mut slot_to_ref = vec![None; bodies.len()];
        let mut particles = Vec::new();
        let mut walls = Vec::new();
        for (slot, reference) in slot_to_ref.iter_mut().enumerate() {
            if !bodies.alive[slot] {
                continue;
            }
            let id = gc2d_engine::BodyId(slot as u32);
            // Disks, capsules and chamber circles are traced as fine polygons (a chamber by its circle).
            let vertices = bodies.shape_view(id).traced_outline().boundary().to_vec();
            match bodies.kind[slot] {
                BodyKind::Particle => {
                    let scale = bodies.pose[slot].scale;
                    *reference = Some(BodyRef::Particle(particles.len()));
                    particles.push(ParticleOutline {
                        id: id.0,
                        centroid: bodies.pose[slot].position,
                        vertices,
                        area: bodies.area[slot] * scale * scale,
                        mass: bodies.mass[slot],
                        is_disk: bodies.shape[slot] == ShapeKind::Disk,
                    });
                }
                BodyKind::Wall => {
                    *reference = Some(BodyRef::Wall(walls.len()));
                    walls.push(Wall { id: id.0, vertices });
                }
            }
        }
        let contacts = world
            .contacts()
            .filter_map(|(a, b, contact)| {
                let a = slot_to_ref.get(a.index()).copied().flatten()?;
                let b = slot_to_ref.get(b.index()).copied().flatten()?;
                Some(Contact { a, b, force_on_a: contact.force_on_a, point: contact.point })
            })
            .collect();
        Self { time: world.time(), gravity: world.gravity(), particles, walls, contacts }
    }

    /// Total particle mass, kg.
    pub fn total_mass(&self) -> f64 {
        self.particles.iter().map(|p| p.mass).sum()
    }

    /// Total particle area, m².
    pub fn total_particle_area(&self) -> f64 {
        self.particles.iter().map(|p| p.area).sum()
    }

    /// Area density of the particle material (Σm / Σa), kg/m²; 0 without particles.
    pub fn particle_area_density(&self) -> f64 {
        let area = self.total_particle_area();
        if area > 0.0 { self.total_mass() / area } else { 0.0 }
    }

    /// Mean diameter of the circle of equal area, m; 0 without particles.
    pub fn mean_particle_diameter(&self) -> f64 {
        if self.particles.is_empty() {
            return 0.0;
        }
        let sum: f64 = self.particles.iter().map(|p| 2.0 * (p.area.max(0.0) / std::f64::consts::PI).sqrt()).sum();
        sum / self.particles.len() as f64
    }

    /// Indices of the particles in the largest group connected by particle–particle contacts (ties: the group with
    /// the lowest particle index). Isolated particles are groups of one, so a pile at rest is one group and a
    /// particle still falling from a source, or one that bounced away, is left out.
    pub fn largest_cluster(&self) -> Vec<usize> {
        let mut parent: Vec<usize> = (0..self.particles.len()).collect();
        fn root(parent: &mut [usize], mut i: usize) -> usize {
            while parent[i] != i {
                parent[i] = parent[parent[i]];
                i = parent[i];
            }
            i
        }
        for contact in &self.contacts {
            if let (BodyRef::Particle(a), BodyRef::Particle(b)) = (contact.a, contact.b) {
                let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
                if ra != rb {
                    parent[ra.max(rb)] = ra.min(rb);
                }
            }
        }
        let mut size = vec![0usize; parent.len()];
        for i in 0..parent.len() {
            let r = root(&mut parent, i);
            size[r] += 1;
        }
        let Some(best) = (0..size.len()).max_by(|&x, &y| size[x].cmp(&size[y]).then(y.cmp(&x))) else {
            return Vec::new();
        };
        (0..parent.len()).filter(|&i| root(&mut parent, i) == best).collect()
    }

    /// The snapshot restricted to the particles `keep` (indices into [`Self::particles`]), with every wall and the
    /// contacts whose particle sides are all kept. Particle indices are renumbered in the order of `keep`.
    pub fn restricted_to(&self, keep: &[usize]) -> Snapshot {
        let mut new_index = vec![None; self.particles.len()];
        let mut particles = Vec::with_capacity(keep.len());
        for &i in keep {
            if new_index.get(i) == Some(&None) {
                new_index[i] = Some(particles.len());
                particles.push(self.particles[i].clone());
            }
        }
        let remap = |body: BodyRef| match body {
            BodyRef::Particle(i) => new_index.get(i).copied().flatten().map(BodyRef::Particle),
            wall => Some(wall),
        };
        let contacts =
            self.contacts.iter().filter_map(|c| Some(Contact { a: remap(c.a)?, b: remap(c.b)?, ..*c })).collect();
        Snapshot { time: self.time, gravity: self.gravity, particles, walls: self.walls.clone(), contacts }
    }
}
