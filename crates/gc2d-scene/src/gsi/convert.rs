//! From a read gsi file ([`GsiImport`]) to a RON [`Scene`]: every object and command mapped to its scene field, and
//! everything the scene format cannot say reported as a warning at its line (see `docs/model.md`, "Legacy gsi
//! import (§9)", subsection "Conversion").

use gc2d_engine::motion::Waveform as EngineWaveform;
use gc2d_engine::schedules::GravityProfile as EngineGravityProfile;
use gc2d_engine::{DropHeight as EngineDropHeight, MassModel, TimeWindow};
use gc2d_geometry::{AngleMode, DVec2, Randomization};

use super::locate;
use super::{
    GsiBlock, GsiDisplay, GsiDropSource, GsiError, GsiErrorKind, GsiErrors, GsiGeneral, GsiImport, GsiParticle,
    GsiScene, GsiShape, GsiWall, GsiWallMotion, GsiWarning, GsiWarningKind, Sourced,
};
use crate::SceneError;
use crate::schema::{
    Area, Block, CornerPositions, CountSpread, DragSpring, DropHeight, Gravity, GravityProfile, Heating, Material,
    Motion, Orientation, Particle, Recipe, Run, Scene, Shape, SizeSpread, Source, WallItem, Waveform, Window,
};

/// The name of the one material an imported scene has: gsi has one global material in GENERAL.
pub const IMPORTED_MATERIAL: &str = "gsi";

/// A converted gsi file: the scene and every warning about it.
#[derive(Debug, Clone, PartialEq)]
pub struct GsiConversion {
    /// The scene, ready for [`Scene::to_ron_string`].
    pub scene: Scene,
    /// The reader's warnings and the converter's (what the scene format cannot express), in line order.
    pub warnings: Vec<GsiWarning>,
}

/// Converts a read gsi file into a scene named `name`.
///
/// Fails where a value has no meaning in the scene at all (a gravity step count that is not a whole number ≥ 1,
/// `STEPS_DATA 0`) and where the scene refuses a value (out of range, say): the converted scene is validated and
/// each refusal is reported at the gsi line and command that set the value ([`GsiErrorKind::InvalidValue`]).
/// Refusals found only when the scene is built (start overlaps) are not looked for. Values the scene format cannot
/// hold are dropped with a [`GsiWarningKind::NotConverted`] warning.
pub fn to_scene(import: &GsiImport, name: &str) -> Result<GsiConversion, GsiErrors> {
    let mut converter = Converter::default();
    let source = &import.scene;
    let general = &source.general;
    let description = if source.identification.trim().is_empty() {
        "Imported from a gc2d gsi file".to_owned()
    } else {
        format!("{} (imported from a gc2d gsi file)", source.identification.trim())
    };
    let scene = Scene {
        name: name.to_owned(),
        description,
        run: converter.run(general),
        gravity: converter.gravity(general),
        heating: general.heating.as_ref().map(|heating| Heating {
            window_s: window(heating.window.value),
            amplitude: heating.amplitude.value,
            frequency_hz: heating.frequency.value,
            slope: heating.slope.value,
        }),
        mass_model: MassModel::PerUnitThickness,
        materials: vec![material(general)],
        interactions: Vec::new(),
        walls: source.walls.iter().map(|wall| converter.wall(wall)).collect(),
        particles: source.particles.iter().map(|particle| converter.particle(particle)).collect(),
        blocks: source.blocks.iter().map(block).collect(),
        sources: source.drop_sources.iter().map(drop_source).collect(),
        inlets: Vec::new(),
        outlets: Vec::new(),
        fluid: None,
        mill: None,
        view: source.display.as_ref().map(|display| converter.view(display)),
        source: None,
    };
    if !converter.errors.is_empty() {
        converter.errors.sort_by_key(|error| error.line);
        return Err(GsiErrors(converter.errors));
    }
    if let Err(error) = scene.validate() {
        let errors = invalid_values(&error, source);
        // Errors in fields the file does not set are left to the written scene's own check.
        if !errors.is_empty() {
            return Err(GsiErrors(errors));
        }
    }
    let mut scene = scene;
    converter.fit_time_step(&mut scene, &general.time_step);
    let mut warnings = import.warnings.clone();
    warnings.extend(converter.warnings);
    warnings.sort_by_key(|warning| warning.line);
    Ok(GsiConversion { scene, warnings })
}

/// The scene's validation errors (`error` and its related ones) at the gsi lines and commands that set the refused
/// values, in line order; those in fields no command sets are left out.
fn invalid_values(error: &SceneError, source: &GsiScene) -> Vec<GsiError> {
    let mut errors: Vec<GsiError> = std::iter::once(error)
        .chain(error.related_errors())
        .filter_map(|error| {
            let blame = locate::blame(error.path(), source)?;
            let kind = GsiErrorKind::InvalidValue {
                keyword: blame.keyword,
                written: blame.written,
                message: error.message().to_owned(),
                field: error.path().to_owned(),
            };
            Some(GsiError { line: blame.line, kind })
        })
        .collect();
    errors.sort_by_key(|error| error.line);
    errors
}

/// The conversion's own errors and warnings.
#[derive(Default)]
struct Converter {
    errors: Vec<GsiError>,
    warnings: Vec<GsiWarning>,
}

impl Converter {
    /// Warns that a command written in the file is not carried into the scene, and what that means.
    fn not_converted<T>(&mut self, value: &Sourced<T>, keyword: &'static str, consequence: &str) {
        if value.origin.is_written() {
            let kind = GsiWarningKind::NotConverted { keyword, consequence: consequence.to_owned() };
            self.warnings.push(GsiWarning { line: value.line(), kind });
        }
    }

    /// GENERAL's time stepping, outputs and seed.
    fn run(&mut self, general: &GsiGeneral) -> Run {
        let time_step = general.time_step.value;
        let time = general.time.value;
        if time.start != 0.0 {
            let consequence = format!(
                "the scene starts at t = 0, not at TIME's start {} s; every time stays absolute, so the run covers \
                 [0, {}] s",
                time.start, time.end
            );
            let kind = GsiWarningKind::NotConverted { keyword: "TIME", consequence };
            self.warnings.push(GsiWarning { line: general.time.line(), kind });
        }
        if general.steps_data.value == 0 {
            self.errors.push(GsiError {
                line: general.steps_data.line(),
                kind: GsiErrorKind::NotConvertible {
                    keyword: "STEPS_DATA",
                    reason: "0 steps between data outputs; it must be at least 1 (a frame is written every \
                             STEPS_DATA × DELTA_T)"
                        .to_owned(),
                },
            });
        }
        let seed = self.seed(&general.seed);
        self.not_converted(
            &general.basename,
            "BASENAME",
            "outputs are named after the scene and written where `gc2d-rs run --out` says",
        );
        let restart_state = "file counters are restart state of gc2d's own checkpoints";
        self.not_converted(&general.next_data_file_number, "NEXT_DATA_FILENUMBER", restart_state);
        self.not_converted(&general.next_setup_file_number, "NEXT_SETUP_FILENUMBER", restart_state);
        self.not_converted(
            &general.steps_checkpoint,
            "STEPS_CHECKPOINT",
            "gc2d-rs keeps no overwritten rolling checkpoint; `gc2d-rs run` writes final.ckpt when the run ends or is \
             interrupted, and numbered checkpoints at STEPS_SETUP or `--checkpoint-every`",
        );
        self.not_converted(&general.steps_dumpline, "STEPS_DUMPLINE", "gc2d-rs writes no trajectory lines (gpl)");
        Run {
            time_step_s: Some(time_step),
            end_time_s: time.end,
            frames_per_second: 1.0 / (time_step * general.steps_data.value.max(1) as f64),
            checkpoint_interval_s: general
                .steps_setup
                .origin
                .is_written()
                .then_some(general.steps_setup.value as f64 * time_step),
            seed,
            ..Run::default()
        }
    }

    /// Keeps `DELTA_T` unless it is above the stable bound of the scene's particles, which the scene refuses; then
    /// the scene leaves Δt automatic (`AUTOMATIC_TIME_STEP_FRACTION` of the bound) and a warning gives both numbers.
    /// The bound depends on the particles' shapes and materials, not on where they sit, so it is measured with the
    /// overlap check off: a wall that overlaps the particles is then reported as such when the scene is loaded back,
    /// not as a time step above the bound. A scene that does not build for other reasons keeps `DELTA_T`: loading it
    /// reports those reasons.
    fn fit_time_step(&mut self, scene: &mut Scene, time_step: &Sourced<f64>) {
        let run = Run { time_step_s: None, ..scene.run.clone() };
        let automatic = Scene { run, ..scene.clone() };
        let Ok(summary) = automatic.summary_ignoring_start_overlaps() else { return };
        let Some(bound) = summary.refusal_time_step_s else { return };
        if time_step.value > bound {
            // `check` prints the stable bound, which the flat-contact and damping limits can put below this one.
            let stable = summary.stable_time_step_s.map_or(String::new(), |stable| {
                format!(" (the stable bound, with the limits of flat and damped contacts, is {stable:.3e} s)")
            });
            let consequence = format!(
                "DELTA_T = {:e} s is above {bound:.3e} s = (pi/10)*sqrt(m/E) of the lightest particle, where the \
                 scene is refused{stable}, so the scene leaves the time step automatic: {:e} s",
                time_step.value, summary.time_step_s
            );
            let kind = GsiWarningKind::NotConverted { keyword: "DELTA_T", consequence };
            self.warnings.push(GsiWarning { line: time_step.line(), kind });
            scene.run.time_step_s = None;
        }
    }

    /// `SEED s1 s2` as one u64: s1 in the low 32 bits, s2 in the high 32 bits, each truncated to a whole number
    /// and clamped into [0, 2³² − 1], so `SEED 5` is seed 5. A value that needed truncating or clamping warns.
    fn seed(&mut self, seed: &Sourced<[f64; 2]>) -> u64 {
        let word = |value: f64| value.trunc().clamp(0.0, u32::MAX as f64) as u64;
        let [low, high] = seed.value;
        let packed = word(low) | (word(high) << 32);
        if seed.value.iter().any(|&value| word(value) as f64 != value) {
            let consequence = format!(
                "the scene's seed is a whole number; SEED {low} {high} becomes {packed} (each value truncated into \
                 [0, 2^32 - 1], the first in the low 32 bits)"
            );
            let kind = GsiWarningKind::NotConverted { keyword: "SEED", consequence };
            self.warnings.push(GsiWarning { line: seed.line(), kind });
        }
        packed
    }

    /// `G`, `G_TIME`, `G_PARAMETER` and `G_TYPE`.
    fn gravity(&mut self, general: &GsiGeneral) -> Gravity {
        let gravity = &general.gravity;
        let profile = match gravity.profile.value {
            EngineGravityProfile::Constant => {
                if gravity.end.value != gravity.start.value {
                    let consequence = format!("G_TYPE CONSTANT keeps g = {} m/s^2 at all times", gravity.start.value);
                    let kind = GsiWarningKind::NotConverted { keyword: "G (second value)", consequence };
                    self.warnings.push(GsiWarning { line: gravity.end.line(), kind });
                }
                return Gravity::Constant(gravity.start.value);
            }
            EngineGravityProfile::Linear => GravityProfile::Linear,
            EngineGravityProfile::Step => GravityProfile::Step,
            EngineGravityProfile::SmoothStep => GravityProfile::SmoothStep,
        };
        let [steps, ramp_fraction] = gravity.parameters.value;
        let whole_steps = steps.fract() == 0.0 && (1.0..=u32::MAX as f64).contains(&steps);
        if !whole_steps && profile != GravityProfile::Linear {
            self.errors.push(GsiError {
                line: gravity.parameters.line(),
                kind: GsiErrorKind::NotConvertible {
                    keyword: "G_PARAMETER",
                    reason: format!("the number of gravity steps p1 = {steps} must be a whole number of at least 1"),
                },
            });
        }
        Gravity::Varying {
            profile,
            from_m_s2: gravity.start.value,
            to_m_s2: gravity.end.value,
            window_s: window(gravity.window.value),
            steps: if whole_steps { steps as u32 } else { 5 },
            ramp_fraction,
        }
    }

    /// DISPLAY's ranges; the X11 settings are dropped.
    fn view(&mut self, display: &GsiDisplay) -> Area {
        let window_only = "it sets up gc2d's X11 window, which gc2d-rs does not have";
        self.not_converted(&display.screen, "SCREEN", window_only);
        self.not_converted(&display.interval, "INTERVAL", window_only);
        self.not_converted(&display.modus, "MODUS", window_only);
        let range = |bounds: super::Bounds| [bounds.min, bounds.max];
        Area { x_range_m: range(display.x_range.value), y_range_m: range(display.y_range.value) }
    }

    /// A WALL: its world corners, surface velocity and motion.
    fn wall(&mut self, wall: &GsiWall) -> WallItem {
        if let Some(id) = &wall.id {
            self.not_converted(id, "ID", "scene walls are numbered in file order");
        }
        let motion = match &wall.motion {
            GsiWallMotion::Static => Motion::Static,
            GsiWallMotion::Piston(piston) => Motion::Piston {
                direction_rad: piston.direction_angle.value,
                force_n: piston.force.value,
                max_speed_m_s: piston.v_max.value,
            },
            GsiWallMotion::Vibration(vibration) => Motion::Vibration {
                amplitude_m: vibration.amplitude.value,
                frequency_hz: vibration.frequency.value,
                direction_rad: vibration.direction_angle.value,
                waveform: waveform(vibration.waveform.value),
                window_s: window(vibration.window.value),
            },
        };
        WallItem::Wall {
            shape: polygon(&wall.corners.value),
            position_m: None,
            angle_rad: 0.0,
            surface_velocity_m_s: wall.surface_velocity.value.to_array(),
            motion,
            material: None,
        }
    }

    /// A PARTICLE: body-frame corners placed at its centroid, its velocities and its drag spring.
    fn particle(&mut self, particle: &GsiParticle) -> Particle {
        let restart_state = "a new particle starts with its accelerations and higher Gear derivatives at zero";
        if particle.acceleration.value != DVec2::ZERO {
            self.not_converted(&particle.acceleration, "ACCELERATION", restart_state);
        }
        if particle.angular_acceleration.value != 0.0 {
            self.not_converted(&particle.angular_acceleration, "OMEGA_DOT", restart_state);
        }
        for (derivative, keyword) in particle.higher_translation.iter().zip(["PC_TRANS3", "PC_TRANS4", "PC_TRANS5"]) {
            if derivative.value != DVec2::ZERO {
                self.not_converted(derivative, keyword, restart_state);
            }
        }
        for (derivative, keyword) in particle.higher_rotation.iter().zip(["PC_ROT3", "PC_ROT4", "PC_ROT5"]) {
            if derivative.value != 0.0 {
                self.not_converted(derivative, keyword, restart_state);
            }
        }
        if let Some(id) = &particle.id {
            self.not_converted(id, "ID", "scene particles are numbered in file order");
        }
        let angle = particle.angle.value;
        let drag_spring = particle.drag.as_ref().map(|drag| DragSpring {
            stiffness_n_m: drag.stiffness.value,
            // gsi gives the point in world axes at the start; the scene wants it in the particle's frame.
            fixing_point_m: DVec2::from_angle(-angle).rotate(drag.fixing_point.value).to_array(),
            pulling_start_m: drag.pulling_point.value.to_array(),
            direction_rad: drag.direction_angle.value,
            speed_m_s: drag.speed.value,
            window_s: window(drag.window.value),
        });
        Particle {
            shape: polygon(&particle.corners.value),
            position_m: Some(particle.position.value.to_array()),
            angle_rad: angle,
            velocity_m_s: particle.velocity.value.to_array(),
            angular_velocity_rad_s: particle.angular_velocity.value,
            material: None,
            drag_spring,
        }
    }
}

/// GENERAL's material values as the scene's one material; the density is the scene default (gsi has none).
fn material(general: &GsiGeneral) -> Material {
    Material {
        youngs_modulus_n_m: general.youngs_modulus.value,
        gamma: general.damping.value,
        mu: general.friction.value,
        cohesion_n_m: general.cohesion.value,
        ..Material::named(IMPORTED_MATERIAL)
    }
}

/// A GENERATE_BLOCK: ranges, spacing, lattice, recipe and initial velocity ranges.
fn block(block: &GsiBlock) -> Block {
    let range = |bounds: &Sourced<super::Bounds>| [bounds.value.min, bounds.value.max];
    Block {
        grid: block.grid_type.value,
        speed_range_m_s: range(&block.speed_range),
        direction_range_rad: range(&block.velocity_direction_range),
        ..Block::new(
            range(&block.x_range),
            range(&block.y_range),
            block.grid_distance.value.to_array(),
            recipe(&block.shape),
        )
    }
}

/// A DROPSOURCE.
fn drop_source(source: &GsiDropSource) -> Source {
    Source {
        width_m: source.width.value,
        height: match source.height.value {
            EngineDropHeight::Absolute => DropHeight::Absolute,
            EngineDropHeight::AboveHighest => DropHeight::AboveHighest,
        },
        window_s: window(source.window.value),
        interval_s: source.interval.value,
        ..Source::new(source.position.value.to_array(), recipe(&source.shape))
    }
}

/// The shape commands as a recipe: semi-axes per the file's PART_SIZE reading, spreads only where the
/// randomisation uses them (gc2d ignores `PART_VAR_*` under CONST).
fn recipe(shape: &GsiShape) -> Recipe {
    let count = |value: u64| usize::try_from(value).unwrap_or(usize::MAX);
    let variation = shape.size_variation.value;
    let corner_variation = count(shape.corner_variation.value);
    let rotation = shape.rotation.value;
    Recipe {
        semi_axes_m: shape.semi_axes().to_array(),
        size_spread: match shape.size_randomization.value {
            Randomization::Const => SizeSpread::Const,
            Randomization::Equal => SizeSpread::Equal(variation),
            Randomization::Gauss => SizeSpread::Gauss(variation),
        },
        corners: count(shape.corners.value),
        corner_spread: match shape.corner_randomization.value {
            Randomization::Const => CountSpread::Const,
            Randomization::Equal => CountSpread::Equal(corner_variation),
            Randomization::Gauss => CountSpread::Gauss(corner_variation),
        },
        corner_positions: match shape.angle_mode.value {
            AngleMode::Regular => CornerPositions::Regular,
            AngleMode::Rand1 => CornerPositions::Rand1,
            AngleMode::Rand2 => CornerPositions::Rand2,
            AngleMode::Full => CornerPositions::Full,
            AngleMode::SpecialRectangle => CornerPositions::SpecialRectangle,
        },
        orientation: match shape.rotation_randomization.value {
            Randomization::Const => Orientation::Const(rotation),
            Randomization::Equal => Orientation::Equal,
            Randomization::Gauss => Orientation::Gauss(rotation),
        },
        disk: false,
    }
}

fn waveform(waveform: EngineWaveform) -> Waveform {
    match waveform {
        EngineWaveform::Cosine => Waveform::Cosine,
        EngineWaveform::Sawtooth => Waveform::Sawtooth,
        EngineWaveform::Tapping => Waveform::Tapping,
        EngineWaveform::Triangle => Waveform::Triangle,
    }
}

fn window(window: TimeWindow) -> Window {
    [window.start, window.end]
}

fn polygon(corners: &[DVec2]) -> Shape {
    Shape::Polygon { corners_m: corners.iter().map(|corner| corner.to_array()).collect() }
}
