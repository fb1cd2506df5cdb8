//! One step of an incremental spring with a Coulomb-type cap, shared by the tangential spring and the rolling spring.

use crate::reciprocal_or_zero;

/// Result of one step of a capped incremental spring (force or moment; energies in J).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpringStep {
    /// The force (or moment) the spring and its damper apply, capped: clamp(S + damping, ±cap).
    pub force: f64,
    /// The elastic part S to store for the next step, |S| ≤ cap.
    pub stored: f64,
    /// S²/(2k) − S_old²/(2k_old): change of the stored energy.
    pub energy_change: f64,
    /// −(force − S)·displacement ≥ 0: the damping part that survived the cap, times the displacement.
    pub damping_dissipation: f64,
    /// Energy lost to slip ≥ 0: the cap times the slip it removed, plus the spring energy released when the
    /// stiffness or the cap fall under a loaded spring (see [`spring_step`]).
    pub slip_dissipation: f64,
}

/// One step of the spring S (force or moment) against the displacement rate `rate` (m/s or rad/s) over `dt`.
///
/// The stiffness may change with the overlap, from `previous_stiffness` k_old (of the stored `previous` S_old) to
/// `stiffness` k. With S stored as a force (Cundall–Strack, as [`crate::CundallStrack`]):
/// - unloading (k < k_old) rescales S by k/k_old, so the spring's force does not outlast its shrinking contact (as
///   LAMMPS GRANULAR's `mindlin/rescale/force`); loading keeps S. Either way the stored energy S²/(2k) can only
///   fall, by [0, S_old²/(2k_old)]: that loss is booked as slip dissipation (the micro-slip of a Mindlin–Deresiewicz
///   contact), so no energy is created;
/// - a cap that fell below the spring (the normal force dropped) truncates it first, S ← clamp(S, ±cap), releasing
///   (S² − clamp(S)²)/(2k) as slip dissipation: a spring at rest that has to shed force slips, and all the energy it
///   sheds is lost (booking only cap × slip would miss the part above the cap, an error that does not shrink with Δt);
/// - trial S* = S − k·rate·dt (the force on i opposes the motion), stored S = clamp(S*, ±cap), the slip energy
///   −S·(S − S*)/k (exactly C·|rate|·dt in steady sliding), damping −c·rate and the force clamp(S + damping, ±cap),
///   as the area law's tangential step.
///
/// Per step the energy terms then add up to −S·rate·dt − (S − S_start)²/(2k): the trapezoid work of the spring
/// while it sticks and the exact C·|rate|·dt while it slides.
#[inline]
#[allow(clippy::too_many_arguments)]
pub(crate) fn spring_step(
    previous: f64,
    previous_stiffness: f64,
    stiffness: f64,
    rate: f64,
    dt: f64,
    damping_coefficient: f64,
    cap: f64,
) -> SpringStep {
    let previous_energy = 0.5 * previous * previous * reciprocal_or_zero(previous_stiffness);
    let rescaled = if stiffness < previous_stiffness { previous * stiffness / previous_stiffness } else { previous };
    let inv_stiffness = reciprocal_or_zero(stiffness);
    // A cap that fell below the spring (the normal force dropped) truncates it before it moves.
    let start = clamp_magnitude(rescaled, cap);
    let start_energy = 0.5 * start * start * inv_stiffness;
    let displacement = rate * dt;
    let trial = start - stiffness * displacement;
    let stored = clamp_magnitude(trial, cap);
    let force = clamp_magnitude(stored - damping_coefficient * rate, cap);
    SpringStep {
        force,
        stored,
        energy_change: 0.5 * stored * stored * inv_stiffness - previous_energy,
        damping_dissipation: -(force - stored) * displacement,
        slip_dissipation: (previous_energy - start_energy) - stored * (stored - trial) * inv_stiffness,
    }
}

/// `x` limited to [−cap, cap] for cap ≥ 0 (never panics, unlike `f64::clamp`).
#[inline]
pub(crate) fn clamp_magnitude(x: f64, cap: f64) -> f64 {
    x.min(cap).max(-cap)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_stiffness_is_the_area_laws_step() {
        let (k, dt, v, c) = (2e6, 1e-6, 1e-3, 5.0);
        let mut s = 0.0;
        for n in 1..=20 {
            let step = spring_step(s, k, k, v, dt, c, 100.0);
            assert!((step.stored + n as f64 * k * v * dt).abs() < 1e-12);
            assert!((step.force - (step.stored - c * v)).abs() < 1e-12);
            assert_eq!(step.slip_dissipation, 0.0);
            s = step.stored;
        }
    }

    #[test]
    fn energy_terms_add_up_to_the_documented_step_work() {
        // (S_old, k_old, k, rate, cap): stick, slide, reversal, cap drop, stiffness up and down, unloading to 0.
        let cases = [
            (0.5, 2e6, 2e6, 1e-3, 10.0),
            (3.0, 2e6, 2e6, 2.0, 3.0),
            (-3.0, 2e6, 2e6, 0.5, 3.0),
            (4.0, 2e6, 2e6, -0.3, 1.0),
            (2.0, 1e6, 3e6, 0.7, 2.5),
            (2.0, 3e6, 1e6, -0.7, 2.5),
            (2.0, 3e6, 0.0, 0.2, 0.0),
        ];
        let (dt, c) = (1e-6, 7.0);
        for (previous, k_old, k, rate, cap) in cases {
            let step = spring_step(previous, k_old, k, rate, dt, c, cap);
            let rescaled = if k < k_old { previous * k / k_old } else { previous };
            let start = clamp_magnitude(rescaled, cap);
            let absorbed = step.energy_change + step.slip_dissipation + step.damping_dissipation;
            // −F·rate·Δt is the work of the force on the motion; the second term is the trapezoid correction of a
            // sticking spring (zero while sliding at the cap).
            let expected = -step.force * rate * dt - 0.5 * (step.stored - start).powi(2) * reciprocal_or_zero(k);
            assert!((absorbed - expected).abs() < 1e-15 * previous.abs().max(1.0), "{previous} {k_old} {k} {rate}");
            assert!(step.slip_dissipation >= 0.0 && step.damping_dissipation >= 0.0);
            assert!(step.force.abs() <= cap && step.stored.abs() <= cap);
        }
    }

    #[test]
    fn changing_stiffness_never_creates_energy() {
        for (k_old, k_new) in [(1e6, 2e6), (2e6, 1e6), (1e6, 0.0)] {
            let step = spring_step(3.0, k_old, k_new, 0.0, 1e-6, 0.0, 10.0);
            assert!(step.slip_dissipation >= 0.0, "{k_old} → {k_new}");
            assert!(step.slip_dissipation <= 9.0 / (2.0 * k_old) + 1e-18);
            assert!((step.energy_change + step.slip_dissipation).abs() < 1e-18, "no motion: the loss is the change");
            let expected = if k_new < k_old { 3.0 * k_new / k_old } else { 3.0 };
            assert_eq!(step.stored, expected);
        }
    }
}
