//! The rules of the gsi language (§9.2): case, spellings, missing parameters, comments, END_OF_FILE, repetition.

use gc2d_engine::DropHeight;
use gc2d_engine::schedules::GravityProfile;
use gc2d_geometry::{AngleMode, DVec2, Randomization};

use super::{PISTON, file, read, warned};
use crate::gsi::{GsiWarningKind, Note};
use crate::schema::GridType;

#[test]
fn keywords_objects_and_option_values_ignore_case() {
    let mixed = PISTON
        .lines()
        .enumerate()
        .map(|(i, line)| match i % 3 {
            0 if i > 0 => line.to_ascii_uppercase(),
            1 => line.to_ascii_lowercase(),
            _ => line.to_string(),
        })
        .collect::<Vec<_>>()
        .join("\n");
    let original = read(PISTON).scene;
    let changed = read(&mixed).scene;
    // BASENAME is case-sensitive (§9.2 rule 1): line 10 is upper-cased by the mapping above.
    assert_eq!(changed.general.basename.value, "DATA/PISTON2");
    let mut restored = changed.clone();
    restored.general.basename = original.general.basename.clone();
    assert_eq!(restored, original);
}

#[test]
fn both_spellings_of_the_random_options_mean_the_same() {
    let short =
        file("GENERATE_BLOCK\nRandom_Size EQUAL\nRandom_Num_Corners GAUSS\nRandom_Pos_Corners RAND2\nRandom_Rot GAUSS");
    let long = file(
        "GENERATE_BLOCK\nPart_Random_Size EQUAL\nPart_Random_Num_Corners GAUSS\nPart_Random_Pos_Corners RAND2\n\
         Part_Random_Rot GAUSS",
    );
    let (a, b) = (read(&short).scene.blocks, read(&long).scene.blocks);
    assert_eq!(a, b);
    let shape = &a[0].shape;
    assert_eq!(shape.size_randomization.value, Randomization::Equal);
    assert_eq!(shape.corner_randomization.value, Randomization::Gauss);
    assert_eq!(shape.angle_mode.value, AngleMode::Rand2);
    assert_eq!(shape.rotation_randomization.value, Randomization::Gauss);
}

#[test]
fn a_second_parameter_documented_as_optional_may_be_left_out() {
    // gc2d set any missing second parameter to 0 (§9.2 rule 2); gc2d-rs keeps that only where the reference
    // documents one value (SEED, G, DRAG_VELOCITY, SCREEN) and refuses it elsewhere (see `values.rs`).
    let import = read(&file("Time 0 1\nSeed 3\nDISPLAY\nScreen 800"));
    let general = &import.scene.general;
    assert_eq!(general.seed.value, [3.0, 0.0]);
    let display = import.scene.display.as_ref().expect("display");
    assert_eq!(display.screen.value, [800, 0]);
    assert!(import.warnings.is_empty(), "{:?}", import.warnings);
}

#[test]
fn comments_trailing_text_and_blank_lines() {
    let text = "PARAMETER v1.4\nrun 17 of the piston series\n$ Hello from gc2d\n  # ignored\n\n\
                Delta_T 0.001 Zeitschritt\n\tGamma\t0.7 # damping\n   $  second note  \nE_Modul 2e7 trailing\n\
                END_OF_FILE\nanything at all here is ignored: Frobnicate 3\n";
    let import = read(text);
    assert_eq!(import.scene.identification, "run 17 of the piston series");
    assert_eq!(
        import.notes,
        [Note { line: 3, text: "Hello from gc2d".into() }, Note { line: 8, text: "second note".into() }]
    );
    let general = &import.scene.general;
    assert_eq!(general.time_step.value, 0.001);
    assert_eq!(general.damping.value, 0.7);
    assert_eq!(general.damping.line(), 7);
    assert_eq!(general.youngs_modulus.value, 2e7);
    // Text after the parameters without `#` is read as gc2d reads it, a comment, but named (§9.2 rule 3).
    assert!(warned(
        &import,
        6,
        |k| matches!(k, GsiWarningKind::TrailingText { keyword: "DELTA_T", text } if text == "Zeitschritt")
    ));
    assert!(warned(
        &import,
        9,
        |k| matches!(k, GsiWarningKind::TrailingText { keyword: "E_MODUL", text } if text == "trailing")
    ));
    // The third warning: the file has no TIME.
    assert!(warned(&import, 1, |k| matches!(k, GsiWarningKind::DefaultUsed { keyword: "TIME", .. })));
    assert_eq!(import.warnings.len(), 3, "{:?}", import.warnings);
}

#[test]
fn comments_inside_corners_are_tolerated_and_crlf_is_read() {
    let text = "PARAMETER v1.4\r\n\r\nWALL\r\nCorners # Vorgabe der Ecken\r\n0 0 # first\r\n\r\n1 0\r\n0 1\r\nEND\r\n\
                END_OF_FILE\r\n";
    let wall = &read(text).scene.walls[0];
    assert_eq!(wall.corners.value, [DVec2::ZERO, DVec2::X, DVec2::Y]);
    assert_eq!(wall.corners.line(), 4);
}

#[test]
fn a_missing_end_of_file_is_a_warning() {
    let import = read("PARAMETER v1.4\n\nDelta_T 0.1\n");
    assert_eq!(import.scene.general.time_step.value, 0.1);
    assert!(import.warnings.iter().any(|w| w.kind == GsiWarningKind::MissingEndOfFile));
}

#[test]
fn unused_ignored_system_and_repeated_commands_warn() {
    let text = file(
        "Mue_Dynamisch 0.3\nEmail someone@example.org\nNext_Data_Filenumber 4\nGamma 0.1\nGamma 0.2\n\
         DISPLAY\nInterval 5\nDISPLAY\nInterval 7",
    );
    let import = read(&text);
    let general = &import.scene.general;
    assert_eq!(general.dynamic_friction.value, 0.3);
    assert_eq!(general.next_data_file_number.value, 4);
    assert_eq!(general.damping.value, 0.2);
    assert_eq!(import.scene.display.as_ref().map(|d| (d.line, d.interval.value)), Some((10, 7)));
    assert!(warned(&import, 3, |k| *k == GsiWarningKind::UnusedDynamicFriction));
    assert!(warned(&import, 4, |k| *k == GsiWarningKind::EmailIgnored));
    assert!(warned(&import, 5, |k| matches!(k, GsiWarningKind::SystemCommand { keyword: "NEXT_DATA_FILENUMBER" })));
    assert!(warned(&import, 7, |k| *k == GsiWarningKind::Repeated { keyword: "GAMMA", first: 6 }));
    assert!(warned(&import, 8, |k| *k == GsiWarningKind::DisplayReplaced { used: 10 }));
    assert!(warned(&import, 1, |k| matches!(k, GsiWarningKind::DefaultUsed { keyword: "TIME", .. })));
    assert_eq!(import.warnings.len(), 6, "{:?}", import.warnings);
}

#[test]
fn an_identification_that_looks_like_a_command_warns() {
    let import = read("PARAMETER v1.4\nDelta_T 0.5\nEND_OF_FILE\n");
    assert_eq!(import.scene.general.time_step.value, 1e-4, "line 2 is never a command");
    assert!(warned(&import, 2, |k| matches!(k, GsiWarningKind::IdentificationLooksLikeCommand { keyword: "DELTA_T" })));
}

#[test]
fn defaults_of_every_object() {
    let text = file(
        "GENERATE_BLOCK\nDROPSOURCE\nWALL\nVib_Width 0.001\nCorners\n0 0\n1 0\n0 1\nEND\n\
         PARTICLE\nDrag_K 50\nCorners\n0 0\n1 0\n0 1\nEND",
    );
    let scene = read(&text).scene;
    let general = &scene.general;
    assert_eq!(general.time_step.value, 1e-4);
    assert_eq!((general.gravity.start.value, general.gravity.end.value), (9.81, 9.81));
    assert_eq!(general.gravity.parameters.value, [5.0, 0.5]);
    assert_eq!(general.steps_setup.value, crate::gsi::BIG_NUMBER);
    assert_eq!(general.basename.value, "default");
    let block = &scene.blocks[0];
    assert_eq!(block.grid_type.value, GridType::Fcc);
    assert_eq!(block.grid_distance.value, DVec2::splat(2.0));
    assert_eq!((block.y_range.value.min, block.y_range.value.max), (0.0, 10.0));
    assert_eq!(block.shape.part_size.value, DVec2::splat(1.0));
    assert_eq!((block.shape.corners.value, block.shape.corner_variation.value), (6, 2));
    assert_eq!(block.velocity_direction_range.value.max, std::f64::consts::TAU);
    // Defaults: semi-axes 1 on a grid of spacing 2 just touch, so Auto keeps semi-axes.
    assert_eq!(scene.part_size_reading, crate::gsi::PartSizeReading::SemiAxes);
    assert_eq!(block.shape.part_size.line(), 3, "a default names its object's line");
    let source = &scene.drop_sources[0];
    assert_eq!(source.position.value, DVec2::new(0.0, 0.01));
    assert_eq!(source.height.value, DropHeight::Absolute);
    assert_eq!(source.interval.value, 0.1);
    assert_eq!((source.shape.corners.value, source.shape.size_variation.value), (8, 0.1));
    let crate::gsi::GsiWallMotion::Vibration(vibration) = &scene.walls[0].motion else { panic!("vibrates") };
    assert_eq!(vibration.direction_angle.value, std::f64::consts::FRAC_PI_2);
    assert_eq!(vibration.window.value.end, f64::INFINITY);
    assert_eq!(vibration.amplitude.value, 0.001);
    assert_eq!(vibration.frequency.value, 1.0);
    let drag = scene.particles[0].drag.as_ref().expect("drag");
    assert_eq!((drag.stiffness.value, drag.speed.value), (50.0, 0.1));
    assert_eq!((drag.window.value.start, drag.window.value.end), (0.0, 1.0));
}

#[test]
fn variable_gravity_and_heating() {
    let import = read(&file("G 9.81 9.0\nG_Time 0.1 1.1\nG_Parameter 5 0.2\nG_Type smooth_step\nHeat_Amplitude 0.02"));
    let general = &import.scene.general;
    let gravity = &general.gravity;
    assert_eq!((gravity.start.value, gravity.end.value), (9.81, 9.0));
    assert_eq!((gravity.window.value.start, gravity.window.value.end), (0.1, 1.1));
    assert_eq!(gravity.parameters.value, [5.0, 0.2]);
    assert_eq!(gravity.profile.value, GravityProfile::SmoothStep);
    let heating = general.heating.as_ref().expect("heating is on when a HEAT_* command is written");
    assert_eq!(heating.amplitude.value, 0.02);
    assert_eq!(heating.slope.value, 4.0);
    assert_eq!(heating.window.value.start, f64::INFINITY);
    let import = read(&file("G 3\nG_Type LINEAR"));
    let gravity = &import.scene.general.gravity;
    assert_eq!((gravity.start.value, gravity.end.value), (3.0, 3.0), "G with one value is a constant g");
    assert!(warned(&import, 3, |k| matches!(k, GsiWarningKind::GravityWithoutEndValue { .. })));
}

#[test]
fn drop_sources_read_abs_and_rel() {
    let scene =
        read(&file("DROPSOURCE\nType rel\nPos 0.1 0.2\nWidth 0.05\nTime 1 2\nDelta_T 0.01\nDROPSOURCE\nType ABS"))
            .scene;
    let [relative, absolute] = scene.drop_sources.as_slice() else { panic!("two sources") };
    assert_eq!(relative.height.value, DropHeight::AboveHighest);
    assert_eq!(relative.height.line(), 4);
    assert_eq!(relative.position.value, DVec2::new(0.1, 0.2));
    assert_eq!(relative.width.value, 0.05);
    assert_eq!((relative.window.value.start, relative.window.value.end), (1.0, 2.0));
    assert_eq!(relative.interval.value, 0.01);
    assert_eq!(absolute.height.value, DropHeight::Absolute);
}
