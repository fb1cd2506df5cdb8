//! Random mutations of a valid scene never make loading, building, stepping or rendering an error panic.

mod common;

use gc2d_scene::Scene;
use proptest::prelude::*;

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
