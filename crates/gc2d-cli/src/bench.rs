//! `gc2d-rs bench`: the standard piles (gc2d_bench::StandardPile) built, settled once and cached, then stepped on
//! pools of the thread counts asked for; prints particle-steps per second, contacts per grain and memory per grain,
//! so that anyone can measure gc2d-rs on their own machine (docs/performance.md).

use crate::console;
use crate::failure::CommandFailure;
use crate::runner::simulation_bar;
use gc2d_bench::timing::{load_average, measure, pool, stage_table_header, table_header};
use gc2d_bench::{Measurement, StandardPile};
use gc2d_engine::{Stage, World};
use indicatif::ProgressBar;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Bumped whenever a standard pile or its settling changes, so that older cached states are not taken for the new.
const PILES_VERSION: u32 = 1;
/// Fewest timed steps of one measurement, whatever `--particle-steps` gives.
const MIN_TIMED_STEPS: u64 = 20;
/// Simulated time between two updates of the settling progress bar, as a fraction of the settling time.
const SETTLE_CHUNKS: u32 = 200;

/// The arguments of `gc2d-rs bench`.
#[derive(Debug, Clone, clap::Args)]
pub struct BenchArgs {
    /// The piles to measure: dense7 (the thesis's 7-gons, twice as wide as high), squares (the LAMMPS comparison's),
    /// layer (7-gons 1 cm deep), disks.
    #[arg(long, value_delimiter = ',', value_parser = parse_pile, default_value = "dense7,squares,layer,disks")]
    pub pile: Vec<StandardPile>,
    /// Particles per pile [default: dense7 2000,10000; squares 800,3200,12800; layer 1000,10000,100000; disks
    /// 10000].
    #[arg(long, value_delimiter = ',')]
    pub size: Vec<usize>,
    /// Thread counts to measure each pile on [default: 1, 2, 4, … up to the cores, and the cores].
    #[arg(long, value_delimiter = ',')]
    pub threads: Vec<usize>,
    /// Particle-steps per measurement: the timed steps are this divided by the particles (at least 20).
    #[arg(long, default_value_t = 20_000_000)]
    pub particle_steps: u64,
    /// Timed steps per measurement, the same for every size (instead of `--particle-steps`, which may not be given
    /// with it): to compare sizes over the same stretch of simulated time after settling, where the budget of
    /// particle-steps would time a small pile for many more steps than a large one.
    #[arg(long, conflicts_with = "particle_steps")]
    pub steps: Option<u64>,
    /// Simulated time each pile settles before it is measured, s [default: the pile's own, e.g. 0.06 s for dense7].
    #[arg(long, allow_hyphen_values = true)]
    pub settle_time: Option<f64>,
    /// Folder of the settled piles [default: $XDG_CACHE_HOME/gc2d-rs/bench, else ~/.cache/gc2d-rs/bench].
    #[arg(long)]
    pub cache: Option<PathBuf>,
    /// Settle again even where a settled state is cached.
    #[arg(long)]
    pub no_cache: bool,
    /// Also write the measurements as CSV (one row per pile, size and thread count).
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Also time each stage of the step (predictor, broadphase, narrowphase, …) and print µs per step in each, to
    /// see which stages keep more threads from paying.
    #[arg(long)]
    pub stages: bool,
    /// Hide the progress bars.
    #[arg(long)]
    pub quiet: bool,
}

/// One measurement with the pile it was made on: a row of the CSV.
struct BenchRow {
    pile: StandardPile,
    measurement: Measurement,
}

fn parse_pile(name: &str) -> Result<StandardPile, String> {
    StandardPile::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = StandardPile::ALL.iter().map(|p| p.name()).collect();
        format!("no standard pile is called `{name}`; the piles are {}", names.join(", "))
    })
}

/// Runs `gc2d-rs bench`; returns the exit code.
pub fn bench(args: &BenchArgs) -> Result<u8, CommandFailure> {
    if let Some(zero) = args.size.iter().chain(&args.threads).find(|&&n| n == 0) {
        return Err(CommandFailure::input(format!("--size and --threads take counts of at least 1, got {zero}")));
    }
    if let Some(size) = args.size.iter().find(|&&n| n > gc2d_scene::MAX_INITIAL_PARTICLES) {
        return Err(CommandFailure::input(format!(
            "--size {size}: a standard pile has at most {} particles, as a scene may start with",
            gc2d_scene::MAX_INITIAL_PARTICLES
        )));
    }
    let pile_names: Vec<&str> = args.pile.iter().map(|p| p.name()).collect();
    refuse_repeats("--pile", &pile_names)?;
    refuse_repeats("--size", &args.size)?;
    refuse_repeats("--threads", &args.threads)?;
    for &threads in &args.threads {
        crate::refuse_too_many_threads("--threads", threads).map_err(CommandFailure::input)?;
    }
    if args.particle_steps == 0 || args.steps == Some(0) {
        return Err(CommandFailure::input("--particle-steps and --steps must be at least 1"));
    }
    if let Some(t) = args.settle_time
        && !(t.is_finite() && t >= 0.0)
    {
        return Err(CommandFailure::input(format!("--settle-time must be a time in seconds, at least 0; got {t}")));
    }
    if let Some(path) = &args.csv {
        refuse_unwritable_csv(path)?;
    }
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let threads = if args.threads.is_empty() { default_threads(cores) } else { args.threads.clone() };
    let cache = if args.no_cache { None } else { args.cache.clone().or_else(default_cache) };
    let say = |text: &str| console::out(text).map_err(|e| CommandFailure::stdout(&e));
    say(&machine_summary(cores))?;
    if let Some(over) = threads.iter().find(|&&t| t > cores) {
        console::err(&format!("note: {over} threads on {cores} cores: the threads share cores, so expect no speed-up"));
    }
    let mut rows = Vec::new();
    // The piles whose end states differ between thread counts.
    let mut differing = Vec::new();
    for &pile in &args.pile {
        let sizes = if args.size.is_empty() { pile.default_sizes().to_vec() } else { args.size.clone() };
        let settle_time = args.settle_time.unwrap_or(pile.settle_time());
        say(&format!("\n{} (settled {settle_time} s)\n\n{}", pile.name(), table_header("grain")))?;
        for &particles in &sizes {
            let settled_state =
                checkpoint_bytes(&settled(pile, particles, settle_time, cores, cache.as_deref(), args.quiet)?)?;
            let first_row = rows.len();
            let steps = args.steps.unwrap_or((args.particle_steps / particles as u64).max(MIN_TIMED_STEPS));
            let mut ends = Vec::new();
            for &n in &threads {
                let blew_up = |e| {
                    CommandFailure::failed(format!("{} pile of {particles} stopped while measured: {e}", pile.name()))
                };
                let mut world = World::load_checkpoint(settled_state.as_slice()).map_err(checkpoint_failure)?;
                let measurement = measure(&mut world, n, steps, args.stages).map_err(blew_up)?;
                ends.push(EndState { threads: n, checksum: world.state_checksum().map_err(checkpoint_failure)? });
                say(&measurement.row())?;
                rows.push(BenchRow { pile, measurement });
            }
            let verdict = compare_end_states(&ends);
            console::err(&format!("{} {particles}, the state after the timed steps: {}", pile.name(), verdict.text));
            differing.extend(verdict.differs.then(|| format!("{} {particles}", pile.name())));
            if args.stages {
                let stage_rows: Vec<String> =
                    rows[first_row..].iter().filter_map(|r| r.measurement.stage_row()).collect();
                say(&format!(
                    "\n{} {particles}, µs per step in each stage:\n\n{}\n{}\n",
                    pile.name(),
                    stage_table_header("grain"),
                    stage_rows.join("\n")
                ))?;
            }
        }
    }
    say(&format!("\nload average after: {}", load_average()))?;
    if let Some(path) = &args.csv {
        std::fs::write(path, csv(&rows))
            .map_err(|e| CommandFailure::failed(format!("cannot write {}: {e}", path.display())))?;
    }
    if !differing.is_empty() {
        return Err(CommandFailure::failed(format!(
            "the results depend on the thread count (the engine promises the same bits on any): {}; please report \
             this with the output above",
            differing.join(", ")
        )));
    }
    Ok(0)
}

/// Refuses a list option (`--pile`, `--size`, `--threads`) that gives one entry twice: it would be measured twice, and
/// the verdict on the end states would read "identical on 1, 1 threads".
fn refuse_repeats<T: PartialEq + std::fmt::Display>(option: &str, items: &[T]) -> Result<(), CommandFailure> {
    match items.iter().enumerate().find(|(k, item)| items[..*k].contains(item)) {
        Some((_, twice)) => {
            Err(CommandFailure::input(format!("{option}: {twice} is given twice; give each once, it is measured once")))
        }
        None => Ok(()),
    }
}

/// Refuses a `--csv` path that cannot take the table, before the measurements rather than after them: a folder (or a
/// name ending in a separator), a file in a folder that does not exist or under a file (named as a file, not as a
/// missing folder), or one that cannot be opened for writing (tried without changing an existing file; a new one is
/// removed again).
fn refuse_unwritable_csv(path: &std::path::Path) -> Result<(), CommandFailure> {
    let refuse = |why: String| Err(CommandFailure::input(format!("--csv {}: {why}", path.display())));
    if path.is_dir() || path.as_os_str().to_string_lossy().ends_with(std::path::MAIN_SEPARATOR) {
        return refuse("this is a folder; give a file name".to_owned());
    }
    if let Some(folder) = path.parent().filter(|parent| !parent.as_os_str().is_empty())
        && !folder.is_dir()
    {
        // A file where a folder of the path should be is named as what it is.
        if let Some(file) = folder.ancestors().find(|a| !a.as_os_str().is_empty() && a.exists() && !a.is_dir()) {
            return refuse(format!("{} is a file, not a folder", file.display()));
        }
        return refuse(format!("the folder {} does not exist", folder.display()));
    }
    let existed = path.exists();
    if let Err(e) = std::fs::OpenOptions::new().append(true).create(true).open(path) {
        return refuse(format!("cannot write it: {e}"));
    }
    if !existed {
        let _ = std::fs::remove_file(path);
    }
    Ok(())
}

/// The checksum of a pile's state after the timed steps on `threads` threads.
struct EndState {
    threads: usize,
    checksum: u64,
}

/// Whether every thread count ended in the same state, and the sentence that says so.
struct Verdict {
    differs: bool,
    text: String,
}

/// Compares the end states of one pile measured on several thread counts from the same settled state: the engine
/// promises bitwise-identical results for any thread count, so they must all be equal.
fn compare_end_states(ends: &[EndState]) -> Verdict {
    let Some(first) = ends.first() else {
        return Verdict { differs: false, text: "not measured".into() };
    };
    let differing: Vec<&EndState> = ends.iter().filter(|e| e.checksum != first.checksum).collect();
    if differing.is_empty() {
        let text = format!("bitwise identical on {} threads (checksum {:#018x})", thread_list(ends), first.checksum);
        Verdict { differs: false, text }
    } else {
        let text =
            format!("DIFFERS: on {} threads it is not the state reached on {}", thread_list(differing), first.threads);
        Verdict { differs: true, text }
    }
}

/// "1, 2, 4": the thread counts of `ends`.
fn thread_list<'e>(ends: impl IntoIterator<Item = &'e EndState>) -> String {
    ends.into_iter().map(|e| e.threads.to_string()).collect::<Vec<_>>().join(", ")
}

/// A settled pile as checkpoint bytes, from which every thread count starts its measurement.
fn checkpoint_bytes(world: &World) -> Result<Vec<u8>, CommandFailure> {
    let mut bytes = Vec::new();
    world.save_checkpoint(&mut bytes).map_err(checkpoint_failure)?;
    Ok(bytes)
}

/// A pile's state that cannot be encoded or decoded in memory: a failure of the engine, not of the input.
fn checkpoint_failure(error: gc2d_engine::CheckpointError) -> CommandFailure {
    CommandFailure::failed(format!("cannot copy the pile's state in memory: {error}"))
}

/// 1, 2, 4, … below `cores`, then `cores`.
fn default_threads(cores: usize) -> Vec<usize> {
    let mut threads: Vec<usize> = std::iter::successors(Some(1), |&n| Some(n * 2)).take_while(|&n| n < cores).collect();
    threads.push(cores);
    threads
}

/// `$XDG_CACHE_HOME/gc2d-rs/bench`, else `$HOME/.cache/gc2d-rs/bench`; `None` where neither is set.
fn default_cache() -> Option<PathBuf> {
    let base = std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|home| PathBuf::from(home).join(".cache")))?;
    Some(base.join("gc2d-rs").join("bench"))
}

/// The program version, the machine and its load, for the head of the output.
fn machine_summary(cores: usize) -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|info| {
            info.lines()
                .find_map(|l| l.strip_prefix("model name").map(|m| m.trim_start_matches([' ', '\t', ':']).to_string()))
        })
        .unwrap_or_else(|| "unknown CPU".into());
    format!(
        "gc2d-rs {} bench on {cpu}, {cores} cores; load average before: {}",
        env!("CARGO_PKG_VERSION"),
        load_average()
    )
}

/// The cached file of a settled pile.
fn cache_file(cache: &Path, pile: StandardPile, particles: usize, settle_time: f64) -> PathBuf {
    cache.join(format!("{}-{particles}-settled-{settle_time}s-v{PILES_VERSION}.ckpt", pile.name()))
}

/// The pile of `particles` settled for `settle_time` on `threads` threads: read from the cache where it holds one
/// that this program can load, else built, settled and written there.
fn settled(
    pile: StandardPile,
    particles: usize,
    settle_time: f64,
    threads: usize,
    cache: Option<&Path>,
    quiet: bool,
) -> Result<World, CommandFailure> {
    let file = cache.map(|dir| cache_file(dir, pile, particles, settle_time));
    if let Some(file) = &file
        && file.exists()
    {
        match World::load_checkpoint_file(file).map_err(|e| e.to_string()).and_then(|world| {
            cached_pile_matches(&world, pile, particles, settle_time)?;
            Ok(world)
        }) {
            Ok(world) => {
                let (name, file) = (pile.name(), file.display());
                console::err(&format!("{name} {particles}: settled state from {file}{}", bands_note(&world)));
                return Ok(world);
            }
            Err(e) => console::err(&format!("{}: {e}; settling again", file.display())),
        }
    }
    let started = Instant::now();
    let mut world = pile.build(particles);
    let bar = settling_bar(pile, particles, quiet);
    let chunk = settle_time / f64::from(SETTLE_CHUNKS);
    let result = pool(threads).install(|| {
        for k in 1..=SETTLE_CHUNKS {
            world.run_until(chunk * f64::from(k))?;
            bar.set_position(u64::from(k));
        }
        Ok::<(), gc2d_engine::WorldError>(())
    });
    bar.finish_and_clear();
    result.map_err(|e| {
        CommandFailure::failed(format!("{} pile of {particles} stopped while settling: {e}", pile.name()))
    })?;
    console::err(&format!(
        "{} {particles}: built and settled {settle_time} s ({} steps) in {:.1} s on {threads} threads{}",
        pile.name(),
        world.steps(),
        started.elapsed().as_secs_f64(),
        bands_note(&world)
    ));
    if let Some(file) = &file {
        let saved = std::fs::create_dir_all(file.parent().unwrap_or(Path::new(".")))
            .map_err(|e| e.to_string())
            .and_then(|()| world.save_checkpoint_file(file).map_err(|e| e.to_string()));
        if let Err(e) = saved {
            console::err(&format!("note: cannot cache the settled pile in {}: {e}", file.display()));
        }
    }
    Ok(world)
}

/// Whether a cached `world` is the pile asked for: its particle count, its seed and its settling time, so that a
/// checkpoint of another pile under this name (a cache copied or edited by hand) is not measured under this label.
fn cached_pile_matches(world: &World, pile: StandardPile, particles: usize, settle_time: f64) -> Result<(), String> {
    let count = world.bodies().particles().count();
    if count != particles {
        return Err(format!("it holds {count} particles, not {particles}"));
    }
    if world.config().seed != pile.seed() {
        return Err(format!("its seed is {}, not the {} pile's {}", world.config().seed, pile.name(), pile.seed()));
    }
    // Settling runs to the first step at or after the settling time.
    if !(world.time() >= settle_time - 1e-12 && world.time() < settle_time + world.time_step() * (1.0 + 1e-9)) {
        return Err(format!("it was settled for {} s, not {settle_time} s", world.time()));
    }
    Ok(())
}

/// "; y axis in N bands" for a pile wide enough for the broadphase to split its y axis (docs/model.md, "The y axis
/// in bands of x"), which explains a broadphase stage that does not grow with the width; nothing for the others.
fn bands_note(world: &World) -> String {
    match world.y_bands() {
        1 => String::new(),
        bands => format!("; y axis in {bands} bands"),
    }
}

/// The progress bar of a settling run, hidden with `quiet`.
fn settling_bar(pile: StandardPile, particles: usize, quiet: bool) -> ProgressBar {
    let bar = simulation_bar(u64::from(SETTLE_CHUNKS), !quiet);
    bar.set_message(format!("settling {} {particles}", pile.name()));
    bar
}

/// The measurements as CSV, one row per pile, size and thread count; the stage columns (s over the timed steps)
/// are empty where the stages were not timed.
fn csv(rows: &[BenchRow]) -> String {
    let mut out = String::from(
        "pile,particles,threads,steps,wall_s,cpu_s,particle_steps_per_s,contacts_per_particle,heap_bytes_per_particle,\
         cache_line_round_trip_ns",
    );
    for stage in Stage::ALL {
        let _ = write!(out, ",stage_{}_s", stage.name());
    }
    out.push('\n');
    for BenchRow { pile, measurement: m } in rows {
        let _ = write!(
            out,
            "{},{},{},{},{},{},{},{},{},{}",
            pile.name(),
            m.particles,
            m.threads,
            m.steps,
            m.seconds,
            m.cpu_seconds,
            m.particle_steps_per_second(),
            m.contacts_per_particle(),
            m.heap_bytes as f64 / m.particles as f64,
            m.line_trip_ns.map_or_else(String::new, |ns| ns.to_string())
        );
        for stage in Stage::ALL {
            out.push(',');
            if let Some(stages) = &m.stages {
                let _ = write!(out, "{}", stages.seconds(stage));
            }
        }
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn end(threads: usize, checksum: u64) -> EndState {
        EndState { threads, checksum }
    }

    #[test]
    fn equal_end_states_read_identical_and_a_different_one_is_named() {
        let same = compare_end_states(&[end(1, 7), end(2, 7), end(4, 7)]);
        assert!(!same.differs);
        assert_eq!(same.text, "bitwise identical on 1, 2, 4 threads (checksum 0x0000000000000007)");
        let different = compare_end_states(&[end(1, 7), end(2, 7), end(4, 8), end(8, 9)]);
        assert!(different.differs);
        assert_eq!(different.text, "DIFFERS: on 4, 8 threads it is not the state reached on 1");
    }
}
