//! Which gsi line and keyword set a field of the converted scene, so that a value the scene refuses is reported at
//! the gsi file (`FILE.gsi:LINE: KEYWORD: …`) rather than at a line of the written RON. The field paths are those of
//! [`crate::SceneError::path`], e.g. `blocks[0].shape.semi_axes_m` or `walls[2].motion.force_n`.

use super::scene::{GsiScene, GsiShape, GsiWallMotion, Sourced};

/// The gsi command (or object) a scene field came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Blame {
    /// The line: the command's where it is written, else its object's (1 for GENERAL).
    pub line: usize,
    /// The command, or the object name where no single command set the field.
    pub keyword: &'static str,
    /// Whether the command is written in the file (false: gc2d's default was used).
    pub written: bool,
}

fn at<T>(value: &Sourced<T>, keyword: &'static str) -> Blame {
    Blame { line: value.line(), keyword, written: value.origin.is_written() }
}

fn object(line: usize, keyword: &'static str) -> Blame {
    Blame { line, keyword, written: true }
}

/// The first segment of a field path and the rest: `blocks[0].shape.corners` gives `("blocks", Some(0),
/// "shape.corners")`.
fn split(path: &str) -> (&str, Option<usize>, &str) {
    let (head, rest) = path.split_once('.').unwrap_or((path, ""));
    match head.split_once('[') {
        Some((name, index)) => (name, index.trim_end_matches(']').parse().ok(), rest),
        None => (head, None, rest),
    }
}

/// The gsi command that set the scene field `path` of the scene converted from `scene`. A field of an object that
/// no single command sets is blamed on the object's line. `None` for a field the file does not set (the scene's
/// name, which comes from the output file, and fields the converter leaves at the scene's defaults).
pub(super) fn blame(path: &str, scene: &GsiScene) -> Option<Blame> {
    let general = &scene.general;
    let (head, index, rest) = split(path);
    let (field, _, inner) = split(rest);
    Some(match (head, index) {
        ("description", _) => object(2, "the identification text (line 2)"),
        ("run", _) => match field {
            "time_step_s" => at(&general.time_step, "DELTA_T"),
            "end_time_s" => at(&general.time, "TIME"),
            "frames_per_second" => at(&general.steps_data, "STEPS_DATA"),
            "checkpoint_interval_s" => at(&general.steps_setup, "STEPS_SETUP"),
            "seed" => at(&general.seed, "SEED"),
            _ => return None,
        },
        ("gravity", _) => {
            let gravity = &general.gravity;
            match field {
                "to_m_s2" => at(&gravity.end, "G"),
                "window_s" => at(&gravity.window, "G_TIME"),
                "steps" | "ramp_fraction" => at(&gravity.parameters, "G_PARAMETER"),
                "profile" => at(&gravity.profile, "G_TYPE"),
                _ => at(&gravity.start, "G"),
            }
        }
        ("heating", _) => match (&general.heating, field) {
            (Some(heating), "window_s") => at(&heating.window, "HEAT_TIME"),
            (Some(heating), "amplitude") => at(&heating.amplitude, "HEAT_AMPLITUDE"),
            (Some(heating), "frequency_hz") => at(&heating.frequency, "HEAT_FREQUENCE"),
            (Some(heating), "slope") => at(&heating.slope, "HEAT_SLOPE"),
            _ => return None,
        },
        ("materials", _) => match field {
            "youngs_modulus_n_m" => at(&general.youngs_modulus, "E_MODUL"),
            "gamma" => at(&general.damping, "GAMMA"),
            "mu" => at(&general.friction, "MUE_STATISCH"),
            "cohesion_n_m" => at(&general.cohesion, "COHESION"),
            _ => return None,
        },
        ("walls", Some(i)) => {
            return scene.walls.get(i).map(|wall| match (field, &wall.motion) {
                ("shape", _) => at(&wall.corners, "CORNERS"),
                ("surface_velocity_m_s", _) => at(&wall.surface_velocity, "VELOCITY"),
                ("motion", GsiWallMotion::Piston(piston)) => match inner {
                    "force_n" => at(&piston.force, "PISTON_FORCE"),
                    "max_speed_m_s" => at(&piston.v_max, "PISTON_V_MAX"),
                    "direction_rad" => at(&piston.direction_angle, "PISTON_ANGLE"),
                    _ => object(wall.line, "WALL"),
                },
                ("motion", GsiWallMotion::Vibration(vibration)) => match inner {
                    "amplitude_m" => at(&vibration.amplitude, "VIB_WIDTH"),
                    "frequency_hz" => at(&vibration.frequency, "VIB_FREQUENCE"),
                    "direction_rad" => at(&vibration.direction_angle, "VIB_ANGLE"),
                    "window_s" => at(&vibration.window, "VIB_TIME"),
                    "waveform" => at(&vibration.waveform, "VIB_TYPE"),
                    _ => object(wall.line, "WALL"),
                },
                _ => object(wall.line, "WALL"),
            });
        }
        ("particles", Some(i)) => {
            return scene.particles.get(i).map(|particle| match field {
                "shape" => at(&particle.corners, "CORNERS"),
                "position_m" => at(&particle.position, if particle.position_absolute { "CORNERS" } else { "COM" }),
                "angle_rad" => at(&particle.angle, "ANGLE"),
                "velocity_m_s" => at(&particle.velocity, "VELOCITY"),
                "angular_velocity_rad_s" => at(&particle.angular_velocity, "OMEGA"),
                "drag_spring" => match (&particle.drag, inner) {
                    (Some(drag), "stiffness_n_m") => at(&drag.stiffness, "DRAG_K"),
                    (Some(drag), "fixing_point_m") => at(&drag.fixing_point, "DRAG_FIXING_POINT"),
                    (Some(drag), "pulling_start_m") => at(&drag.pulling_point, "DRAG_PULLING_POINT"),
                    (Some(drag), "direction_rad") => at(&drag.direction_angle, "DRAG_ANGLE"),
                    (Some(drag), "speed_m_s") => at(&drag.speed, "DRAG_VELOCITY"),
                    (Some(drag), "window_s") => at(&drag.window, "DRAG_TIME"),
                    _ => object(particle.line, "PARTICLE"),
                },
                _ => object(particle.line, "PARTICLE"),
            });
        }
        ("blocks", Some(i)) => {
            return scene.blocks.get(i).map(|block| {
                let whole = object(block.line, "GENERATE_BLOCK");
                match field {
                    "x_range_m" => at(&block.x_range, "X_RANGE"),
                    "y_range_m" => at(&block.y_range, "Y_RANGE"),
                    "grid_spacing_m" => at(&block.grid_distance, "GRID_DISTANCE"),
                    "grid" => at(&block.grid_type, "GRID_TYPE"),
                    "speed_range_m_s" => at(&block.speed_range, "VELOCITY_RANGE"),
                    "direction_range_rad" => at(&block.velocity_direction_range, "ANGLE_RANGE"),
                    "shape" => shape(&block.shape, inner).unwrap_or(whole),
                    _ => whole,
                }
            });
        }
        ("sources", index) => {
            return scene.drop_sources.get(index.unwrap_or(0)).map(|source| {
                let whole = object(source.line, "DROPSOURCE");
                match (index, field) {
                    (None, _) => whole,
                    (_, "position_m") => at(&source.position, "POS"),
                    (_, "width_m") => at(&source.width, "WIDTH"),
                    (_, "height") => at(&source.height, "TYPE"),
                    (_, "window_s") => at(&source.window, "TIME"),
                    (_, "interval_s") => at(&source.interval, "DELTA_T"),
                    (_, "shape") => shape(&source.shape, inner).unwrap_or(whole),
                    _ => whole,
                }
            });
        }
        ("view", _) => {
            return scene.display.as_ref().map(|display| match field {
                "x_range_m" => at(&display.x_range, "X_RANGE"),
                "y_range_m" => at(&display.y_range, "Y_RANGE"),
                _ => object(display.line, "DISPLAY"),
            });
        }
        _ => return None,
    })
}

/// The shape command that set the recipe field `path` (below `shape`), if one did.
fn shape(shape: &GsiShape, path: &str) -> Option<Blame> {
    let (field, _, _) = split(path);
    Some(match field {
        "semi_axes_m" => at(&shape.part_size, "PART_SIZE"),
        "size_spread" => at(&shape.size_variation, "PART_VAR_SIZE"),
        "corners" => at(&shape.corners, "PART_NUM_CORNERS"),
        "corner_spread" => at(&shape.corner_variation, "PART_VAR_CORNERS"),
        "corner_positions" => at(&shape.angle_mode, "PART_RANDOM_POS_CORNERS"),
        "orientation" => at(&shape.rotation, "PART_ROT"),
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::split;

    #[test]
    fn paths_split_at_their_first_field() {
        assert_eq!(split("blocks[0].shape.corners"), ("blocks", Some(0), "shape.corners"));
        assert_eq!(split("materials[12].gamma"), ("materials", Some(12), "gamma"));
        assert_eq!(split("run.end_time_s"), ("run", None, "end_time_s"));
        assert_eq!(split("walls[1].shape.corners_m[3]"), ("walls", Some(1), "shape.corners_m[3]"));
        assert_eq!(split("corners_m[3]"), ("corners_m", Some(3), ""));
        assert_eq!(split("sources"), ("sources", None, ""));
        assert_eq!(split(""), ("", None, ""));
    }
}
