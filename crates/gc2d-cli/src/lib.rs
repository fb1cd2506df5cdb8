//! The `gc2d-rs` command line as a library: the run loop and the files a run writes. `main.rs` parses the
//! arguments and wires scenes, recordings and checkpoints to these.

pub mod analysis;
pub mod bench;
pub mod chatter;
pub mod console;
pub mod csv_rows;
pub mod dumps;
pub mod earlier_run;
pub mod events;
pub mod export;
pub mod failure;
pub mod import;
pub mod live;
pub mod numbered_files;
pub mod object_names;
pub mod outputs;
pub mod parquet_table;
pub mod resume;
pub mod resumed_csv;
pub mod run_lock;
pub mod runner;
pub mod segments;
pub mod sinks;
pub mod sweep;
pub mod transits;

/// The most worker threads a command accepts (`--threads`). Starting a pool takes time that grows faster than its
/// threads (measured on two cores: 5 s for 2,000, over 100 s for 10,000, all before the first step and with nothing
/// printed), results are the same for any count, and no machine the engine runs on has more cores.
pub const MAX_THREADS: usize = 1024;

/// Refuses a thread count above [`MAX_THREADS`] given to `flag`, naming this machine's cores.
pub fn refuse_too_many_threads(flag: &str, threads: usize) -> Result<(), String> {
    if threads <= MAX_THREADS {
        return Ok(());
    }
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    Err(format!(
        "{flag} {threads} is more than the {MAX_THREADS} threads allowed (this machine has {cores} cores; results are \
         the same for any count, and starting thousands of threads alone takes minutes)"
    ))
}
