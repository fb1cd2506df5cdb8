//! The thesis's example file (App. B.1.8) read into the expected scene, and the PART_SIZE decision on it.

use gc2d_engine::schedules::GravityProfile;
use gc2d_geometry::{AngleMode, DVec2, Randomization};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::{PISTON, read};
use crate::gsi::{GsiWallMotion, GsiWarningKind, ImportOptions, PartSizeConvention, PartSizeReading, parse_gsi};
use crate::schema::GridType;

fn assert_corners(actual: &[DVec2], expected: [[f64; 2]; 4]) {
    assert_eq!(actual.len(), 4);
    for (a, e) in actual.iter().zip(expected) {
        assert!((*a - DVec2::from_array(e)).length() < 1e-12, "{actual:?} != {expected:?}");
    }
}

#[test]
fn general_and_display_are_as_written() {
    let import = read(PISTON);
    let scene = &import.scene;
    assert_eq!(scene.identification, "");
    assert!(import.notes.is_empty());
    let general = &scene.general;
    assert_eq!(general.time_step.value, 1.5e-5);
    assert_eq!(general.time_step.line(), 4);
    assert_eq!((general.time.value.start, general.time.value.end), (0.0, 0.2));
    assert_eq!(general.youngs_modulus.value, 1e7);
    assert_eq!(general.damping.value, 0.5);
    assert_eq!(general.steps_data.value, 1000);
    assert_eq!(general.steps_checkpoint.value, 100);
    assert_eq!(general.basename.value, "data/piston2");
    assert_eq!((general.gravity.start.value, general.gravity.end.value), (0.0, 0.0));
    assert_eq!(general.gravity.profile.value, GravityProfile::Constant);
    assert_eq!(general.gravity.start.line(), 11);
    assert!(general.heating.is_none());
    // Defaults carry the GENERAL "object line" 1.
    assert_eq!(general.friction.value, 0.6);
    assert!(!general.friction.origin.is_written());
    assert_eq!(general.friction.line(), 1);
    let display = scene.display.as_ref().expect("DISPLAY");
    assert_eq!(display.line, 13);
    assert_eq!((display.x_range.value.min, display.x_range.value.max), (-0.35, 0.15));
    assert_eq!((display.y_range.value.min, display.y_range.value.max), (-0.05, 0.15));
    assert_eq!(display.screen.value, [800, 0]);
    assert_eq!(display.interval.value, 100);
    assert_eq!(display.modus.value, 3);
}

#[test]
fn four_walls_with_offsets_applied_and_a_piston_along_plus_x() {
    let scene = read(PISTON).scene;
    assert_eq!(scene.walls.len(), 4);
    let lines: Vec<usize> = scene.walls.iter().map(|w| w.line).collect();
    assert_eq!(lines, [19, 31, 40, 49]);
    let stamp = &scene.walls[0];
    assert_eq!(stamp.offset.value, DVec2::new(-0.3, 0.0));
    assert_eq!(stamp.offset.line(), 20);
    assert_eq!(stamp.corners.line(), 24);
    assert_corners(&stamp.corners.value, [[-0.35, 0.01], [-0.25, 0.01], [-0.25, 0.1], [-0.35, 0.1]]);
    let GsiWallMotion::Piston(piston) = &stamp.motion else { panic!("the stamp is a piston: {:?}", stamp.motion) };
    let direction = DVec2::from_angle(piston.direction_angle.value);
    assert!((direction - DVec2::X).length() < 1e-15);
    assert_eq!(piston.force.value, 1e4);
    assert_eq!(piston.force.line(), 22);
    assert_eq!(piston.v_max.value, 1.0);
    assert_corners(&scene.walls[1].corners.value, [[-0.3, -0.01], [0.1, -0.01], [0.1, 0.01], [-0.3, 0.01]]);
    assert_corners(&scene.walls[2].corners.value, [[-0.3, 0.1], [0.1, 0.1], [0.1, 0.12], [-0.3, 0.12]]);
    assert_eq!(scene.walls[2].offset.value, DVec2::new(0.0, 0.11));
    assert_corners(&scene.walls[3].corners.value, [[0.1, -0.01], [0.12, -0.01], [0.12, 0.12], [0.1, 0.12]]);
    for wall in &scene.walls[1..] {
        assert_eq!(wall.motion, GsiWallMotion::Static);
        assert_eq!(wall.angle.value, 0.0);
        assert_eq!(wall.surface_velocity.value, DVec2::ZERO);
    }
}

#[test]
fn the_block_has_its_ranges_grid_and_shape_options() {
    let scene = read(PISTON).scene;
    assert!(scene.particles.is_empty() && scene.drop_sources.is_empty());
    let [block] = scene.blocks.as_slice() else { panic!("one block") };
    assert_eq!(block.line, 58);
    assert_eq!((block.x_range.value.min, block.x_range.value.max), (-0.247, 0.098));
    assert_eq!((block.y_range.value.min, block.y_range.value.max), (0.012, 0.098));
    assert_eq!(block.grid_distance.value, DVec2::splat(0.005));
    assert_eq!(block.grid_type.value, GridType::Fcc);
    assert_eq!(block.grid_type.line(), 66);
    let shape = &block.shape;
    assert_eq!(shape.part_size.value, DVec2::splat(0.003));
    assert_eq!(shape.part_size.line(), 65);
    assert_eq!(shape.corners.value, 8);
    assert_eq!(shape.corner_variation.value, 1);
    assert_eq!(shape.corner_randomization.value, Randomization::Equal);
    assert_eq!(shape.corner_randomization.line(), 69);
    assert_eq!(shape.angle_mode.value, AngleMode::Rand1);
    assert_eq!(shape.size_randomization.value, Randomization::Const);
    assert_eq!(shape.rotation.value, -1.0, "PART_ROT 1 clockwise is −1 counter-clockwise");
    assert_eq!(shape.rotation_randomization.value, Randomization::Equal);
    assert_eq!(shape.size_variation.value, 0.5, "default PART_VAR_SIZE");
    assert!(!shape.size_variation.origin.is_written());
    assert_eq!((block.speed_range.value.min, block.speed_range.value.max), (0.0, 0.0));
    // 18 rows (y = 0.012 … 0.097), alternately 70 and 69 sites: the "≈ 1200 particles" of §9.9.
    assert_eq!(block.row_count(), 18);
    assert_eq!((block.column_count(0), block.column_count(1)), (70, 69));
    assert_eq!(block.site_count(), 1251);
    assert_eq!(block.grid_sites().len(), 1251);
    assert_eq!(block.nearest_site_distance(), Some(0.005));
}

#[test]
fn auto_reads_part_size_as_full_axes_and_says_why() {
    let import = read(PISTON);
    assert_eq!(import.scene.part_size_reading, PartSizeReading::FullAxes);
    let shape = &import.scene.blocks[0].shape;
    assert_eq!(shape.semi_axes(), DVec2::splat(0.0015));
    let warning = import
        .warnings
        .iter()
        .find(|w| matches!(w.kind, GsiWarningKind::PartSizeReadAsFullAxes { .. }))
        .expect("the importer reports its PART_SIZE decision");
    assert_eq!(warning.line, 58);
    let GsiWarningKind::PartSizeReadAsFullAxes { semi_axes_diameter, spacing } = warning.kind else { unreachable!() };
    assert!((semi_axes_diameter - 0.006).abs() < 1e-15 && (spacing - 0.005).abs() < 1e-15);
    let message = warning.to_string();
    assert!(message.starts_with("line 58: "), "{message}");
    assert!(message.contains("6.000 mm") && message.contains("5.000 mm") && message.contains("17 %"), "{message}");
    assert!(!import.warnings.iter().any(|w| matches!(w.kind, GsiWarningKind::GridNeighboursOverlap { .. })));
}

#[test]
fn semi_axes_reading_reports_the_overlap() {
    let options = ImportOptions { part_size: PartSizeConvention::SemiAxes };
    let import = parse_gsi(PISTON, &options).expect("reads");
    assert_eq!(import.scene.blocks[0].shape.semi_axes(), DVec2::splat(0.003));
    let overlap = import
        .warnings
        .iter()
        .find(|w| matches!(w.kind, GsiWarningKind::GridNeighboursOverlap { .. }))
        .expect("overlap reported");
    assert_eq!(overlap.line, 58);
    assert!(overlap.to_string().contains("17 %"), "{overlap}");
    let options = ImportOptions { part_size: PartSizeConvention::FullAxes };
    let import = parse_gsi(PISTON, &options).expect("reads");
    assert_eq!(import.scene.part_size_reading, PartSizeReading::FullAxes);
    assert!(import.warnings.iter().all(|w| !matches!(
        w.kind,
        GsiWarningKind::GridNeighboursOverlap { .. } | GsiWarningKind::PartSizeReadAsFullAxes { .. }
    )));
}

/// With full axes every generated particle (inside its 1.5 mm circle) clears the walls and its neighbours, so the
/// run starts without contacts; with semi-axes the bottom row would reach 1 mm into the floor.
#[test]
fn full_axes_particles_clear_every_wall_and_each_other() {
    let scene = read(PISTON).scene;
    let block = &scene.blocks[0];
    let radius = block.shape.largest_semi_axis();
    assert_eq!(radius, 0.0015);
    let sites = block.grid_sites();
    for wall in &scene.walls {
        let corners = &wall.corners.value;
        let low = corners.iter().copied().reduce(DVec2::min).expect("corners");
        let high = corners.iter().copied().reduce(DVec2::max).expect("corners");
        for &site in &sites {
            let nearest = site.clamp(low, high);
            assert!((site - nearest).length() >= radius, "site {site} reaches wall {}", wall.line);
        }
    }
    let lowest = sites.iter().map(|s| s.y).fold(f64::INFINITY, f64::min);
    assert!(lowest - 2.0 * radius < 0.01, "as semi-axes the bottom row would overlap the floor top at y = 0.01");
}

#[test]
fn the_recipe_draws_admissible_particles_of_the_stated_size() {
    let scene = read(PISTON).scene;
    let recipe = scene.blocks[0].shape.recipe();
    recipe.validate().expect("piston's recipe is admissible");
    assert_eq!(recipe.semi_axes, DVec2::splat(0.0015));
    assert_eq!(recipe.rotation, -1.0);
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for _ in 0..200 {
        let (polygon, _) = recipe.draw(&mut rng).expect("draws");
        assert!((7..=9).contains(&polygon.len()));
        assert!(polygon.bounding_radius() <= 0.0015 * 1.5);
    }
}
