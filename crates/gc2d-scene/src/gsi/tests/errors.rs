//! Every class of gsi error, with the line it names and the words of its message.

use super::{file, read_errors};
use crate::gsi::{GsiErrorKind, ImportOptions, MAX_LINE_LENGTH, parse_gsi};

/// The only error of `text`, as (line, message).
fn only_error(text: &str) -> (usize, GsiErrorKind, String) {
    let errors = read_errors(text);
    assert_eq!(errors.0.len(), 1, "{errors}");
    let error = errors.0[0].clone();
    (error.line, error.kind.clone(), error.to_string())
}

#[test]
fn missing_header_is_named() {
    for text in ["", "Delta_T 0.1\n", "PARAMETER\n", "# PARAMETER v1.4\n"] {
        let (line, kind, message) = only_error(text);
        assert_eq!(line, 1);
        assert!(matches!(kind, GsiErrorKind::MissingHeader { .. }), "{message}");
        assert!(message.contains("PARAMETER v1.4"), "{message}");
    }
    let (_, kind, message) = only_error("PARAMETER v1.3\n\nEND_OF_FILE\n");
    assert!(matches!(kind, GsiErrorKind::UnsupportedVersion { .. }));
    assert_eq!(message, "line 1: gsi version `v1.3` is not supported; gc2d-rs reads `PARAMETER v1.4`");
}

#[test]
fn unknown_keywords_get_a_suggestion() {
    let (line, _, message) = only_error(&file("Delta_T 0.1\nDelta_Y 0.2"));
    assert_eq!(line, 4);
    assert_eq!(message, "line 4: unknown keyword `Delta_Y` in GENERAL; did you mean `DELTA_T`?");
    let (line, _, message) = only_error(&file("WALL\nPiston_Frce 3\nCorners\n0 0\n1 0\n0 1\nEND"));
    assert_eq!(line, 4);
    assert!(message.ends_with("in WALL; did you mean `PISTON_FORCE`?"), "{message}");
    let (_, _, message) = only_error(&file("WAL\n"));
    assert!(message.ends_with("did you mean `WALL`?"), "{message}");
    let (_, kind, message) = only_error(&file("Frobnicate 3"));
    assert_eq!(
        kind,
        GsiErrorKind::UnknownKeyword { keyword: "Frobnicate".into(), object: "GENERAL", suggestion: None }
    );
    assert!(!message.contains("did you mean"));
}

#[test]
fn commands_of_another_object_are_named_as_such() {
    let (line, kind, message) = only_error(&file("Offset 0 0"));
    assert_eq!(line, 3);
    assert!(matches!(kind, GsiErrorKind::WrongObject { .. }));
    assert_eq!(message, "line 3: `Offset` is a command of WALL, not of GENERAL");
    let (line, _, message) = only_error(&file("WALL\nCorners\n0 0\n1 0\n0 1\nEND\nG 9.81"));
    assert_eq!(line, 9);
    assert!(message.contains("`G` is a command of GENERAL, not of WALL"), "{message}");
    assert!(message.contains("GENERAL cannot be re-entered"), "{message}");
    let (line, kind, _) = only_error(&file("DISPLAY\nGENERAL\n"));
    assert_eq!((line, kind), (4, GsiErrorKind::GeneralNamed));
}

#[test]
fn bad_numbers_are_named_with_the_word() {
    let (line, _, message) = only_error(&file("E_Modul 1e7x"));
    assert_eq!(line, 3);
    assert_eq!(message, "line 3: E_MODUL: `1e7x` is not a finite number");
    for text in ["Time nan 1", "Time 0 inf", "Gamma -Infinity", "E_Modul 1e400"] {
        let (_, kind, message) = only_error(&file(text));
        assert!(matches!(kind, GsiErrorKind::BadNumber { .. }), "{message}");
    }
    let (_, _, message) = only_error(&file("WALL\nCorners\n0 0\n1 inf\n0 1\nEND"));
    assert!(message.contains("found `1 inf`"), "{message}");
    let (_, _, message) = only_error(&file("Steps_Data 10.5"));
    assert_eq!(message, "line 3: STEPS_DATA: `10.5` is not a non-negative whole number");
    let (_, _, message) = only_error(&file("Steps_Data -3"));
    assert!(message.contains("not a non-negative whole number"), "{message}");
    let (_, _, message) = only_error(&file("Delta_T"));
    assert_eq!(message, "line 3: DELTA_T: expected 1 value, found none");
    let (line, _, message) = only_error(&file("WALL\nCorners\n0 0\n1 x\n0 1\nEND"));
    assert_eq!(line, 6);
    assert!(message.contains("each line must be a corner `x y`; found `1 x`"), "{message}");
}

#[test]
fn corners_without_end_name_the_opening_line() {
    let (line, _, message) = only_error(&file("WALL\nCorners\n0 0\n1 0\n0 1\nWALL\nCorners\n0 0\n1 0\n0 1\nEND"));
    assert_eq!(line, 8);
    assert_eq!(message, "line 8: CORNERS block opened at line 4 has no END before `WALL` at line 8");
    let errors = read_errors("PARAMETER v1.4\n\nPARTICLE\nCorners\n0 0\n1 0\n0 1\n");
    assert!(errors.0.iter().any(
        |e| e.kind == GsiErrorKind::UnclosedCorners { opened_at: 4, interrupted_by: "the end of the file".into() }
    ));
    let (line, kind, _) = only_error(&file("DISPLAY\nCorners\n0 0\n1 0\n0 1\nEND"));
    assert_eq!((line, kind), (4, GsiErrorKind::CornersNotAllowed { object: "DISPLAY" }));
    let (line, kind, _) = only_error(&file("END"));
    assert_eq!((line, kind), (3, GsiErrorKind::StrayEnd));
}

#[test]
fn objects_without_or_with_bad_corners() {
    let (line, kind, _) = only_error(&file("WALL\nOffset 1 1"));
    assert_eq!((line, kind), (3, GsiErrorKind::MissingCorners { object: "WALL" }));
    let (line, kind, _) = only_error(&file("PARTICLE\nCorners\n0 0\n1 0\nEND"));
    assert_eq!((line, kind), (4, GsiErrorKind::TooFewCorners { count: 2 }));
    let (line, kind, _) = only_error(&file("WALL\nCorners\n0 0\n1 0\n0 1\nEND\nCorners\n0 0\n1 0\n0 1\nEND"));
    assert_eq!((line, kind), (9, GsiErrorKind::DuplicateCorners { object: "WALL", first: 4 }));
}

#[test]
fn corners_that_overflow_when_placed_are_refused() {
    let (line, kind, _) = only_error(&file("WALL\nOffset 1e308 0\nCorners\n1e308 0\n1.7e308 0\n1.7e308 1\nEND"));
    assert_eq!((line, kind), (5, GsiErrorKind::CornersOverflow));
}

#[test]
fn too_long_lines_are_refused() {
    let long = format!("# {}", "x".repeat(MAX_LINE_LENGTH));
    let (line, kind, _) = only_error(&file(&format!("Delta_T 0.1\n{long}")));
    assert_eq!((line, kind), (4, GsiErrorKind::LineTooLong { length: MAX_LINE_LENGTH + 2 }));
    let just_fits = format!("# {}", "x".repeat(MAX_LINE_LENGTH - 2));
    assert!(parse_gsi(&file(&just_fits), &ImportOptions::default()).is_ok());
}

#[test]
fn bad_option_values_list_the_choices() {
    let (line, _, message) = only_error(&file("GENERATE_BLOCK\nGrid_Type HEX"));
    assert_eq!(line, 4);
    assert!(message.contains("HEX") && message.contains("FCC_EQUAL"), "{message}");
    let (_, _, message) = only_error(&file("GENERATE_BLOCK\nRandom_Size NORMAL"));
    assert!(message.contains("CONST, EQUAL, GAUSS"), "{message}");
    let (_, _, message) = only_error(&file("DROPSOURCE\nType ABSOLUTE"));
    assert!(message.contains("ABS or REL"), "{message}");
    let (_, _, message) = only_error(&file("G_Type WOBBLE"));
    assert!(message.contains("SMOOTH_STEP"), "{message}");
    let (_, _, message) = only_error(&file("WALL\nVib_Type SQUARE\nCorners\n0 0\n1 0\n0 1\nEND"));
    assert!(message.contains("COSINUS"), "{message}");
}

#[test]
fn impossible_walls_and_grids() {
    let text = file("WALL\nPiston_Force 1\nVib_Width 0.1\nCorners\n0 0\n1 0\n0 1\nEND");
    let (line, kind, _) = only_error(&text);
    assert_eq!((line, kind), (5, GsiErrorKind::PistonAndVibration { piston_line: 4, vibration_line: 5 }));
    let (line, _, message) = only_error(&file("GENERATE_BLOCK\nGrid_Distance 0.01 0"));
    assert_eq!(line, 4);
    assert!(message.contains("GRID_DISTANCE must be two finite positive spacings"), "{message}");
    let (_, _, message) = only_error(&file("GENERATE_BLOCK\nX_Range 0 1\nY_Range 0 1\nGrid_Distance 1e-6 1e-6"));
    assert!(message.contains("sites, more than"), "{message}");
    let (_, _, message) = only_error(&file("GENERATE_BLOCK\nX_Range -1e308 1e308\nGrid_Distance 1 1"));
    assert!(message.contains("sites, more than"), "{message}");
}

#[test]
fn all_errors_of_a_file_are_reported_in_line_order() {
    let errors = read_errors(&file("Delta_Y 1\nE_Modul x\nWALL\nOffset 0 0\nFoo\n"));
    let lines: Vec<usize> = errors.0.iter().map(|e| e.line).collect();
    assert_eq!(lines, [3, 4, 5, 7]);
    assert_eq!(
        errors.0[0].located("piston.gsi"),
        "piston.gsi:3: unknown keyword `Delta_Y` in GENERAL; did you mean `DELTA_T`?"
    );
    assert_eq!(errors.to_string().lines().count(), 4);
}
