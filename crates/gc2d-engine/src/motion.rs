//! How walls move: prescribed vibration and rotation, and the force-controlled piston (reference §2.11, §9.6).
//!
//! A [`WallMotion`] gives, for a time `t`, the wall's [`WallKinematics`]: the rigid offset of the wall from its rest
//! pose and the velocity field of its material. The engine places the wall with [`WallKinematics::place`] and adds
//! [`WallKinematics::point_velocity`] at the contact point into the contact's relative velocity.
//!
//! gc2d's *virtual surface velocity* (`VELOCITY`, the conveyor-belt lining of rotating drums, §2.11 and D.7) is not a
//! motion: the wall stays where it is and only the tangential velocity seen by the contact law changes. It is a
//! separate wall property that the engine passes to the contact law, not a variant here.
//!
//! All angles are counter-clockwise from +x, in radians; all quantities SI.

use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};
use std::str::FromStr;

use gc2d_geometry::{DVec2, Pose};

use crate::time_window::TimeWindow;

/// The periodic shape of a vibration, `VIB_TYPE` (reference §2.11, Abb. B.5). Each shape rises from 0 and has
/// unit amplitude; [`Vibration`] scales it by the width W.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Waveform {
    /// `COSINUS`: A = W·½(1 − cos 2πft), smooth, one rise and fall per period.
    Cosine,
    /// `SAWTOOTH`: A = W·(t mod 1/f)·f, a linear rise followed by a jump back to 0 at the end of each period.
    Sawtooth,
    /// `TAPPING` ("knocking"): A = W·sin(2πft)^30, a short pulse every half period, i.e. two taps per period.
    Tapping,
    /// `TRIANGLE`: linear up to W at half period and back down to 0, per erratum E27.
    Triangle,
}

impl Waveform {
    /// gc2d's names for the waveforms, in the order of the table in §2.11.
    pub const GC2D_NAMES: [&'static str; 4] = ["COSINUS", "SAWTOOTH", "TAPPING", "TRIANGLE"];

    /// The displacement for unit width at `phase` = (t·f mod 1) ∈ [0, 1).
    #[inline]
    pub fn value(self, phase: f64) -> f64 {
        match self {
            Waveform::Cosine => 0.5 * (1.0 - (TAU * phase).cos()),
            Waveform::Sawtooth => phase,
            Waveform::Tapping => (TAU * phase).sin().powi(30),
            Waveform::Triangle => {
                if phase < 0.5 {
                    2.0 * phase
                } else {
                    2.0 * (1.0 - phase)
                }
            }
        }
    }

    /// d(value)/d(phase). At the kinks of the triangle the rising branch holds for `phase < 0.5`; for the sawtooth
    /// it is the ramp's slope 1 everywhere (the jump back at the period's end is a displacement, not a velocity).
    #[inline]
    pub fn slope(self, phase: f64) -> f64 {
        match self {
            Waveform::Cosine => PI * (TAU * phase).sin(),
            Waveform::Sawtooth => 1.0,
            Waveform::Tapping => {
                let (sin, cos) = (TAU * phase).sin_cos();
                30.0 * sin.powi(29) * cos * TAU
            }
            Waveform::Triangle => {
                if phase < 0.5 {
                    2.0
                } else {
                    -2.0
                }
            }
        }
    }
}

/// A `VIB_TYPE` name that is not one of gc2d's four waveforms.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown vibration type `{0}`; expected one of COSINUS, SAWTOOTH, TAPPING, TRIANGLE")]
pub struct UnknownWaveform(pub String);

impl FromStr for Waveform {
    type Err = UnknownWaveform;

    /// Parses gc2d's `VIB_TYPE` names, case-insensitively like the rest of the gsi language (§9.2). The English
    /// spelling `COSINE` is accepted beside gc2d's `COSINUS`.
    fn from_str(name: &str) -> Result<Self, Self::Err> {
        match name.trim().to_ascii_uppercase().as_str() {
            "COSINUS" | "COSINE" => Ok(Waveform::Cosine),
            "SAWTOOTH" => Ok(Waveform::Sawtooth),
            "TAPPING" => Ok(Waveform::Tapping),
            "TRIANGLE" => Ok(Waveform::Triangle),
            _ => Err(UnknownWaveform(name.to_owned())),
        }
    }
}

/// A wall vibrating along a fixed direction, gc2d's `VIB_*` commands (reference §2.11, B.1.5.2).
///
/// The displacement along `direction_angle` is A(t_c) = W·waveform(t_c·f mod 1), where t_c is the time clamped to
/// the window (B.3). The clamped time enters the formula as absolute time, as in gc2d, so the phase does not restart
/// at t1: unless t1 is a whole number of periods the wall already sits at A(t1) ≠ 0 before the window opens, and it
/// freezes at A(t2) after it closes. Scenes that restart from a settled state should choose t1 = k/f, where all four
/// waveforms are 0.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Vibration {
    /// Direction of the displacement, radians CCW from +x (`VIB_ANGLE`; gc2d's default π/2 is vertical).
    pub direction_angle: f64,
    /// When the wall moves (`VIB_TIME`, default (0, ∞)).
    pub window: TimeWindow,
    /// Width W of the displacement, m (`VIB_WIDTH`, default 1).
    pub amplitude: f64,
    /// Frequency f, 1/s (`VIB_FREQUENCE`, default 1). A non-positive or non-finite frequency keeps the wall still.
    pub frequency: f64,
    /// Shape of the displacement (`VIB_TYPE`, default COSINUS).
    pub waveform: Waveform,
}

impl Default for Vibration {
    /// gc2d's defaults: vertical, window (0, ∞), W = 1 m, f = 1/s, COSINUS.
    fn default() -> Self {
        Self {
            direction_angle: PI / 2.0,
            window: TimeWindow::new(0.0, f64::INFINITY),
            amplitude: 1.0,
            frequency: 1.0,
            waveform: Waveform::Cosine,
        }
    }
}

impl Vibration {
    /// Unit vector of the displacement direction.
    #[inline]
    pub fn direction(&self) -> DVec2 {
        DVec2::from_angle(self.direction_angle)
    }

    /// The phase t_c·f mod 1 of the clamped time, or `None` when the frequency cannot define one.
    #[inline]
    fn phase(&self, t: f64) -> Option<f64> {
        let phase = (self.window.clamp(t) * self.frequency).rem_euclid(1.0);
        (self.frequency > 0.0 && phase.is_finite()).then_some(phase)
    }

    /// The displacement A(t) along the direction, m (table in §2.11 with the clamped time).
    #[inline]
    pub fn displacement(&self, t: f64) -> f64 {
        self.phase(t).map_or(0.0, |phase| self.amplitude * self.waveform.value(phase))
    }

    /// The speed dA/dt along the direction, m/s: the analytic derivative inside the window, 0 outside it.
    #[inline]
    pub fn speed(&self, t: f64) -> f64 {
        if !self.window.is_active(t) {
            return 0.0;
        }
        self.phase(t).map_or(0.0, |phase| self.amplitude * self.frequency * self.waveform.slope(phase))
    }
}

/// A wall turning about a fixed pivot during a window (a mill rotor): from rest up to the angular velocity ω over
/// the spin-up time T (a linear ramp, none when T = 0), then at ω.
///
/// With e the time elapsed in the window (clamped to it), the angle turned is ω·e for T = 0, ω·e²/(2T) during the
/// ramp and ω·(e − T/2) after it, so the wall starts at its rest pose and keeps its last angle after t2. The
/// window's start must be finite for the wall to turn.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Rotation {
    /// The fixed point the wall turns about, world coordinates, m.
    pub pivot: DVec2,
    /// ω, rad/s, counter-clockwise positive.
    pub angular_velocity: f64,
    /// When the wall turns.
    pub window: TimeWindow,
    /// Time to reach ω from rest at the start of the window, s (0: at ω from the start).
    pub spin_up: f64,
}

impl Rotation {
    /// Angle turned from the rest pose at time `t`, radians CCW.
    #[inline]
    pub fn angle(&self, t: f64) -> f64 {
        let elapsed = self.window.elapsed(t);
        if self.spin_up > 0.0 {
            if elapsed < self.spin_up {
                self.angular_velocity * elapsed * elapsed / (2.0 * self.spin_up)
            } else {
                self.angular_velocity * (elapsed - 0.5 * self.spin_up)
            }
        } else {
            self.angular_velocity * elapsed
        }
    }

    /// Angular velocity at time `t`: on the ramp ω·e/T, then ω inside the window, 0 outside.
    #[inline]
    pub fn angular_velocity_at(&self, t: f64) -> f64 {
        if !self.window.is_active(t) {
            return 0.0;
        }
        let elapsed = self.window.elapsed(t);
        if self.spin_up > 0.0 && elapsed < self.spin_up {
            self.angular_velocity * elapsed / self.spin_up
        } else {
            self.angular_velocity
        }
    }
}

/// Relative speed change allowed per step of the piston's adaptive gain: ×`GAIN_GROWTH` while the force error keeps
/// its sign, ×½ when it flips (an overshoot).
const GAIN_GROWTH: f64 = 1.25;
/// Smallest gain, as a fraction of v_max, so that a long run of overshoots cannot freeze the piston for good.
const MIN_GAIN_FRACTION: f64 = 1e-12;

/// A force-controlled wall, gc2d's "wall as stamp" (`PISTON_*`, reference §2.11, B.1.5.1).
///
/// The thesis does not give the control law (D5). gc2d-rs moves the piston kinematically along its direction with
/// speed v = g·e, where e = clamp((F_target − F_measured)/|F_target|, −1, 1) is the relative force error and g ≤ v_max
/// is an adaptive gain (see [`Piston::advance`]). A plain proportional law (g = v_max) converges only if
/// Δt·k·v_max/|F_target| < 2 for the unknown stiffness k of the bed under the piston, which a stiff granular bed
/// (k ~ E) violates by orders of magnitude; the adaptive gain finds a stable gain for any k. Proven bounds: |v| ≤ v_max
/// always, and once the piston has first reached the target the displacement never strays more than v_max·Δt from it
/// (each step moves at most v_max·Δt and always towards the target). On a bed soft enough for g = v_max to be stable,
/// the approach is the monotone exponential of the proportional law, with time constant |F_target|/(k·v_max).
///
/// With F_target = 0 the piston stands still when nothing touches it and gives way at full gain when pushed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Piston {
    /// Direction in which the piston pushes, radians CCW from +x (`PISTON_ANGLE`, default 0).
    pub direction_angle: f64,
    /// Force to exert along the direction, N per unit thickness (`PISTON_FORCE`, default 0).
    pub target_force: f64,
    /// Speed limit, m/s (`PISTON_V_MAX`, default 1; "to lower the stamp gently onto a granular surface").
    pub v_max: f64,
    /// Where the piston is and how it is moving; saved in checkpoints.
    pub state: PistonState,
}

/// The integrated state of a [`Piston`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PistonState {
    /// Distance travelled along the direction from the rest pose, m.
    pub displacement: f64,
    /// Current speed along the direction, m/s (the wall material velocity is this times the direction).
    pub velocity: f64,
    /// Current gain g, m/s per unit relative force error, in (0, v_max].
    pub gain: f64,
    /// Relative force error e of the previous step, in [−1, 1]; a sign change against it halves the gain.
    pub previous_error: f64,
}

impl Default for Piston {
    /// gc2d's defaults: direction 0, target force 0, v_max = 1 m/s, at rest.
    fn default() -> Self {
        Self::new(0.0, 0.0, 1.0)
    }
}

impl Piston {
    /// A piston at its rest pose, standing still, with the full gain v_max.
    pub fn new(direction_angle: f64, target_force: f64, v_max: f64) -> Self {
        let state = PistonState { displacement: 0.0, velocity: 0.0, gain: v_max.max(0.0), previous_error: 0.0 };
        Self { direction_angle, target_force, v_max, state }
    }

    /// Unit vector of the pushing direction.
    #[inline]
    pub fn direction(&self) -> DVec2 {
        DVec2::from_angle(self.direction_angle)
    }

    /// F_measured from the total contact force the particles exert on the piston wall: its component against the
    /// pushing direction, so that pressing back on the piston counts positive.
    #[inline]
    pub fn measured_force(&self, force_on_wall: DVec2) -> f64 {
        -force_on_wall.dot(self.direction())
    }

    /// The relative force error e ∈ [−1, 1]; with a zero target, ±1 by the sign of the push (0 when untouched).
    #[inline]
    fn relative_error(&self, measured_force: f64) -> f64 {
        let scale = self.target_force.abs();
        let error = if scale > 0.0 {
            (self.target_force - measured_force) / scale
        } else if measured_force > 0.0 {
            -1.0
        } else if measured_force < 0.0 {
            1.0
        } else {
            0.0
        };
        if error.is_nan() { 0.0 } else { error.clamp(-1.0, 1.0) }
    }

    /// One control step: from the force measured at the current position, choose the speed for the next `dt` and
    /// integrate the displacement. The gain halves when the error changes sign (the last move overshot) and otherwise
    /// grows by a factor 1.25 up to v_max, so the loop gain settles where the discrete loop contracts. A
    /// non-positive or non-finite `dt` or force stops the piston for this step.
    pub fn advance(&mut self, measured_force: f64, dt: f64) {
        if !(dt > 0.0 && dt.is_finite() && measured_force.is_finite()) {
            self.state.velocity = 0.0;
            return;
        }
        let v_max = self.v_max.max(0.0);
        let error = self.relative_error(measured_force);
        let state = &mut self.state;
        let gain = if error * state.previous_error < 0.0 { 0.5 * state.gain } else { GAIN_GROWTH * state.gain };
        state.gain = gain.max(MIN_GAIN_FRACTION * v_max).min(v_max);
        state.velocity = state.gain * error;
        state.displacement += state.velocity * dt;
        state.previous_error = error;
    }
}

/// Where a moving wall is and how its material moves at one instant: the rigid map
/// x ↦ pivot + R(rotation)·(x − pivot) + displacement applied to the rest pose, and its velocity field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallKinematics {
    /// Translation after the rotation, m.
    pub displacement: DVec2,
    /// Rotation about `pivot`, radians CCW.
    pub rotation: f64,
    /// Fixed point of the rotation (before the displacement), world coordinates, m.
    pub pivot: DVec2,
    /// Velocity of the material point at `pivot + displacement`, m/s.
    pub velocity: DVec2,
    /// Angular velocity of the wall, rad/s CCW.
    pub angular_velocity: f64,
}

impl WallKinematics {
    /// A wall at its rest pose, not moving.
    pub const REST: Self = Self {
        displacement: DVec2::ZERO,
        rotation: 0.0,
        pivot: DVec2::ZERO,
        velocity: DVec2::ZERO,
        angular_velocity: 0.0,
    };

    /// The wall's current pose from its rest pose: position moved by the rigid map, angle increased by `rotation`.
    #[inline]
    pub fn place(&self, rest: Pose) -> Pose {
        let position =
            self.pivot + DVec2::from_angle(self.rotation).rotate(rest.position - self.pivot) + self.displacement;
        Pose { position, angle: rest.angle + self.rotation, scale: rest.scale }
    }

    /// Velocity of the wall's material at `world_point` (where the wall is now): v + ω × (p − (pivot + displacement)).
    #[inline]
    pub fn point_velocity(&self, world_point: DVec2) -> DVec2 {
        self.velocity + self.angular_velocity * (world_point - self.pivot - self.displacement).perp()
    }
}

/// How a wall moves. One variant per wall, so a wall that is both a piston and vibrating (forbidden by gc2d,
/// B.1.5.1/B.1.5.2) cannot be represented.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub enum WallMotion {
    /// The wall never moves (it may still have a virtual surface velocity; see the module docs).
    #[default]
    Static,
    /// Prescribed periodic displacement along a direction.
    Vibrating(Vibration),
    /// Prescribed rotation about a pivot.
    Rotating(Rotation),
    /// Force-controlled motion; the engine calls [`Piston::advance`] once per step with the measured force.
    Piston(Piston),
}

impl WallMotion {
    /// True for walls that never move, so the engine can leave them out of the per-step wall update.
    pub fn is_static(&self) -> bool {
        matches!(self, WallMotion::Static)
    }

    /// The wall's offset from its rest pose and its velocity at time `t` (a piston reports its integrated state).
    #[inline]
    pub fn kinematics(&self, t: f64) -> WallKinematics {
        match self {
            WallMotion::Static => WallKinematics::REST,
            WallMotion::Vibrating(vibration) => {
                let direction = vibration.direction();
                WallKinematics {
                    displacement: vibration.displacement(t) * direction,
                    velocity: vibration.speed(t) * direction,
                    ..WallKinematics::REST
                }
            }
            WallMotion::Rotating(rotation) => WallKinematics {
                rotation: rotation.angle(t),
                pivot: rotation.pivot,
                angular_velocity: rotation.angular_velocity_at(t),
                ..WallKinematics::REST
            },
            WallMotion::Piston(piston) => {
                let direction = piston.direction();
                WallKinematics {
                    displacement: piston.state.displacement * direction,
                    velocity: piston.state.velocity * direction,
                    ..WallKinematics::REST
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    const WAVEFORMS: [Waveform; 4] = [Waveform::Cosine, Waveform::Sawtooth, Waveform::Tapping, Waveform::Triangle];

    fn vibration(waveform: Waveform, window: TimeWindow) -> Vibration {
        Vibration { direction_angle: 0.3, window, amplitude: 0.2, frequency: 4.0, waveform }
    }

    #[test]
    fn waveforms_at_quarter_half_and_three_quarter_periods() {
        // f = 4/s: the period 0.25 s and its quarters are exact binary fractions.
        let expected = [
            (Waveform::Cosine, [0.1, 0.2, 0.1]),
            (Waveform::Sawtooth, [0.05, 0.1, 0.15]),
            (Waveform::Tapping, [0.2, 0.0, 0.2]),
            (Waveform::Triangle, [0.1, 0.2, 0.1]),
        ];
        for (waveform, values) in expected {
            let wall = vibration(waveform, TimeWindow::new(0.0, f64::INFINITY));
            assert_eq!(wall.displacement(0.0), 0.0, "{waveform:?} starts at rest");
            for (quarter, value) in values.into_iter().enumerate() {
                let t = 0.0625 * (quarter + 1) as f64;
                assert_relative_eq!(wall.displacement(t), value, epsilon = 1e-15);
            }
        }
        // TAPPING at an eighth period: W·(√2/2)^30 = W·2^-15.
        let tapping = vibration(Waveform::Tapping, TimeWindow::new(0.0, 1.0));
        assert_relative_eq!(tapping.displacement(0.03125), 0.2 / 32768.0, max_relative = 1e-12);
    }

    #[test]
    fn speed_is_the_derivative_of_the_displacement() {
        let window = TimeWindow::new(0.0, 10.0);
        for waveform in WAVEFORMS {
            let wall = vibration(waveform, window);
            for phase in [0.1, 0.23, 0.3, 0.37, 0.6, 0.85, 0.97] {
                let t = 2.0 + phase / wall.frequency;
                let h = 1e-6;
                let difference = (wall.displacement(t + h) - wall.displacement(t - h)) / (2.0 * h);
                let scale = wall.amplitude * wall.frequency;
                assert!(
                    (wall.speed(t) - difference).abs() < 1e-6 * scale,
                    "{waveform:?} at phase {phase}: {} vs {difference}",
                    wall.speed(t)
                );
            }
        }
    }

    #[test]
    fn sawtooth_reports_the_ramp_speed_across_its_jump() {
        let wall = vibration(Waveform::Sawtooth, TimeWindow::new(0.0, 10.0));
        let ramp_speed = wall.amplitude * wall.frequency;
        for t in [0.25 - 1e-9, 0.25, 0.25 + 1e-9] {
            assert_eq!(wall.speed(t), ramp_speed);
        }
        assert!(wall.displacement(0.25 - 1e-9) > 0.19 && wall.displacement(0.25 + 1e-9) < 0.01);
    }

    #[test]
    fn vibration_uses_the_clamped_time_and_is_still_outside_the_window() {
        let window = TimeWindow::new(0.3, 0.8);
        let wall = Vibration { frequency: 1.0, ..vibration(Waveform::Cosine, window) };
        let at_start = 0.1 * (1.0 - (0.6 * PI).cos());
        let at_end = 0.1 * (1.0 - (1.6 * PI).cos());
        assert_relative_eq!(wall.displacement(0.0), at_start, epsilon = 1e-15);
        assert_relative_eq!(wall.displacement(0.3), at_start, epsilon = 1e-15);
        assert_relative_eq!(wall.displacement(5.0), at_end, epsilon = 1e-15);
        assert_eq!((wall.speed(0.1), wall.speed(0.8), wall.speed(5.0)), (0.0, 0.0, 0.0));
        assert_relative_eq!(wall.speed(0.5), 0.2 * PI * (PI).sin(), epsilon = 1e-15);
        assert_relative_eq!(wall.speed(0.55), 0.2 * PI * (1.1 * PI).sin(), epsilon = 1e-15);

        let kinematics = WallMotion::Vibrating(wall).kinematics(0.55);
        let direction = DVec2::new(0.3f64.cos(), 0.3f64.sin());
        assert_relative_eq!(kinematics.displacement, wall.displacement(0.55) * direction, epsilon = 1e-15);
        assert_relative_eq!(kinematics.point_velocity(DVec2::new(5.0, -3.0)), wall.speed(0.55) * direction);
    }

    #[test]
    fn a_vibration_without_a_frequency_stays_still() {
        for frequency in [0.0, -2.0, f64::NAN, f64::INFINITY] {
            let wall = Vibration { frequency, ..vibration(Waveform::Sawtooth, TimeWindow::new(0.0, 1.0)) };
            assert_eq!((wall.displacement(0.4), wall.speed(0.4)), (0.0, 0.0));
        }
    }

    #[test]
    fn rotating_wall_turns_about_its_pivot() {
        let pivot = DVec2::new(1.0, 2.0);
        let motion = WallMotion::Rotating(Rotation {
            pivot,
            angular_velocity: 0.7,
            window: TimeWindow::new(1.0, 3.0),
            spin_up: 0.0,
        });
        let rest = Pose::new(DVec2::new(3.0, 2.0), 0.1);

        assert_eq!(motion.kinematics(0.5).place(rest), rest);
        let now = motion.kinematics(2.0);
        let pose = now.place(rest);
        assert_relative_eq!(pose.position, pivot + 2.0 * DVec2::new(0.7f64.cos(), 0.7f64.sin()), epsilon = 1e-15);
        assert_relative_eq!(pose.angle, 0.8, epsilon = 1e-15);

        // A body point of the wall: its velocity is ω × (p − pivot) and matches the motion of the placed point.
        let body_point = DVec2::new(-0.4, 0.25);
        let world_at = |t: f64| motion.kinematics(t).place(rest).apply(body_point);
        let p = world_at(2.0);
        assert_relative_eq!(now.point_velocity(p), 0.7 * (p - pivot).perp(), epsilon = 1e-15);
        let h = 1e-6;
        let difference = (world_at(2.0 + h) - world_at(2.0 - h)) / (2.0 * h);
        assert_relative_eq!(now.point_velocity(p), difference, epsilon = 1e-8);

        let after = motion.kinematics(5.0);
        assert_relative_eq!(after.rotation, 1.4, epsilon = 1e-15);
        assert_eq!(after.point_velocity(p), DVec2::ZERO);
    }

    /// Drives a piston against a bed whose reaction is `reaction(x)` and returns the displacement after each step,
    /// asserting the speed limit on the way.
    fn drive_piston(piston: &mut Piston, reaction: impl Fn(f64) -> f64, dt: f64, steps: usize) -> Vec<f64> {
        (0..steps)
            .map(|_| {
                piston.advance(reaction(piston.state.displacement), dt);
                assert!(piston.state.velocity.abs() <= piston.v_max);
                piston.state.displacement
            })
            .collect()
    }

    #[test]
    fn piston_on_a_soft_spring_approaches_monotonically() {
        // k = 100 N/m, F = 10 N: x* = 0.1 m. Loop gain Δt·k·v_max/F = 0.005, so the full gain v_max is stable and the
        // approach is the exponential x*(1 − e^(−t/τ)) with τ = F/(k·v_max) = 0.2 s.
        let (k, force, dt) = (100.0, 10.0, 1e-3);
        let mut piston = Piston::new(0.0, force, 0.5);
        let path = drive_piston(&mut piston, |x| k * x, dt, 5000);
        let target = force / k;
        assert!(path.iter().all(|&x| x <= target), "no overshoot");
        assert_relative_eq!(path[199], target * (1.0 - (-1.0f64).exp()), max_relative = 3e-3);
        assert_relative_eq!(path[4999], target, max_relative = 1e-9);
        assert_eq!(piston.state.gain, 0.5);
    }

    #[test]
    fn piston_on_a_stiff_bed_settles_within_one_step_of_travel() {
        // A bed 1 mm away with k = 1e7 N/m (a granular bed at E ~ 1e7 N/m); the proportional loop gain would be 1e4.
        let (k, gap, force, v_max, dt) = (1e7, 1e-3, 10.0, 1.0, 1e-5);
        let mut piston = Piston::new(-PI / 2.0, force, v_max);
        let path = drive_piston(&mut piston, |x| k * (x - gap).max(0.0), dt, 1000);
        let target = gap + force / k;

        let first_contact = path.iter().position(|&x| x >= target).expect("the piston reaches the bed");
        assert_eq!(first_contact, 100, "travels the gap at v_max");
        let largest_excursion = path[first_contact..].iter().map(|&x| (x - target).abs()).fold(0.0, f64::max);
        assert!(largest_excursion <= v_max * dt, "{largest_excursion}");
        let settled = &path[first_contact + 20..];
        assert!(settled.iter().all(|&x| (k * (x - gap) - force).abs() < 1e-6 * force));
        assert_relative_eq!(piston.direction(), DVec2::new(0.0, -1.0), epsilon = 1e-15);
        assert_relative_eq!(piston.measured_force(DVec2::new(3.0, 12.0)), 12.0, epsilon = 1e-14);
    }

    #[test]
    fn piston_with_zero_target_yields_only_when_pushed() {
        let mut piston = Piston::default();
        piston.advance(0.0, 1e-3);
        assert_eq!((piston.state.displacement, piston.state.velocity), (0.0, 0.0));
        piston.advance(2.0, 1e-3);
        assert_eq!(piston.state.velocity, -1.0);
        piston.advance(f64::NAN, 1e-3);
        assert_eq!(piston.state.velocity, 0.0);
        let kinematics = WallMotion::Piston(piston).kinematics(123.0);
        assert_eq!(kinematics.displacement, DVec2::new(-1e-3, 0.0));
    }

    #[test]
    fn waveform_names_follow_gc2d() {
        for (name, waveform) in Waveform::GC2D_NAMES.iter().zip(WAVEFORMS) {
            assert_eq!(name.parse::<Waveform>(), Ok(waveform));
        }
        assert_eq!(" cosinus ".parse::<Waveform>(), Ok(Waveform::Cosine));
        assert_eq!("Tapping".parse::<Waveform>(), Ok(Waveform::Tapping));
        let error = "SINE".parse::<Waveform>().unwrap_err().to_string();
        assert!(Waveform::GC2D_NAMES.iter().all(|name| error.contains(name)) && error.contains("SINE"), "{error}");
    }

    #[test]
    fn only_static_walls_are_static() {
        assert!(WallMotion::default().is_static());
        assert!(!WallMotion::Vibrating(Vibration::default()).is_static());
        assert_eq!(WallMotion::Static.kinematics(1.0), WallKinematics::REST);
    }

    #[test]
    fn a_spin_up_ramps_the_angular_velocity_and_integrates_to_the_angle() {
        let rotation = Rotation {
            pivot: DVec2::ZERO,
            angular_velocity: 4.0,
            window: TimeWindow::new(1.0, f64::INFINITY),
            spin_up: 0.5,
        };
        assert_eq!((rotation.angle(1.0), rotation.angular_velocity_at(0.9)), (0.0, 0.0));
        assert_relative_eq!(rotation.angular_velocity_at(1.25), 2.0, epsilon = 1e-15);
        assert_relative_eq!(rotation.angle(1.25), 4.0 * 0.25 * 0.25 / 1.0, epsilon = 1e-15);
        assert_relative_eq!(rotation.angle(1.5), 1.0, epsilon = 1e-15);
        assert_eq!(rotation.angular_velocity_at(2.0), 4.0);
        assert_relative_eq!(rotation.angle(2.0), 1.0 + 4.0 * 0.5, epsilon = 1e-14);
        // The angle is the integral of the angular velocity (midpoint rule, exact for a piecewise linear ω).
        let n = 1000;
        let integral: f64 =
            (0..n).map(|k| rotation.angular_velocity_at(1.0 + (k as f64 + 0.5) / n as f64) / n as f64).sum();
        assert_relative_eq!(integral, rotation.angle(2.0), max_relative = 1e-12);
    }
}
