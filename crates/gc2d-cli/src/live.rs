//! `gc2d-rs run --live [ADDR]`: the run served to the Foxglove app over the Foxglove WebSocket protocol while it
//! goes on (docs/recording.md, "Live view"). The view only observes: it sees the World on the frame cadence and
//! builds a frame only while a client is subscribed.

use crate::runner::FrameSink;
use gc2d_engine::World;
use gc2d_record::RecordOptions;

/// Feeds a live view one frame per tick.
#[cfg(feature = "live")]
pub struct LiveSink {
    view: gc2d_record::LiveView,
    interval: f64,
}

/// Feeds a live view one frame per tick (this build has none: the `live` feature is off).
#[cfg(not(feature = "live"))]
pub enum LiveSink {}

impl LiveSink {
    /// Starts serving on `address` (`host:port`, port 0 for a free one) frames that look as `options` say, one per
    /// `interval` of simulated time, and says on stderr where to connect.
    #[cfg(feature = "live")]
    pub fn start(address: &str, options: RecordOptions, interval: f64) -> Result<Self, String> {
        let view = gc2d_record::LiveView::start(address, options).map_err(|e| e.to_string())?;
        let host = address.rsplit_once(':').map_or(address, |(host, _)| host);
        eprintln!(
            "live view at ws://{host}:{}: in Foxglove, Open connection -> Foxglove WebSocket (frames are sent while a \
             client is connected)",
            view.port()
        );
        Ok(Self { view, interval })
    }

    /// Refuses: this build has no live view.
    #[cfg(not(feature = "live"))]
    pub fn start(address: &str, _options: RecordOptions, _interval: f64) -> Result<Self, String> {
        Err(format!("cannot serve a live view on {address}: this gc2d-rs was built without the `live` feature"))
    }

    /// Stops the server and closes the clients' connections.
    pub fn stop(self) {
        #[cfg(feature = "live")]
        self.view.stop();
    }
}

impl FrameSink for LiveSink {
    fn interval(&self) -> f64 {
        #[cfg(feature = "live")]
        return self.interval;
        #[cfg(not(feature = "live"))]
        match *self {}
    }

    fn take(&mut self, world: &World) -> Result<(), String> {
        #[cfg(feature = "live")]
        {
            self.view.publish(world);
            Ok(())
        }
        #[cfg(not(feature = "live"))]
        {
            let _ = world;
            match *self {}
        }
    }
}
