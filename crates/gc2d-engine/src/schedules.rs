//! Time laws acting on all particles or on one: variable gravity g(t) (reference §2.13), global heating s(t) (§1.6,
//! B.1/B.2) and the drag spring that pulls a particle towards a moving point (§2.12).
//!
//! Each is a small value type evaluated by the engine once per step; none of them knows about the World. Angles are
//! counter-clockwise from +x, quantities SI per unit thickness.

use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;
use std::str::FromStr;

use gc2d_geometry::{DVec2, Pose, cross};

use crate::time_window::TimeWindow;

/// How g changes from g1 to g2 over the window, `G_TYPE` (reference §2.13).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum GravityProfile {
    /// g = g1 at all times.
    Constant,
    /// Linear from g1 at t1 to g2 at t2.
    Linear,
    /// p1 equal jumps; see [`GravitySchedule`] for where they sit.
    Step,
    /// p1 equal steps, each a plateau followed by a linear ramp over the fraction p2 of the step.
    SmoothStep,
}

impl GravityProfile {
    /// gc2d's `G_TYPE` names.
    pub const GC2D_NAMES: [&'static str; 4] = ["CONSTANT", "LINEAR", "STEP", "SMOOTH_STEP"];
}

/// A `G_TYPE` name that is not one of gc2d's four profiles.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown gravity type `{0}`; expected one of CONSTANT, LINEAR, STEP, SMOOTH_STEP")]
pub struct UnknownGravityProfile(pub String);

impl FromStr for GravityProfile {
    type Err = UnknownGravityProfile;

    /// Parses gc2d's `G_TYPE` names, case-insensitively like the rest of the gsi language (§9.2).
    fn from_str(name: &str) -> Result<Self, Self::Err> {
        match name.trim().to_ascii_uppercase().as_str() {
            "CONSTANT" => Ok(GravityProfile::Constant),
            "LINEAR" => Ok(GravityProfile::Linear),
            "STEP" => Ok(GravityProfile::Step),
            "SMOOTH_STEP" => Ok(GravityProfile::SmoothStep),
            _ => Err(UnknownGravityProfile(name.to_owned())),
        }
    }
}

/// The magnitude of gravity as a function of time (`G`, `G_TIME`, `G_PARAMETER`, `G_TYPE`; reference §2.13).
/// Gravity acts along −y (erratum E39).
///
/// The thesis names the profiles but not where the steps sit. gc2d-rs splits the window into p1 equal intervals;
/// interval k (k = 0 … p1−1) holds g1 + k·Δ, Δ = (g2 − g1)/p1, and ends with a linear ramp to g1 + (k+1)·Δ over the
/// last fraction p2 of the interval. So g stays g1 until the first ramp, reaches g2 exactly at t2, SMOOTH_STEP with
/// p2 = 0 is STEP (jumps at t1 + k·(t2 − t1)/p1, k = 1 … p1) and with p2 = 1 is LINEAR.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GravitySchedule {
    /// Shape of the change.
    pub profile: GravityProfile,
    /// g1, the value before and at t1, m/s².
    pub start_value: f64,
    /// g2, the value from t2 on, m/s².
    pub end_value: f64,
    /// [t1, t2] over which g changes (`G_TIME`, default (0, 1)).
    pub window: TimeWindow,
    /// p1, the number of steps (gc2d default 5); 0 counts as 1.
    pub steps: u32,
    /// p2, the ramp's share of each step in [0, 1] (gc2d default 0.5); values outside are clamped.
    pub ramp_fraction: f64,
}

impl Default for GravitySchedule {
    /// gc2d's default: a constant 9.81 m/s².
    fn default() -> Self {
        Self::constant(9.81)
    }
}

impl GravitySchedule {
    /// A constant g with gc2d's defaults for the unused parameters.
    pub fn constant(g: f64) -> Self {
        Self {
            profile: GravityProfile::Constant,
            start_value: g,
            end_value: g,
            window: TimeWindow::new(0.0, 1.0),
            steps: 5,
            ramp_fraction: 0.5,
        }
    }

    /// True when g never changes, so the engine can compute the gravity forces once.
    pub fn is_constant(&self) -> bool {
        self.profile == GravityProfile::Constant || self.start_value == self.end_value
    }

    /// g(t), m/s².
    pub fn magnitude(&self, t: f64) -> f64 {
        let (g1, g2) = (self.start_value, self.end_value);
        let progress = self.window.progress(t);
        let steps = f64::from(self.steps.max(1));
        let fraction_done = match self.profile {
            GravityProfile::Constant => return g1,
            GravityProfile::Linear => progress,
            GravityProfile::Step => (progress * steps).floor() / steps,
            GravityProfile::SmoothStep => {
                let position = progress * steps;
                let whole_steps = position.floor();
                let within_step = position - whole_steps;
                let ramp = self.ramp_fraction.clamp(0.0, 1.0);
                let plateau = 1.0 - ramp;
                let ramp_done = if within_step > plateau { (within_step - plateau) / ramp } else { 0.0 };
                (whole_steps + ramp_done) / steps
            }
        };
        g1 + (g2 - g1) * fraction_done
    }

    /// The gravitational acceleration vector (0, −g(t)).
    #[inline]
    pub fn acceleration(&self, t: f64) -> DVec2 {
        DVec2::new(0.0, -self.magnitude(t))
    }
}

/// Global heating: the uniform size factor s(t) of every particle, eqs. (B.1)/(B.2) (reference §1.6).
///
/// s(t) = 1 + a·(½ − ½·tanh(S·cos(2πf·t_c))) with t_c the time clamped to the window. s swings between
/// 1 + a·(½ − ½ tanh S) ≈ 1 and 1 + a·(½ + ½ tanh S) ≈ 1 + a; larger S gives a squarer wave. Before the window s is
/// frozen at s(t1), which for t1 = k/f is the lower value, not exactly 1 (by a·(½ − ½ tanh S), 3.4e-4·a for S = 4).
///
/// Mass stays constant as the particle grows (D8): the material expands and its area density drops as 1/s², as the
/// thesis says of thermal expansion ("area and density change", §2.3.1). The moment of inertia about the centroid
/// then scales as s² (see [`HeatingSchedule::inertia_factor`]). Keeping mass fixed conserves mass and momentum and
/// keeps the energy ledger closed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct HeatingSchedule {
    /// [t1, t2] during which the temperature cycles (`HEAT_TIME`, default (∞, ∞): never).
    pub window: TimeWindow,
    /// a, the relative size change (`HEAT_AMPLITUDE`, default 0.01); negative values cool.
    pub amplitude: f64,
    /// f, 1/s (`HEAT_FREQUENCE`, default 1).
    pub frequency: f64,
    /// S, the steepness of the switch between cold and hot (`HEAT_SLOPE`, default [`HeatingSchedule::DEFAULT_SLOPE`]).
    pub slope: f64,
}

impl Default for HeatingSchedule {
    /// gc2d's defaults, with the illegible slope default replaced by [`HeatingSchedule::DEFAULT_SLOPE`].
    fn default() -> Self {
        Self {
            window: TimeWindow::new(f64::INFINITY, f64::INFINITY),
            amplitude: 0.01,
            frequency: 1.0,
            slope: Self::DEFAULT_SLOPE,
        }
    }
}

impl HeatingSchedule {
    /// S = 4, for gc2d's illegible `HEAT_SLOPE` default (erratum E26). It is the middle of the three slopes the
    /// thesis plots (Abb. B.2: 2, 4, 8): the swing reaches tanh 4 = 99.93 % of a, while the switch still takes
    /// about a tenth of a period, so the expansion rate stays bounded by a·π·f·S.
    pub const DEFAULT_SLOPE: f64 = 4.0;

    /// The phase angle 2πf·t_c, or `None` when it is not finite (e.g. the default window at ∞: no heating).
    #[inline]
    fn phase_angle(&self, t: f64) -> Option<f64> {
        let angle = TAU * self.frequency * self.window.clamp(t);
        angle.is_finite().then_some(angle)
    }

    /// s(t), eq. (B.2); exactly 1 when the phase or the result is not finite.
    pub fn scale(&self, t: f64) -> f64 {
        let scale = self
            .phase_angle(t)
            .map_or(1.0, |angle| 1.0 + self.amplitude * (0.5 - 0.5 * (self.slope * angle.cos()).tanh()));
        if scale.is_finite() { scale } else { 1.0 }
    }

    /// ds/dt = a·π·f·S·sin(2πft)·sech²(S·cos(2πft)) inside the window, 0 outside: the rate at which particle
    /// vertices move away from their centroids (v = ṡ/s · (vertex − centroid)).
    pub fn scale_rate(&self, t: f64) -> f64 {
        if !self.window.is_active(t) {
            return 0.0;
        }
        let rate = self.phase_angle(t).map_or(0.0, |angle| {
            let (sin, cos) = angle.sin_cos();
            let sech = 1.0 / (self.slope * cos).cosh();
            self.amplitude * 0.5 * TAU * self.frequency * self.slope * sin * sech * sech
        });
        if rate.is_finite() { rate } else { 0.0 }
    }

    /// The factor I(s)/I(1) = s² by which a particle's moment of inertia scales at size factor `s` (D8: the mass
    /// is kept, every length scales by s). The mass factor is 1.
    #[inline]
    pub fn inertia_factor(scale: f64) -> f64 {
        scale * scale
    }
}

/// A spring from a point of one particle to a pulling point that moves along a straight line ("Teilchen mit Feder",
/// reference §2.12, `DRAG_*` commands).
///
/// Decisions (D5): rest length 0, so the force on the particle is F = K·(p_pull − p_fix); no damping (gc2d names
/// none); the fixing point is given in the particle's body frame and turns (and scales, through the pose) with the
/// particle, the "massless rod" of §2.12; the pulling point is in absolute world coordinates; `direction_angle` is
/// counter-clockwise from +x like every direction in gc2d-rs, and the gsi importer passes `DRAG_ANGLE` through
/// unchanged (it is a direction, not a clockwise particle angle).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DragSpring {
    /// K, N/m (`DRAG_K`, default 100).
    pub stiffness: f64,
    /// Attachment point relative to the centroid in the body frame, m (`DRAG_FIXING_POINT`, default (0, 0)).
    pub fixing_point: DVec2,
    /// Position of the pulling point up to t1, world coordinates, m (`DRAG_PULLING_POINT`, default (0, 0)).
    pub pulling_start: DVec2,
    /// Direction of the pulling point's travel, radians CCW from +x (`DRAG_ANGLE`, default 0).
    pub direction_angle: f64,
    /// Speed of the pulling point inside the window, m/s (`DRAG_VELOCITY`, default 0.1).
    pub speed: f64,
    /// [t1, t2] during which the pulling point moves (`DRAG_TIME`, default (0, 1)); it rests before and after.
    pub window: TimeWindow,
}

impl Default for DragSpring {
    /// gc2d's defaults: K = 100 N/m, both points at the origin, direction 0, 0.1 m/s during (0, 1) s.
    fn default() -> Self {
        Self {
            stiffness: 100.0,
            fixing_point: DVec2::ZERO,
            pulling_start: DVec2::ZERO,
            direction_angle: 0.0,
            speed: 0.1,
            window: TimeWindow::new(0.0, 1.0),
        }
    }
}

impl DragSpring {
    /// Unit vector of the pulling point's travel.
    #[inline]
    pub fn direction(&self) -> DVec2 {
        DVec2::from_angle(self.direction_angle)
    }

    /// Where the pulling point is at time `t`: p0 + v·(t_c − t1)·direction.
    #[inline]
    pub fn pulling_point(&self, t: f64) -> DVec2 {
        self.pulling_start + self.speed * self.window.elapsed(t) * self.direction()
    }

    /// The pulling point's velocity: v·direction inside the window, zero outside.
    #[inline]
    pub fn pulling_velocity(&self, t: f64) -> DVec2 {
        if self.window.is_active(t) { self.speed * self.direction() } else { DVec2::ZERO }
    }

    /// The fixing point in world coordinates for a particle at `particle_pose`.
    #[inline]
    pub fn fixing_point_world(&self, particle_pose: Pose) -> DVec2 {
        particle_pose.apply(self.fixing_point)
    }

    /// The spring's extension p_pull − p_fix.
    #[inline]
    fn extension(&self, particle_pose: Pose, t: f64) -> DVec2 {
        self.pulling_point(t) - self.fixing_point_world(particle_pose)
    }

    /// The force on the particle, K·(p_pull − p_fix), and its torque about the centroid, r × F with r the lever from
    /// the centroid to the fixing point (CCW positive).
    #[inline]
    pub fn force_and_torque(&self, particle_pose: Pose, t: f64) -> (DVec2, f64) {
        let lever = self.fixing_point_world(particle_pose) - particle_pose.position;
        let force = self.stiffness * self.extension(particle_pose, t);
        (force, cross(lever, force))
    }

    /// Elastic energy stored in the spring, ½·K·|p_pull − p_fix|², J per unit thickness.
    #[inline]
    pub fn stored_energy(&self, particle_pose: Pose, t: f64) -> f64 {
        0.5 * self.stiffness * self.extension(particle_pose, t).length_squared()
    }

    /// Power fed into the system by whatever drives the pulling point, F·v_pull, W per unit thickness. The energy
    /// balance is d(stored)/dt = driving power − F·v_fix, the last term being the power the particle receives.
    #[inline]
    pub fn driving_power(&self, particle_pose: Pose, t: f64) -> f64 {
        self.stiffness * self.extension(particle_pose, t).dot(self.pulling_velocity(t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use std::f64::consts::FRAC_PI_4;

    /// Abb. B.1's schedule: G 9.81 9.0, G_TIME 0.1 1.1, with `steps` and `ramp_fraction` as given.
    fn figure_b1(profile: GravityProfile, steps: u32, ramp_fraction: f64) -> GravitySchedule {
        GravitySchedule {
            profile,
            start_value: 9.81,
            end_value: 9.0,
            window: TimeWindow::new(0.1, 1.1),
            steps,
            ramp_fraction,
        }
    }

    #[test]
    fn gravity_profiles_at_chosen_times() {
        let constant = figure_b1(GravityProfile::Constant, 5, 0.2);
        assert_eq!([constant.magnitude(0.0), constant.magnitude(0.6), constant.magnitude(9.0)], [9.81; 3]);
        assert!(constant.is_constant() && GravitySchedule::default().is_constant());

        let linear = figure_b1(GravityProfile::Linear, 5, 0.2);
        assert_eq!(linear.magnitude(0.0), 9.81);
        assert_relative_eq!(linear.magnitude(0.35), 9.81 - 0.81 * 0.25, epsilon = 1e-12);
        assert_eq!(linear.magnitude(1.1), 9.0);
        assert_eq!(linear.magnitude(50.0), 9.0);
        assert!(!linear.is_constant());

        // Five steps of −0.162 at t = 0.3, 0.5, 0.7, 0.9, 1.1.
        let step = figure_b1(GravityProfile::Step, 5, 0.2);
        for (t, steps_done) in [(0.1, 0.0), (0.29, 0.0), (0.31, 1.0), (0.65, 2.0), (1.09, 4.0), (1.1, 5.0), (3.0, 5.0)]
        {
            assert_relative_eq!(step.magnitude(t), 9.81 - 0.162 * steps_done, epsilon = 1e-12);
        }

        // Ramps over the last fifth of each step: 0.26..0.30, 0.46..0.50, ...
        let smooth = figure_b1(GravityProfile::SmoothStep, 5, 0.2);
        for (t, steps_done) in
            [(0.25, 0.0), (0.28, 0.5), (0.30, 1.0), (0.4, 1.0), (0.47, 1.25), (1.08, 4.5), (1.1, 5.0)]
        {
            assert_relative_eq!(smooth.magnitude(t), 9.81 - 0.162 * steps_done, epsilon = 1e-12);
        }
        assert_eq!(smooth.acceleration(2.0), DVec2::new(0.0, -9.0));
    }

    #[test]
    fn smooth_step_limits_are_step_and_linear() {
        let times: Vec<f64> = (0..=1300).map(|i| -0.05 + 0.001 * i as f64).collect();
        for steps in [1, 3, 5] {
            let (step, linear) =
                (figure_b1(GravityProfile::Step, steps, 0.7), figure_b1(GravityProfile::Linear, 1, 0.0));
            let (sharp, full) =
                (figure_b1(GravityProfile::SmoothStep, steps, 0.0), figure_b1(GravityProfile::SmoothStep, steps, 1.0));
            for &t in &times {
                assert_eq!(sharp.magnitude(t), step.magnitude(t), "p2 = 0 at t = {t}");
                assert_relative_eq!(full.magnitude(t), linear.magnitude(t), epsilon = 1e-12);
            }
        }
        // Zero steps count as one, and a parameter outside [0, 1] is clamped.
        assert_eq!(figure_b1(GravityProfile::Step, 0, 0.0).magnitude(0.9), 9.81);
        assert_relative_eq!(figure_b1(GravityProfile::SmoothStep, 1, 3.0).magnitude(0.6), 9.405, epsilon = 1e-12);
    }

    #[test]
    fn gravity_type_names_follow_gc2d() {
        let profiles =
            [GravityProfile::Constant, GravityProfile::Linear, GravityProfile::Step, GravityProfile::SmoothStep];
        for (name, profile) in GravityProfile::GC2D_NAMES.iter().zip(profiles) {
            assert_eq!(name.parse::<GravityProfile>(), Ok(profile));
        }
        assert_eq!("smooth_step".parse::<GravityProfile>(), Ok(GravityProfile::SmoothStep));
        let error = "RAMP".parse::<GravityProfile>().unwrap_err().to_string();
        assert!(GravityProfile::GC2D_NAMES.iter().all(|name| error.contains(name)), "{error}");
    }

    fn heating(slope: f64) -> HeatingSchedule {
        HeatingSchedule { window: TimeWindow::new(0.0, 10.0), amplitude: 0.3, frequency: 3.0, slope }
    }

    #[test]
    fn heating_stays_between_one_and_one_plus_a() {
        for slope in [0.5, 2.0, 4.0, 8.0, 40.0] {
            let schedule = heating(slope);
            let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
            for i in 0..2000 {
                let s = schedule.scale(0.0005 * i as f64);
                (low, high) = (low.min(s), high.max(s));
            }
            assert!(low >= 1.0 && high <= 1.3, "S = {slope}: [{low}, {high}]");
            // The extremes sit at cos = ±1: 1 + a(½ ∓ ½ tanh S).
            assert_relative_eq!(low, 1.0 + 0.3 * (0.5 - 0.5 * slope.tanh()), epsilon = 1e-12);
            assert_relative_eq!(high, 1.0 + 0.3 * (0.5 + 0.5 * slope.tanh()), epsilon = 1e-12);
        }
    }

    #[test]
    fn large_slope_gives_a_square_wave() {
        // f = 3: cold (s = 1) while cos(6πt) > 0, hot (s = 1 + a) while it is negative; switches at t = 1/12, 3/12.
        let schedule = heating(200.0);
        for (t, expected) in [(0.02, 1.0), (0.07, 1.0), (0.1, 1.3), (0.16, 1.3), (0.24, 1.3), (0.26, 1.0), (0.32, 1.0)]
        {
            assert_relative_eq!(schedule.scale(t), expected, epsilon = 1e-12);
        }
        assert_relative_eq!(schedule.scale(1.0 / 12.0), 1.15, epsilon = 1e-9);
    }

    #[test]
    fn heating_rate_is_the_derivative_and_the_window_freezes_s() {
        let schedule = heating(4.0);
        for t in [0.013, 0.05, 0.0833, 0.11, 0.29] {
            let h = 1e-7;
            let difference = (schedule.scale(t + h) - schedule.scale(t - h)) / (2.0 * h);
            assert_relative_eq!(schedule.scale_rate(t), difference, epsilon = 1e-6);
        }
        let windowed = HeatingSchedule { window: TimeWindow::new(0.5, 0.6), ..schedule };
        assert_eq!(windowed.scale(0.1), windowed.scale(0.5));
        assert_eq!(windowed.scale(7.0), windowed.scale(0.6));
        assert_eq!((windowed.scale_rate(0.1), windowed.scale_rate(7.0)), (0.0, 0.0));
        assert_eq!(HeatingSchedule::default().scale(12.0), 1.0);
        assert_eq!(HeatingSchedule { slope: f64::NAN, ..schedule }.scale(0.2), 1.0);
        assert_eq!(HeatingSchedule::inertia_factor(1.1), 1.1 * 1.1);
    }

    /// The B.1.4.2 example: particle at (0.1, 0.1), rod to (0.2, 0.1) from the centroid, pulled from (0.5, 0.3) at
    /// 1 m/s and π/4 during [1, 2] s, K = 100 N/m.
    fn example_spring() -> DragSpring {
        DragSpring {
            stiffness: 100.0,
            fixing_point: DVec2::new(0.2, 0.1),
            pulling_start: DVec2::new(0.5, 0.3),
            direction_angle: FRAC_PI_4,
            speed: 1.0,
            window: TimeWindow::new(1.0, 2.0),
        }
    }

    #[test]
    fn pulling_point_moves_only_inside_its_window() {
        let spring = example_spring();
        let diagonal = DVec2::splat(0.5f64.sqrt());
        assert_eq!(spring.pulling_point(0.5), DVec2::new(0.5, 0.3));
        assert_eq!(spring.pulling_velocity(0.5), DVec2::ZERO);
        assert_relative_eq!(spring.pulling_point(1.25), DVec2::new(0.5, 0.3) + 0.25 * diagonal, epsilon = 1e-15);
        assert_relative_eq!(spring.pulling_velocity(1.25), diagonal, epsilon = 1e-15);
        assert_relative_eq!(spring.pulling_point(3.0), DVec2::new(0.5, 0.3) + diagonal, epsilon = 1e-15);
        assert_eq!(spring.pulling_velocity(3.0), DVec2::ZERO);
    }

    #[test]
    fn spring_force_and_torque_on_a_turned_particle() {
        let spring = example_spring();
        // Unturned, as in the example: the rod ends at (0.3, 0.2), 0.2 right and 0.1 up of the centroid.
        let pose = Pose::new(DVec2::new(0.1, 0.1), 0.0);
        let (force, torque) = spring.force_and_torque(pose, 0.0);
        assert_relative_eq!(force, 100.0 * DVec2::new(0.2, 0.1), epsilon = 1e-12);
        assert_relative_eq!(torque, 0.2 * 10.0 - 0.1 * 20.0, epsilon = 1e-12);

        // Turned a quarter CCW, the rod points to (−0.1, 0.2) from the centroid.
        let turned = Pose::new(DVec2::new(0.1, 0.1), std::f64::consts::FRAC_PI_2);
        let (force, torque) = spring.force_and_torque(turned, 0.0);
        let lever = DVec2::new(-0.1, 0.2);
        assert_relative_eq!(force, 100.0 * (DVec2::new(0.5, 0.3) - DVec2::new(0.1, 0.1) - lever), epsilon = 1e-12);
        assert_relative_eq!(torque, lever.x * force.y - lever.y * force.x, epsilon = 1e-12);
        assert_relative_eq!(spring.stored_energy(turned, 0.0), 0.5 * force.length_squared() / 100.0, epsilon = 1e-12);
    }

    #[test]
    fn spring_energy_changes_by_driving_power_minus_power_to_the_particle() {
        let spring = example_spring();
        // A particle moving and spinning along a prescribed path while the pulling point moves.
        let position = |t: f64| DVec2::new(0.1 + 0.3 * t, 0.1 - 0.2 * t * t);
        let velocity = |t: f64| DVec2::new(0.3, -0.4 * t);
        let (angle, omega) = (|t: f64| 0.2 + 1.5 * t, 1.5);
        let pose_at = |t: f64| Pose::new(position(t), angle(t));
        for t in [1.2, 1.5, 1.9] {
            let h = 1e-6;
            let energy_rate =
                (spring.stored_energy(pose_at(t + h), t + h) - spring.stored_energy(pose_at(t - h), t - h)) / (2.0 * h);
            let (force, torque) = spring.force_and_torque(pose_at(t), t);
            let power_to_particle = force.dot(velocity(t)) + torque * omega;
            let balance = spring.driving_power(pose_at(t), t) - power_to_particle;
            assert_relative_eq!(energy_rate, balance, epsilon = 1e-7);
            assert!(spring.driving_power(pose_at(t), t).abs() > 1.0, "the check exercises the driving term");
        }
    }
}
