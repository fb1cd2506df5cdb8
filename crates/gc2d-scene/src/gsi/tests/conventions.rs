//! Conversions to gc2d-rs conventions: clockwise gc2d angles negated, direction angles passed through, particles
//! recentred on their centroid, walls kept in place, clockwise corner lists re-oriented.

use std::f64::consts::FRAC_PI_2;

use gc2d_geometry::DVec2;

use super::{file, read, warned};
use crate::gsi::{GsiWallMotion, GsiWarningKind};

fn close(a: DVec2, b: DVec2) -> bool {
    (a - b).length() < 1e-12
}

/// The thesis's PARTICLE example (§9.5): a clockwise triangle, COM (0.5, 0.3), ANGLE π/4 clockwise.
#[test]
fn the_thesis_particle_example_is_recentred_and_turned_the_same_way_as_in_gc2d() {
    let text = file(
        "PARTICLE\nCom 0.5 0.3 # Position des Schwerpunktes\nCorners\n0.0 0.0\n0.0 0.2\n0.1 0.45\nEND\nAngle 0.7853975",
    );
    let import = read(&text);
    assert!(warned(&import, 5, |k| *k == GsiWarningKind::ClockwiseCorners));
    let particle = &import.scene.particles[0];
    assert_eq!(particle.position.value, DVec2::new(0.5, 0.3));
    assert_eq!(particle.position.line(), 4);
    assert_eq!(particle.angle.value, -0.7853975);
    let centroid = DVec2::new(0.1, 0.65) / 3.0;
    let expected = [DVec2::new(0.1, 0.45), DVec2::new(0.0, 0.2), DVec2::ZERO].map(|v| v - centroid);
    assert!(particle.corners.value.iter().zip(expected).all(|(&a, b)| close(a, b)), "{:?}", particle.corners.value);
    // gc2d's world transform (2.35) with its clockwise φ equals a counter-clockwise turn by the converted angle.
    let phi = 0.7853975_f64;
    for &v in &particle.corners.value {
        let gc2d = DVec2::new(v.x * phi.cos() + v.y * phi.sin(), -v.x * phi.sin() + v.y * phi.cos());
        assert!(close(DVec2::from_angle(particle.angle.value).rotate(v), gc2d));
    }
}

#[test]
fn rotational_state_is_negated_and_translational_state_kept() {
    let text = file(
        "PARTICLE\nCorners\n0 0\n1 0\n0 1\nEND\nVelocity 1 2\nAcceleration 3 4\nOmega 2\nOmega_Dot 3\nPc_Rot3 4\n\
         Pc_Rot4 5\nPc_Rot5 6\nPc_Trans3 7 8\nId 12",
    );
    let particle = &read(&text).scene.particles[0];
    assert_eq!(particle.velocity.value, DVec2::new(1.0, 2.0));
    assert_eq!(particle.acceleration.value, DVec2::new(3.0, 4.0));
    assert_eq!(particle.angular_velocity.value, -2.0);
    assert_eq!(particle.angular_acceleration.value, -3.0);
    assert_eq!(particle.higher_rotation.map(|r| r.value), [-4.0, -5.0, -6.0]);
    assert_eq!(particle.higher_translation[0].value, DVec2::new(7.0, 8.0));
    assert_eq!(particle.id.map(|id| (id.value, id.line())), Some((12, 17)));
}

#[test]
fn position_absolut_keeps_the_corners_where_they_are() {
    let text = file("PARTICLE\nCom 9 9\nPosition_Absolut\nCorners\n1 1\n3 1\n3 3\n1 3\nEND");
    let import = read(&text);
    assert!(warned(&import, 4, |k| *k == GsiWarningKind::ComIgnored));
    let particle = &import.scene.particles[0];
    assert!(particle.position_absolute);
    assert_eq!(particle.position.value, DVec2::new(2.0, 2.0));
    assert_eq!(particle.position.line(), 6, "the position comes from the CORNERS block");
    assert_eq!(particle.corners.value[0], DVec2::new(-1.0, -1.0));
}

/// A 4 × 2 rectangle turned by gc2d's ANGLE π/2 (clockwise) about its centroid (2, 1), then offset by (10, 0):
/// its lower right corner (4, 0) swings down to (1, −1).
#[test]
fn walls_turn_clockwise_about_their_centroid_and_are_not_recentred() {
    let text = file("WALL\nOffset 10 0\nAngle 1.5707963267948966\nCorners\n0 0\n4 0\n4 2\n0 2\nEND");
    let wall = &read(&text).scene.walls[0];
    assert_eq!(wall.angle.value, -FRAC_PI_2);
    let expected = [[1.0, 3.0], [1.0, -1.0], [3.0, -1.0], [3.0, 3.0]].map(|[x, y]| DVec2::new(x + 10.0, y));
    assert!(wall.corners.value.iter().zip(expected).all(|(&a, b)| close(a, b)), "{:?}", wall.corners.value);
}

#[test]
fn clockwise_wall_corners_are_reversed() {
    let import = read(&file("WALL\nCorners\n0 0\n0 1\n1 0\nEND"));
    assert!(warned(&import, 4, |k| *k == GsiWarningKind::ClockwiseCorners));
    assert_eq!(import.scene.walls[0].corners.value, [DVec2::X, DVec2::Y, DVec2::ZERO]);
}

/// PISTON_ANGLE, VIB_ANGLE, DRAG_ANGLE and ANGLE_RANGE are directions, counter-clockwise from +x as written.
#[test]
fn direction_angles_pass_through() {
    let text = file(
        "WALL\nPiston_Angle 0.3\nCorners\n0 0\n1 0\n0 1\nEND\nWALL\nVib_Angle 1\nCorners\n0 0\n1 0\n0 1\nEND\n\
         PARTICLE\nDrag_Angle 0.785397\nCorners\n0 0\n1 0\n0 1\nEND\nGENERATE_BLOCK\nAngle_Range 0.5 1.5\nPart_Rot 0.25",
    );
    let scene = read(&text).scene;
    let GsiWallMotion::Piston(piston) = &scene.walls[0].motion else { panic!("piston") };
    assert_eq!(piston.direction_angle.value, 0.3);
    let GsiWallMotion::Vibration(vibration) = &scene.walls[1].motion else { panic!("vibration") };
    assert_eq!(vibration.direction_angle.value, 1.0);
    assert_eq!(scene.particles[0].drag.as_ref().map(|d| d.direction_angle.value), Some(0.785397));
    let block = &scene.blocks[0];
    assert_eq!((block.velocity_direction_range.value.min, block.velocity_direction_range.value.max), (0.5, 1.5));
    assert_eq!(block.shape.rotation.value, -0.25, "PART_ROT is an orientation, clockwise in gc2d");
}
