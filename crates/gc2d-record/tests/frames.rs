//! What a frame shows: colours, pressures, coordination, wall updates and force-line widths, checked against the
//! physics of simple Worlds and read back with the mcap crate's reader.

mod common;

use common::{DENSITY, add_box, add_heptagon, empty_world, heptagon_on_the_floor};
use foxglove::Decode;
use foxglove::schemas::SceneUpdate;
use gc2d_engine::motion::Vibration;
use gc2d_engine::{WallMotion, World};
use gc2d_geometry::{DVec2, Pose, regular_polygon};
use gc2d_record::colour::{category, force_colour, viridis};
use gc2d_record::network::{
    FORCE_WIDTH_CLASSES, class_width, collect_contact_forces, contact_segments, line_width, width_class,
};
use gc2d_record::quantities::{
    ParticleColours, contact_pressures, mean_coordination, mean_inscribed_radius, perimeter,
};
use gc2d_record::recorder::DEFAULT_FORCE_WIDTH_RADII;
use gc2d_record::{ColourBy, ColourRange, Observer, RecordOptions, Recorder, RunInfo};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn scratch_file(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("frames");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Every message of an MCAP file, by topic, in file order, read with the mcap crate.
fn messages_by_topic(path: &Path) -> BTreeMap<String, Vec<(u64, Vec<u8>)>> {
    let bytes = std::fs::read(path).unwrap();
    let mut topics: BTreeMap<String, Vec<(u64, Vec<u8>)>> = BTreeMap::new();
    for message in mcap::MessageStream::new(&bytes).unwrap() {
        let message = message.unwrap();
        topics.entry(message.channel.topic.clone()).or_default().push((message.log_time, message.data.into_owned()));
    }
    topics
}

/// Runs `world` to `t_end` with `recorder` observing every step.
fn run(world: &mut World, recorder: &mut Recorder, t_end: f64) {
    recorder.observe(world).unwrap();
    while world.time() + 0.5 * world.time_step() < t_end {
        world.step().unwrap();
        recorder.observe(world).unwrap();
    }
}

#[test]
fn a_resting_heptagon_presses_with_its_weight_over_its_perimeter() {
    let mut world = heptagon_on_the_floor();
    world.run_until(1.0).unwrap();
    let b = world.bodies();
    let particle = b.particles().next().unwrap();
    assert!(b.velocity[particle.index()].length() < 1e-4, "settled: v = {}", b.velocity[particle.index()]);

    let mut forces = Vec::new();
    let max_force = collect_contact_forces(&world, &mut forces);
    assert_eq!(forces.len(), 1, "one contact, with the floor");
    let weight = b.mass[particle.index()] * 9.81;
    assert!((max_force - weight).abs() < 1e-3 * weight, "|F| = {max_force}, m g = {weight}");

    let mut pressures = Vec::new();
    contact_pressures(&world, &forces, &mut pressures);
    let expected = weight / perimeter(b.world_vertices_of(particle));
    assert!((pressures[particle.index()] - expected).abs() < 1e-3 * expected, "p = {}", pressures[particle.index()]);
    assert_eq!(pressures[0], 0.0, "walls carry no pressure value");
    assert_eq!(mean_coordination(&world, &forces), 1.0, "a wall contact counts once, for its particle");
}

/// Three heptagons at rest apart, moving at 0, 1 and 2 m/s, of densities 1000, 2000 and 1000 kg/m².
fn three_heptagons() -> World {
    let mut world = empty_world();
    add_box(&mut world, WallMotion::Static);
    let shape = regular_polygon(7, common::RADIUS).unwrap();
    for (k, (speed, density)) in [(0.0, DENSITY), (1.0, 2.0 * DENSITY), (2.0, DENSITY)].into_iter().enumerate() {
        let pose = Pose::new(DVec2::new(-0.1 + 0.1 * k as f64, 0.2), 0.0);
        world.add_particle(&shape, pose, density, DVec2::new(speed, 0.0), 0.0).unwrap();
    }
    world
}

#[test]
fn colours_map_speed_age_and_material_as_documented() {
    let world = three_heptagons();
    let slots: Vec<usize> = world.bodies().particles().map(|id| id.index()).collect();
    let mut colours = ParticleColours::default();
    let colours_of = |colours: &ParticleColours| slots.iter().map(|&i| colours.colours[i]).collect::<Vec<_>>();

    colours.update(&world, ColourBy::Speed, ColourRange::Auto, &[]);
    assert_eq!(colours_of(&colours), vec![viridis(0.0), viridis(0.5), viridis(1.0)], "0 to the frame's fastest");
    colours.update(&world, ColourBy::Speed, ColourRange::Fixed { min: 0.0, max: 4.0 }, &[]);
    assert_eq!(colours_of(&colours), vec![viridis(0.0), viridis(0.25), viridis(0.5)]);
    colours.update(&world, ColourBy::Age, ColourRange::Auto, &[]);
    assert_eq!(colours_of(&colours), vec![viridis(0.0), viridis(0.5), viridis(1.0)], "first to last particle");
    colours.update(&world, ColourBy::Material, ColourRange::Auto, &[]);
    assert_eq!(colours_of(&colours), vec![category(0), category(1), category(0)], "by density rank");
    colours.update(&world, ColourBy::Pressure, ColourRange::Auto, &[]);
    assert_eq!(colours_of(&colours), vec![viridis(0.0); 3], "no contacts, no pressure");
}

#[test]
fn walls_are_written_again_only_in_frames_where_a_wall_moved() {
    let vibration = Vibration { amplitude: 0.002, frequency: 5.0, ..Vibration::default() };
    for (motion, moving) in [(WallMotion::Static, false), (WallMotion::Vibrating(vibration), true)] {
        let mut world = empty_world();
        add_box(&mut world, motion);
        add_heptagon(&mut world, DVec2::new(0.0, 0.05), 0.0);
        let path = scratch_file(if moving { "vibrating.mcap" } else { "static.mcap" });
        let mut recorder = Recorder::create(&path, RecordOptions::default(), &RunInfo::default()).unwrap();
        run(&mut world, &mut recorder, 0.2);
        let frames = recorder.finish().unwrap().frames;
        assert_eq!(frames, 7);
        let topics = messages_by_topic(&path);
        let walls = topics["/walls"].len() as u64;
        assert_eq!(walls, if moving { frames } else { 1 }, "moving floor: {moving}");
        let first = SceneUpdate::decode(topics["/walls"][0].1.as_slice()).unwrap();
        assert_eq!(first.entities.len(), 3, "floor and two side walls");
    }
}

#[test]
fn force_lines_are_as_wide_as_the_force_with_the_largest_at_the_documented_width() {
    let mut world = common::falling_heptagons(30);
    world.run_until(0.3).unwrap();
    let path = scratch_file("forces.mcap");
    let mut recorder = Recorder::create(&path, RecordOptions::default(), &RunInfo::default()).unwrap();
    assert!(recorder.record_frame(&world).unwrap());
    assert!(!recorder.record_frame(&world).unwrap(), "a second frame at the same time is refused");
    recorder.finish().unwrap();

    let topics = messages_by_topic(&path);
    let contacts = SceneUpdate::decode(topics["/contacts"][0].1.as_slice()).unwrap();
    assert_eq!(contacts.entities.len(), 1);
    assert_eq!(contacts.entities[0].id, "forces");
    let lines = &contacts.entities[0].lines;
    let mut forces = Vec::new();
    let max_force = collect_contact_forces(&world, &mut forces);
    let max_width = DEFAULT_FORCE_WIDTH_RADII * mean_inscribed_radius(&world).unwrap();
    // The segments each width class should hold, in contact order: from each particle of the pair to the point.
    let mut expected: BTreeMap<usize, Vec<(DVec2, DVec2, f64)>> = BTreeMap::new();
    for force in &forces {
        let class = width_class(force.magnitude, max_force).unwrap();
        let exact = line_width(force.magnitude, max_force, max_width);
        let drawn = class_width(class, max_width);
        assert!(drawn >= exact && drawn - exact < max_width / 16.0 + 1e-15, "{drawn} vs {exact}");
        let wall_contact = force.a.index() < 3;
        let segments: Vec<_> = contact_segments(&world, force).into_iter().flatten().collect();
        assert_eq!(segments.len(), if wall_contact { 1 } else { 2 }, "a segment per particle of the contact");
        let t = force.magnitude / max_force;
        expected.entry(class).or_default().extend(segments.into_iter().map(|(from, to)| (from, to, t)));
    }
    assert_eq!(lines.len(), expected.len(), "one line list per width class in use");
    assert!(lines.len() <= FORCE_WIDTH_CLASSES);
    for (line, (class, segments)) in lines.iter().zip(&expected) {
        assert!((line.thickness - class_width(*class, max_width)).abs() <= 1e-15 * max_width);
        assert_eq!(line.points.len(), 2 * segments.len());
        assert_eq!(line.colors.len(), line.points.len(), "a colour per point");
        for (k, (from, to, t)) in segments.iter().enumerate() {
            let (start, end) = (line.points[2 * k], line.points[2 * k + 1]);
            assert_eq!((start.x, start.y, end.x, end.y), (from.x, from.y, to.x, to.y));
            let shade = force_colour(*t);
            let eight_bit = |x: f64| (x * 255.0).round() / 255.0;
            assert_eq!((line.colors[2 * k].r, line.colors[2 * k].g), (eight_bit(shade.r), eight_bit(shade.g)));
        }
    }
    let widest = lines.iter().map(|l| l.thickness).fold(0.0, f64::max);
    assert!((widest - max_width).abs() < 1e-15, "the largest force is drawn at full width");
    let particles = SceneUpdate::decode(topics["/particles"][0].1.as_slice()).unwrap();
    assert_eq!(particles.entities.len(), 1, "slots 0 to 1023 share one entity");
    let entity = &particles.entities[0];
    assert_eq!(entity.id, "particles/0");
    assert_eq!((entity.triangles.len(), entity.lines.len()), (1, 1), "one triangle list and one line list");
    assert_eq!(entity.triangles[0].points.len(), 30 * 7, "30 heptagons");
    assert_eq!(entity.triangles[0].indices.len(), 30 * 15, "five triangles each");
    assert_eq!(entity.lines[0].indices.len(), 30 * 14, "seven outline segments each");
    // Slot order: the first particle (slot 3; slots 0–2 are the walls) comes first.
    let first = world.bodies().world_vertices_of(gc2d_engine::BodyId(3));
    assert_eq!((entity.triangles[0].points[0].x, entity.triangles[0].points[0].y), (first[0].x, first[0].y));
}
