//! The live view: the recording's topics served over the Foxglove WebSocket protocol while a run goes on, so the
//! Foxglove app can connect to a running simulation (Open connection → Foxglove WebSocket, `ws://127.0.0.1:8765`).
//!
//! The server is the foxglove SDK's; it runs on its own threads (a tokio runtime) and only observes: the run loop
//! hands it the World at each frame tick, and a frame is built and encoded only when a client is subscribed to one
//! of the topics, so a run nobody watches pays one check per tick. Walls are sent in every frame, since a client may
//! join at any time.

use crate::RecordError;
use crate::frame::FrameBuilder;
use crate::recorder::{RecordOptions, simulated_nanoseconds};
use crate::stats::{STATS_JSON_SCHEMA, STATS_SCHEMA_NAME};
use foxglove::schemas::SceneUpdate;
use foxglove::{Channel, ChannelBuilder, Context, PartialMetadata, RawChannel, Schema, WebSocketServer};
use gc2d_engine::World;
use std::sync::Arc;

/// A running live view.
pub struct LiveView {
    /// The channels' and the server's context; they hold it weakly, so the view keeps it alive.
    _context: Arc<Context>,
    server: foxglove::WebSocketServerHandle,
    particles: Channel<SceneUpdate>,
    walls: Channel<SceneUpdate>,
    contacts: Channel<SceneUpdate>,
    fluid: Channel<SceneUpdate>,
    stats: Arc<RawChannel>,
    builder: FrameBuilder,
    frames: u64,
}

impl LiveView {
    /// Starts the server on `address` (`host:port`; port 0 picks a free one, see [`Self::port`]) with frames that
    /// look as `options` say (its cadence is the caller's).
    pub fn start(address: &str, options: RecordOptions) -> Result<Self, RecordError> {
        let invalid = || {
            RecordError::InvalidOption(format!(
                "live view address must be host:port (e.g. 127.0.0.1:8765), got {address:?}"
            ))
        };
        let (host, port) = address.rsplit_once(':').ok_or_else(invalid)?;
        let port: u16 = port.parse().map_err(|_| invalid())?;
        let host = host.trim_start_matches('[').trim_end_matches(']');
        if host.is_empty() {
            return Err(invalid());
        }
        // A context of its own: the channels and the server belong to this view, not to the process.
        let context = Context::new();
        let particles = ChannelBuilder::new("/particles").context(&context).build::<SceneUpdate>();
        let walls = ChannelBuilder::new("/walls").context(&context).build::<SceneUpdate>();
        let contacts = ChannelBuilder::new("/contacts").context(&context).build::<SceneUpdate>();
        let fluid = ChannelBuilder::new("/fluid").context(&context).build::<SceneUpdate>();
        let stats = ChannelBuilder::new("/stats")
            .context(&context)
            .message_encoding("json")
            .schema(Schema::new(STATS_SCHEMA_NAME, "jsonschema", STATS_JSON_SCHEMA.as_bytes()))
            .build_raw()
            .map_err(|e| RecordError::Live(format!("cannot create the /stats channel: {e}")))?;
        let server = WebSocketServer::new()
            .name(format!("gc2d-rs {}", env!("CARGO_PKG_VERSION")))
            .context(&context)
            .bind(host, port)
            .start_blocking()
            .map_err(|e| RecordError::Live(format!("cannot serve the live view on {address}: {e}")))?;
        Ok(Self {
            _context: context,
            server,
            particles,
            walls,
            contacts,
            fluid,
            stats,
            builder: FrameBuilder::new(options).walls_every_frame(),
            frames: 0,
        })
    }

    /// The port the server listens on.
    pub fn port(&self) -> u16 {
        self.server.port()
    }

    /// True when a client is subscribed to at least one topic.
    pub fn has_subscribers(&self) -> bool {
        self.particles.has_sinks()
            || self.walls.has_sinks()
            || self.contacts.has_sinks()
            || self.fluid.has_sinks()
            || self.stats.has_sinks()
    }

    /// Frames sent so far.
    pub fn frames(&self) -> u64 {
        self.frames
    }

    /// Sends the frame of `world` to the subscribed clients. Builds nothing and returns false when nobody is
    /// subscribed.
    pub fn publish(&mut self, world: &World) -> bool {
        if !self.has_subscribers() {
            return false;
        }
        let log_time = simulated_nanoseconds(world.time());
        let meta = PartialMetadata { log_time: Some(log_time) };
        let frame = self.builder.build(world, log_time);
        self.particles.log_with_meta(&frame.particles, meta);
        if let Some(walls) = &frame.walls {
            self.walls.log_with_meta(walls, meta);
        }
        if let Some(contacts) = &frame.contacts {
            self.contacts.log_with_meta(contacts, meta);
        }
        if let Some(fluid) = &frame.fluid {
            self.fluid.log_with_meta(fluid, meta);
        }
        if self.stats.has_sinks() {
            self.stats.log_with_meta(frame.stats.to_json().to_string().as_bytes(), meta);
        }
        self.frames += 1;
        true
    }

    /// Stops the server, closing the clients' connections, and waits for it to finish.
    pub fn stop(self) {
        self.server.stop().wait_blocking();
    }
}
