//! The composed penetration law and its single entry point, [`PenetrationLaw::evaluate`].

use super::spring::{SpringStep, spring_step};
use super::{
    NormalSpring, PairProperties, PenetrationDamping, PenetrationGeometry, PenetrationState, RollingResistance,
    TangentialSpring,
};
use crate::{BodyMotion, EnergyTerms};
use gc2d_geometry::{DVec2, cross};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// A contact law for disks (spheres moving in a plane) driven by the penetration depth δ, assembled from
/// sub-models that all read one [`PenetrationGeometry`] and one [`PairProperties`]. A `None` sub-model is switched
/// off and costs one branch.
///
/// - normal: [`NormalSpring`] (linear or Hertz), always present;
/// - `damping`: [`PenetrationDamping`], a dashpot 2D·√(m*·k_n(δ)) with D given or mapped from e or e(v);
/// - `tangential`: [`TangentialSpring`], Cundall–Strack or Mindlin stiffness with Coulomb cap and dashpot;
/// - `rolling`: [`RollingResistance`], a capped rotational spring–dashpot;
/// - `tensile_clamp`: whether the total normal force is floored at 0.
///
/// The thesis has no clamp (feedpipe.md §2.3), so the laws built here default to `tensile_clamp: false`. The
/// restitution of [`PenetrationDamping::Restitution`] and [`PenetrationDamping::VelocityDependent`] is met either
/// way: the mapping e → D follows the flag (the unclamped one of feedpipe.md §2.4, or the clamped one of
/// [`crate::penetration::linear_clamped_restitution`]). A [`PenetrationDamping::DampingRatio`] D gives a higher e
/// with the clamp (by up to 0.16, feedpipe.md §2.4 table).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PenetrationLaw {
    /// The elastic normal force F(δ).
    pub normal: NormalSpring,
    /// Normal damping.
    pub damping: Option<PenetrationDamping>,
    /// Tangential spring, dashpot and Coulomb slider.
    pub tangential: Option<TangentialSpring>,
    /// Rolling resistance.
    pub rolling: Option<RollingResistance>,
    /// Floor the total normal force at 0: the contact exerts no force (normal, tangential or rolling) while the
    /// dashpot would make it pull. Off in the thesis and by default.
    #[serde(default)]
    pub tensile_clamp: bool,
}

/// A penetration-law parameter outside its range. `name` is the parameter's path in the law (as a scene would
/// spell it), e.g. `tangential.mu`.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum PenetrationLawError {
    /// A stiffness, modulus or offset that must be positive.
    #[error("{name} must be a positive finite number, got {value}")]
    NotPositive {
        /// The parameter.
        name: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// A coefficient that must be non-negative.
    #[error("{name} must be a non-negative finite number, got {value}")]
    Negative {
        /// The parameter.
        name: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// A number that must be finite.
    #[error("{name} must be a finite number, got {value}")]
    NotFinite {
        /// The parameter.
        name: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// A restitution coefficient outside [0, 1].
    #[error("{name} must lie in [0, 1], got {value}")]
    OutsideUnitInterval {
        /// The parameter.
        name: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// A restitution table needs 1 to 32 points.
    #[error("a restitution table needs 1 to 32 (speed, e) points, got {0}")]
    TableLength(usize),
    /// Table speeds must be finite, non-negative and strictly increasing.
    #[error("restitution table point {index}: the speed must be finite, >= 0 and above the previous one, got {value}")]
    TableSpeed {
        /// Index of the point, from 0.
        index: usize,
        /// The rejected speed, m/s.
        value: f64,
    },
    /// Table restitution values must lie in [0, 1].
    #[error("restitution table point {index}: e must lie in [0, 1], got {value}")]
    TableRestitution {
        /// Index of the point, from 0.
        index: usize,
        /// The rejected e.
        value: f64,
    },
}

/// Everything one evaluation of a penetration contact produces.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PenetrationResponse {
    /// Total contact force on body i, N; body j receives the opposite. It acts at the contact point.
    pub force_on_i: DVec2,
    /// Torque on body i about its centre of mass, r_i × F plus the rolling moment, N·m, counter-clockwise positive.
    pub torque_on_i: f64,
    /// Torque on body j about its centre of mass, r_j × (−F) minus the rolling moment, N·m.
    pub torque_on_j: f64,
    /// Total normal force on i along the normal, elastic + damping (after the clamp), N; positive = repulsive.
    pub normal_force: f64,
    /// Tangential force on i along the tangent, N.
    pub tangential_force: f64,
    /// Rolling moment on i, N·m (included in `torque_on_i`).
    pub rolling_moment: f64,
    /// Energy terms of the step. The rolling spring's terms are booked with the tangential ones: its energy change
    /// in `spring_change`, its dashpot in `tangential_damping`, its slip in `sliding`.
    pub energy: EnergyTerms,
    /// The history to pass to the next evaluation of this pair.
    pub state: PenetrationState,
}

impl PenetrationLaw {
    /// The purely elastic law with normal spring `normal`: no damping, friction or rolling resistance, no clamp.
    pub fn elastic(normal: NormalSpring) -> Self {
        Self { normal, damping: None, tangential: None, rolling: None, tensile_clamp: false }
    }

    /// Checks that every parameter lies in its range, naming the first one that does not.
    pub fn validate(&self) -> Result<(), PenetrationLawError> {
        use super::damping::positive;
        match self.normal {
            NormalSpring::Linear { stiffness_n_m } => positive("normal.stiffness_n_m", stiffness_n_m)?,
            NormalSpring::Hertz { effective_modulus_pa } => {
                positive("normal.effective_modulus_pa", effective_modulus_pa)?
            }
        }
        if let Some(damping) = &self.damping {
            damping.validate()?;
        }
        if let Some(tangential) = &self.tangential {
            tangential.validate()?;
        }
        if let Some(rolling) = &self.rolling {
            rolling.validate()?;
        }
        Ok(())
    }

    /// Energy stored in a contact with history `state` between a pair with properties `properties`, J:
    /// U(δ) + S²/(2k_t(δ)) + M²/(2k_r(δ)) at the stored depth. Summed over all contacts it is the contact term of the
    /// engine's energy ledger.
    pub fn stored_energy(&self, properties: &PairProperties, state: &PenetrationState) -> f64 {
        let (depth, radius) = (state.previous_depth, properties.effective_radius);
        let spring = |force: f64, stiffness: f64| {
            if stiffness > 0.0 { 0.5 * force * force / stiffness } else { 0.0 }
        };
        let tangential =
            self.tangential.map_or(0.0, |t| spring(state.spring, t.stiffness(&self.normal, depth, radius)));
        let rolling = self.rolling.map_or(0.0, |r| spring(state.rolling, r.stiffness(&self.normal, depth, radius)));
        self.normal.energy(depth, radius) + tangential + rolling
    }

    /// Evaluates one contact for one time step `dt`.
    ///
    /// `previous` is the state returned by the last evaluation of this pair (the default state for a new pair).
    /// The normal velocity and the sliding velocity are those of the contact points of `body_i` relative to
    /// `body_j`; the impact speed of the episode is the normal approach speed at the first touching step. A
    /// geometry that does not touch ends an active contact (it opens) and resets the state. Non-finite geometry
    /// gives no force; a non-positive or non-finite `dt` freezes the springs and books no rate terms.
    ///
    /// Normal force on i (feedpipe.md (3.34), (3.44)): F_n = F(δ) + c·v_approach with c = 2·D·√(m*·k_n(δ)), and
    /// with the tensile clamp F_n = max(F_n, 0). Energy terms of the step: the exact U(δ) − U(δ_old), the dashpot's
    /// F_d·v_approach·Δt (≥ 0), and the tangential and rolling terms of their capped springs.
    ///
    /// Always inlined, as [`crate::ContactLaw::evaluate`] is: the engine's pair evaluation is compiled twice (with and
    /// without heating), and left to itself the compiler then called this law out of line, 6 % more instructions a
    /// particle-step of a pile of disks (docs/performance.md, "Heating's work: what the others pay").
    #[inline(always)]
    pub fn evaluate(
        &self,
        geometry: &PenetrationGeometry,
        properties: &PairProperties,
        body_i: &BodyMotion,
        body_j: &BodyMotion,
        previous: &PenetrationState,
        dt: f64,
    ) -> PenetrationResponse {
        if !geometry.is_touching() {
            return self.separate(properties, previous);
        }
        let dt = if (dt > 0.0) & dt.is_finite() { dt } else { 0.0 };
        let (depth, radius, mass) = (geometry.depth, properties.effective_radius, properties.effective_mass);
        let normal = geometry.normal;
        // Relative velocity of the material contact points (the wall's virtual surface velocity acts only along the
        // tangent, below).
        let relative =
            material_point_velocity(body_i, geometry.arm_i) - material_point_velocity(body_j, geometry.arm_j);
        let approach_speed = -relative.dot(normal);

        let (impact_speed, damping_ratio) = if previous.is_touching() {
            (previous.impact_speed, previous.damping_ratio)
        } else {
            let impact = if approach_speed > 0.0 { approach_speed } else { 0.0 };
            (impact, self.damping.as_ref().map_or(0.0, |d| d.episode_ratio(impact, &self.normal, self.tensile_clamp)))
        };

        let elastic = self.normal.force(depth, radius);
        let stiffness = self.normal.secant_stiffness(depth, radius);
        let dashpot = 2.0 * damping_ratio * (mass * stiffness).sqrt() * approach_speed;
        let (normal_force, damping) = if self.tensile_clamp {
            let total = (elastic + dashpot).max(0.0);
            (total, total - elastic)
        } else {
            (elastic + dashpot, dashpot)
        };
        let load = normal_force.max(0.0);

        let previous_depth = previous.previous_depth;
        let tangent = geometry.tangent();
        let (tangential, surface_work) = match &self.tangential {
            Some(t) => {
                let k = t.stiffness(&self.normal, depth, radius);
                let k_old = t.stiffness(&self.normal, previous_depth, radius);
                let c = 2.0 * t.damping_ratio * (properties.tangential_mass * k).sqrt();
                let sliding_velocity = (relative + body_i.surface_velocity - body_j.surface_velocity).dot(tangent);
                let step = spring_step(previous.spring, k_old, k, sliding_velocity, dt, c, t.mu * load);
                let surface_slip = (body_j.surface_velocity - body_i.surface_velocity).dot(tangent);
                (step, step.force * surface_slip * dt)
            }
            None => (SpringStep::default(), 0.0),
        };
        let rolling = match &self.rolling {
            Some(r) => {
                let k = r.stiffness(&self.normal, depth, radius);
                let k_old = r.stiffness(&self.normal, previous_depth, radius);
                let c = 2.0 * r.damping_ratio * (properties.rolling_inertia * k).sqrt();
                let rate = body_i.angular_velocity - body_j.angular_velocity;
                spring_step(previous.rolling, k_old, k, rate, dt, c, r.mu_r * radius * load)
            }
            None => SpringStep::default(),
        };

        let force = normal_force * normal + tangential.force * tangent;
        PenetrationResponse {
            force_on_i: force,
            torque_on_i: cross(geometry.arm_i, force) + rolling.force,
            torque_on_j: -cross(geometry.arm_j, force) - rolling.force,
            normal_force,
            tangential_force: tangential.force,
            rolling_moment: rolling.force,
            energy: EnergyTerms {
                normal_elastic_change: self.normal.energy(depth, radius) - self.normal.energy(previous_depth, radius),
                spring_change: tangential.energy_change + rolling.energy_change,
                normal_damping: damping * approach_speed * dt,
                tangential_damping: tangential.damping_dissipation + rolling.damping_dissipation,
                sliding: tangential.slip_dissipation + rolling.slip_dissipation,
                surface_work,
                ..EnergyTerms::default()
            },
            state: PenetrationState {
                impact_speed,
                damping_ratio,
                previous_depth: depth,
                spring: tangential.stored,
                rolling: rolling.stored,
            },
        }
    }

    /// The response of a pair that does not (or no longer) touch: no force, a reset state and, if a contact was
    /// active, its last energy terms. The normal elastic energy U(δ_old) is returned to the motion as the overlap
    /// closes (the potential is exact, so nothing is left over); the springs' energies are dropped as the opening
    /// residual.
    fn separate(&self, properties: &PairProperties, previous: &PenetrationState) -> PenetrationResponse {
        if !previous.is_touching() {
            return PenetrationResponse::default();
        }
        let normal = self.normal.energy(previous.previous_depth, properties.effective_radius);
        let springs = self.stored_energy(properties, previous) - normal;
        PenetrationResponse {
            energy: EnergyTerms {
                normal_elastic_change: -normal,
                spring_change: -springs,
                opening_residual: springs,
                ..EnergyTerms::default()
            },
            ..PenetrationResponse::default()
        }
    }

    /// The largest depth a head-on impact at normal speed `max_speed` (m/s) reaches, undamped, m (see
    /// [`NormalSpring::max_depth`]).
    pub fn max_depth(&self, properties: &PairProperties, max_speed: f64) -> f64 {
        self.normal.max_depth(max_speed, properties.effective_mass, properties.effective_radius)
    }

    /// The largest normal tangent stiffness dF/dδ reached in impacts up to `max_speed` (m/s), N/m: k for the linear
    /// spring, 2·E*·√(R*·δ_max) for Hertz with δ_max = (15·m*·v²/(16·E*·√R*))^{2/5} (ballmill.md §7.4).
    pub fn max_stiffness(&self, properties: &PairProperties, max_speed: f64) -> f64 {
        let depth = self.max_depth(properties, max_speed);
        self.normal.tangent_stiffness(depth, properties.effective_radius)
    }

    /// The largest time step for this law and pair with impact speeds up to `max_speed` (m/s), s, or `None` when no
    /// mode has a positive finite stiffness and inertia.
    ///
    /// For each oscillator — normal (m*, the tangent stiffness of [`Self::max_stiffness`], damping ratio D up to
    /// [`PenetrationDamping::max_ratio`]), tangential (m_t, k_t at δ_max, D_t) and rolling (J*, k_r at δ_max, D_r) —
    /// with ω = √(k/m): the smaller of (π/10)/ω, a tenth of the undamped half period as the area law's bound
    /// (reference (2.9)), and half the stability limit of the explicit central-difference/Verlet scheme with a
    /// dashpot, (√(1 + D²) − D)/ω. The minimum over the modes is returned. For Hertz this is at least ten steps
    /// over the contact at `max_speed`, and more at lower speeds.
    pub fn max_time_step(&self, properties: &PairProperties, max_speed: f64) -> Option<f64> {
        let depth = self.max_depth(properties, max_speed);
        let radius = properties.effective_radius;
        let normal_ratio =
            self.damping.as_ref().map_or(0.0, |d| d.max_ratio(max_speed, &self.normal, self.tensile_clamp));
        let mut modes = [(properties.effective_mass, self.max_stiffness(properties, max_speed), normal_ratio); 3];
        if let Some(t) = &self.tangential {
            modes[1] = (properties.tangential_mass, t.stiffness(&self.normal, depth, radius), t.damping_ratio);
        }
        if let Some(r) = &self.rolling {
            modes[2] = (properties.rolling_inertia, r.stiffness(&self.normal, depth, radius), r.damping_ratio);
        }
        modes
            .iter()
            .filter(|(inertia, stiffness, _)| {
                *inertia > 0.0 && inertia.is_finite() && *stiffness > 0.0 && stiffness.is_finite()
            })
            .map(|&(inertia, stiffness, ratio)| {
                let period = (inertia / stiffness).sqrt();
                let ratio = ratio.max(0.0);
                (std::f64::consts::PI / 10.0 * period).min(((1.0 + ratio * ratio).sqrt() - ratio) * period)
            })
            .reduce(f64::min)
            .filter(|dt| *dt > 0.0 && dt.is_finite())
    }
}

/// Velocity of the material point at `arm` from the centre of mass, v + ω×r, without a wall's virtual surface
/// velocity (which acts only along the tangent).
#[inline]
fn material_point_velocity(body: &BodyMotion, arm: DVec2) -> DVec2 {
    body.velocity + body.angular_velocity * arm.perp()
}

#[cfg(test)]
mod tests;
