//! A recording of a tiny ball mill (tests/data/mill_tiny.ron) read back: the rotor turns at its speed in the `/walls`
//! frames, the balls are coloured by speed, and `/stats` carries the rotor's power and the median ball speed.

use foxglove::Decode;
use foxglove::schemas::{Color, SceneUpdate};
use gc2d_engine::{BodyKind, World};
use gc2d_geometry::ShapeView;
use gc2d_record::colour::viridis;
use gc2d_record::{Observer, RecordOptions, Recorder, RunInfo};
use gc2d_scene::Scene;
use std::collections::BTreeMap;
use std::path::Path;

/// The rotor's speed in mill_tiny.ron, rad/s (1700 rpm).
const ROTOR_OMEGA: f64 = 1700.0 * std::f64::consts::TAU / 60.0;

/// What the World was at one recorded frame.
struct FrameTruth {
    /// |v| of every ball, in slot order, m/s.
    speeds: Vec<f64>,
    /// `World::rotor_power().power_from_work`, W.
    rotor_power: f64,
}

fn eight_bit(c: gc2d_record::colour::Rgba) -> [f64; 3] {
    let q = |x: f64| (x * 255.0).round() / 255.0;
    [q(c.r), q(c.g), q(c.b)]
}

fn rgb(c: &Color) -> [f64; 3] {
    [c.r, c.g, c.b]
}

/// The direction of the segment from a primitive's first to its second point, rad.
fn heading(update: &SceneUpdate, id: &str) -> f64 {
    let entity = update.entities.iter().find(|e| e.id == id).unwrap_or_else(|| panic!("no wall entity {id}"));
    let points = &entity.triangles[0].points;
    (points[1].y - points[0].y).atan2(points[1].x - points[0].x)
}

#[test]
fn a_mill_recording_turns_the_rotor_colours_balls_by_speed_and_carries_rotor_power_and_median_speed() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/mill_tiny.ron");
    let scene = Scene::from_str(&std::fs::read_to_string(&data).unwrap(), "mill_tiny.ron").unwrap();
    let mut world = scene.build().unwrap();
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("mill_tiny.mcap");
    let options = RecordOptions { frames_per_second: scene.run.frames_per_second, ..RecordOptions::default() };
    let mut recorder = Recorder::create(&path, options, &RunInfo::default()).unwrap();

    let mut truth: BTreeMap<u64, FrameTruth> = BTreeMap::new();
    let mut observe = |world: &World, recorder: &mut Recorder| {
        let before = recorder.frames();
        recorder.observe(world).unwrap();
        if recorder.frames() > before {
            let b = world.bodies();
            let speeds = b.particles().map(|id| b.velocity[id.index()].length()).collect();
            let log_time = gc2d_record::recorder::simulated_nanoseconds(world.time());
            truth.insert(log_time, FrameTruth { speeds, rotor_power: world.rotor_power().power_from_work });
        }
    };
    observe(&world, &mut recorder);
    while world.time() + 0.5 * world.time_step() < scene.run.end_time_s {
        world.step().unwrap();
        observe(&world, &mut recorder);
    }
    let frames = recorder.finish().unwrap().frames;
    assert_eq!(frames, 9, "frames at 0, 0.5, …, 4 ms");

    let bytes = std::fs::read(&path).unwrap();
    let mut topics: BTreeMap<String, Vec<(u64, Vec<u8>)>> = BTreeMap::new();
    for message in mcap::MessageStream::new(&bytes).unwrap() {
        let message = message.unwrap();
        topics.entry(message.channel.topic.clone()).or_default().push((message.log_time, message.data.into_owned()));
    }
    // The world's metadata gives no overlap-area modulus for a mill whose pairs all have a Hertz law (it said 0).
    let world_record = mcap::read::LinearReader::new(&bytes)
        .unwrap()
        .filter_map(|record| match record.unwrap() {
            mcap::records::Record::Metadata(metadata) if metadata.name == "gc2d-rs.world" => Some(metadata.metadata),
            _ => None,
        })
        .next()
        .expect("a gc2d-rs.world record");
    assert!(world_record.contains_key("time_step") && !world_record.contains_key("e_modulus"), "{world_record:?}");

    // The rotor turns: walls are re-sent in every frame, and each blade has turned by ω·Δt since the last one (the
    // hub is a circle, traced the same at any angle).
    let walls: Vec<(u64, SceneUpdate)> =
        topics["/walls"].iter().map(|(t, data)| (*t, SceneUpdate::decode(data.as_slice()).unwrap())).collect();
    assert_eq!(walls.len() as u64, frames, "the rotor moves between any two frames");
    let b = world.bodies();
    let rotor: Vec<String> = (0..b.len())
        .filter(|&i| b.kind[i] == BodyKind::Wall && b.angular_velocity[i] != 0.0)
        .filter(|&i| matches!(b.shape_view(gc2d_engine::BodyId(i as u32)), ShapeView::Capsule { .. }))
        .map(|i| format!("w{i}"))
        .collect();
    assert_eq!(rotor.len(), 2, "the bar's two blades turn");
    for pair in walls.windows(2) {
        let ((t0, before), (t1, after)) = (&pair[0], &pair[1]);
        let expected = ROTOR_OMEGA * (t1 - t0) as f64 * 1e-9;
        for id in &rotor {
            let turned = (heading(after, id) - heading(before, id)).rem_euclid(std::f64::consts::TAU);
            assert!(
                (turned - expected).abs() < 1e-6,
                "{id} turned {turned} rad in {} ns, expected {expected}",
                t1 - t0
            );
        }
    }

    // Balls coloured by speed (viridis from 0 to the frame's fastest ball), and the statistics of the World.
    let mut colours_seen = std::collections::BTreeSet::new();
    let mut rotor_worked = false;
    for ((log_time, particles), (stats_time, stats)) in topics["/particles"].iter().zip(&topics["/stats"]) {
        assert_eq!(log_time, stats_time);
        let frame = &truth[log_time];
        let update = SceneUpdate::decode(particles.as_slice()).unwrap();
        let colours: Vec<&Color> = update.entities.iter().flat_map(|e| &e.triangles[0].colors).collect();
        let per_ball = colours.len() / frame.speeds.len();
        assert_eq!(per_ball * frame.speeds.len(), colours.len(), "every ball has the same number of points");
        let fastest = frame.speeds.iter().copied().fold(0.0, f64::max);
        for (k, speed) in frame.speeds.iter().enumerate() {
            let expected = eight_bit(viridis(speed / fastest));
            let ball = &colours[k * per_ball..(k + 1) * per_ball];
            assert!(ball.iter().all(|c| rgb(c) == expected), "frame {log_time}: ball {k} at {speed} m/s");
            colours_seen.insert(expected.map(f64::to_bits));
        }

        let stats: serde_json::Value = serde_json::from_slice(stats).unwrap();
        let mut sorted = frame.speeds.clone();
        sorted.sort_by(f64::total_cmp);
        let n = sorted.len();
        let median = if n % 2 == 1 { sorted[n / 2] } else { 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]) };
        // serde_json's default number parser may miss the written f64 by an ulp.
        let close = |field: &str, expected: f64| {
            let got = stats[field].as_f64().unwrap();
            assert!((got - expected).abs() <= 1e-15 * expected.abs(), "frame {log_time}: {field} {got} != {expected}");
        };
        close("median_speed", median);
        close("rotor_power", frame.rotor_power);
        assert!(stats["rotor_torque"].is_number());
        rotor_worked |= frame.rotor_power != 0.0;
    }
    assert!(colours_seen.len() > 10, "speeds differ, so do colours: {} colours", colours_seen.len());
    assert!(rotor_worked, "the rotor hit a ball in a recorded frame, so /stats shows a non-zero power");
}
