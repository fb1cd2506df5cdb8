//! `gc2d-rs run --live`: an independent WebSocket client (tungstenite, speaking the Foxglove WebSocket protocol by
//! hand) connects to a running gc2d-rs, subscribes to `/stats` and decodes a frame; and the live view leaves the
//! run's results untouched.
#![cfg(feature = "live")]

use std::io::{BufRead, BufReader};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};
use tungstenite::client::IntoClientRequest;
use tungstenite::stream::MaybeTlsStream;
use tungstenite::{Message, WebSocket};

/// How long the test waits for the server before it fails (a guard against a hang, not a timing assertion).
const DEADLINE: Duration = Duration::from_secs(60);

/// The tiny mill of gc2d-record's recording tests: 40 balls, a 1700 rpm rotor bar.
fn scene() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../gc2d-record/tests/data/mill_tiny.ron")
}

/// Kills the run when the test ends, however it ends.
struct Running(Child);

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// The next message, or `None` after the read timeout.
fn next_message(client: &mut WebSocket<MaybeTlsStream<TcpStream>>) -> Option<Message> {
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
fn a_websocket_client_decodes_a_stats_frame_of_a_running_simulation() {
    let out = tempfile::tempdir().unwrap();
    let child = Command::new(env!("CARGO_BIN_EXE_gc2d-rs"))
        .args(["run", scene().to_str().unwrap(), "--quiet", "--until", "10", "--live", "127.0.0.1:0", "--out"])
        .arg(out.path())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut running = Running(child);
    let stderr = BufReader::new(running.0.stderr.take().unwrap());
    let line = stderr
        .lines()
        .map_while(Result::ok)
        .find(|line| line.starts_with("live view at ws://"))
        .expect("gc2d-rs says where the live view is");
    let url = line.trim_start_matches("live view at ").split(':').take(3).collect::<Vec<_>>().join(":");
    let port: u16 = url.rsplit(':').next().unwrap().parse().unwrap();
    assert_ne!(port, 0, "the port the server got: {line}");

    let mut request = url.as_str().into_client_request().unwrap();
    request.headers_mut().insert("sec-websocket-protocol", "foxglove.sdk.v1".parse().unwrap());
    let (mut client, _) = tungstenite::connect(request).expect("connect to the live view");
    if let MaybeTlsStream::Plain(stream) = client.get_ref() {
        stream.set_read_timeout(Some(Duration::from_millis(200))).unwrap();
    }
    let started = Instant::now();
    let mut stats_channel = None;
    while stats_channel.is_none() {
        assert!(started.elapsed() < DEADLINE, "/stats was not advertised");
        if let Some(Message::Text(text)) = next_message(&mut client) {
            let json: serde_json::Value = serde_json::from_str(&text).unwrap();
            if json["op"] == "advertise" {
                stats_channel = json["channels"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .find(|c| c["topic"] == "/stats")
                    .map(|c| c["id"].as_u64().unwrap());
            }
        }
    }
    let subscribe = serde_json::json!({
        "op": "subscribe",
        "subscriptions": [{ "id": 7, "channelId": stats_channel.unwrap() }],
    });
    client.send(Message::text(subscribe.to_string())).unwrap();
    let data = loop {
        assert!(started.elapsed() < DEADLINE, "no /stats frame arrived");
        if let Some(Message::Binary(data)) = next_message(&mut client) {
            break data;
        }
    };
    // Message data: opcode 1, subscription id (u32), log time (u64, simulated ns), then the JSON.
    assert_eq!((data[0], u32::from_le_bytes(data[1..5].try_into().unwrap())), (1, 7));
    let log_time = u64::from_le_bytes(data[5..13].try_into().unwrap());
    let stats: serde_json::Value = serde_json::from_slice(&data[13..]).unwrap();
    assert_eq!(stats["particles"], 40, "the tiny mill's 40 balls");
    let time = stats["time"].as_f64().unwrap();
    assert!(
        (time * 1e9 - log_time as f64).abs() <= 0.5,
        "log time {log_time} ns is the frame's simulated time {time} s"
    );
    // Frames come on the scene's cadence (2000 per simulated second): at whole multiples of 0.5 ms, within a step.
    let ticks = time / 5e-4;
    assert!((ticks - ticks.round()).abs() * 5e-4 <= 0.5 * 7.5e-7 + 1e-12, "t = {time} s is not a frame tick");
    for field in ["rotor_power", "rotor_torque", "median_speed", "kinetic"] {
        assert!(stats[field].is_number(), "/stats.{field}");
    }
}

#[test]
fn the_live_view_leaves_the_run_bitwise_unchanged() {
    let run = |live: bool| {
        let out = tempfile::tempdir().unwrap();
        let mut command = Command::new(env!("CARGO_BIN_EXE_gc2d-rs"));
        command.args(["run", scene().to_str().unwrap(), "--quiet", "--until", "0.002", "--out"]).arg(out.path());
        if live {
            command.args(["--live", "127.0.0.1:0"]);
        }
        let output = command.output().unwrap();
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
        let read = |name: &str| std::fs::read(out.path().join(name)).unwrap();
        (read("final.ckpt"), read("timeseries.csv"))
    };
    assert!(run(false) == run(true), "final.ckpt and timeseries.csv are the same with --live");
}
