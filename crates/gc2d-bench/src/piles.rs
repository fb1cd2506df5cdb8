//! The standard benchmark piles: how each is built and how long it settles before it is measured.

use crate::deposition::{DepositionPlan, deposit};
use crate::{benchmark_config, disk_material, square_material, thesis_material};
use gc2d_engine::{BodyShape, InteractionTable, MassModel, MaterialId, MaterialPair, WallMotion, World};
use gc2d_geometry::{ConvexPolygon, DVec2, Pose, rectangle, square};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Packing fraction assumed when sizing the box of a deposited pile; sequential deposition packs somewhat looser.
const ASSUMED_PACKING: f64 = 0.75;
/// Depth of the layers, m.
const LAYER_DEPTH: f64 = 0.01;
/// Thickness of the container walls, m.
const WALL_THICKNESS: f64 = 0.01;

/// One of the piles every benchmark of gc2d-rs measures on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum StandardPile {
    /// The thesis's 7-gons (RAND1, semi-axes 1.75 mm ± 25 %, E = 10⁷ N/m, γ = 0.75, μ = 0.6, Δt = 2 µs) deposited
    /// in a box twice as wide as the pile is high: the dense pile of the throughput tables.
    Dense7gons,
    /// Squares of 4.5 mm with the contact law of the LAMMPS comparison, deposited in its box (12·sqrt(N/2) mm wide).
    Squares,
    /// The thesis's 7-gons in a layer 1 cm deep, as wide as it takes: the same local packing at every size, so its
    /// time per particle-step shows how the step scales with the number of grains.
    Layer,
    /// Exact disks of 1 mm ± 20 % (linear spring, e = 0.5, μ = 0.5) settled from a hexagonal lattice.
    Disks,
}

impl StandardPile {
    /// Every standard pile, in the order the benchmarks print them.
    pub const ALL: [StandardPile; 4] = [Self::Dense7gons, Self::Squares, Self::Layer, Self::Disks];

    /// The pile's name on the command line and in tables.
    pub fn name(self) -> &'static str {
        match self {
            Self::Dense7gons => "dense7",
            Self::Squares => "squares",
            Self::Layer => "layer",
            Self::Disks => "disks",
        }
    }

    /// The pile of this name, if any.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|pile| pile.name() == name)
    }

    /// The sizes (particles) measured when none are asked for: those of docs/performance.md.
    pub fn default_sizes(self) -> &'static [usize] {
        match self {
            Self::Dense7gons => &[2_000, 10_000],
            Self::Squares => &[800, 3_200, 12_800],
            Self::Layer => &[1_000, 10_000, 100_000],
            Self::Disks => &[10_000],
        }
    }

    /// Simulated time the pile settles before it is measured, s: the kinetic energy has peaked and decayed (dense
    /// piles: 30,000 steps; squares: the 20,000 steps of the LAMMPS comparison; disks: until the energy levels off).
    pub fn settle_time(self) -> f64 {
        match self {
            Self::Dense7gons => 0.06,
            Self::Squares => 0.06,
            Self::Layer => 0.005,
            Self::Disks => 0.4,
        }
    }

    /// The seed of the pile's random draws (shapes, orientations, deposition offsets, radii): the ones the
    /// figures of docs/performance.md were measured with.
    pub fn seed(self) -> u64 {
        match self {
            Self::Dense7gons | Self::Layer => 2_000,
            Self::Squares => 2_025,
            Self::Disks => 10_000,
        }
    }

    /// The pile of `particles` grains before settling: deposited (polygons) or on a lattice (disks), at rest,
    /// nothing overlapping; its random draws seeded with [`seed`](Self::seed).
    pub fn build(self, particles: usize) -> World {
        let seed = self.seed();
        let mut world = match self {
            Self::Dense7gons => thesis_pile(particles, None, seed),
            Self::Layer => thesis_pile(particles, Some(LAYER_DEPTH), seed),
            Self::Squares => square_pile(particles, seed),
            Self::Disks => disk_pile(particles, seed),
        };
        world.shrink_to_fit();
        world
    }
}

/// Floor with its top at y = 0 between x = 0 and x = `width`, and side walls of height `height` on both sides.
pub fn add_container(world: &mut World, width: f64, height: f64) {
    let t = WALL_THICKNESS;
    let floor = rectangle(width + 2.0 * t, t).expect("positive size");
    world.add_wall(&floor, Pose::new(DVec2::new(0.5 * width, -0.5 * t), 0.0), DVec2::ZERO, WallMotion::Static);
    let side = rectangle(t, height).expect("positive size");
    for x in [-0.5 * t, width + 0.5 * t] {
        world.add_wall(&side, Pose::new(DVec2::new(x, 0.5 * height), 0.0), DVec2::ZERO, WallMotion::Static);
    }
}

/// `count` of the thesis's 7-gons deposited in a box twice as wide as high, or in a layer of depth `layer` (m).
fn thesis_pile(count: usize, layer: Option<f64>, seed: u64) -> World {
    use thesis_material::{DENSITY, SEMI_AXIS, SIZE_VARIATION, thesis_config, thesis_recipe};
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let recipe = thesis_recipe();
    let shapes: Vec<(ConvexPolygon, f64)> =
        (0..count).map(|_| recipe.draw(&mut rng).expect("the thesis recipe is valid")).collect();
    let covered = shapes.iter().map(|(shape, _)| shape.area()).sum::<f64>() / ASSUMED_PACKING;
    let (width, height) = match layer {
        None => ((2.0 * covered).sqrt(), (2.0 * covered).sqrt()),
        Some(depth) => (covered / depth, 4.0 * depth),
    };
    let mut world = World::new(thesis_config(seed)).expect("the thesis parameters are valid");
    add_container(&mut world, width, height);
    let plan = DepositionPlan { width, column_width: 2.0 * SEMI_AXIS * (1.0 + SIZE_VARIATION), turn_span: TAU };
    deposit(&mut world, &shapes, plan, DENSITY, &mut rng);
    world
}

/// `count` squares deposited in the LAMMPS comparison's box, each at a random angle turned to the one of 12 quarter
/// turn steps (7.5° apart) that rests lowest.
fn square_pile(count: usize, seed: u64) -> World {
    use square_material::{DENSITY, SIDE, box_width, square_config};
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let shape = square(SIDE).expect("positive side");
    let shapes: Vec<(ConvexPolygon, f64)> =
        (0..count).map(|_| (shape.clone(), rng.random_range(0.0..FRAC_PI_2))).collect();
    let width = box_width(count);
    let height = 2.0 * count as f64 * SIDE * SIDE / width / ASSUMED_PACKING;
    let mut world = World::new(square_config(seed)).expect("the squares' parameters are valid");
    add_container(&mut world, width, height);
    let plan = DepositionPlan { width, column_width: SIDE * 2f64.sqrt(), turn_span: FRAC_PI_2 };
    deposit(&mut world, &shapes, plan, DENSITY, &mut rng);
    world
}

/// `count` disks on a hexagonal lattice in a box twice as wide as the settled pile will be high (floor and side walls
/// high enough for the lattice), at rest, under gravity.
fn disk_pile(count: usize, seed: u64) -> World {
    use disk_material::{ASSUMED_PACKING, DENSITY, LATTICE_GAP, RADIUS, SIZE_VARIATION, contact_model, time_step};
    let model = contact_model();
    let interactions = InteractionTable::new(1, &[MaterialPair { a: MaterialId(0), b: MaterialId(0), model }])
        .expect("a complete table");
    let config = benchmark_config(time_step(&model), interactions, MassModel::SphereEquivalent, 9.81, seed);
    let mut world = World::new(config).expect("valid configuration");
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let radii: Vec<f64> =
        (0..count).map(|_| RADIUS * (1.0 + rng.random_range(-SIZE_VARIATION..SIZE_VARIATION))).collect();
    let covered = radii.iter().map(|r| PI * r * r).sum::<f64>() / ASSUMED_PACKING;
    let width = (2.0 * covered).sqrt();
    let spacing = 2.0 * RADIUS * (1.0 + SIZE_VARIATION) + LATTICE_GAP;
    let columns = (((width - spacing) / spacing).floor() as usize).max(1);
    let row_height = spacing * 3f64.sqrt() / 2.0;
    let rows = count.div_ceil(columns);
    add_container(&mut world, width, (rows as f64 + 1.0) * row_height);
    for (k, &radius) in radii.iter().enumerate() {
        let (row, column) = (k / columns, k % columns);
        let shift = if row % 2 == 0 { 0.5 } else { 1.0 };
        let position = DVec2::new((column as f64 + shift) * spacing, (row as f64 + 0.5) * row_height + 0.5 * spacing);
        world
            .add_particle(BodyShape::Disk { radius }, Pose::new(position, 0.0), DENSITY, DVec2::ZERO, 0.0)
            .expect("finite pose");
    }
    world
}
