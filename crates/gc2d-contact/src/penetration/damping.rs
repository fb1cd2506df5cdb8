//! Normal damping of the penetration laws: a Lehr damping ratio, given directly or mapped from a restitution
//! coefficient that may depend on the impact speed (feedpipe.md §2.3, §2.4; ballmill.md §3.2, §7.3).

use super::{NormalSpring, PenetrationLawError};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Normal damping: a dashpot F_d = c·v_approach with c = 2·D·√(m*·k_n(δ)) (Lehr's damping ratio D; feedpipe.md
/// (3.43), (3.44)), k_n(δ) the secant stiffness of the [`NormalSpring`]. For the linear spring c is constant; for Hertz
/// c ∝ δ^{1/4}, the Tsuji et al. (1992) dashpot, whose restitution depends on D only (feedpipe.md §2.3).
///
/// D is fixed once per contact episode, at the first touching step, from the variant:
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[allow(
    clippy::large_enum_variant,
    reason = "the table is inline on purpose, to keep the law Copy; see RestitutionTable"
)]
pub enum PenetrationDamping {
    /// D given directly (the thesis input `#D`, feedpipe.md §2.3). D = 0 is undamped.
    DampingRatio(f64),
    /// A constant restitution coefficient e ∈ [0, 1], mapped to D by [`NormalSpring::damping_ratio_for`]: exact for
    /// the linear spring and for Hertz + δ^{1/4} dashpot, with or without the law's tensile clamp (feedpipe.md
    /// §2.4 for the unclamped mapping; the clamped one is derived in [`linear_clamped_restitution`]).
    Restitution(f64),
    /// e(v) evaluated at the impact normal speed stored at the first touching step, mapped to D for the whole
    /// episode (ballmill.md §7.3).
    VelocityDependent(ImpactLaw),
}

impl PenetrationDamping {
    /// The damping ratio D of an episode whose impact normal speed is `impact_speed` (m/s), with normal spring
    /// `spring`, for a law with or without `tensile_clamp`.
    pub fn episode_ratio(&self, impact_speed: f64, spring: &NormalSpring, tensile_clamp: bool) -> f64 {
        match self {
            Self::DampingRatio(ratio) => *ratio,
            Self::Restitution(e) => spring.damping_ratio_for(*e, tensile_clamp),
            Self::VelocityDependent(law) => spring.damping_ratio_for(law.restitution(impact_speed), tensile_clamp),
        }
    }

    /// The largest damping ratio an episode can get with impact speeds up to `max_speed` (m/s): for the time-step
    /// bound (damping lowers the stable step). Tables are searched at their points and at `max_speed`; the power laws
    /// fall with speed for c ≥ 0, and are searched at 0 and `max_speed` otherwise.
    pub fn max_ratio(&self, max_speed: f64, spring: &NormalSpring, tensile_clamp: bool) -> f64 {
        let at = |speed: f64| self.episode_ratio(speed, spring, tensile_clamp);
        match self {
            Self::VelocityDependent(ImpactLaw::Table(table)) => table
                .points()
                .iter()
                .filter(|(speed, _)| *speed <= max_speed)
                .map(|(speed, _)| at(*speed))
                .fold(at(max_speed).max(at(0.0)), f64::max),
            _ => at(0.0).max(at(max_speed)),
        }
    }

    /// Checks the parameters, naming the first one out of range.
    pub fn validate(&self) -> Result<(), PenetrationLawError> {
        match self {
            Self::DampingRatio(ratio) => non_negative("damping.damping_ratio", *ratio),
            Self::Restitution(e) => unit_interval("damping.restitution", *e),
            Self::VelocityDependent(law) => law.validate(),
        }
    }
}

/// A restitution coefficient as a function of the impact normal speed v (m/s). Every variant is clipped to
/// [0, 1], so e(v) ≤ 1 even where a fitted formula exceeds 1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[allow(
    clippy::large_enum_variant,
    reason = "the table is inline on purpose, to keep the law Copy; see RestitutionTable"
)]
pub enum ImpactLaw {
    /// Reichardt's steel ball on steel plate fit, e = 0.985/(v + 0.9494)^0.291 (ballmill.md (7-2), Spahn et al.
    /// form (6-7); measured 0–50 m/s; e(0) = 1.0000).
    SteelReichardt,
    /// Spahn et al. (1997) form e = a/(v + b)^c (ballmill.md (6-7)); b > 0.
    PowerLaw {
        /// Prefactor a.
        a: f64,
        /// Speed offset b, m/s.
        b: f64,
        /// Exponent c.
        c: f64,
    },
    /// Measured points, interpolated linearly in v and constant beyond the first and last point.
    Table(RestitutionTable),
}

impl ImpactLaw {
    /// The constants (a, b, c) of [`ImpactLaw::SteelReichardt`] (ballmill.md (7-2)).
    pub const STEEL_REICHARDT: (f64, f64, f64) = (0.985, 0.9494, 0.291);

    /// e(v) ∈ [0, 1] at impact normal speed `speed` (m/s; negative speeds count as 0).
    pub fn restitution(&self, speed: f64) -> f64 {
        let speed = if speed > 0.0 { speed } else { 0.0 };
        let e = match self {
            Self::SteelReichardt => {
                let (a, b, c) = Self::STEEL_REICHARDT;
                a / (speed + b).powf(c)
            }
            Self::PowerLaw { a, b, c } => a / (speed + b).powf(*c),
            Self::Table(table) => table.restitution(speed),
        };
        if e.is_nan() { 1.0 } else { e.clamp(0.0, 1.0) }
    }

    /// Checks the parameters, naming the first one out of range (a table is checked when it is built).
    pub fn validate(&self) -> Result<(), PenetrationLawError> {
        match *self {
            Self::PowerLaw { a, b, c } => {
                non_negative("damping.power_law.a", a)?;
                positive("damping.power_law.b", b)?;
                finite("damping.power_law.c", c)
            }
            _ => Ok(()),
        }
    }
}

/// Points (v_k, e_k) of a measured e(v), at most [`RestitutionTable::CAPACITY`] of them, in a fixed-capacity array.
///
/// The array keeps the table — and with it [`ImpactLaw`] and the whole [`super::PenetrationLaw`] — `Copy`, free of
/// heap allocation and pointer chasing, like the area law. The price is a law of about 0.5 kB, copied only when a
/// scene is built. Cost does not matter much either way: e(v) is evaluated once per contact episode (at the first
/// touching step), not per step. Thirty-two points hold e.g. the 17 tabulated values of ballmill.md §3.7.
///
/// Serialised as a list of `(speed, e)` pairs; deserialising checks it like [`RestitutionTable::new`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "Vec<(f64, f64)>", into = "Vec<(f64, f64)>")]
pub struct RestitutionTable {
    points: [(f64, f64); RestitutionTable::CAPACITY],
    len: usize,
}

impl RestitutionTable {
    /// The largest number of points.
    pub const CAPACITY: usize = 32;

    /// A table of `points` (speed in m/s, e): 1 to [`Self::CAPACITY`] points, speeds finite, ≥ 0 and strictly
    /// increasing, every e in [0, 1].
    pub fn new(points: &[(f64, f64)]) -> Result<Self, PenetrationLawError> {
        if points.is_empty() || points.len() > Self::CAPACITY {
            return Err(PenetrationLawError::TableLength(points.len()));
        }
        let mut previous = -1.0;
        for (index, &(speed, e)) in points.iter().enumerate() {
            if !(speed.is_finite() && speed >= 0.0 && speed > previous) {
                return Err(PenetrationLawError::TableSpeed { index, value: speed });
            }
            if !(0.0..=1.0).contains(&e) {
                return Err(PenetrationLawError::TableRestitution { index, value: e });
            }
            previous = speed;
        }
        let mut table = Self { points: [(0.0, 0.0); Self::CAPACITY], len: points.len() };
        table.points[..points.len()].copy_from_slice(points);
        Ok(table)
    }

    /// The points, in increasing speed.
    pub fn points(&self) -> &[(f64, f64)] {
        &self.points[..self.len]
    }

    /// e at speed `speed` (m/s): linear between neighbouring points, the end values beyond the ends.
    pub fn restitution(&self, speed: f64) -> f64 {
        let points = self.points();
        let (first, last) = (points[0], points[points.len() - 1]);
        if speed <= first.0 {
            return first.1;
        }
        if speed >= last.0 {
            return last.1;
        }
        // The first point above `speed` exists and is not the first one.
        let upper = points.partition_point(|(v, _)| *v <= speed);
        let ((v0, e0), (v1, e1)) = (points[upper - 1], points[upper]);
        e0 + (e1 - e0) * (speed - v0) / (v1 - v0)
    }
}

impl TryFrom<Vec<(f64, f64)>> for RestitutionTable {
    type Error = PenetrationLawError;
    fn try_from(points: Vec<(f64, f64)>) -> Result<Self, Self::Error> {
        Self::new(&points)
    }
}

impl From<RestitutionTable> for Vec<(f64, f64)> {
    fn from(table: RestitutionTable) -> Self {
        table.points().to_vec()
    }
}

/// The damping ratio of a linear spring–dashpot with restitution `e`: D = −ln e/√(π² + ln² e) (feedpipe.md (3.78)
/// simplified, §2.4). Exact when the contact ends at zero overlap and the force is not clamped. e is clipped to
/// [0, 1]; e = 0 gives D = 1 (critical damping).
pub fn linear_damping_ratio(e: f64) -> f64 {
    let e = e.clamp(0.0, 1.0);
    if e <= 0.0 {
        return 1.0;
    }
    let log = -e.ln();
    log / (PI * PI + log * log).sqrt()
}

/// The restitution of a linear spring–dashpot with damping ratio `ratio`: e = exp(−π·D/√(1 − D²)), 0 for D ≥ 1
/// (the inverse of [`linear_damping_ratio`]; feedpipe.md §2.4).
pub fn linear_restitution(ratio: f64) -> f64 {
    if ratio >= 1.0 {
        return 0.0;
    }
    let ratio = ratio.max(0.0);
    (-PI * ratio / (1.0 - ratio * ratio).sqrt()).exp()
}

/// √5/2: the factor between the damping ratio a Hertz spring with the δ^{1/4} dashpot needs and the one a linear
/// spring needs for the same restitution (feedpipe.md §2.4, §7.1 item 3). It is exact, with or without the tensile
/// clamp:
///
/// In units where m* = k_Hz = v₀ = 1 the impact is ẍ + 2D·x^{1/4}·ẋ + x^{3/2} = 0 (feedpipe.md (3.34), (3.44)). With
/// the time change dt = x^{−1/4}·ds and x = y^{4/5} it becomes the *linear* oscillator y'' + 2D·y' + (5/4)·y = 0,
/// whose damping ratio is D' = D/√(5/4) = 2D/√5. Because ẋ = (4/5)·y', x and y start and end at 0 together, and
/// ẍ = (4/5)·y^{1/5}·y'' (the force vanishes exactly when the linear oscillator's force does), e(D) of the Hertz
/// model is the linear e(2D/√5), unclamped and clamped. (Derived for this crate; feedpipe.md §2.4 found the factor
/// numerically.)
pub const HERTZ_DAMPING_FACTOR: f64 = 1.118_033_988_749_895;

/// The damping ratio of the Hertz spring with the Tsuji δ^{1/4} dashpot (c = 2D·√(m*·k_Hz)·δ^{1/4}) for restitution
/// `e`: D = (√5/2)·(−ln e)/√(π² + ln² e) (feedpipe.md §2.4), without clamp. Exact (see [`HERTZ_DAMPING_FACTOR`]);
/// a fourth-order integration of the dimensionless impact realises the target to |Δe| < 1e-14 for
/// e ∈ [0.01, 0.999] (test `hertz_restitution_mapping_is_exact`).
pub fn hertz_damping_ratio(e: f64) -> f64 {
    HERTZ_DAMPING_FACTOR * linear_damping_ratio(e)
}

/// The restitution of the Hertz spring with the δ^{1/4} dashpot and damping ratio `ratio`, the inverse of
/// [`hertz_damping_ratio`]: e = exp(−π·D'/√(1 − D'²)) with D' = 2D/√5; 0 for D ≥ √5/2.
pub fn hertz_restitution(ratio: f64) -> f64 {
    linear_restitution(ratio / HERTZ_DAMPING_FACTOR)
}

/// The restitution of a linear spring–dashpot whose total force is clamped at 0 (the contact ends when the force
/// would pull), for damping ratio `ratio` D:
///
/// e = exp(−D·ω₀·t_s) with ω₀·t_s = 2·acos(D)/√(1 − D²) for D < 1, 2 for D = 1, 2·acosh(D)/√(D² − 1) for D > 1.
///
/// Derivation (this crate, checked by the tests against feedpipe.md §2.4's clamped table and against integration):
/// with x(t) = (v₀/ω)·e^{−βt}·sin ωt (β = D·ω₀, ω = ω₀√(1 − D²)) the force k·x + c·ẋ vanishes where
/// tan ωt = −2βω/(ω² − β²), i.e. ωt_s = π − 2·asin D, and there ẋ = −v₀·e^{−βt_s} exactly; the overdamped case is the
/// same with sinh. Compare the unclamped e = exp(−π·D/√(1 − D²)). e < 1/D² for D > 1 and e → 1/(4D²): every e > 0
/// is reached.
pub fn linear_clamped_restitution(ratio: f64) -> f64 {
    let d = ratio.max(0.0);
    let time = if d < 1.0 {
        2.0 * d.acos() / (1.0 - d * d).sqrt()
    } else if d > 1.0 {
        2.0 * d.acosh() / (d * d - 1.0).sqrt()
    } else {
        2.0
    };
    (-d * time).exp()
}

/// The smallest restitution the clamped mappings aim at: below it the damping ratio (≈ 1/(2√e)) would make the
/// dashpot, and the time step, unreasonable. Smaller targets give this e.
pub const MIN_CLAMPED_RESTITUTION: f64 = 1e-3;

/// The damping ratio of a clamped linear spring–dashpot with restitution `e`, the inverse of
/// [`linear_clamped_restitution`] (by bisection, 64 halvings: about 1 µs, once per contact episode). e is clipped to
/// [[`MIN_CLAMPED_RESTITUTION`], 1].
pub fn linear_clamped_damping_ratio(e: f64) -> f64 {
    if e >= 1.0 || e.is_nan() {
        return 0.0;
    }
    let e = e.max(MIN_CLAMPED_RESTITUTION);
    // e(D) falls monotonically, e(1) = e^{−2} and e(D) < 1/D² above 1, so [0, max(1, 1/√e)] brackets the root.
    let (mut lo, mut hi) = (0.0, (1.0 / e.sqrt()).max(1.0));
    for _ in 0..64 {
        let mid = 0.5 * (lo + hi);
        if linear_clamped_restitution(mid) > e { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}

/// The restitution of the Hertz spring with the δ^{1/4} dashpot and the tensile clamp, damping ratio `ratio`:
/// [`linear_clamped_restitution`] of 2D/√5, exactly (see [`HERTZ_DAMPING_FACTOR`]; checked against integration to
/// 1e-8 in the tests, and it reproduces feedpipe.md §2.4's "Hertz, clamp" column).
pub fn hertz_clamped_restitution(ratio: f64) -> f64 {
    linear_clamped_restitution(ratio / HERTZ_DAMPING_FACTOR)
}

/// The damping ratio of the clamped Hertz spring with the δ^{1/4} dashpot for restitution `e`, the inverse of
/// [`hertz_clamped_restitution`].
pub fn hertz_clamped_damping_ratio(e: f64) -> f64 {
    HERTZ_DAMPING_FACTOR * linear_clamped_damping_ratio(e)
}

impl NormalSpring {
    /// The damping ratio D that gives restitution `e` (clipped to [0, 1]) with this spring, for a law with or
    /// without `tensile_clamp`: [`linear_damping_ratio`], [`hertz_damping_ratio`], [`linear_clamped_damping_ratio`]
    /// or [`hertz_clamped_damping_ratio`].
    pub fn damping_ratio_for(&self, e: f64, tensile_clamp: bool) -> f64 {
        match (self, tensile_clamp) {
            (Self::Linear { .. }, false) => linear_damping_ratio(e),
            (Self::Hertz { .. }, false) => hertz_damping_ratio(e),
            (Self::Linear { .. }, true) => linear_clamped_damping_ratio(e),
            (Self::Hertz { .. }, true) => hertz_clamped_damping_ratio(e),
        }
    }

    /// The restitution of a head-on impact with damping ratio `ratio`, with or without `tensile_clamp`: the inverse
    /// of [`Self::damping_ratio_for`].
    pub fn restitution_for(&self, ratio: f64, tensile_clamp: bool) -> f64 {
        match (self, tensile_clamp) {
            (Self::Linear { .. }, false) => linear_restitution(ratio),
            (Self::Hertz { .. }, false) => hertz_restitution(ratio),
            (Self::Linear { .. }, true) => linear_clamped_restitution(ratio),
            (Self::Hertz { .. }, true) => hertz_clamped_restitution(ratio),
        }
    }
}

pub(crate) fn finite(name: &'static str, value: f64) -> Result<(), PenetrationLawError> {
    if value.is_finite() { Ok(()) } else { Err(PenetrationLawError::NotFinite { name, value }) }
}

pub(crate) fn non_negative(name: &'static str, value: f64) -> Result<(), PenetrationLawError> {
    if value >= 0.0 && value.is_finite() { Ok(()) } else { Err(PenetrationLawError::Negative { name, value }) }
}

pub(crate) fn positive(name: &'static str, value: f64) -> Result<(), PenetrationLawError> {
    if value > 0.0 && value.is_finite() { Ok(()) } else { Err(PenetrationLawError::NotPositive { name, value }) }
}

pub(crate) fn unit_interval(name: &'static str, value: f64) -> Result<(), PenetrationLawError> {
    if (0.0..=1.0).contains(&value) { Ok(()) } else { Err(PenetrationLawError::OutsideUnitInterval { name, value }) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steel_law_matches_the_tabulated_values() {
        // ballmill.md §3.7 table of (7-2), three decimals.
        let law = ImpactLaw::SteelReichardt;
        for (v, e) in [(0.0, 1.000), (0.1, 0.971), (1.0, 0.811), (5.0, 0.586), (20.0, 0.406), (50.0, 0.314)] {
            assert!((law.restitution(v) - e).abs() < 6e-4, "v = {v}: {}", law.restitution(v));
        }
        assert!(law.restitution(0.0) <= 1.0 && law.restitution(-3.0) <= 1.0);
    }

    #[test]
    fn table_interpolates_and_is_constant_beyond_the_ends() {
        let table = RestitutionTable::new(&[(0.5, 0.9), (1.5, 0.7), (3.5, 0.3)]).unwrap();
        assert_eq!(table.restitution(0.0), 0.9);
        assert_eq!(table.restitution(0.5), 0.9);
        assert!((table.restitution(1.0) - 0.8).abs() < 1e-15);
        assert_eq!(table.restitution(1.5), 0.7);
        assert!((table.restitution(2.5) - 0.5).abs() < 1e-15);
        assert_eq!(table.restitution(10.0), 0.3);
        let single = RestitutionTable::new(&[(2.0, 0.6)]).unwrap();
        assert_eq!((single.restitution(0.0), single.restitution(9.0)), (0.6, 0.6));
        assert_eq!(RestitutionTable::new(&[]), Err(PenetrationLawError::TableLength(0)));
        assert_eq!(
            RestitutionTable::new(&[(1.0, 0.5), (1.0, 0.4)]),
            Err(PenetrationLawError::TableSpeed { index: 1, value: 1.0 })
        );
        assert_eq!(
            RestitutionTable::new(&[(1.0, 1.5)]),
            Err(PenetrationLawError::TableRestitution { index: 0, value: 1.5 })
        );
        let too_many: Vec<_> = (0..33).map(|k| (k as f64, 0.5)).collect();
        assert_eq!(RestitutionTable::new(&too_many), Err(PenetrationLawError::TableLength(33)));
    }

    #[test]
    fn linear_mapping_round_trips_and_matches_the_reference_values() {
        // feedpipe.md §2.4: D = 0.1 → e = 0.72925, 0.3 → 0.37233, 0.5 → 0.16303 (linear).
        for (d, e) in [(0.1, 0.72925), (0.3, 0.37233), (0.5, 0.16303)] {
            assert!((linear_restitution(d) - e).abs() < 1e-5);
        }
        for e in [0.01, 0.1, 0.5, 0.9, 0.999] {
            assert!((linear_restitution(linear_damping_ratio(e)) - e).abs() < 1e-14);
            assert!((hertz_restitution(hertz_damping_ratio(e)) - e).abs() < 1e-14);
        }
        assert_eq!(linear_damping_ratio(1.0), 0.0);
        assert_eq!(linear_damping_ratio(0.0), 1.0);
        assert_eq!(linear_restitution(1.2), 0.0);
        assert!((HERTZ_DAMPING_FACTOR - 5f64.sqrt() / 2.0).abs() < 1e-16);
        // feedpipe.md §2.4 clamped columns: linear and Hertz.
        for (d, linear, hertz) in
            [(0.05, 0.8588, 0.8723), (0.1, 0.7441, 0.7664), (0.3, 0.4510, 0.4849), (0.7, 0.2103, 0.2379)]
        {
            assert!(
                (linear_clamped_restitution(d) - linear).abs() < 1e-4,
                "D = {d}: {}",
                linear_clamped_restitution(d)
            );
            assert!((hertz_clamped_restitution(d) - hertz).abs() < 1e-4, "D = {d}: {}", hertz_clamped_restitution(d));
        }
        assert_eq!(linear_clamped_restitution(1.0), (-2.0f64).exp());
        // Continuous through D = 1 and ≈ 1/(4D²) far above it.
        for d in [1.0 - 1e-9, 1.0 + 1e-9] {
            assert!((linear_clamped_restitution(d) - (-2.0f64).exp()).abs() < 1e-8);
        }
        assert!((linear_clamped_restitution(1e4) * 4e8 - 1.0).abs() < 1e-3);
        for e in [0.001, 0.01, 0.1, 0.5, 0.9, 0.999] {
            assert!((linear_clamped_restitution(linear_clamped_damping_ratio(e)) - e).abs() < 1e-14);
            assert!((hertz_clamped_restitution(hertz_clamped_damping_ratio(e)) - e).abs() < 1e-14);
        }
        assert_eq!(linear_clamped_damping_ratio(1.0), 0.0);
        assert_eq!(linear_clamped_damping_ratio(0.0), linear_clamped_damping_ratio(MIN_CLAMPED_RESTITUTION));
        // feedpipe.md §2.4 table, Hertz column.
        for (d, e) in [(0.1, 0.7542), (0.5, 0.2079), (1.0, 0.0019)] {
            assert!((hertz_restitution(d) - e).abs() < 1e-4, "D = {d}: {}", hertz_restitution(d));
        }
    }
}
