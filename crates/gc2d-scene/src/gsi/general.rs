//! GENERAL and DISPLAY (reference §9.3, §9.4, §2.13, §1.6): global settings with gc2d's defaults.

use gc2d_engine::schedules::{GravityProfile, HeatingSchedule};

use super::diagnostics::GsiWarningKind;
use super::reader::ObjectReader;
use super::scene::{BIG_NUMBER, GsiDisplay, GsiGeneral, GsiGravity, GsiHeating, Sourced};

/// Standard gravity, gc2d's default `G`, m/s².
const STANDARD_GRAVITY: f64 = 9.81;

const HEATING_COMMANDS: [&str; 4] = ["HEAT_TIME", "HEAT_AMPLITUDE", "HEAT_FREQUENCE", "HEAT_SLOPE"];

/// Converts the GENERAL object.
pub(super) fn read_general(reader: &mut ObjectReader<'_, '_>) -> GsiGeneral {
    let dynamic_friction = reader.float("MUE_DYNAMISCH", 0.6);
    if dynamic_friction.origin.is_written() {
        reader.diagnostics.warn(dynamic_friction.line(), GsiWarningKind::UnusedDynamicFriction);
    }
    if let Some(line) = reader.flag("EMAIL") {
        reader.diagnostics.warn(line, GsiWarningKind::EmailIgnored);
    }
    let heating = reader.first_line_of(&HEATING_COMMANDS).map(|_| read_heating(reader));
    let time = reader.window("TIME", [0.0, 1.0]);
    reader.warn_if_defaulted(
        &time,
        GsiWarningKind::DefaultUsed {
            keyword: "TIME",
            object: "GENERAL",
            default: "0 1 (s)",
            consequence: "the run ends at t = 1 s",
        },
    );
    GsiGeneral {
        time_step: reader.float("DELTA_T", 1e-4),
        time,
        friction: reader.float("MUE_STATISCH", 0.6),
        dynamic_friction,
        youngs_modulus: reader.float("E_MODUL", 1e7),
        damping: reader.float("GAMMA", 0.5),
        cohesion: reader.float("COHESION", 0.0),
        steps_data: reader.whole("STEPS_DATA", 10_000),
        steps_checkpoint: reader.whole("STEPS_CHECKPOINT", 10_000),
        steps_setup: reader.whole("STEPS_SETUP", BIG_NUMBER),
        steps_dumpline: reader.whole("STEPS_DUMPLINE", BIG_NUMBER),
        seed: reader.pair("SEED", [0.0, 0.0]),
        basename: reader.word("BASENAME", "default"),
        next_data_file_number: reader.whole("NEXT_DATA_FILENUMBER", 1),
        next_setup_file_number: reader.whole("NEXT_SETUP_FILENUMBER", 1),
        gravity: read_gravity(reader),
        heating,
    }
}

/// `G` with one value means a constant g (g2 = g1), which is what a file written for gc2d without
/// `USE_VARIABLE_G` means; with two values it is the start and end of a change.
fn read_gravity(reader: &mut ObjectReader<'_, '_>) -> GsiGravity {
    let (start, end, single_value_line) = match reader.numbers("G") {
        Some((line, [g1, _], 1)) => (Sourced::written(g1, line), Sourced::written(g1, line), Some(line)),
        Some((line, [g1, g2], _)) => (Sourced::written(g1, line), Sourced::written(g2, line), None),
        None => {
            let default = Sourced::default_for(STANDARD_GRAVITY, reader.line());
            (default, default, None)
        }
    };
    let profile = reader.option("G_TYPE", GravityProfile::Constant);
    if let (Some(line), true) = (single_value_line, profile.value != GravityProfile::Constant) {
        let profile = format!("{:?}", profile.value).to_ascii_uppercase();
        reader.diagnostics.warn(line, GsiWarningKind::GravityWithoutEndValue { profile });
    }
    GsiGravity {
        start,
        end,
        window: reader.window("G_TIME", [0.0, 1.0]),
        parameters: reader.pair("G_PARAMETER", [5.0, 0.5]),
        profile,
    }
}

fn read_heating(reader: &mut ObjectReader<'_, '_>) -> GsiHeating {
    GsiHeating {
        window: reader.window("HEAT_TIME", [f64::INFINITY, f64::INFINITY]),
        amplitude: reader.float("HEAT_AMPLITUDE", 0.01),
        frequency: reader.float("HEAT_FREQUENCE", 1.0),
        slope: reader.float("HEAT_SLOPE", HeatingSchedule::DEFAULT_SLOPE),
    }
}

/// Converts a DISPLAY object.
pub(super) fn read_display(reader: &mut ObjectReader<'_, '_>) -> GsiDisplay {
    GsiDisplay {
        line: reader.line(),
        x_range: reader.bounds("X_RANGE", [-0.1, 0.1]),
        y_range: reader.bounds("Y_RANGE", [-0.1, 0.1]),
        screen: reader.integers("SCREEN", [640, 0]),
        interval: reader.whole("INTERVAL", 100),
        modus: reader.whole("MODUS", 3),
    }
}
