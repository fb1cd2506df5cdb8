//! Frame size and encode time of a recording at 1,000, 10,000 and 100,000 particles: the recorder's layout beside
//! the layout it replaced (one entity with its own primitives per particle, one line primitive per contact), which
//! this example keeps as a reference so that both are measured in one run on the same Worlds.
//!
//! ```sh
//! cargo run --release -p gc2d-record --example bench_frames            # 1e3, 1e4, 1e5 particles
//! cargo run --release -p gc2d-record --example bench_frames -- 2000    # other counts
//! ```
//!
//! A frame here is what the recorder builds and compresses per tick: the `/particles` and `/contacts` scene updates
//! and the `/stats` message, protobuf- and JSON-encoded, then compressed together with zstd at the level MCAP
//! chunks use (the default, 3). Encode time covers building the messages from the World (colours, force network,
//! statistics), encoding and compressing; not the file write. The World is a square grid of 7-gons (circumradius
//! 1 cm, 1.9 radii apart, turned by 0.37 rad per particle) on a floor, after one step, so the touching corners
//! make a force network of about one contact per particle.

use foxglove::Encode;
use foxglove::schemas::{
    Color, LinePrimitive, Point3, Pose as FoxglovePose, Quaternion, SceneEntity, SceneEntityDeletion, SceneUpdate,
    Timestamp, TriangleListPrimitive, Vector3, line_primitive, scene_entity_deletion,
};
use gc2d_contact::{ContactLaw, CundallStrack, NormalDamping};
use gc2d_engine::schedules::GravitySchedule;
use gc2d_engine::{InteractionTable, MassModel, SafetyLimits, WallMotion, World, WorldConfig};
use gc2d_geometry::{DVec2, Pose, TracedOutline, rectangle, regular_polygon};
use gc2d_record::colour::{Rgba, force_colour};
use gc2d_record::network::{collect_contact_forces, contact_segments, line_width};
use gc2d_record::quantities::{ParticleColours, mean_inscribed_radius};
use gc2d_record::recorder::DEFAULT_FORCE_WIDTH_RADII;
use gc2d_record::{FrameBuilder, FrameStats, RecordOptions};
use std::time::Instant;

/// Circumradius of the 7-gons, m.
const RADIUS: f64 = 0.01;

fn main() {
    let counts: Vec<usize> = std::env::args().skip(1).map(|a| a.parse().expect("particle count")).collect();
    let counts = if counts.is_empty() { vec![1_000, 10_000, 100_000] } else { counts };
    println!("load average before: {}", load_average());
    println!(
        "| particles | layout | /particles primitives | /contacts primitives | protobuf bytes | zstd bytes | \
         bytes/particle (zstd) | encode ms | repeats |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    let mut ratios = Vec::new();
    for &n in &counts {
        let world = grid_world(n);
        let repeats = (50_000 / n).clamp(7, 50);
        let [before, after] = measure(&world, repeats);
        for (name, m) in [("per-particle entities (before)", &before), ("recorder (after)", &after)] {
            println!(
                "| {n} | {name} | {} | {} | {} | {} | {:.1} | {:.2} | {repeats} |",
                m.particle_primitives,
                m.contact_primitives,
                m.raw_bytes,
                m.compressed_bytes,
                m.compressed_bytes as f64 / n as f64,
                1e3 * m.seconds,
            );
        }
        ratios.push((n, before, after));
    }
    println!();
    println!("| particles | contacts | protobuf after/before | zstd after/before | encode time after/before |");
    println!("|---|---|---|---|---|");
    for (n, before, after) in &ratios {
        println!(
            "| {n} | {} | {:.3} | {:.3} | {:.3} |",
            after.contacts,
            after.raw_bytes as f64 / before.raw_bytes as f64,
            after.compressed_bytes as f64 / before.compressed_bytes as f64,
            after.seconds / before.seconds,
        );
    }
    println!("load average after: {}", load_average());
}

/// Which layout builds the frame.
#[derive(Debug, Clone, Copy)]
enum Layout {
    /// The reference copy of the layout before packing ([`per_particle_frame`]).
    PerParticle,
    /// gc2d-record's [`FrameBuilder`].
    Recorder,
}

/// One layout's frame, measured.
struct Measurement {
    particle_primitives: usize,
    contact_primitives: usize,
    contacts: usize,
    raw_bytes: usize,
    compressed_bytes: usize,
    /// Median encode time of one frame, s.
    seconds: f64,
}

/// Both layouts' frames of `world`, built `repeats` times each, the two layouts taking turns so that both see the
/// same machine load.
fn measure(world: &World, repeats: usize) -> [Measurement; 2] {
    let mut builder = FrameBuilder::new(RecordOptions::default());
    let mut times = [Vec::with_capacity(repeats), Vec::with_capacity(repeats)];
    let mut last = [None, None];
    for _ in 0..repeats {
        for (k, layout) in [Layout::PerParticle, Layout::Recorder].into_iter().enumerate() {
            let started = Instant::now();
            let (particles, contacts, stats) = match layout {
                Layout::PerParticle => per_particle_frame(world),
                Layout::Recorder => {
                    let frame = builder.build(world, 1);
                    (frame.particles, frame.contacts.expect("force network on"), frame.stats)
                }
            };
            let mut raw = Vec::new();
            particles.encode(&mut raw).expect("encode /particles");
            contacts.encode(&mut raw).expect("encode /contacts");
            serde_json::to_writer(&mut raw, &stats.to_json()).expect("encode /stats");
            let compressed = zstd::bulk::compress(&raw, 0).expect("zstd");
            times[k].push(started.elapsed().as_secs_f64());
            last[k] = Some((particles, contacts, stats, raw.len(), compressed.len()));
        }
    }
    let primitives = |u: &SceneUpdate| u.entities.iter().map(|e| e.triangles.len() + e.lines.len()).sum();
    [0, 1].map(|k| {
        times[k].sort_by(f64::total_cmp);
        let (particles, contacts, stats, raw_bytes, compressed_bytes) = last[k].take().expect("at least one repeat");
        Measurement {
            particle_primitives: primitives(&particles),
            contact_primitives: primitives(&contacts),
            contacts: stats.contacts,
            raw_bytes,
            compressed_bytes,
            seconds: times[k][times[k].len() / 2],
        }
    })
}

/// `n` 7-gons on a square grid on a floor, after one step.
fn grid_world(n: usize) -> World {
    let mut world = World::new(WorldConfig {
        time_step: 1e-5,
        integrator: Default::default(),
        interactions: InteractionTable::uniform(ContactLaw {
            damping: Some(NormalDamping { gamma: 0.3 }),
            friction: Some(CundallStrack { mu: 0.5 }),
            ..ContactLaw::elastic(1e5)
        }),
        mass_model: MassModel::PerUnitThickness,
        gravity: GravitySchedule::default(),
        heating: None,
        // The grid's corners overlap by up to a few per cent of a particle's area; their first step is a kick, not a
        // sign of instability.
        safety: SafetyLimits {
            max_initial_overlap_fraction: 0.05,
            max_energy_gain_fraction: f64::INFINITY,
            ..SafetyLimits::default()
        },
        domain: None,
        seed: 1,
    })
    .expect("world");
    let columns = (n as f64).sqrt().ceil() as usize;
    let spacing = 1.9 * RADIUS;
    let width = columns as f64 * spacing;
    let floor = rectangle(width + 0.1, 0.05).expect("floor");
    world.add_wall(&floor, Pose::new(DVec2::new(0.5 * width, -0.025), 0.0), DVec2::ZERO, WallMotion::Static);
    let shape = regular_polygon(7, RADIUS).expect("7-gon");
    for k in 0..n {
        let position = DVec2::new((k % columns) as f64 + 0.5, (k / columns) as f64 + 0.5) * spacing;
        world.add_particle(&shape, Pose::new(position, 0.37 * k as f64), 1000.0, DVec2::ZERO, 0.0).expect("7-gon");
    }
    world.step().expect("one step");
    world
}

/// The frame as gc2d-record built it before the packing: every particle its own entity `p<slot>` with a triangle
/// list and a line loop, and one line list per contact.
fn per_particle_frame(world: &World) -> (SceneUpdate, SceneUpdate, FrameStats) {
    let radius = mean_inscribed_radius(world).expect("particles");
    let layer = 0.05 * radius;
    let stamp = Timestamp::new(0, 1);
    let mut forces = Vec::new();
    let max_force = collect_contact_forces(world, &mut forces);
    let mut colours = ParticleColours::default();
    let options = RecordOptions::default();
    colours.update(world, options.colour_by, options.colour_range, &forces);
    let entity =
        |id: String| SceneEntity { timestamp: Some(stamp), frame_id: "world".into(), id, ..Default::default() };
    let clear = || SceneEntityDeletion {
        timestamp: Some(stamp),
        r#type: scene_entity_deletion::Type::All as i32,
        id: String::new(),
    };
    let bodies = world.bodies();
    let entities = bodies
        .particles()
        .map(|id| {
            let outline = bodies.shape_view(id).traced_outline();
            let TracedOutline::Convex(vertices) = outline else { unreachable!("particles are convex") };
            let fill = colours.colours[id.index()];
            let mut e = entity(format!("p{}", id.0));
            let points: Vec<Point3> = vertices.iter().map(|&v| point(v)).collect();
            e.triangles.push(TriangleListPrimitive {
                pose: Some(lifted(0.0)),
                points: points.clone(),
                color: Some(color(fill)),
                colors: Vec::new(),
                indices: (1..vertices.len() as u32 - 1).flat_map(|k| [0, k, k + 1]).collect(),
            });
            e.lines.push(LinePrimitive {
                r#type: line_primitive::Type::LineLoop as i32,
                pose: Some(lifted(layer)),
                thickness: 1.0,
                scale_invariant: true,
                points,
                color: Some(color(fill.darkened(0.55))),
                colors: Vec::new(),
                indices: Vec::new(),
            });
            e
        })
        .collect();
    let particles = SceneUpdate { deletions: vec![clear()], entities };
    let max_width = DEFAULT_FORCE_WIDTH_RADII * radius;
    let mut network = entity("forces".into());
    for force in &forces {
        let width = line_width(force.magnitude, max_force, max_width);
        let points: Vec<Point3> =
            contact_segments(world, force).into_iter().flatten().flat_map(|(a, b)| [point(a), point(b)]).collect();
        if width <= 0.0 || points.is_empty() {
            continue;
        }
        network.lines.push(LinePrimitive {
            r#type: line_primitive::Type::LineList as i32,
            pose: Some(lifted(2.0 * layer)),
            thickness: width,
            scale_invariant: false,
            points,
            color: Some(color(force_colour(force.magnitude / max_force))),
            colors: Vec::new(),
            indices: Vec::new(),
        });
    }
    let contacts = SceneUpdate { deletions: vec![clear()], entities: vec![network] };
    (particles, contacts, FrameStats::of(world, &forces, max_force))
}

fn point(v: DVec2) -> Point3 {
    Point3 { x: v.x, y: v.y, z: 0.0 }
}

fn color(c: Rgba) -> Color {
    Color { r: c.r, g: c.g, b: c.b, a: c.a }
}

fn lifted(z: f64) -> FoxglovePose {
    FoxglovePose {
        position: Some(Vector3 { x: 0.0, y: 0.0, z }),
        orientation: Some(Quaternion { x: 0.0, y: 0.0, z: 0.0, w: 1.0 }),
    }
}

/// The system's load average, as `/proc/loadavg` gives it.
fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg").map_or_else(|_| "unknown".into(), |s| s.trim().to_string())
}
