//! `wbv simulate --serve`: a WebSocket client (tungstenite, independent of the Foxglove SDK's
//! server) speaks the Foxglove WebSocket protocol to the running binary. The SDK's server (0.30)
//! negotiates only the subprotocols `foxglove.sdk.v1` (inline schemas, the `foxglove.websocket.v1`
//! protocol under a new name) and `foxglove.sdk.v1.1`; the client offers `foxglove.sdk.v1` and
//! it reads `serverInfo` and `advertise`, subscribes to `/wbv/measured` and decodes the binary
//! message-data frames (opcode 0x01, subscription id u32 LE, log time u64 LE, payload) with
//! `prost-reflect` and the descriptor compiled from `proto/wbv.proto`, not with the encoder that
//! wrote them.
#![cfg(feature = "live")]

use base64::Engine;
use prost_reflect::{DescriptorPool, DynamicMessage, Value};
use serde_json::json;
use std::io::{BufRead, BufReader};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};
use tungstenite::client::IntoClientRequest;
use tungstenite::{Message, WebSocket, stream::MaybeTlsStream};

/// Kills the child if a check fails.
struct Killed(Child);

impl Drop for Killed {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Starts `wbv simulate --serve 127.0.0.1:0 …` and returns it with the URL it printed on stderr
/// and the rest of its stderr lines (as they come).
fn start(extra: &[&str]) -> (Killed, String, mpsc::Receiver<String>) {
    start_with(
        &["simulate", "--serve", "127.0.0.1:0", "--no-record"],
        extra,
    )
}

fn start_with(args: &[&str], extra: &[&str]) -> (Killed, String, mpsc::Receiver<String>) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_wbv"))
        .args(args)
        .args(extra)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let stderr = child.stderr.take().unwrap();
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines() {
            let Ok(line) = line else { break };
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    let child = Killed(child);
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        let line = rx
            .recv_timeout(deadline.saturating_duration_since(Instant::now()))
            .expect("the server prints its URL");
        if let Some(i) = line.find("ws://") {
            let url = line[i..].split_whitespace().next().unwrap().to_string();
            return (child, url, rx);
        }
    }
}

fn connect(url: &str) -> WebSocket<MaybeTlsStream<TcpStream>> {
    let mut request = url.into_client_request().unwrap();
    request
        .headers_mut()
        .insert("sec-websocket-protocol", "foxglove.sdk.v1".parse().unwrap());
    let (mut ws, response) = tungstenite::connect(request).unwrap();
    assert_eq!(
        response.headers()["sec-websocket-protocol"],
        "foxglove.sdk.v1"
    );
    if let MaybeTlsStream::Plain(s) = ws.get_mut() {
        s.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    }
    ws
}

fn text(ws: &mut WebSocket<MaybeTlsStream<TcpStream>>) -> serde_json::Value {
    loop {
        match ws.read().unwrap() {
            Message::Text(t) => return serde_json::from_str(&t).unwrap(),
            Message::Binary(_) => panic!("binary frame before subscribing"),
            _ => {}
        }
    }
}

/// Handles a text frame read after subscribing: the SDK 0.30 server sends `advertise` before it
/// enters the channel in the client's table (`ConnectedClient::advertise_channels`), so a client
/// that subscribes at once may get the status "Unknown channel ID" and no data; it then asks again,
/// as a viewer would. Any other error status fails the test.
fn on_text(ws: &mut WebSocket<MaybeTlsStream<TcpStream>>, t: &str, subscribe: &serde_json::Value) {
    let m: serde_json::Value = serde_json::from_str(t).unwrap();
    if m["op"] == "status" && m["level"] == 2 {
        let message = m["message"].as_str().unwrap_or_default();
        assert!(message.starts_with("Unknown channel ID"), "{m}");
        std::thread::sleep(Duration::from_millis(20));
        ws.send(Message::text(subscribe.to_string())).unwrap();
    }
}

#[test]
fn a_client_subscribes_and_decodes_the_measured_channel() {
    let (mut child, url, _stderr) = start(&["--duration", "2", "--realtime"]);
    let mut ws = connect(&url);

    let info = text(&mut ws);
    assert_eq!(info["op"], "serverInfo", "{info}");
    assert!(info["name"].as_str().unwrap().starts_with("wbv "), "{info}");

    // The SDK may advertise the channels in more than one message.
    let mut channels = Vec::new();
    while channels.len() < 5 {
        let m = text(&mut ws);
        if m["op"] == "advertise" {
            channels.extend(m["channels"].as_array().unwrap().iter().cloned());
        }
    }
    let topics: Vec<&str> = channels
        .iter()
        .map(|c| c["topic"].as_str().unwrap())
        .collect();
    for t in [
        "/wbv/measured",
        "/wbv/state",
        "/wbv/links",
        "/wbv/scene",
        "/tf",
    ] {
        assert!(topics.contains(&t), "{t} not in {topics:?}");
    }
    let measured = channels
        .iter()
        .find(|c| c["topic"] == "/wbv/measured")
        .unwrap();
    assert_eq!(measured["encoding"], "protobuf");
    assert_eq!(measured["schemaName"], "wbv.Measured");
    assert_eq!(measured["schemaEncoding"], "protobuf");
    // The advertised schema is a FileDescriptorSet holding wbv.Measured.
    let fds = base64::engine::general_purpose::STANDARD
        .decode(measured["schema"].as_str().unwrap())
        .unwrap();
    let advertised = DescriptorPool::decode(fds.as_slice()).unwrap();
    assert!(advertised.get_message_by_name("wbv.Measured").is_some());

    // Decode with the descriptor compiled from proto/wbv.proto.
    let pool =
        DescriptorPool::from_file_descriptor_set(wbv::record::proto::base_descriptor()).unwrap();
    let message = pool.get_message_by_name("wbv.Measured").unwrap();

    let sub_id = 7u32;
    let subscribe = json!({"op": "subscribe", "subscriptions": [
        {"id": sub_id, "channelId": measured["id"]}
    ]});
    ws.send(Message::text(subscribe.to_string())).unwrap();

    let started = Instant::now();
    let (mut count, mut last_log, mut last_t) = (0usize, None::<u64>, f64::NEG_INFINITY);
    let mut first_t = None;
    while count < 200 {
        let frame = match ws.read().unwrap() {
            Message::Binary(b) => b,
            Message::Close(_) => break,
            Message::Text(t) => {
                on_text(&mut ws, &t, &subscribe);
                continue;
            }
            _ => continue,
        };
        assert_eq!(frame[0], 0x01, "message data opcode");
        assert_eq!(u32::from_le_bytes(frame[1..5].try_into().unwrap()), sub_id);
        let log_time = u64::from_le_bytes(frame[5..13].try_into().unwrap());
        let msg = DynamicMessage::decode(message.clone(), &frame[13..]).unwrap();
        let get = |name: &str| match msg.get_field_by_name(name).as_deref() {
            Some(Value::F64(v)) => *v,
            other => panic!("{name}: {other:?}"),
        };
        let (t, a_seat) = (get("t"), get("a_seat_z"));
        assert!(a_seat.is_finite());
        assert!(t > last_t, "time increases: {t} after {last_t}");
        assert_eq!(
            log_time,
            (t * 1e9).round() as u64,
            "log time is simulation time"
        );
        if let Some(l) = last_log {
            assert!(log_time > l);
        }
        first_t.get_or_insert(t);
        (last_log, last_t) = (Some(log_time), t);
        count += 1;
    }
    assert_eq!(count, 200, "messages received before the run ended");
    // --realtime: 200 consecutive 1 kHz steps span ≈ 0.2 s of simulated time, which cannot
    // arrive faster than the wall clock (they may arrive slower on a busy machine).
    let span = last_t - first_t.unwrap();
    assert!(span >= 0.19, "span {span}");
    assert!(
        started.elapsed().as_secs_f64() >= span - 0.05,
        "{} s of simulation streamed in {:?} of wall time",
        span,
        started.elapsed()
    );
    drop(ws);
    let status = child.0.wait().unwrap();
    assert!(status.success());
}

#[test]
fn live_messages_are_the_recorded_messages() {
    // Record the same run per-sample beside the live view: every /wbv/state message received
    // must be byte for byte the recorded message of the same log time.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let (mut child, url, _stderr) = start_with(
        &["simulate", "--serve", "127.0.0.1:0"],
        &[
            "--duration",
            "1",
            "--realtime",
            "--layout",
            "per-sample",
            "--out",
            out.to_str().unwrap(),
        ],
    );
    let mut ws = connect(&url);
    let mut state = None;
    while state.is_none() {
        let m = text(&mut ws);
        if m["op"] == "advertise" {
            state = (m["channels"].as_array().unwrap().iter())
                .find(|c| c["topic"] == "/wbv/state")
                .cloned();
        }
    }
    let subscribe = json!({"op": "subscribe", "subscriptions": [
        {"id": 1, "channelId": state.unwrap()["id"]}
    ]});
    ws.send(Message::text(subscribe.to_string())).unwrap();
    let mut live = std::collections::BTreeMap::new();
    while let Ok(m) = ws.read() {
        match m {
            Message::Binary(b) => {
                let log_time = u64::from_le_bytes(b[5..13].try_into().unwrap());
                live.insert(log_time, b[13..].to_vec());
            }
            Message::Close(_) => break,
            Message::Text(t) => on_text(&mut ws, &t, &subscribe),
            _ => {}
        }
    }
    assert!(child.0.wait().unwrap().success());
    assert!(live.len() > 100, "{} messages received", live.len());
    let bytes = std::fs::read(out.join("run.mcap")).unwrap();
    let mut recorded = std::collections::BTreeMap::new();
    for m in mcap::MessageStream::new(&bytes).unwrap() {
        let m = m.unwrap();
        if m.channel.topic == "/wbv/state" {
            assert_eq!(m.channel.schema.as_ref().unwrap().name, "wbv.State");
            recorded.insert(m.log_time, m.data.into_owned());
        }
    }
    for (t, payload) in &live {
        assert_eq!(Some(payload), recorded.get(t), "message at {t} ns");
    }
}

/// Runs `wbv simulate --serve ADDR` and checks it fails with an error naming `--serve` and `what`.
fn refused(addr: &str, what: &str) {
    let out = Command::new(env!("CARGO_BIN_EXE_wbv"))
        .args([
            "simulate",
            "--serve",
            addr,
            "--no-record",
            "--duration",
            "1",
        ])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--serve") && err.contains(what), "{err}");
}

#[test]
fn a_bad_address_is_one_clear_error() {
    refused("not-an-address", "not-an-address");
    refused("127.0.0.1:99999", "expected an address host:port");
}

#[test]
fn a_busy_port_is_one_clear_error() {
    let busy = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    refused(&busy.local_addr().unwrap().to_string(), "cannot listen");
}
