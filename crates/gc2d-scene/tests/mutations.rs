//! Random mutations of valid scenes and gsi files never make loading, building, stepping or rendering an error
//! panic or hang, and every rejected input is reported at a file, line and column (issue 16.5).
//!
//! Two tests: a proptest that also steps the mutated scenes that build, and a bounded deterministic campaign of
//! 12,000 inputs (fixed seeds; 10,000 scenes from five bases, a tenth of them mutated at the byte level, and 2,000
//! gsi files; a fifth of that in a debug build) that parses and validates each one and builds the small ones, in
//! about ten seconds in release. The same inputs can be explored without bounds with the cargo-fuzz targets in
//! `fuzz/` (docs/scene-format.md, "Fuzzing").

mod common;

use gc2d_scene::Scene;
use gc2d_scene::gsi::{ImportOptions, parse_gsi, to_scene};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// Scenes larger than this are loaded and validated but not built, to keep the test fast.
const MAX_BUILT_PARTICLES: usize = 3_000;

/// Text inserted by mutations: RON punctuation, numbers at the edges of their ranges, names of fields and variants.
const FRAGMENTS: &[&str] = &[
    "(",
    ")",
    "[",
    "]",
    "{",
    "}",
    ",",
    ":",
    "\"",
    "'",
    "/*",
    "//",
    "\n",
    "#",
    "r#\"",
    "-",
    "0",
    "-1",
    "1e300",
    "1e-300",
    "inf",
    "-inf",
    "NaN",
    "0.0",
    "9999999999999999999999",
    "Some(",
    "None",
    "true",
    "x_range_m: (1, 0)",
    "corners: 2",
    "corners: 65",
    "Rand1",
    "Polygon(corners_m: [(0, 0)])",
    "μ",
    "é",
    "Box",
    "Drum",
    "gamm",
    "segments: 0",
    "grid_spacing_m: (1e-12, 1e-12)",
    "semi_axes_m: (0, 0)",
];

#[derive(Debug, Clone)]
enum Mutation {
    Delete { at: usize, len: usize },
    Insert { at: usize, fragment: usize },
    Digit { at: usize, digit: char },
    Duplicate { at: usize, len: usize },
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), 1usize..40).prop_map(|(at, len)| Mutation::Delete { at, len }),
        (any::<usize>(), 0..FRAGMENTS.len()).prop_map(|(at, fragment)| Mutation::Insert { at, fragment }),
        (any::<usize>(), proptest::char::range('0', '9')).prop_map(|(at, digit)| Mutation::Digit { at, digit }),
        (any::<usize>(), 1usize..80).prop_map(|(at, len)| Mutation::Duplicate { at, len }),
    ]
}

/// Applies the mutations on characters, so the text stays valid UTF-8.
fn mutate(text: &str, mutations: &[Mutation]) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for mutation in mutations {
        let n = chars.len().max(1);
        match *mutation {
            Mutation::Delete { at, len } => {
                let start = at % n;
                chars.drain(start..(start + len).min(chars.len()));
            }
            Mutation::Insert { at, fragment } => {
                let at = at % (chars.len() + 1);
                chars.splice(at..at, FRAGMENTS[fragment].chars());
            }
            Mutation::Digit { at, digit } => {
                let digits: Vec<usize> = (0..chars.len()).filter(|&i| chars[i].is_ascii_digit()).collect();
                if !digits.is_empty() {
                    chars[digits[at % digits.len()]] = digit;
                }
            }
            Mutation::Duplicate { at, len } => {
                let start = at % n;
                let copied: Vec<char> = chars[start.min(chars.len())..(start + len).min(chars.len())].to_vec();
                chars.splice(start.min(chars.len())..start.min(chars.len()), copied);
            }
        }
    }
    chars.into_iter().collect()
}

/// A small scene with every feature, cheap to build: the shared full scene without its big block.
fn base_scene() -> String {
    common::FULL_SCENE.replace(
        "x_range_m: (-0.15, 0.15), y_range_m: (0.01, 0.03)",
        "x_range_m: (-0.15, -0.12), y_range_m: (0.01, 0.02)",
    )
}

fn exercise(text: &str) {
    match Scene::from_str(text, "mutated.ron") {
        Err(error) => {
            let rendered = error.render_plain();
            assert!(!rendered.is_empty());
            if let Some(span) = error.span() {
                assert!(span.start <= span.end && span.end <= text.len() && text.is_char_boundary(span.start));
            }
        }
        Ok(scene) => {
            if scene.initial_particle_count() > MAX_BUILT_PARTICLES {
                return;
            }
            match scene.build() {
                Err(error) => drop(error.render_plain()),
                Ok(mut world) => {
                    for _ in 0..5 {
                        if world.step().is_err() {
                            break;
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn the_base_scene_is_valid() {
    let scene = Scene::from_str(&base_scene(), "base.ron").unwrap_or_else(|e| panic!("{}", e.render_plain()));
    assert!(scene.build().is_ok());
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn mutated_scenes_never_panic(mutations in proptest::collection::vec(mutation(), 1..5)) {
        exercise(&mutate(&base_scene(), &mutations));
    }
}

/// Scenes of the repository that the campaign mutates besides the shared full scene.
const REPOSITORY_SCENES: [(&str, &str); 4] = [
    ("pile", include_str!("../../../scenes/pile.ron")),
    ("silo", include_str!("../../../scenes/silo.ron")),
    ("drum", include_str!("../../../scenes/drum.ron")),
    ("mill", include_str!("../../../scenes/mill.ron")),
];

/// The thesis's gsi example.
const PISTON_GSI: &str = include_str!("../src/gsi/testdata/piston.gsi");

/// Scene inputs of the campaign (a fifth of them in a debug build, which runs about ten times slower).
const SCENE_INPUTS: usize = if cfg!(debug_assertions) { 2_000 } else { 10_000 };
/// Gsi inputs of the campaign (likewise).
const GSI_INPUTS: usize = if cfg!(debug_assertions) { 400 } else { 2_000 };

/// Bytes the byte-level mutations insert: invalid UTF-8 (a lone continuation byte, a truncated two-byte sequence, a
/// byte never used), NUL and a byte-order mark.
const BYTES: &[&[u8]] = &[b"\xff", b"\x80", b"\xc3", b"\xfe\xfe", b"\0", b"\xef\xbb\xbf"];

/// Hang guard: an input still running after this long ends the test binary with the input's number and seed. Far
/// above any input's work (milliseconds): it only turns a hang into a failure instead of a stuck suite.
const HANG_LIMIT: Duration = Duration::from_secs(60);

/// A random mutation as the proptest strategy draws them.
fn random_mutation(rng: &mut ChaCha8Rng) -> Mutation {
    let at = rng.random::<u64>() as usize;
    match rng.random_range(0..4) {
        0 => Mutation::Delete { at, len: rng.random_range(1..40) },
        1 => Mutation::Insert { at, fragment: rng.random_range(0..FRAGMENTS.len()) },
        2 => Mutation::Digit { at, digit: char::from(b'0' + rng.random_range(0..10u8)) },
        _ => Mutation::Duplicate { at, len: rng.random_range(1..80) },
    }
}

/// Byte-level edits of `text` (up to three insertions of [`BYTES`] anywhere, even inside a character).
fn mutate_bytes(text: &str, rng: &mut ChaCha8Rng) -> Vec<u8> {
    let mut bytes = text.as_bytes().to_vec();
    for _ in 0..rng.random_range(1..4) {
        let at = rng.random_range(0..=bytes.len());
        let insert = BYTES[rng.random_range(0..BYTES.len())];
        bytes.splice(at..at, insert.iter().copied());
    }
    bytes
}

/// Asserts that a rejected scene names `mutated.ron`, a line and a column inside `text`, and renders.
fn assert_located(error: &gc2d_scene::SceneError, text: &str, input: &str) {
    let rendered = error.render_plain();
    let location = error.location().unwrap_or_else(|| panic!("{input}: an error without a location:\n{rendered}"));
    assert_eq!(location.file, "mutated.ron", "{input}");
    let lines = text.split('\n').count();
    assert!(location.line >= 1 && location.line <= lines && location.column >= 1, "{input}: {location}");
    assert!(error.to_string().starts_with(&format!("{location}: ")), "{input}: {error}");
    if let Some(span) = error.span() {
        assert!(span.start <= span.end && span.end <= text.len() && text.is_char_boundary(span.start), "{input}");
    }
}

/// What became of an input.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Outcome {
    /// Rejected when loading (syntax, names, types, ranges).
    Rejected,
    /// Loaded, then rejected when building (overlaps, time step).
    RejectedByBuild,
    /// Loaded (and built, if small).
    Accepted,
}

/// Loads (parse and validate) `bytes` as `mutated.ron` and builds the scene if it is small; each rejection must be
/// located. The scene's text for locating is the lossy one (identical up to the first invalid byte).
fn exercise_bounded(bytes: Vec<u8>, input: &str) -> Outcome {
    let text = String::from_utf8_lossy(&bytes).into_owned();
    match Scene::from_bytes(bytes, "mutated.ron") {
        Err(error) => {
            assert_located(&error, &text, input);
            Outcome::Rejected
        }
        Ok(scene) => {
            if scene.initial_particle_count() > MAX_BUILT_PARTICLES {
                return Outcome::Accepted;
            }
            match scene.build() {
                Err(error) => {
                    assert_located(&error, &text, input);
                    Outcome::RejectedByBuild
                }
                Ok(_) => Outcome::Accepted,
            }
        }
    }
}

/// Imports a mutated gsi file as `gc2d-rs import-gsi` does (read, convert, write RON, load back): every error names
/// a line of the file, and the written scene loads or is rejected with a located error.
fn exercise_gsi(text: &str, input: &str) -> Outcome {
    let lines = text.split('\n').count() + 1;
    let located = |errors: &gc2d_scene::gsi::GsiErrors| {
        assert!(!errors.0.is_empty(), "{input}: an empty error list");
        for error in &errors.0 {
            assert!(error.line >= 1 && error.line <= lines, "{input}: line {} of {lines}", error.line);
            assert!(error.located("mutated.gsi").starts_with(&format!("mutated.gsi:{}: ", error.line)), "{input}");
        }
        Outcome::Rejected
    };
    let import = match parse_gsi(text, &ImportOptions::default()) {
        Ok(import) => import,
        Err(errors) => return located(&errors),
    };
    let conversion = match to_scene(&import, "mutated") {
        Ok(conversion) => conversion,
        Err(errors) => return located(&errors),
    };
    let ron = conversion.scene.to_ron_string().unwrap_or_else(|e| panic!("{input}: cannot write RON: {e}"));
    exercise_bounded(ron.into_bytes(), input)
}

/// Runs `work` for each of `count` inputs under the hang guard; returns how many had each outcome (rejected when
/// loading, rejected by the build, accepted).
fn campaign(count: usize, work: impl Fn(usize) -> Outcome) -> [usize; 3] {
    let progress = Arc::new(AtomicUsize::new(0));
    let done = Arc::new(AtomicUsize::new(0));
    let watched = (Arc::clone(&progress), Arc::clone(&done));
    let guard = std::thread::spawn(move || {
        let (mut last, mut since) = (usize::MAX, Instant::now());
        while watched.1.load(Ordering::Relaxed) == 0 {
            let now = watched.0.load(Ordering::Relaxed);
            if now != last {
                (last, since) = (now, Instant::now());
            } else if since.elapsed() > HANG_LIMIT {
                eprintln!("input {now} has run for more than {HANG_LIMIT:?}: a hang");
                std::process::exit(101);
            }
            std::thread::sleep(Duration::from_millis(50));
        }
    });
    let mut outcomes = [0; 3];
    for i in 0..count {
        progress.store(i, Ordering::Relaxed);
        outcomes[work(i) as usize] += 1;
    }
    done.store(1, Ordering::Relaxed);
    guard.join().unwrap();
    outcomes
}

#[test]
fn ten_thousand_mutated_scenes_are_loaded_or_rejected_at_a_location() {
    let mut bases = vec![("full", base_scene())];
    bases.extend(REPOSITORY_SCENES.iter().map(|(name, text)| (*name, (*text).to_owned())));
    for (name, text) in &bases {
        Scene::from_str(text, "mutated.ron").unwrap_or_else(|e| panic!("{name}: {}", e.render_plain()));
    }
    let outcomes = campaign(SCENE_INPUTS, |i| {
        // One seed per input: a failure names the input, which reruns alone with the same draws.
        let mut rng = ChaCha8Rng::seed_from_u64(i as u64);
        let (name, base) = &bases[i % bases.len()];
        let mutations: Vec<Mutation> = (0..rng.random_range(1..5)).map(|_| random_mutation(&mut rng)).collect();
        let text = mutate(base, &mutations);
        let bytes = if i % 10 == 9 { mutate_bytes(&text, &mut rng) } else { text.into_bytes() };
        exercise_bounded(bytes, &format!("scene input {i} (seed {i}, base {name})"))
    });
    // The mutations reach every stage: most break the text, some the build, some leave a valid scene.
    eprintln!("scenes rejected when loading, by the build, accepted: {outcomes:?}");
    assert!(outcomes.iter().all(|&n| n >= SCENE_INPUTS / 100), "{outcomes:?}");
}

#[test]
fn two_thousand_mutated_gsi_files_are_imported_or_rejected_at_a_line() {
    let outcomes = campaign(GSI_INPUTS, |i| {
        let mut rng = ChaCha8Rng::seed_from_u64(1_000_000 + i as u64);
        let mutations: Vec<Mutation> = (0..rng.random_range(1..4)).map(|_| random_mutation(&mut rng)).collect();
        exercise_gsi(&mutate(PISTON_GSI, &mutations), &format!("gsi input {i} (seed {})", 1_000_000 + i))
    });
    eprintln!("gsi files rejected, rejected by the build, accepted: {outcomes:?}");
    assert!(outcomes[0] >= GSI_INPUTS / 100 && outcomes[2] >= GSI_INPUTS / 100, "{outcomes:?}");
}
