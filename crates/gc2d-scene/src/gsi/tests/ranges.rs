//! Values the scene refuses (out of range) are reported at the gsi line and keyword that set them, not at a line of
//! the written RON (QA report 1, section 10).

use super::{PISTON, file, read};
use crate::gsi::{GsiErrorKind, GsiErrors, to_scene};

/// The thesis's example with the line starting (after spaces) with `keyword` replaced by `replacement`.
fn piston_with(keyword: &str, replacement: &str) -> String {
    let lines: Vec<&str> =
        PISTON.lines().map(|line| if line.trim_start().starts_with(keyword) { replacement } else { line }).collect();
    lines.join("\n") + "\n"
}

/// The conversion's errors of `text`, which must read.
fn conversion_errors(text: &str) -> GsiErrors {
    match to_scene(&read(text), "test") {
        Ok(conversion) => panic!("expected errors, got {:?}", conversion.scene),
        Err(errors) => errors,
    }
}

/// The errors as `line N: message`.
fn messages(errors: &GsiErrors) -> Vec<String> {
    errors.0.iter().map(ToString::to_string).collect()
}

#[test]
fn a_negative_gamma_is_named_at_its_gsi_line() {
    let errors = conversion_errors(&piston_with("Gamma", "        Gamma               -0.5"));
    assert_eq!(
        messages(&errors),
        ["line 7: GAMMA: -0.5: must be a finite number ≥ 0 (scene field `materials[0].gamma`)"]
    );
    assert!(matches!(errors.0[0].kind, GsiErrorKind::InvalidValue { keyword: "GAMMA", .. }));
}

#[test]
fn part_size_and_corner_counts_are_named_at_their_gsi_lines() {
    let errors = conversion_errors(&piston_with("Part_Size", "        Part_Size           0 0"));
    assert_eq!(errors.0.len(), 1, "{errors}");
    assert_eq!(errors.0[0].line, 65);
    assert!(errors.0[0].to_string().starts_with("line 65: PART_SIZE: "), "{errors}");
    assert!(errors.0[0].to_string().ends_with("(scene field `blocks[0].shape.semi_axes_m`)"), "{errors}");

    let errors = conversion_errors(&piston_with("Part_Num_Corners", "        Part_Num_Corners    100"));
    assert_eq!(errors.0.len(), 1, "{errors}");
    assert_eq!(errors.0[0].line, 63);
    assert!(errors.0[0].to_string().starts_with("line 63: PART_NUM_CORNERS: 100"), "{errors}");
}

#[test]
fn steps_data_0_is_refused_at_its_line() {
    let errors = conversion_errors(&piston_with("Steps_Data", "        Steps_Data          0"));
    assert_eq!(
        messages(&errors),
        ["line 8: STEPS_DATA cannot be converted to a scene: 0 steps between data outputs; it must be at least 1 \
          (a frame is written every STEPS_DATA × DELTA_T)"]
    );
}

#[test]
fn values_of_every_object_are_traced_back_to_their_keyword() {
    let text = file(
        "Time 0 1\nE_Modul -5\nMue_Statisch -1\nHeat_Amplitude -2\nDISPLAY\nX_Range 1 -1\n\
         WALL\nVib_Width 0.01\nVib_Frequence -2\nCorners\n0 0\n1 0\n0 1\nEND\n\
         PARTICLE\nDrag_K -3\nCorners\n5 5\n6 5\n5 6\nEND\n\
         DROPSOURCE\nPos 0 10\nDelta_T 0\nPart_Size 0.01 0.01",
    );
    let errors = conversion_errors(&text);
    let found: Vec<(usize, &str)> = errors
        .0
        .iter()
        .map(|error| match &error.kind {
            GsiErrorKind::InvalidValue { keyword, .. } => (error.line, *keyword),
            other => panic!("{other}"),
        })
        .collect();
    for expected in [
        (4, "E_MODUL"),
        (5, "MUE_STATISCH"),
        (6, "HEAT_AMPLITUDE"),
        (8, "X_RANGE"),
        (11, "VIB_FREQUENCE"),
        (18, "DRAG_K"),
        (26, "DELTA_T"),
    ] {
        assert!(found.contains(&expected), "{expected:?} not in {found:?}\n{errors}");
    }
}

#[test]
fn a_reversed_time_window_is_named_at_its_keyword() {
    let text = file("Time 0 1\nWALL\nVib_Time 2 1\nCorners\n0 0\n1 0\n0 1\nEND");
    let errors = conversion_errors(&text);
    assert_eq!(errors.0.len(), 1, "{errors}");
    assert_eq!(errors.0[0].line, 5);
    assert!(errors.0[0].to_string().starts_with("line 5: VIB_TIME: "), "{errors}");
}
