//! The live view read by an independent WebSocket client (tungstenite, speaking the Foxglove WebSocket protocol by
//! hand): it subscribes to `/stats` and `/particles` of a running World and decodes a frame of each.
#![cfg(feature = "live")]

mod common;

use common::falling_heptagons;
use foxglove::Decode;
use foxglove::schemas::SceneUpdate;
use gc2d_record::network::collect_contact_forces;
use gc2d_record::recorder::simulated_nanoseconds;
use gc2d_record::{FrameStats, LiveView, RecordOptions};
use std::collections::BTreeMap;
use std::net::TcpStream;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use tungstenite::client::IntoClientRequest;
use tungstenite::stream::MaybeTlsStream;
use tungstenite::{Message, WebSocket};

/// The subprotocol the foxglove SDK's server speaks.
const SUBPROTOCOL: &str = "foxglove.sdk.v1";
/// Opcode of a server's binary message-data frame: u32 subscription id, u64 log time, payload (little endian).
const MESSAGE_DATA: u8 = 0x01;
/// How long the test waits for the server before it fails (a guard against a hang, not a timing assertion).
const DEADLINE: Duration = Duration::from_secs(30);

type Client = WebSocket<MaybeTlsStream<TcpStream>>;

fn connect(port: u16) -> Client {
    let mut request = format!("ws://127.0.0.1:{port}").into_client_request().unwrap();
    request.headers_mut().insert("sec-websocket-protocol", SUBPROTOCOL.parse().unwrap());
    let (client, response) = tungstenite::connect(request).expect("connect to the live view");
    assert_eq!(response.headers()["sec-websocket-protocol"], SUBPROTOCOL);
    if let MaybeTlsStream::Plain(stream) = client.get_ref() {
        stream.set_read_timeout(Some(Duration::from_millis(200))).unwrap();
    }
    client
}

/// The next message, or `None` after the read timeout.
fn next_message(client: &mut Client) -> Option<Message> {
    match client.read() {
        Ok(message) => Some(message),
        Err(tungstenite::Error::Io(e))
            if matches!(e.kind(), std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut) =>
        {
            None
        }
        Err(e) => panic!("live view connection failed: {e}"),
    }
}

#[test]
fn a_websocket_client_subscribes_and_decodes_stats_and_particles_of_a_running_world() {
    let mut live = LiveView::start("127.0.0.1:0", RecordOptions::default()).unwrap();
    let port = live.port();
    assert_ne!(port, 0);

    // Nobody connected: nothing is built.
    let world = falling_heptagons(12);
    assert!(!live.has_subscribers());
    assert!(!live.publish(&world));
    assert_eq!(live.frames(), 0, "no frame is built while nobody is subscribed");

    // The run: steps the World and publishes a frame every 10 steps until the client has what it needs, keeping the
    // statistics of every published frame by log time to compare with what the client decodes.
    let published: Arc<Mutex<BTreeMap<u64, (FrameStats, usize)>>> = Arc::default();
    let done = Arc::new(AtomicBool::new(false));
    let runner = {
        let (published, done) = (Arc::clone(&published), Arc::clone(&done));
        std::thread::spawn(move || {
            let mut world = world;
            while !done.load(Ordering::Relaxed) {
                for _ in 0..10 {
                    world.step().unwrap();
                }
                let log_time = simulated_nanoseconds(world.time());
                let mut forces = Vec::new();
                let max_force = collect_contact_forces(&world, &mut forces);
                let stats = FrameStats::of(&world, &forces, max_force);
                published.lock().unwrap().insert(log_time, (stats, world.bodies().particles().count()));
                live.publish(&world);
                std::thread::sleep(Duration::from_millis(5));
            }
            live
        })
    };

    let mut client = connect(port);
    let started = Instant::now();
    let mut channels: BTreeMap<String, (u64, String, String)> = BTreeMap::new();
    while channels.len() < 4 {
        assert!(started.elapsed() < DEADLINE, "no advertisement of the four topics: {channels:?}");
        if let Some(Message::Text(text)) = next_message(&mut client) {
            let json: serde_json::Value = serde_json::from_str(&text).unwrap();
            if json["op"] == "advertise" {
                for c in json["channels"].as_array().unwrap() {
                    let entry = (
                        c["id"].as_u64().unwrap(),
                        c["encoding"].as_str().unwrap().to_string(),
                        c["schemaName"].as_str().unwrap().to_string(),
                    );
                    channels.insert(c["topic"].as_str().unwrap().to_string(), entry);
                }
            }
        }
    }
    assert_eq!(channels["/stats"].1, "json");
    assert_eq!(channels["/stats"].2, "gc2d.FrameStats");
    assert_eq!(
        (channels["/particles"].1.as_str(), channels["/particles"].2.as_str()),
        ("protobuf", "foxglove.SceneUpdate")
    );
    let subscribe = serde_json::json!({
        "op": "subscribe",
        "subscriptions": [
            { "id": 1, "channelId": channels["/stats"].0 },
            { "id": 2, "channelId": channels["/particles"].0 },
        ],
    });
    client.send(Message::text(subscribe.to_string())).unwrap();

    let (mut stats, mut particles) = (None, None);
    while stats.is_none() || particles.is_none() {
        assert!(started.elapsed() < DEADLINE, "no frame of /stats and /particles arrived");
        let Some(Message::Binary(data)) = next_message(&mut client) else { continue };
        assert_eq!(data[0], MESSAGE_DATA);
        let subscription = u32::from_le_bytes(data[1..5].try_into().unwrap());
        let log_time = u64::from_le_bytes(data[5..13].try_into().unwrap());
        let payload = data[13..].to_vec();
        match subscription {
            1 => stats = Some((log_time, payload)),
            2 => particles = Some((log_time, payload)),
            other => panic!("a message for subscription {other}"),
        }
    }
    done.store(true, Ordering::Relaxed);
    let live = runner.join().unwrap();
    assert!(live.frames() > 0);
    live.stop();

    let published = published.lock().unwrap();
    let (log_time, payload) = stats.unwrap();
    let decoded: serde_json::Value = serde_json::from_slice(&payload).unwrap();
    let (expected, _) = &published[&log_time];
    let expected = expected.to_json();
    let fields = expected.as_object().unwrap();
    assert_eq!(decoded.as_object().unwrap().len(), fields.len());
    for (field, value) in fields {
        // serde_json's default number parser may miss the written f64 by an ulp.
        let (got, want) = (decoded[field].as_f64().unwrap(), value.as_f64().unwrap());
        assert!((got - want).abs() <= 1e-15 * want.abs(), "/stats.{field} at {log_time} ns: {got} != {want}");
    }

    let (log_time, payload) = particles.unwrap();
    let update = SceneUpdate::decode(payload.as_slice()).unwrap();
    let (_, count) = published[&log_time];
    let points: usize = update.entities.iter().map(|e| e.triangles[0].points.len()).sum();
    assert_eq!(update.entities.len(), 1, "12 particles in block particles/0");
    assert_eq!(points, 7 * count, "every heptagon of the frame at {log_time} ns");
}

#[test]
fn bad_addresses_and_a_taken_port_are_errors_that_name_the_address() {
    for address in ["8765", "127.0.0.1:port", ":8765", "127.0.0.1:70000"] {
        let error = LiveView::start(address, RecordOptions::default()).err().expect(address).to_string();
        assert!(error.contains("host:port") && error.contains(address), "{address}: {error}");
    }
    let first = LiveView::start("127.0.0.1:0", RecordOptions::default()).unwrap();
    let taken = format!("127.0.0.1:{}", first.port());
    let error = LiveView::start(&taken, RecordOptions::default()).err().expect("the port is taken").to_string();
    assert!(error.contains(&taken), "{error}");
    first.stop();
}
