//! [`LiveView`]: an [`Observer`] that streams a run to the Foxglove app or Lichtblick over the
//! Foxglove WebSocket protocol (subprotocol `foxglove.sdk.v1`, the SDK 0.30 name of
//! `foxglove.websocket.v1`) while it is simulated
//! (`wbv simulate --serve`).
//!
//! The channels are the recording's, built by the same code (`channels::add`): topics
//! `/wbv/measured`, `/wbv/state`, `/wbv/links` with the protobuf schemas `wbv.Measured`,
//! `wbv.State`, `wbv.Links` of a per-sample recording (`--layout per-sample`: one message per
//! step, so every field plots as it arrives), and `/wbv/scene`, `/tf` (`foxglove.SceneUpdate`,
//! `foxglove.FrameTransforms`). The message bytes come from the same encoders, so a live message
//! equals the message of a per-sample MCAP recording of the same step. Log times are simulation
//! time in ns from 0, as in the file. The server is the Foxglove SDK's own (`foxglove` crate,
//! feature `websocket`), on its tokio runtime; logging a message only queues it for the clients
//! that subscribed, so a slow viewer never stalls the simulation (the SDK drops what it cannot
//! send).

use super::channels::{self, ChannelSink};
use super::pipeline::Encoder;
use super::scene::{self, Scene};
use super::topics::{Quantity, eval, topics};
use super::{Encoding, RecordOptions};
use crate::error::{Error, Result};
use crate::simulate::observer::{Layout, Observer, Step};
use foxglove::{ChannelBuilder, Context, PartialMetadata, RawChannel, WebSocketServer};
use std::net::SocketAddr;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Default address of `--serve`: the Foxglove app's default `ws://localhost:8765`.
pub const DEFAULT_ADDR: &str = "127.0.0.1:8765";

/// How the live view runs.
#[derive(Debug, Clone)]
pub struct LiveOptions {
    /// Address to listen on (`host:port`; port 0 picks a free port).
    pub addr: String,
    /// Pace the simulation to wall-clock time: simulation time never runs ahead of the wall time
    /// since the first step.
    pub realtime: bool,
    /// Before the first step, wait up to this long for a client to subscribe to a channel (the
    /// Foxglove app subscribes when a panel shows a topic); zero starts at once.
    pub wait: Duration,
    /// Rate of the 3-D scene in Hz (as recorded).
    pub scene_rate_hz: f64,
    /// Displacement magnification of the 3-D scene (as recorded).
    pub magnification: f64,
}

impl Default for LiveOptions {
    fn default() -> Self {
        let r = RecordOptions::default();
        LiveOptions {
            addr: DEFAULT_ADDR.to_string(),
            realtime: false,
            wait: Duration::from_secs(30),
            scene_rate_hz: r.scene_rate_hz,
            magnification: r.magnification,
        }
    }
}

/// Parses a `--serve` address `host:port` (an IP address; `localhost` stands for 127.0.0.1).
pub fn parse_addr(addr: &str) -> Result<SocketAddr> {
    let a = addr.replacen("localhost:", "127.0.0.1:", 1);
    a.parse().map_err(|_| {
        Error::parameter(
            "--serve",
            format!("`{addr}`: expected an address host:port such as 127.0.0.1:8765 or 0.0.0.0:0"),
        )
    })
}

/// The SDK's channels, numbered in the order they were added (the ids `channels::add` hands out).
struct LiveSink<'a> {
    context: &'a Arc<Context>,
    channels: Vec<Arc<RawChannel>>,
}

impl ChannelSink for LiveSink<'_> {
    fn add_channel(
        &mut self,
        topic: &str,
        encoding: Encoding,
        schema_name: &str,
        schema: &[u8],
    ) -> Result<u16> {
        let (message_encoding, schema_encoding) = match encoding {
            Encoding::Json => ("json", "jsonschema"),
            Encoding::Protobuf => ("protobuf", "protobuf"),
        };
        let schema = foxglove::Schema::new(schema_name, schema_encoding, schema.to_vec());
        let channel = ChannelBuilder::new(topic)
            .message_encoding(message_encoding)
            .schema(schema)
            .context(self.context)
            .build_raw()
            .map_err(|e| Error::parameter("--serve", format!("channel {topic}: {e}")))?;
        let id = u16::try_from(self.channels.len()).expect("a run has a handful of channels");
        self.channels.push(channel);
        Ok(id)
    }
}

/// Streams a run live (see the module documentation).
pub struct LiveView {
    options: LiveOptions,
    context: Arc<Context>,
    server: Option<foxglove::WebSocketServerHandle>,
    port: u16,
    channels: Vec<Arc<RawChannel>>,
    /// Time-series channels: channel index and encoder, in value order.
    encoders: Vec<(usize, Encoder)>,
    scene: Option<(Scene, usize, usize)>,
    layout: Option<Layout>,
    quantities: Vec<Quantity>,
    measured: Vec<f64>,
    values: Vec<f64>,
    buf: Vec<u8>,
    next_scene_frame: u64,
    start: Option<Instant>,
}

impl LiveView {
    /// Starts the server on `options.addr`; a bad or busy address is an error naming `--serve`.
    pub fn start(options: LiveOptions) -> Result<Self> {
        let addr = parse_addr(&options.addr)?;
        let context = Context::new();
        let server = WebSocketServer::new()
            .name(format!("wbv {}", env!("CARGO_PKG_VERSION")))
            .bind(addr.ip().to_string(), addr.port())
            .context(&context)
            .start_blocking()
            .map_err(|e| Error::parameter("--serve", format!("cannot listen on {addr}: {e}")))?;
        let port = server.port();
        Ok(LiveView {
            options,
            context,
            server: Some(server),
            port,
            channels: Vec::new(),
            encoders: Vec::new(),
            scene: None,
            layout: None,
            quantities: Vec::new(),
            measured: Vec::new(),
            values: Vec::new(),
            buf: Vec::new(),
            next_scene_frame: 0,
            start: None,
        })
    }

    /// The port the server listens on (the one picked when the address asked for port 0).
    pub fn port(&self) -> u16 {
        self.port
    }

    /// The WebSocket URL clients connect to.
    pub fn url(&self) -> String {
        let addr = parse_addr(&self.options.addr).expect("checked in start");
        format!("ws://{}:{}", addr.ip(), self.port)
    }

    /// Whether a client has subscribed to any channel.
    fn subscribed(&self) -> bool {
        self.channels.iter().any(|c| c.has_sinks())
    }

    fn log(&self, channel: usize, msg: &[u8], time_ns: u64) {
        self.channels[channel].log_with_meta(
            msg,
            PartialMetadata {
                log_time: Some(time_ns),
            },
        );
    }

    /// Sleeps until the wall time since the first step reaches the simulation time `t`.
    fn pace(&mut self, t: f64) {
        let start = *self.start.get_or_insert_with(Instant::now);
        let ahead = t - start.elapsed().as_secs_f64();
        // Sleeping in steps of at least 2 ms keeps the pacing cheap at 1 kHz steps.
        if ahead > 2e-3 {
            std::thread::sleep(Duration::from_secs_f64(ahead));
        }
    }
}

impl Observer for LiveView {
    fn begin(&mut self, layout: &Layout) -> Result<()> {
        let mut sink = LiveSink {
            context: &self.context,
            channels: Vec::new(),
        };
        let topics = topics(layout)?;
        self.quantities = topics.iter().flat_map(|t| t.quantities.clone()).collect();
        let c = channels::add(&mut sink, layout, topics, Encoding::Protobuf, false)?;
        self.channels = sink.channels;
        self.encoders = (c.topics.iter().zip(c.encoders))
            .map(|((_, id), e)| (usize::from(*id), e))
            .collect();
        let scene = Scene::new(layout, self.options.magnification);
        self.scene = Some((scene, usize::from(c.scene), usize::from(c.transforms)));
        self.layout = Some(layout.clone());
        if !self.options.wait.is_zero() {
            eprintln!(
                "live view: waiting up to {:.0} s for a viewer to subscribe on {}",
                self.options.wait.as_secs_f64(),
                self.url()
            );
            let until = Instant::now() + self.options.wait;
            while !self.subscribed() && Instant::now() < until {
                std::thread::sleep(Duration::from_millis(20));
            }
            if !self.subscribed() {
                eprintln!("live view: no viewer subscribed; simulating anyway");
            }
        }
        Ok(())
    }

    fn step(&mut self, s: &Step<'_>) -> Result<()> {
        if self.options.realtime {
            self.pace(s.t);
        }
        let time_ns = (s.t * 1e9).round() as u64;
        if let Some(l) = &self.layout {
            l.measured(s, &mut self.measured);
        }
        eval(&self.quantities, s, &self.measured, &mut self.values);
        // A viewer plots what it gets; a non-finite value is refused by the recorder (and the
        // run stops there), so the live view skips the step's time series instead.
        if self.values.iter().all(|v| v.is_finite()) {
            let mut offset = 0;
            for k in 0..self.encoders.len() {
                let (channel, encoder) = &self.encoders[k];
                let n = encoder.len();
                self.buf.clear();
                encoder.render(&self.values[offset..offset + n], &mut self.buf);
                self.log(*channel, &self.buf, time_ns);
                offset += n;
            }
        }
        if scene::frame_due(&mut self.next_scene_frame, self.options.scene_rate_hz, s.t).is_some() {
            let (scene, scene_id, tf_id) = self.scene.as_ref().expect("begin() called");
            let (scene_id, tf_id) = (*scene_id, *tf_id);
            let mut buf = std::mem::take(&mut self.buf);
            buf.clear();
            scene.scene_update_pb(s, &mut buf);
            self.log(scene_id, &buf, time_ns);
            buf.clear();
            scene.frame_transforms_pb(s, &mut buf);
            self.log(tf_id, &buf, time_ns);
            self.buf = buf;
        }
        Ok(())
    }

    fn end(&mut self) -> Result<()> {
        // Give the server a moment to send what is queued, then close it gracefully.
        std::thread::sleep(Duration::from_millis(200));
        for c in &self.channels {
            c.close();
        }
        if let Some(server) = self.server.take() {
            server.stop().wait_blocking();
        }
        Ok(())
    }
}

impl Drop for LiveView {
    fn drop(&mut self) {
        if let Some(server) = self.server.take() {
            drop(server.stop());
        }
    }
}
