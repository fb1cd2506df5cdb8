//! How many values each command takes (QA report 1, section 2): a missing or extra number is an error naming the
//! command, the count expected and the values found; words after the values are gc2d's inline comments, accepted
//! with a warning; a missing TIME, PISTON_FORCE or PART_SIZE warns with the documented default it gets.

use super::{PISTON, file, read, read_errors, warned};
use crate::gsi::{GsiErrorKind, GsiWarningKind};

/// The thesis's example with line `line` (1-based) replaced by `replacement` (`None`: the line removed, which
/// shifts the later lines up by one).
fn piston_with(line: usize, replacement: Option<&str>) -> String {
    let mut lines: Vec<&str> = PISTON.lines().collect();
    match replacement {
        Some(text) => lines[line - 1] = text,
        None => {
            lines.remove(line - 1);
        }
    }
    lines.join("\n") + "\n"
}

/// The errors of `text` as `line N: message` lines.
fn messages(text: &str) -> Vec<String> {
    read_errors(text).0.iter().map(ToString::to_string).collect()
}

#[test]
fn a_missing_second_value_is_an_error_not_zero() {
    // `Time 0`: the end time is missing (the old reader ran to t = 0).
    let errors = messages(&piston_with(5, Some("        Time                0")));
    assert_eq!(errors, ["line 5: TIME: expected 2 values (start end, s), found 1: `0`"]);
    // `Offset 0.11` on the lid: y is missing (the old reader moved the lid onto the floor).
    let errors = messages(&piston_with(41, Some("        Offset              0.11")));
    assert_eq!(errors, ["line 41: OFFSET: expected 2 values (x y, m), found 1: `0.11`"]);
    // `Grid_Distance 0.005`: the old message invented a second value 0.
    let errors = messages(&piston_with(61, Some("        Grid_Distance       0.005")));
    assert_eq!(errors, ["line 61: GRID_DISTANCE: expected 2 values (Δx Δy, m), found 1: `0.005`"]);
    // A word where the second number should be is not read as 0 either.
    let errors = messages(&file("DISPLAY\nX_Range -1 oops"));
    assert_eq!(errors, ["line 4: X_RANGE: expected 2 values (min max, m), found 1: `-1` (`oops` is not a number)"]);
    let errors = messages(&file("Delta_T"));
    assert_eq!(errors, ["line 3: DELTA_T: expected 1 value, found none"]);
}

#[test]
fn an_extra_value_is_an_error_not_dropped() {
    // `Gamma 0.5 0.9`: the old reader kept 0.5 and dropped 0.9 silently.
    let errors = messages(&piston_with(7, Some("        Gamma               0.5 0.9")));
    assert_eq!(errors, ["line 7: GAMMA: expected 1 value, found 2: `0.5 0.9`"]);
    let errors = messages(&file("Time 0 1 2\nSteps_Data 10 20\nWALL\nOffset 1 2 3\nCorners\n0 0\n1 0\n0 1\nEND"));
    assert_eq!(
        errors,
        [
            "line 3: TIME: expected 2 values (start end, s), found 3: `0 1 2`",
            "line 4: STEPS_DATA: expected 1 value, found 2: `10 20`",
            "line 6: OFFSET: expected 2 values (x y, m), found 3: `1 2 3`",
        ]
    );
    // A number after a comment word is part of the comment.
    let import = read(&file("Gamma 0.5 damping 0.9"));
    assert_eq!(import.scene.general.damping.value, 0.5);
}

#[test]
fn commands_documented_with_one_or_two_values_take_either() {
    let import =
        read(&file("G 9.81\nSeed 5\nDISPLAY\nScreen 800\nPARTICLE\nDrag_Velocity 0.2\nCorners\n0 0\n1 0\n0 1\nEND"));
    assert_eq!(import.scene.general.gravity.end.value, 9.81);
    assert_eq!(import.scene.general.seed.value, [5.0, 0.0]);
    assert_eq!(import.scene.display.as_ref().map(|d| d.screen.value), Some([800, 0]));
    assert!(import.warnings.iter().all(|w| !matches!(w.kind, GsiWarningKind::TrailingText { .. })));
    let errors = messages(&file("G 9.81 1 2"));
    assert_eq!(errors, ["line 3: G: expected 1 or 2 values (g1 g2, m/s²), found 3: `9.81 1 2`"]);
}

#[test]
fn words_after_the_values_are_accepted_as_a_comment_with_a_warning() {
    // gc2d ignores text after the parameters (§9.2 rule 3), so a legacy inline comment without `#` still reads,
    // but is named in case it is a typo.
    let import = read(&piston_with(6, Some("        E_Modul             1E7  stiffness of the grains")));
    assert_eq!(import.scene.general.youngs_modulus.value, 1e7);
    assert!(warned(&import, 6, |k| matches!(
        k,
        GsiWarningKind::TrailingText { keyword: "E_MODUL", text } if text == "stiffness of the grains"
    )));
    let message = import.warnings.iter().find(|w| w.line == 6).map(ToString::to_string).unwrap_or_default();
    assert_eq!(
        message,
        "line 6: E_MODUL: the text after the parameters, `stiffness of the grains`, is ignored (gc2d reads it as a \
         comment; start comments with `#` to silence this)"
    );
    // A `#` comment is the documented form and is silent.
    let import = read(&piston_with(6, Some("        E_Modul             1E7  # stiffness")));
    assert_eq!(import.scene.general.youngs_modulus.value, 1e7);
    assert!(!import.warnings.iter().any(|w| w.line == 6), "{:?}", import.warnings);
    // Words after a word or a flag, too.
    let import = read(&file("Basename out extra\nPARTICLE\nPosition_Absolut yes\nCorners\n0 0\n1 0\n0 1\nEND"));
    assert!(warned(&import, 3, |k| matches!(k, GsiWarningKind::TrailingText { keyword: "BASENAME", .. })));
    assert!(warned(&import, 5, |k| matches!(k, GsiWarningKind::TrailingText { keyword: "POSITION_ABSOLUT", .. })));
}

#[test]
fn a_missing_time_piston_force_or_part_size_warns_with_the_default_used() {
    let import = read(&piston_with(5, None));
    assert_eq!(import.scene.general.time.value.end, 1.0);
    assert!(warned(&import, 1, |k| *k
        == GsiWarningKind::DefaultUsed {
            keyword: "TIME",
            object: "GENERAL",
            default: "0 1 (s)",
            consequence: "the run ends at t = 1 s",
        }));
    let message = import.warnings.iter().find(|w| w.line == 1).map(ToString::to_string).unwrap_or_default();
    assert_eq!(message, "line 1: GENERAL has no TIME: gc2d's default 0 1 (s) is used, so the run ends at t = 1 s");

    let import = read(&piston_with(22, None));
    let crate::gsi::GsiWallMotion::Piston(piston) = &import.scene.walls[0].motion else { panic!("not a piston") };
    assert_eq!(piston.force.value, 0.0);
    assert!(warned(&import, 19, |k| matches!(k, GsiWarningKind::DefaultUsed { keyword: "PISTON_FORCE", .. })));

    let import = read(&piston_with(65, None));
    assert!(warned(&import, 58, |k| matches!(
        k,
        GsiWarningKind::DefaultUsed { keyword: "PART_SIZE", object: "GENERATE_BLOCK", default: "1 1 (m)", .. }
    )));
    let import = read(&file("DROPSOURCE\nPos 0 1"));
    assert!(warned(&import, 3, |k| matches!(
        k,
        GsiWarningKind::DefaultUsed { keyword: "PART_SIZE", object: "DROPSOURCE", default: "0.01 0.01 (m)", .. }
    )));
    // The thesis's example writes all three and gets none of these warnings.
    let import = read(PISTON);
    assert!(!import.warnings.iter().any(|w| matches!(w.kind, GsiWarningKind::DefaultUsed { .. })));
}

#[test]
fn every_numeric_command_checks_its_count() {
    // One missing and one extra value for every command that takes numbers, in every object that has it.
    use crate::gsi::keywords::{Arity, ObjectKind};
    for kind in ObjectKind::ALL {
        for command in kind.commands() {
            let (too_few, too_many) = match command.arity {
                Arity::Float | Arity::Whole => ("", "1 2"),
                Arity::FloatPair => ("1", "1 2 3"),
                Arity::FloatOneOrTwo | Arity::IntegerOneOrTwo => ("", "1 2 3"),
                Arity::Word | Arity::Flag => continue,
            };
            let object = if kind == ObjectKind::General { String::new() } else { format!("{}\n", kind.name()) };
            for values in [too_few, too_many] {
                let text = file(&format!("{object}{} {values}", command.name));
                let errors = read_errors(&text);
                let line = if kind == ObjectKind::General { 3 } else { 4 };
                assert!(
                    errors.0.iter().any(|e| e.line == line && matches!(e.kind, GsiErrorKind::ValueCount { .. })),
                    "{} {values} in {}: {errors}",
                    command.name,
                    kind.name()
                );
            }
        }
    }
}
