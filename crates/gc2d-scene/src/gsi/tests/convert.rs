//! The converter on the thesis's example (App. B.1.8) and on files using the commands the example leaves out.

use std::f64::consts::FRAC_PI_2;

use super::{PISTON, file, read};
use crate::gsi::{GsiConversion, GsiErrorKind, GsiWarningKind, IMPORTED_MATERIAL, ImportOptions, parse_gsi, to_scene};
use crate::{Scene, schema::*};

fn convert(text: &str) -> GsiConversion {
    to_scene(&read(text), "test").unwrap_or_else(|errors| panic!("{errors}"))
}

/// The lines of the converter's NotConverted warnings for `keyword`.
fn not_converted_lines(conversion: &GsiConversion, keyword: &str) -> Vec<usize> {
    let matches =
        |kind: &GsiWarningKind| matches!(kind, GsiWarningKind::NotConverted { keyword: k, .. } if *k == keyword);
    conversion.warnings.iter().filter(|w| matches(&w.kind)).map(|w| w.line).collect()
}

fn round_trip(scene: &Scene) -> Scene {
    let text = scene.to_ron_string().expect("serialises");
    Scene::from_str(&text, "test.ron").unwrap_or_else(|e| panic!("{}", e.render_plain()))
}

#[test]
fn the_piston_walls_keep_their_corners_and_the_stamp_pushes_along_plus_x_with_10_kn() {
    let scene = convert(PISTON).scene;
    let corners: Vec<Vec<[f64; 2]>> = scene
        .walls
        .iter()
        .map(|wall| match wall {
            WallItem::Wall { shape: Shape::Polygon { corners_m }, position_m: None, angle_rad, .. } => {
                assert_eq!(*angle_rad, 0.0);
                corners_m.clone()
            }
            other => panic!("a polygon wall placed by its corners, got {other:?}"),
        })
        .collect();
    let expected = [
        [[-0.35, 0.01], [-0.25, 0.01], [-0.25, 0.1], [-0.35, 0.1]],
        [[-0.3, -0.01], [0.1, -0.01], [0.1, 0.01], [-0.3, 0.01]],
        [[-0.3, 0.1], [0.1, 0.1], [0.1, 0.12], [-0.3, 0.12]],
        [[0.1, -0.01], [0.12, -0.01], [0.12, 0.12], [0.1, 0.12]],
    ];
    assert_eq!(corners.len(), 4);
    for (wall, expected) in corners.iter().zip(expected) {
        for (corner, e) in wall.iter().zip(expected) {
            assert!((corner[0] - e[0]).abs() < 1e-12 && (corner[1] - e[1]).abs() < 1e-12, "{wall:?} != {expected:?}");
        }
    }
    let motions: Vec<Motion> = scene
        .walls
        .iter()
        .map(|wall| match wall {
            WallItem::Wall { motion, surface_velocity_m_s, .. } => {
                assert_eq!(*surface_velocity_m_s, [0.0, 0.0]);
                *motion
            }
            other => panic!("{other:?}"),
        })
        .collect();
    let Motion::Piston { direction_rad, force_n, max_speed_m_s } = motions[0] else { panic!("{:?}", motions[0]) };
    assert_eq!((direction_rad.cos(), direction_rad.sin()), (1.0, 0.0));
    assert_eq!((force_n, max_speed_m_s), (1e4, 1.0));
    assert!(motions[1..].iter().all(|motion| *motion == Motion::Static));
}

#[test]
fn the_piston_general_display_and_block_map_to_run_material_view_and_block() {
    let conversion = convert(PISTON);
    let scene = &conversion.scene;
    assert_eq!(scene.name, "test");
    assert_eq!(scene.gravity, Gravity::Constant(0.0));
    assert_eq!(scene.heating, None);
    assert_eq!(scene.run.end_time_s, 0.2);
    // STEPS_DATA 1000 of Δt = 1.5e-5 s keeps its simulated-time cadence; STEPS_CHECKPOINT (gc2d's overwritten
    // restart file) has no counterpart, and without STEPS_SETUP there are no numbered checkpoints.
    assert!((scene.run.frames_per_second - 1.0 / 0.015).abs() < 1e-9);
    assert_eq!(scene.run.checkpoint_interval_s, None);
    assert_eq!(not_converted_lines(&conversion, "STEPS_CHECKPOINT"), [9]);
    assert_eq!(scene.run.seed, 0);
    let material = &scene.materials[..];
    assert_eq!(material.len(), 1);
    assert_eq!(material[0].name, IMPORTED_MATERIAL);
    assert_eq!((material[0].youngs_modulus_n_m, material[0].gamma, material[0].mu), (1e7, 0.5, 0.6));
    assert_eq!((material[0].density_kg_m2, material[0].cohesion_n_m), (5000.0, 0.0));
    assert_eq!(scene.view, Some(Area { x_range_m: [-0.35, 0.15], y_range_m: [-0.05, 0.15] }));
    assert_eq!(scene.blocks.len(), 1);
    let block = &scene.blocks[0];
    assert_eq!((block.x_range_m, block.y_range_m, block.grid_spacing_m), ([-0.247, 0.098], [0.012, 0.098], [0.005; 2]));
    assert_eq!(block.grid, GridType::Fcc);
    assert_eq!((block.speed_range_m_s, block.direction_range_rad), ([0.0, 0.0], [0.0, std::f64::consts::TAU]));
    // Auto reads PART_SIZE 0.003 as full axes: semi-axes 1.5 mm; 7–9 RAND1 corners, uniform orientation.
    let recipe = block.shape;
    assert_eq!(recipe.semi_axes_m, [0.0015, 0.0015]);
    assert_eq!(
        (recipe.size_spread, recipe.corners, recipe.corner_spread),
        (SizeSpread::Const, 8, CountSpread::Equal(1))
    );
    assert_eq!((recipe.corner_positions, recipe.orientation), (CornerPositions::Rand1, Orientation::Equal));
    let summary = round_trip(scene).summary().unwrap_or_else(|e| panic!("{}", e.render_plain()));
    assert_eq!((summary.wall_bodies, summary.moving_walls, summary.particles), (4, 1, 1251));
    let semi_axes = parse_gsi(PISTON, &ImportOptions { part_size: crate::gsi::PartSizeConvention::SemiAxes });
    let semi_axes = to_scene(&semi_axes.unwrap(), "piston").unwrap();
    assert_eq!(semi_axes.scene.blocks[0].shape.semi_axes_m, [0.003, 0.003]);
}

#[test]
fn the_piston_delta_t_above_the_stable_bound_leaves_the_time_step_automatic_with_a_warning() {
    let conversion = convert(PISTON);
    assert_eq!(conversion.scene.run.time_step_s, None);
    assert_eq!(not_converted_lines(&conversion, "DELTA_T"), [4]);
    let summary = conversion.scene.summary().unwrap();
    let bound = summary.refusal_time_step_s.unwrap();
    assert!(bound < 1.5e-5 && bound > 1.2e-5, "{bound}");
    assert!(summary.time_step_is_automatic && summary.time_step_s <= crate::AUTOMATIC_TIME_STEP_FRACTION * bound);
    // The warning names the stable bound `check` prints as well, lest the two numbers read as a contradiction.
    let stable = format!("the stable bound, with the limits of flat and damped contacts, is {:.3e} s", {
        summary.stable_time_step_s.unwrap()
    });
    assert!(conversion.warnings.iter().any(|w| w.to_string().contains(&stable)), "{:?}", conversion.warnings);
    // A Δt below the bound is kept as written.
    let kept = convert(&PISTON.replace("0.000015", "0.00001"));
    assert_eq!(kept.scene.run.time_step_s, Some(1e-5));
    assert!(not_converted_lines(&kept, "DELTA_T").is_empty());
}

#[test]
fn the_piston_warnings_name_basename_display_and_part_size_in_line_order() {
    let conversion = convert(PISTON);
    assert_eq!(not_converted_lines(&conversion, "BASENAME"), [10]);
    assert_eq!(not_converted_lines(&conversion, "SCREEN"), [16]);
    assert_eq!(not_converted_lines(&conversion, "INTERVAL"), [17]);
    assert!(not_converted_lines(&conversion, "MODUS").is_empty(), "MODUS is not written");
    assert!(
        conversion
            .warnings
            .iter()
            .any(|w| w.line == 58 && matches!(w.kind, GsiWarningKind::PartSizeReadAsFullAxes { .. }))
    );
    let lines: Vec<usize> = conversion.warnings.iter().map(|w| w.line).collect();
    assert!(lines.is_sorted(), "{lines:?}");
}

#[test]
fn material_values_round_trip_through_ron() {
    let text = file("Delta_T 1e-6\nMue_Statisch 0.4\nE_Modul 5e6\nGamma 0.2\nCohesion 2.5\nG 9.81");
    let scene = convert(&text).scene;
    let material = &scene.materials[0];
    assert_eq!((material.youngs_modulus_n_m, material.gamma, material.mu, material.cohesion_n_m), (5e6, 0.2, 0.4, 2.5));
    let loaded = round_trip(&scene);
    assert_eq!(Scene { source: None, ..loaded }, scene);
}

#[test]
fn particles_keep_their_pose_and_the_drag_fixing_point_turns_into_the_body_frame() {
    // gc2d's ANGLE π/2 is clockwise: the particle is turned by −π/2 CCW. OMEGA 3 (clockwise) is −3 CCW.
    let text = file(
        "PARTICLE\nCom 0.5 0.3\nAngle 1.5707963267948966\nVelocity 1 2\nOmega 3\nDrag_Fixing_Point 0.01 0\n\
         Drag_Pulling_Point 0.6 0.3\nDrag_K 50\nDrag_Angle 0.7\nDrag_Velocity 0.2\nDrag_Time 0.1 0.9\n\
         Corners\n-0.01 -0.01\n0.01 -0.01\n0.01 0.01\n-0.01 0.01\nEND",
    );
    let scene = convert(&text).scene;
    let particle = &scene.particles[0];
    assert_eq!(particle.position_m, Some([0.5, 0.3]));
    assert_eq!((particle.angle_rad, particle.angular_velocity_rad_s), (-FRAC_PI_2, -3.0));
    assert_eq!(particle.velocity_m_s, [1.0, 2.0]);
    let spring = particle.drag_spring.unwrap();
    // World (0.01, 0) at angle −π/2 is body-frame (0, 0.01): turning it back by the angle gives the world point.
    assert!((spring.fixing_point_m[0]).abs() < 1e-15 && (spring.fixing_point_m[1] - 0.01).abs() < 1e-15);
    assert_eq!((spring.stiffness_n_m, spring.direction_rad, spring.speed_m_s), (50.0, 0.7, 0.2));
    assert_eq!((spring.pulling_start_m, spring.window_s), ([0.6, 0.3], [0.1, 0.9]));
    let Shape::Polygon { corners_m } = &particle.shape else { panic!("{:?}", particle.shape) };
    assert_eq!(corners_m[0], [-0.01, -0.01]);
    let world = round_trip(&scene).build().unwrap();
    let bodies = world.bodies();
    let built = bodies.particles().next().unwrap().index();
    assert!((bodies.pose[built].position - gc2d_geometry::DVec2::new(0.5, 0.3)).length() < 1e-12);
    assert_eq!((bodies.pose[built].angle, bodies.angular_velocity[built]), (-FRAC_PI_2, -3.0));
}

#[test]
fn vibration_sources_varying_gravity_and_heating_are_converted() {
    let text = file(
        "Delta_T 1e-6\nG 9.81 0\nG_Type SMOOTH_STEP\nG_Time 0.1 0.5\nG_Parameter 4 0.25\nHeat_Time 0 2\nHeat_Amplitude 0.02\n\
         WALL\nVelocity 0.3 0\nVib_Width 0.002\nVib_Frequence 20\nVib_Type TAPPING\nVib_Time 0 1\n\
         Corners\n0 0\n1 0\n1 0.1\n0 0.1\nEND\n\
         DROPSOURCE\nPos 0.5 0.5\nWidth 0.1\nType REL\nTime 0 0.5\nDelta_T 0.05\nPart_Size 0.002 0.002\n\
         Part_Var_Size 0.2\nRandom_Size GAUSS\nRandom_Rot GAUSS\nPart_Rot 0.3",
    );
    let scene = convert(&text).scene;
    assert_eq!(
        scene.gravity,
        Gravity::Varying {
            profile: GravityProfile::SmoothStep,
            from_m_s2: 9.81,
            to_m_s2: 0.0,
            window_s: [0.1, 0.5],
            steps: 4,
            ramp_fraction: 0.25
        }
    );
    assert_eq!(scene.heating, Some(Heating { window_s: [0.0, 2.0], amplitude: 0.02, frequency_hz: 1.0, slope: 4.0 }));
    let WallItem::Wall { surface_velocity_m_s, motion, .. } = &scene.walls[0] else { panic!() };
    assert_eq!(*surface_velocity_m_s, [0.3, 0.0]);
    assert_eq!(
        *motion,
        Motion::Vibration {
            amplitude_m: 0.002,
            frequency_hz: 20.0,
            direction_rad: FRAC_PI_2,
            waveform: Waveform::Tapping,
            window_s: [0.0, 1.0]
        }
    );
    let source = &scene.sources[0];
    assert_eq!((source.position_m, source.width_m, source.height), ([0.5, 0.5], 0.1, DropHeight::AboveHighest));
    assert_eq!((source.window_s, source.interval_s), ([0.0, 0.5], 0.05));
    // Without a GENERATE_BLOCK nothing forces full axes: PART_SIZE is the semi-axis. PART_ROT is clockwise.
    assert_eq!(source.shape.semi_axes_m, [0.002, 0.002]);
    assert_eq!(
        (source.shape.size_spread, source.shape.orientation),
        (SizeSpread::Gauss(0.2), Orientation::Gauss(-0.3))
    );
    assert_eq!(source.shape.corners, 8);
    round_trip(&scene).build().unwrap_or_else(|e| panic!("{}", e.render_plain()));
}

#[test]
fn what_the_scene_cannot_say_is_warned_at_its_line() {
    let text = file(
        "Time 0.1 1\nSteps_Setup 10\nSteps_Dumpline 5\nNext_Data_Filenumber 3\nSeed 2.5 3\n\
         PARTICLE\nAcceleration 1 0\nOmega_Dot 2\nPc_Rot3 1\nId 7\nCorners\n0 0\n0.01 0\n0 0.01\nEND",
    );
    let conversion = convert(&text);
    for (keyword, line) in [
        ("TIME", 3),
        ("STEPS_DUMPLINE", 5),
        ("NEXT_DATA_FILENUMBER", 6),
        ("SEED", 7),
        ("ACCELERATION", 9),
        ("OMEGA_DOT", 10),
        ("PC_ROT3", 11),
        ("ID", 12),
    ] {
        assert_eq!(not_converted_lines(&conversion, keyword), [line], "{keyword}");
    }
    // The run keeps absolute times: it ends at TIME's end. STEPS_SETUP 10 of the default Δt 1e-4 s: numbered
    // checkpoints every 1 ms.
    assert_eq!(conversion.scene.run.end_time_s, 1.0);
    assert!(not_converted_lines(&conversion, "STEPS_SETUP").is_empty());
    assert!((conversion.scene.run.checkpoint_interval_s.unwrap() - 1e-3).abs() < 1e-18);
}

#[test]
fn seed_packs_the_first_value_low_and_the_second_high() {
    assert_eq!(convert(&file("Seed 5")).scene.run.seed, 5);
    let both = convert(&file("Seed 1 2"));
    assert_eq!(both.scene.run.seed, 1 + (2 << 32));
    assert!(not_converted_lines(&both, "SEED").is_empty());
    let clamped = convert(&file("Seed -4 1e12"));
    assert_eq!(clamped.scene.run.seed, u64::from(u32::MAX) << 32);
    assert_eq!(not_converted_lines(&clamped, "SEED"), [3]);
}

#[test]
fn a_gravity_step_count_that_is_not_whole_is_an_error_at_its_line() {
    let errors = to_scene(&read(&file("G 9.81 0\nG_Type STEP\nG_Parameter 2.5 0.5")), "x").unwrap_err();
    assert_eq!(errors.0.len(), 1);
    assert_eq!(errors.0[0].line, 5);
    assert!(matches!(errors.0[0].kind, GsiErrorKind::NotConvertible { keyword: "G_PARAMETER", .. }));
}

#[test]
fn a_second_g_value_under_constant_gravity_is_warned_and_g1_kept() {
    let conversion = convert(&file("G 9.81 3"));
    assert_eq!(conversion.scene.gravity, Gravity::Constant(9.81));
    assert_eq!(not_converted_lines(&conversion, "G (second value)"), [3]);
}
