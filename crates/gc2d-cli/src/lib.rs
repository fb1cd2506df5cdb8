//! The `gc2d-rs` command line as a library: the run loop and the files a run writes. `main.rs` parses the
//! arguments and wires scenes, recordings and checkpoints to these.

pub mod analysis;
pub mod bench;
pub mod chatter;
pub mod console;
pub mod dumps;
pub mod events;
pub mod export;
pub mod failure;
pub mod import;
pub mod live;
pub mod object_names;
pub mod outputs;
pub mod parquet_table;
pub mod resume;
pub mod resumed_csv;
pub mod runner;
pub mod segments;
pub mod sinks;
pub mod sweep;
pub mod transits;
