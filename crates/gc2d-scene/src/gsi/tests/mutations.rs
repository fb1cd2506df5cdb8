//! Robustness: random edits of the thesis's example never make the reader panic, and whatever it accepts holds
//! no NaN.

use proptest::prelude::*;

use super::PISTON;
use crate::gsi::{ImportOptions, PartSizeConvention, parse_gsi};

/// One edit of the text: delete, insert or replace a character, or duplicate, drop or swap lines.
#[derive(Debug, Clone)]
enum Edit {
    Delete(usize),
    Insert(usize, char),
    Replace(usize, char),
    InsertWord(usize, &'static str),
    DuplicateLine(usize),
    DropLine(usize),
    SwapLines(usize, usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    let character = prop::sample::select(vec![
        ' ', '\t', '\n', '#', '$', '-', '.', 'e', 'E', '0', '1', '9', 'x', '_', 'Z', '\u{e9}', '\r',
    ]);
    prop_oneof![
        any::<usize>().prop_map(Edit::Delete),
        (any::<usize>(), character.clone()).prop_map(|(i, c)| Edit::Insert(i, c)),
        (any::<usize>(), character).prop_map(|(i, c)| Edit::Replace(i, c)),
        (any::<usize>(), word()).prop_map(|(i, w)| Edit::InsertWord(i, w)),
        any::<usize>().prop_map(Edit::DuplicateLine),
        any::<usize>().prop_map(Edit::DropLine),
        (any::<usize>(), any::<usize>()).prop_map(|(i, j)| Edit::SwapLines(i, j)),
    ]
}

fn word() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec![
        " inf ",
        " nan ",
        " 1e400 ",
        " -0 ",
        "\nEND\n",
        "\nCORNERS\n",
        "\nWALL\n",
        "\nPARTICLE\n",
        "\nEND_OF_FILE\n",
        " Angle ",
        "\nAngle 1e300\n",
        " 1e-300 ",
        "\nGrid_Distance 1e-9 1\n",
        "\nVib_Width 1\n",
        "\nPosition_Absolut\n",
    ])
}

fn apply(text: &str, edit: &Edit) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    let mut lines: Vec<&str> = text.lines().collect();
    match *edit {
        Edit::Delete(i) => {
            chars.remove(i % chars.len());
        }
        Edit::Insert(i, c) => chars.insert(i % (chars.len() + 1), c),
        Edit::InsertWord(i, word) => {
            let at = i % (chars.len() + 1);
            chars.splice(at..at, word.chars());
        }
        Edit::Replace(i, c) => {
            let i = i % chars.len();
            chars[i] = c;
        }
        Edit::DuplicateLine(i) => {
            let line = lines[i % lines.len()];
            lines.insert(i % lines.len(), line);
            return lines.join("\n");
        }
        Edit::DropLine(i) => {
            lines.remove(i % lines.len());
            return lines.join("\n");
        }
        Edit::SwapLines(i, j) => {
            let n = lines.len();
            lines.swap(i % n, j % n);
            return lines.join("\n");
        }
    }
    chars.into_iter().collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn mutated_piston_files_never_panic(edits in prop::collection::vec(edit(), 1..6), semi in any::<bool>()) {
        let text = edits.iter().fold(PISTON.to_string(), |text, edit| apply(&text, edit));
        let part_size = if semi { PartSizeConvention::SemiAxes } else { PartSizeConvention::Auto };
        if let Ok(import) = parse_gsi(&text, &ImportOptions { part_size }) {
            // The converter (which builds the scene once to check Δt) and the RON round trip must not panic either;
            // files with huge grids are left out to keep the test fast.
            if import.scene.blocks.iter().map(|block| block.site_count()).sum::<usize>() <= 2000 {
                if let Ok(conversion) = crate::gsi::to_scene(&import, "mutated") {
                    let text = conversion.scene.to_ron_string().expect("a converted scene serialises");
                    let _ = crate::Scene::from_str(&text, "mutated.ron").map(|scene| scene.summary());
                }
            }
            let scene = import.scene;
            prop_assert!(!scene.general.time_step.value.is_nan());
            for wall in &scene.walls {
                prop_assert!(wall.corners.value.iter().all(|c| c.is_finite()));
            }
            for block in &scene.blocks {
                prop_assert!(block.site_count() as f64 <= crate::gsi::MAX_GRID_SITES);
                prop_assert!(!block.shape.semi_axes().is_nan());
            }
        }
    }
}
