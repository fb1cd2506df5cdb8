//! A bounded mutation test of the VTK reader: 3000 deterministic mutants of two good files (words deleted,
//! repeated or replaced, digits changed, lines dropped or swapped, bytes inserted, the file cut short). Each is
//! parsed (and, where it parses, turned into fields and evaluated); none may panic, and every refusal must name the
//! file and a line of it.

use gc2d_fluid::vtk::{DataLocation, VtkFile};
use gc2d_fluid::{Interpolation, Outside, SampledField};
use gc2d_geometry::DVec2;

/// A small deterministic generator (SplitMix64), so the mutants are the same on every run.
struct Mix(u64);

impl Mix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

const WORDS: [&str; 18] = [
    "x",
    "-1",
    "0",
    "1e400",
    "nan",
    "inf",
    "18446744073709551616",
    "99999999999",
    "POINTS",
    "CELLS",
    "FIELD",
    "LOOKUP_TABLE",
    "OFFSETS",
    "POINT_DATA",
    "CELL_DATA",
    "\u{e9}t\u{e9}",
    "1.5",
    "",
];

/// The byte ranges of the whitespace-separated words of `text`.
fn words(text: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < text.len() {
        while i < text.len() && text[i].is_ascii_whitespace() {
            i += 1;
        }
        let start = i;
        while i < text.len() && !text[i].is_ascii_whitespace() {
            i += 1;
        }
        if i > start {
            out.push((start, i));
        }
    }
    out
}

fn mutate(good: &[u8], mix: &mut Mix) -> Vec<u8> {
    let w = words(good);
    let (s, e) = w[mix.below(w.len())];
    let splice = |with: &[u8]| [&good[..s], with, &good[e..]].concat();
    match mix.below(8) {
        0 => splice(b""),
        1 => splice(&[&good[s..e], b" ", &good[s..e]].concat()),
        2 => splice(WORDS[mix.below(WORDS.len())].as_bytes()),
        3 => good[..mix.below(good.len())].to_vec(),
        4 | 5 => {
            let lines: Vec<&[u8]> = good.split(|&b| b == b'\n').collect();
            let mut lines = lines.clone();
            let a = mix.below(lines.len());
            if mix.below(2) == 0 {
                lines.remove(a);
            } else {
                let b = mix.below(lines.len());
                lines.swap(a, b);
            }
            lines.join(&b'\n')
        }
        6 => {
            let at = mix.below(good.len());
            [&good[..at], &[mix.below(256) as u8], &good[at..]].concat()
        }
        _ => {
            let mut word = good[s..e].to_vec();
            let at = mix.below(word.len());
            word[at] = b"0123456789.-e"[mix.below(13)];
            splice(&word)
        }
    }
}

#[test]
fn mutated_files_never_panic_and_every_refusal_is_located() {
    let dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let mut mix = Mix(2024);
    let (mut accepted, mut refused) = (0, 0);
    for name in ["feedpipe_unstructured.vtk", "foam_cavity.vtk"] {
        let good = std::fs::read(dir.join(name)).unwrap();
        for n in 0..1500 {
            let mutant = mutate(&good, &mut mix);
            let file = format!("mutant_{n}.vtk");
            let lines = mutant.split(|&b| b == b'\n').count();
            match VtkFile::parse(&mutant, &file) {
                Ok(vtk) => {
                    accepted += 1;
                    for location in [DataLocation::Points, DataLocation::Cells] {
                        let Ok(samples) = vtk.velocity_samples("U", location) else { continue };
                        for interpolation in [Interpolation::Bilinear, Interpolation::SHEPARD_THESIS] {
                            if let Ok(field) = SampledField::new(&samples, interpolation, Outside::Nearest) {
                                for p in [DVec2::new(0.3, 0.2), DVec2::new(-5.0, 0.5), DVec2::new(0.05, 0.1)] {
                                    let u = field.velocity(p).unwrap();
                                    assert!(u.is_finite(), "{file}: {u}");
                                }
                            }
                        }
                    }
                }
                Err(e) => {
                    refused += 1;
                    let message = e.to_string();
                    let rest = message.strip_prefix(&format!("{file}, line ")).unwrap_or_else(|| panic!("{message}"));
                    let line: usize = rest.split(':').next().unwrap().parse().unwrap();
                    assert!((1..=lines).contains(&line), "{message} (the mutant has {lines} lines)");
                    let what = rest.split_once(": ").map_or("", |(_, what)| what);
                    assert!(what.len() > 10, "{message}");
                    if std::env::var_os("SHOW_VTK_MESSAGES").is_some() {
                        eprintln!("{message}");
                    }
                }
            }
        }
    }
    // Most mutants break the file; some (a changed digit of a coordinate) leave it valid.
    assert!(refused > 2000 && accepted > 100, "refused {refused}, accepted {accepted}");
}
