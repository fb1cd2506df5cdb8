//! PARTICLE and WALL (reference §9.5, §9.6, §2.11, §2.12): corner lists, placement, initial motion, piston,
//! vibration and drag spring. gc2d's clockwise ANGLE, OMEGA, OMEGA_DOT and PC_ROT* are negated here; direction
//! angles (PISTON_ANGLE, VIB_ANGLE, DRAG_ANGLE) are counter-clockwise from +x already and pass through.

use std::f64::consts::FRAC_PI_2;

use gc2d_engine::motion::Waveform;
use gc2d_geometry::{DVec2, cross};

use super::diagnostics::{GsiErrorKind, GsiWarningKind};
use super::reader::ObjectReader;
use super::scene::{GsiDrag, GsiParticle, GsiPiston, GsiVibration, GsiWall, GsiWallMotion, Sourced};

const DRAG_COMMANDS: [&str; 6] =
    ["DRAG_ANGLE", "DRAG_VELOCITY", "DRAG_K", "DRAG_TIME", "DRAG_FIXING_POINT", "DRAG_PULLING_POINT"];
const PISTON_COMMANDS: [&str; 3] = ["PISTON_ANGLE", "PISTON_FORCE", "PISTON_V_MAX"];
const VIBRATION_COMMANDS: [&str; 5] = ["VIB_ANGLE", "VIB_TIME", "VIB_WIDTH", "VIB_FREQUENCE", "VIB_TYPE"];

/// Converts a PARTICLE: the corners are re-oriented counter-clockwise and shifted so their centroid is the body
/// origin; the particle sits at COM, or, with POSITION_ABSOLUT, where the corners put it. `None` after an error.
pub(super) fn read_particle(reader: &mut ObjectReader<'_, '_>) -> Option<GsiParticle> {
    let corners = checked_corners(reader, "PARTICLE")?;
    let centroid = centroid(&corners.value);
    let position_absolute = reader.flag("POSITION_ABSOLUT").is_some();
    let com = reader.vector("COM", [0.0, 0.0]);
    let position = if position_absolute {
        if com.origin.is_written() {
            reader.diagnostics.warn(com.line(), GsiWarningKind::ComIgnored);
        }
        Sourced::written(centroid, corners.line())
    } else {
        com
    };
    let drag = reader.first_line_of(&DRAG_COMMANDS).map(|_| read_drag(reader));
    let corners = finite_or_error(reader, corners.map(|c| c.iter().map(|&v| v - centroid).collect()))?;
    Some(GsiParticle {
        line: reader.line(),
        corners,
        position,
        position_absolute,
        angle: reader.clockwise_angle("ANGLE", 0.0),
        velocity: reader.vector("VELOCITY", [0.0, 0.0]),
        acceleration: reader.vector("ACCELERATION", [0.0, 0.0]),
        angular_velocity: reader.clockwise_angle("OMEGA", 0.0),
        angular_acceleration: reader.clockwise_angle("OMEGA_DOT", 0.0),
        higher_translation: [
            reader.vector("PC_TRANS3", [0.0, 0.0]),
            reader.vector("PC_TRANS4", [0.0, 0.0]),
            reader.vector("PC_TRANS5", [0.0, 0.0]),
        ],
        higher_rotation: [
            reader.clockwise_angle("PC_ROT3", 0.0),
            reader.clockwise_angle("PC_ROT4", 0.0),
            reader.clockwise_angle("PC_ROT5", 0.0),
        ],
        id: reader.optional_whole("ID"),
        drag,
    })
}

fn read_drag(reader: &mut ObjectReader<'_, '_>) -> GsiDrag {
    GsiDrag {
        direction_angle: reader.float("DRAG_ANGLE", 0.0),
        speed: reader.pair("DRAG_VELOCITY", [0.1, 0.0]).map(|[speed, _]| speed),
        stiffness: reader.float("DRAG_K", 100.0),
        window: reader.window("DRAG_TIME", [0.0, 1.0]),
        fixing_point: reader.vector("DRAG_FIXING_POINT", [0.0, 0.0]),
        pulling_point: reader.vector("DRAG_PULLING_POINT", [0.0, 0.0]),
    }
}

/// Converts a WALL: the corners stay where they are written (no recentring), are turned by ANGLE about their
/// centroid and moved by OFFSET. `None` after an error.
pub(super) fn read_wall(reader: &mut ObjectReader<'_, '_>) -> Option<GsiWall> {
    let corners = checked_corners(reader, "WALL");
    let offset = reader.vector("OFFSET", [0.0, 0.0]);
    let angle = reader.clockwise_angle("ANGLE", 0.0);
    let surface_velocity = reader.vector("VELOCITY", [0.0, 0.0]);
    let id = reader.optional_whole("ID");
    let motion = read_wall_motion(reader)?;
    let corners = corners?;
    let centroid = centroid(&corners.value);
    let (sin, cos) = angle.value.sin_cos();
    let place = |v: DVec2| {
        let r = v - centroid;
        centroid + DVec2::new(cos * r.x - sin * r.y, sin * r.x + cos * r.y) + offset.value
    };
    let corners = finite_or_error(reader, corners.map(|c| c.into_iter().map(place).collect()))?;
    Some(GsiWall { line: reader.line(), corners, offset, angle, surface_velocity, id, motion })
}

fn read_wall_motion(reader: &mut ObjectReader<'_, '_>) -> Option<GsiWallMotion> {
    let piston_line = reader.first_line_of(&PISTON_COMMANDS);
    let vibration_line = reader.first_line_of(&VIBRATION_COMMANDS);
    let piston = piston_line.map(|_| {
        let force = reader.float("PISTON_FORCE", 0.0);
        reader.warn_if_defaulted(
            &force,
            GsiWarningKind::DefaultUsed {
                keyword: "PISTON_FORCE",
                object: "WALL",
                default: "0 (N)",
                consequence: "the piston exerts no force",
            },
        );
        GsiPiston {
            direction_angle: reader.float("PISTON_ANGLE", 0.0),
            force,
            v_max: reader.float("PISTON_V_MAX", 1.0),
        }
    });
    let vibration = vibration_line.map(|_| GsiVibration {
        direction_angle: reader.float("VIB_ANGLE", FRAC_PI_2),
        window: reader.window("VIB_TIME", [0.0, f64::INFINITY]),
        amplitude: reader.float("VIB_WIDTH", 1.0),
        frequency: reader.float("VIB_FREQUENCE", 1.0),
        waveform: reader.option("VIB_TYPE", Waveform::Cosine),
    });
    match (piston, vibration, piston_line, vibration_line) {
        (Some(_), Some(_), Some(piston_line), Some(vibration_line)) => {
            let kind = GsiErrorKind::PistonAndVibration { piston_line, vibration_line };
            reader.diagnostics.error(piston_line.max(vibration_line), kind);
            None
        }
        (Some(piston), _, _, _) => Some(GsiWallMotion::Piston(piston)),
        (_, Some(vibration), _, _) => Some(GsiWallMotion::Vibration(vibration)),
        _ => Some(GsiWallMotion::Static),
    }
}

/// The object's corners, counter-clockwise, at least three; errors (missing or too few) are recorded. A block whose
/// lines were refused already gives `None` without a second error.
fn checked_corners(reader: &mut ObjectReader<'_, '_>, object: &'static str) -> Option<Sourced<Vec<DVec2>>> {
    let Some((mut corners, complete)) = reader.corners() else {
        reader.diagnostics.error(reader.line(), GsiErrorKind::MissingCorners { object });
        return None;
    };
    if !complete {
        return None;
    }
    if corners.value.len() < 3 {
        reader.diagnostics.error(corners.line(), GsiErrorKind::TooFewCorners { count: corners.value.len() });
        return None;
    }
    if twice_signed_area(&corners.value) < 0.0 {
        corners.value.reverse();
        reader.diagnostics.warn(corners.line(), GsiWarningKind::ClockwiseCorners);
    }
    Some(corners)
}

/// The placed corners, or `None` with an error if a coordinate overflowed.
fn finite_or_error(reader: &mut ObjectReader<'_, '_>, corners: Sourced<Vec<DVec2>>) -> Option<Sourced<Vec<DVec2>>> {
    if corners.value.iter().all(|c| c.is_finite()) {
        Some(corners)
    } else {
        reader.diagnostics.error(corners.line(), GsiErrorKind::CornersOverflow);
        None
    }
}

/// Twice the signed area of the outline (positive when counter-clockwise), relative to the first corner.
fn twice_signed_area(corners: &[DVec2]) -> f64 {
    let origin = corners.first().copied().unwrap_or(DVec2::ZERO);
    let n = corners.len();
    (0..n).map(|i| cross(corners[i] - origin, corners[(i + 1) % n] - origin)).sum()
}

/// The area centroid of the outline (eq. 2.11), or the mean of the corners when the area is zero (a degenerate
/// outline, which polygon validation rejects later with a precise message).
pub(super) fn centroid(corners: &[DVec2]) -> DVec2 {
    let Some(&origin) = corners.first() else { return DVec2::ZERO };
    let n = corners.len();
    let (mut twice_area, mut moment) = (0.0, DVec2::ZERO);
    for i in 0..n {
        let (a, b) = (corners[i] - origin, corners[(i + 1) % n] - origin);
        let weight = cross(a, b);
        twice_area += weight;
        moment += weight * (a + b);
    }
    let centroid = origin + moment / (3.0 * twice_area);
    if twice_area != 0.0 && centroid.is_finite() { centroid } else { corners.iter().copied().sum::<DVec2>() / n as f64 }
}
