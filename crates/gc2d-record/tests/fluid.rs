//! The fluid drawn under the particles (issue 15 item 6): the arrows' geometry against the field, the `/fluid` topic
//! of a recording read back with the mcap crate (absent without a fluid), and PNG pictures that show the arrows.

mod common;

use common::{TIME_STEP, add_box, add_heptagon, check_with_reference_reader, checker_python, falling_heptagons};
use foxglove::Decode;
use foxglove::schemas::SceneUpdate;
use gc2d_engine::{Fluid, WallMotion, World};
use gc2d_fluid::{DragCoefficient, FluidField, FluidProperties, Poiseuille};
use gc2d_geometry::{Aabb, DVec2};
use gc2d_record::fluid::{ARROWS_ALONG_LONGER_SIDE, MIN_ARROWS_ACROSS, drawn_region, fluid_arrows};
use gc2d_record::png::encode_png;
use gc2d_record::{FLUID_ENTITY, Observer, PngOptions, RecordOptions, Recorder, RunInfo};
use std::path::Path;

fn air(field: FluidField) -> Fluid {
    Fluid {
        field,
        properties: FluidProperties { density_kg_m3: 1.2, dynamic_viscosity_pa_s: 1.8e-5 },
        drag: DragCoefficient::Constant(0.47),
        buoyancy: true,
    }
}

/// The box of the common worlds with one heptagon, in air flowing as `field`.
fn world_in(field: Option<FluidField>) -> World {
    let mut world = common::empty_world();
    add_box(&mut world, WallMotion::Static);
    add_heptagon(&mut world, DVec2::new(0.0, 0.1), 0.0);
    if let Some(field) = field {
        world.set_fluid(air(field)).unwrap();
    }
    world
}

#[test]
fn arrows_follow_the_field_and_the_longest_spans_most_of_a_cell() {
    // A channel along +y, 0.3 m wide: the arrows point up, longest on the axis, zero at the walls.
    let channel = Poiseuille::new(DVec2::new(0.0, 0.3), DVec2::Y, 0.15, 2.0).unwrap();
    let world = world_in(Some(FluidField::Poiseuille(channel)));
    let region = Aabb { min: DVec2::new(-0.15, 0.0), max: DVec2::new(0.15, 0.6) };
    let arrows = fluid_arrows(&world, region).unwrap();
    let spacing = 0.6 / ARROWS_ALONG_LONGER_SIDE as f64;
    let across = ((0.3 / spacing).round() as usize).max(MIN_ARROWS_ACROSS);
    assert_eq!(arrows.len(), ARROWS_ALONG_LONGER_SIDE * across);
    let longest = arrows.iter().map(|a| (a.head - a.tail).length()).fold(0.0, f64::max);
    assert!((longest - 0.9 * spacing).abs() < 1e-12, "{longest} against {}", 0.9 * spacing);
    // Each arrow is u at its grid point, scaled so that the frame's largest speed spans 0.9 of a cell.
    let max_speed = arrows.iter().map(|a| a.speed).fold(0.0, f64::max);
    for arrow in &arrows {
        let u = channel.velocity(arrow.tail);
        assert!((arrow.speed - u.length()).abs() < 1e-12);
        let expected = u * (0.9 * spacing / max_speed);
        assert!(
            (arrow.head - arrow.tail - expected).length() < 1e-12,
            "{} against {expected}",
            arrow.head - arrow.tail
        );
        assert_eq!(arrow.segments().len(), if u == DVec2::ZERO { 0 } else { 3 });
    }
    // A World without a fluid draws none.
    assert!(fluid_arrows(&world_in(None), region).is_none());
}

fn messages_of(path: &Path, topic: &str) -> Vec<Vec<u8>> {
    let bytes = std::fs::read(path).unwrap();
    mcap::MessageStream::new(&bytes)
        .unwrap()
        .map(Result::unwrap)
        .filter(|m| m.channel.topic == topic)
        .map(|m| m.data.into_owned())
        .collect()
}

fn record(world: &mut World, name: &str) -> std::path::PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("fluid");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    let options = RecordOptions { frames_per_second: 100.0, ..RecordOptions::default() };
    let mut recorder = Recorder::create(&path, options, &RunInfo::default()).unwrap();
    recorder.observe(world).unwrap();
    while world.time() < 0.02 {
        world.step().unwrap();
        recorder.observe(world).unwrap();
    }
    recorder.finish().unwrap();
    path
}

#[test]
fn a_recording_carries_the_fluid_on_its_own_topic_only_when_there_is_one() {
    let mut world = world_in(Some(FluidField::Uniform(DVec2::new(3.0, 0.0))));
    let path = record(&mut world, "uniform.mcap");
    let frames = messages_of(&path, "/fluid");
    assert_eq!(frames.len(), messages_of(&path, "/particles").len(), "one /fluid message per frame");
    let update = SceneUpdate::decode(frames[0].as_slice()).unwrap();
    assert_eq!(update.entities.len(), 1);
    let entity = &update.entities[0];
    assert_eq!(entity.id, FLUID_ENTITY);
    let line = &entity.lines[0];
    let region = drawn_region(&world).unwrap();
    let arrows = fluid_arrows(&world, region).unwrap();
    assert_eq!(line.points.len(), 6 * arrows.len(), "a shaft and two barbs per arrow");
    // Every shaft points along +x.
    for shaft in line.points.chunks(6) {
        assert!(shaft[1].x > shaft[0].x && (shaft[1].y - shaft[0].y).abs() < 1e-12);
    }
    let mut still = falling_heptagons(3);
    let path = record(&mut still, "still.mcap");
    assert!(messages_of(&path, "/fluid").is_empty());
}

/// The reference reader (tools/check_mcap.py, the `mcap` Python package) finds the `/fluid` topic with one message
/// per frame, each drawing every arrow.
#[test]
fn the_reference_reader_reads_the_fluid_topic() {
    let mut world = world_in(Some(FluidField::Uniform(DVec2::new(3.0, 0.0))));
    let arrows = fluid_arrows(&world, drawn_region(&world).unwrap()).unwrap().len();
    let path = record(&mut world, "uniform-for-the-reference-reader.mcap");
    let Some(python) = checker_python() else { return };
    let expect = serde_json::json!({
        "frames_per_second": 100.0,
        "time_step": TIME_STEP,
        "particle_counts": [1, 1, 1],
        "walls_messages": 1,
        "attachment": null,
        "truncated": false,
        "fluid_arrows": arrows,
    });
    check_with_reference_reader(&python, &path, &expect);
}

#[test]
fn a_png_shows_the_arrows() {
    let options = PngOptions { width: 400, ..PngOptions::default() };
    let with = encode_png(&world_in(Some(FluidField::Uniform(DVec2::new(3.0, 0.0)))), &options).unwrap();
    let without = encode_png(&world_in(None), &options).unwrap();
    assert_ne!(with, without);
}
