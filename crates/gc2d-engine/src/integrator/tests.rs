//! Tests of the Gear integrator. Numbers quoted in comments are the values observed when the assertions were set.

use super::*;

const BOTH_C0: [GearC0; 2] = [GearC0::PositionDependent, GearC0::VelocityDependent];

fn relative_error(actual: f64, expected: f64) -> f64 {
    (actual - expected).abs() / expected.abs().max(f64::MIN_POSITIVE)
}

/// Physical derivatives 0..5 of x'' = −ω²x − 2ζωx' from x and x', by the recursion d^{n+2} = −ω² dⁿ − 2ζω d^{n+1}.
fn oscillator_derivatives(x: f64, v: f64, omega: f64, zeta: f64) -> [f64; GEAR_ORDER] {
    let mut d = [x, v, 0.0, 0.0, 0.0, 0.0];
    for n in 2..GEAR_ORDER {
        d[n] = -omega * omega * d[n - 2] - 2.0 * zeta * omega * d[n - 1];
    }
    d
}

/// How the oscillator's derivatives 3..5 are seeded.
#[derive(Clone, Copy)]
enum Start {
    /// The exact values: isolates the integrator's own truncation error.
    Exact,
    /// Zero, as the engine seeds a new body (and as a contact's onset looks to the integrator).
    Zero,
}

struct OscillatorRun {
    final_position: f64,
    final_velocity: f64,
    /// Largest |E − E₀|/E₀ over the first and the last `window` steps.
    energy_error_first: f64,
    energy_error_last: f64,
    /// Signed relative energy change at the end.
    final_energy_change: f64,
}

/// Integrates x'' = −ω²x − 2ζωx' (m = 1, k = ω² = 1, x(0) = 1, x'(0) = 0) over `periods` periods of 2π with
/// `steps_per_period` steps, in the x component of the linear state.
fn run_oscillator(c0: GearC0, zeta: f64, steps_per_period: usize, periods: usize, start: Start) -> OscillatorRun {
    let omega = 1.0;
    let ts = TimeStep::new(2.0 * PI / steps_per_period as f64).unwrap();
    let gear = Gear6::new(ts, c0);
    let mut d = oscillator_derivatives(1.0, 0.0, omega, zeta);
    if let Start::Zero = start {
        d[3..].fill(0.0);
    }
    let physical = PhysicalDerivatives { linear: d.map(|dn| DVec2::new(dn, 0.0)), angular: [0.0; GEAR_ORDER] };
    let mut states = [GearState::from_physical_derivatives(&physical, &ts)];
    let energy = |s: &GearState| 0.5 * (s.velocity(&ts).x.powi(2) + omega * omega * s.position().x.powi(2));
    let e0 = energy(&states[0]);
    let total = periods * steps_per_period;
    let window = 100.min(periods) * steps_per_period;
    let (mut first, mut last) = (0.0_f64, 0.0_f64);
    for step in 1..=total {
        gear.predict(&mut states);
        let predicted = states[0];
        let a = -omega * omega * predicted.position().x - 2.0 * zeta * omega * predicted.velocity(&ts).x;
        gear.correct(&mut states, &[DVec2::new(a, 0.0)], &[0.0]);
        let error = relative_error(energy(&states[0]), e0);
        if step <= window {
            first = first.max(error);
        }
        if step > total - window {
            last = last.max(error);
        }
    }
    OscillatorRun {
        final_position: states[0].position().x,
        final_velocity: states[0].velocity(&ts).x,
        energy_error_first: first,
        energy_error_last: last,
        final_energy_change: (energy(&states[0]) - e0) / e0,
    }
}

/// log₂ of successive error ratios of the position error at t = 2π (one period) when the step is halved.
fn observed_orders(c0: GearC0, zeta: f64, start: Start, steps_per_period: &[usize]) -> Vec<f64> {
    let wd = (1.0 - zeta * zeta).sqrt();
    let t = 2.0 * PI;
    let exact = (-zeta * t).exp() * ((wd * t).cos() + zeta / wd * (wd * t).sin());
    let errors: Vec<f64> = steps_per_period
        .iter()
        .map(|&n| (run_oscillator(c0, zeta, n, 1, start).final_position - exact).abs())
        .collect();
    errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

#[test]
fn state_is_plain_144_byte_data() {
    assert_eq!(std::mem::size_of::<GearState>(), 144);
}

#[test]
fn time_step_rejects_unusable_values() {
    for bad in [0.0, -1e-6, f64::NAN, f64::INFINITY, 1e-70, 1e62] {
        assert!(matches!(TimeStep::new(bad), Err(IntegratorError::InvalidTimeStep(_))), "{bad}");
    }
    let ts = TimeStep::new(2e-6).unwrap();
    assert_eq!(ts.dt(), 2e-6);
    assert!(relative_error(ts.scale_factors()[5], 2e-6_f64.powi(5) / 120.0) < 1e-15);
}

/// Derivatives 0..5 at `t` of the polynomial Σ coefficients[k]·t^k.
fn polynomial_derivatives(coefficients: &[f64; GEAR_ORDER], t: f64) -> [f64; GEAR_ORDER] {
    std::array::from_fn(|n| {
        (n..GEAR_ORDER)
            .map(|k| {
                let falling: f64 = ((k - n + 1)..=k).map(|f| f as f64).product();
                coefficients[k] * falling * t.powi((k - n) as i32)
            })
            .sum()
    })
}

#[test]
fn predictor_reproduces_a_quintic_exactly() {
    let x = [0.3, -1.2, 0.7, 2.5, -0.8, 0.45];
    let y = [-2.0, 0.4, -0.1, 0.9, 1.1, -0.6];
    let phi = [0.5, 3.0, -2.0, 1.5, 0.25, -0.35];
    let ts = TimeStep::new(0.05).unwrap();
    let gear = Gear6::new(ts, GearC0::default());
    let physical_at = |t: f64| {
        let (dx, dy) = (polynomial_derivatives(&x, t), polynomial_derivatives(&y, t));
        PhysicalDerivatives {
            linear: std::array::from_fn(|n| DVec2::new(dx[n], dy[n])),
            angular: polynomial_derivatives(&phi, t),
        }
    };
    let mut state = GearState::from_physical_derivatives(&physical_at(1.0), &ts);
    gear.predict_body(&mut state);
    let predicted = state.physical_derivatives(&ts);
    let expected = physical_at(1.05);
    let mut worst = 0.0_f64;
    for n in 0..GEAR_ORDER {
        let scale = expected.linear[n].abs().max_element().max(expected.angular[n].abs()).max(1.0);
        worst = worst.max((predicted.linear[n] - expected.linear[n]).abs().max_element() / scale);
        worst = worst.max((predicted.angular[n] - expected.angular[n]).abs() / scale);
    }
    // Observed 2e-16.
    assert!(worst < 1e-14, "worst relative deviation {worst:e}");
}

#[test]
fn quintic_trajectory_under_a_cubic_time_dependent_force_is_integrated_exactly() {
    // a(t) = p''(t) is a cubic in t: the predictor is exact, so the corrector's mismatch is round-off only.
    let p = [0.1, 0.2, -0.3, 0.4, -0.5, 0.6];
    let ts = TimeStep::new(1e-3).unwrap();
    for c0 in BOTH_C0 {
        let gear = Gear6::new(ts, c0);
        let start = polynomial_derivatives(&p, 0.0);
        let physical = PhysicalDerivatives { linear: start.map(|d| DVec2::new(d, -d)), angular: start };
        let mut states = [GearState::from_physical_derivatives(&physical, &ts)];
        for step in 1..=2000 {
            gear.predict(&mut states);
            let a = polynomial_derivatives(&p, step as f64 * ts.dt())[2];
            gear.correct(&mut states, &[DVec2::new(a, -a)], &[a]);
        }
        let exact = polynomial_derivatives(&p, 2.0);
        let s = states[0];
        // Observed ≤ 2.4e-15 relative for both c0 after 2000 steps.
        for (actual, expected) in [
            (s.position().x, exact[0]),
            (-s.position().y, exact[0]),
            (s.angle(), exact[0]),
            (s.velocity(&ts).x, exact[1]),
            (s.angular_velocity(&ts), exact[1]),
            (s.acceleration(&ts).x, exact[2]),
        ] {
            assert!(relative_error(actual, expected) < 1e-12, "{c0:?}: {actual} vs {expected}");
        }
    }
}

/// Free fall from `v0` under constant `g` for `steps` steps of `dt`; returns the position and velocity errors.
fn free_fall_errors(c0: GearC0, v0: DVec2, g: DVec2, dt: f64, steps: usize) -> (f64, f64) {
    let ts = TimeStep::new(dt).unwrap();
    let gear = Gear6::new(ts, c0);
    let x0 = DVec2::new(0.25, 1.5);
    let mut states = [GearState::from_physical(x0, v0, g, 0.0, 0.0, 0.0, &ts)];
    for _ in 0..steps {
        gear.predict(&mut states);
        gear.correct(&mut states, &[g], &[0.0]);
    }
    let t = steps as f64 * dt;
    let exact_x = x0 + v0 * t + 0.5 * g * t * t;
    let exact_v = v0 + g * t;
    ((states[0].position() - exact_x).length(), (states[0].velocity(&ts) - exact_v).length())
}

#[test]
fn free_fall_is_exact_for_both_c0() {
    let g = DVec2::new(0.0, -9.81);
    for c0 in BOTH_C0 {
        for v0 in [DVec2::ZERO, DVec2::new(0.3, 2.0)] {
            let (dx, dv) = free_fall_errors(c0, v0, g, 1e-3, 1000);
            // Observed ≤ 4.6e-14 m and ≤ 7.8e-14 m/s after 1000 steps (|x| ≈ 5 m, |v| ≈ 10 m/s): round-off only.
            assert!(dx < 1e-12 && dv < 1e-12, "{c0:?} v0 {v0}: {dx:e} m, {dv:e} m/s");
        }
    }
}

#[test]
fn constant_torque_spins_up_exactly_like_free_fall() {
    let ts = TimeStep::new(1e-3).unwrap();
    let alpha = 40.0;
    for c0 in BOTH_C0 {
        let gear = Gear6::new(ts, c0);
        let mut states =
            [GearState::from_physical(DVec2::ZERO, DVec2::ZERO, DVec2::new(alpha, 0.0), 0.2, -1.0, alpha, &ts)];
        for _ in 0..500 {
            gear.predict(&mut states);
            gear.correct(&mut states, &[DVec2::new(alpha, 0.0)], &[alpha]);
        }
        let t = 0.5;
        let s = states[0];
        // Observed errors 2e-14 rad and 1e-13 rad/s (round-off over 500 steps).
        assert!((s.angle() - (0.2 - t + 0.5 * alpha * t * t)).abs() < 1e-12, "{c0:?}: {}", s.angle());
        assert!((s.angular_velocity(&ts) - (-1.0 + alpha * t)).abs() < 1e-12);
        assert_eq!(s.angular_acceleration(&ts), alpha);
        assert!((s.position().x - 0.5 * alpha * t * t).abs() < 1e-12);
    }
}

#[test]
fn identical_inputs_give_bitwise_identical_translation_and_rotation() {
    let ts = TimeStep::new(0.01).unwrap();
    let gear = Gear6::new(ts, GearC0::default());
    let mut states =
        [GearState::from_physical(DVec2::new(0.7, 0.0), DVec2::new(-0.3, 0.0), DVec2::ZERO, 0.7, -0.3, 0.0, &ts)];
    for step in 0..300 {
        gear.predict(&mut states);
        // A nonlinear, velocity-dependent law applied identically to x and φ.
        let s = states[0];
        let law = |q: f64, w: f64| -q.sin() - 0.2 * w + (step as f64 * 0.01).cos();
        let (a, alpha) = (law(s.position().x, s.velocity(&ts).x), law(s.angle(), s.angular_velocity(&ts)));
        gear.correct(&mut states, &[DVec2::new(a, 0.0)], &[alpha]);
    }
    for n in 0..GEAR_ORDER {
        assert_eq!(states[0].linear[n].x.to_bits(), states[0].angular[n].to_bits(), "derivative {n}");
    }
}

#[test]
fn harmonic_oscillator_energy_error_is_small_but_drifts_linearly() {
    // m = 1, k = 1, 32 steps per period, 1000 periods. The Gear PC is not symplectic: the energy error grows linearly
    // in time (last 100 periods ≈ 10 × first 100 periods), with opposite signs for the two c₀.
    // Observed (first 100 / last 100 periods / signed change at the end):
    //   c₀ = 3/20: 1.003e-3 / 1.003e-2 / +1.003e-2 (energy is pumped in),
    //   c₀ = 3/16: 2.016e-3 / 2.000e-2 / −2.000e-2 (energy is drained).
    let pos = run_oscillator(GearC0::PositionDependent, 0.0, 32, 1000, Start::Exact);
    assert!(pos.energy_error_first < 1.1e-3 && pos.energy_error_last < 1.1e-2, "3/20 bound");
    assert!(pos.final_energy_change > 0.9e-2, "3/20 gains energy");
    let vel = run_oscillator(GearC0::VelocityDependent, 0.0, 32, 1000, Start::Exact);
    assert!(vel.energy_error_first < 2.1e-3 && vel.energy_error_last < 2.1e-2, "3/16 bound");
    assert!(vel.final_energy_change < -1.9e-2, "3/16 loses energy");
    for run in [&pos, &vel] {
        // Linear, not exponential or accelerating: ten times the time, ten times the error (observed 10.00 and 9.92).
        let growth = run.energy_error_last / run.energy_error_first;
        assert!((9.5..10.5).contains(&growth), "growth over 10× the time: {growth}");
    }
    // The drift falls steeply with Δt. Observed at 64 steps per period: 8.0e-5 (3/20, ∝ Δt⁷) and 9.6e-4 (3/16, ∝ Δt⁴·⁴).
    let pos64 = run_oscillator(GearC0::PositionDependent, 0.0, 64, 1000, Start::Exact);
    let vel64 = run_oscillator(GearC0::VelocityDependent, 0.0, 64, 1000, Start::Exact);
    assert!(pos64.energy_error_last < 8.5e-5 && vel64.energy_error_last < 1.0e-3);
    // Under-resolved, both c₀ gain energy: at 20 steps per period 3/16 gains +2.6e-6 per period (observed +2.6e-4
    // after 100 periods), at 16 steps +5.6e-4 per period.
    let coarse = run_oscillator(GearC0::VelocityDependent, 0.0, 20, 100, Start::Exact);
    assert!((2.0e-4..3.2e-4).contains(&coarse.final_energy_change), "{:e}", coarse.final_energy_change);
    // Seeding derivatives 3..5 with zero (as for a new body) changes none of this (observed 1e-5 relative).
    let zero = run_oscillator(GearC0::VelocityDependent, 0.0, 32, 1000, Start::Zero);
    assert!(relative_error(zero.energy_error_last, vel.energy_error_last) < 1e-3);
}

#[test]
fn damped_oscillator_decays_at_the_analytic_rate() {
    // x'' = −x − 2ζx' (ζ = 0.05) over 20 periods. The amplitude envelope
    // A(t) = sqrt(x² + ((x' + ζx)/ω_d)²) = A(0)·exp(−ζt) exactly, so its logarithm gives the decay rate.
    let zeta: f64 = 0.05;
    let wd = (1.0 - zeta * zeta).sqrt();
    let envelope = |x: f64, v: f64| (x * x + ((v + zeta * x) / wd).powi(2)).sqrt();
    let duration = 20.0 * 2.0 * PI;
    // Observed relative rate errors: 32 steps/period: −1.4e-5 (3/20), +4.0e-5 (3/16); 64: +3.7e-7, +2.1e-6.
    for (steps_per_period, tolerance) in [(32, 5e-5), (64, 4e-6)] {
        for c0 in BOTH_C0 {
            let run = run_oscillator(c0, zeta, steps_per_period, 20, Start::Exact);
            let rate = (envelope(1.0, 0.0) / envelope(run.final_position, run.final_velocity)).ln() / duration;
            let error = (rate - zeta) / zeta;
            assert!(error.abs() < tolerance, "{c0:?}, {steps_per_period} steps: relative rate error {error:e}");
        }
    }
}

#[test]
fn observed_order_of_the_position_error() {
    // Position error at t = 2π (one period) for 32, 64, …, 512 steps per period; the order is log₂ of the error ratio
    // when Δt halves. Observed:
    //   undamped, exact start: 3/20 → 6.98, 7.11, 7.32, 7.96 (round-off at 512); 3/16 → 4.32, 4.85, 4.96, 4.99;
    //   damped (ζ = 0.1), exact start: 3/20 → 3.70, 4.68, 4.88, 4.95; 3/16 → 4.44, 4.83, 4.93, 4.97;
    //   undamped, derivatives 3..5 seeded with zero: 3/20 → 2.77, 3.66, 3.94, 3.99; 3/16 → 3.61, 4.27, 4.27, 4.18;
    //   damped, seeded with zero: both → ≈ 2 (1.95–1.99 at the finest steps).
    // So the scheme is fifth order for velocity-dependent forces, and the start-up with unknown higher derivatives
    // (a new body; likewise a contact switching on) leaves a first-order-in-time-derivative error that shows up as
    // second order in the position.
    let steps = [32, 64, 128, 256, 512];
    let finest = |orders: Vec<f64>| orders[orders.len() - 1];
    let in_range = |order: f64, low: f64, high: f64| assert!((low..high).contains(&order), "order {order}");
    in_range(observed_orders(GearC0::PositionDependent, 0.0, Start::Exact, &steps[..4])[2], 7.0, 7.6);
    in_range(finest(observed_orders(GearC0::VelocityDependent, 0.0, Start::Exact, &steps)), 4.9, 5.1);
    for c0 in BOTH_C0 {
        in_range(finest(observed_orders(c0, 0.1, Start::Exact, &steps)), 4.9, 5.1);
        in_range(finest(observed_orders(c0, 0.0, Start::Zero, &steps)), 3.9, 4.3);
        in_range(finest(observed_orders(c0, 0.1, Start::Zero, &steps)), 1.9, 2.1);
    }
}

#[test]
fn physical_and_scaled_derivatives_round_trip() {
    let physical = PhysicalDerivatives {
        linear: [
            DVec2::new(0.07, -0.02),
            DVec2::new(0.3, -1.1),
            DVec2::new(-9.81, 250.0),
            DVec2::new(1.5e5, -2.0e4),
            DVec2::new(-3.0e9, 7.0e8),
            DVec2::new(4.0e13, -1.0e14),
        ],
        angular: [1.2, -35.0, 4.0e4, -2.0e8, 6.0e11, -5.0e15],
    };
    let ts = TimeStep::new(2e-6).unwrap();
    let state = GearState::from_physical_derivatives(&physical, &ts);
    assert_eq!(state.linear[1], physical.linear[1] * 2e-6);
    assert!(relative_error(state.angular[5], -5.0e15 * 2e-6_f64.powi(5) / 120.0) < 1e-15);
    let back = state.physical_derivatives(&ts);
    for n in 0..GEAR_ORDER {
        let dl = (back.linear[n] - physical.linear[n]).abs().max_element() / physical.linear[n].abs().max_element();
        assert!(dl < 4e-16, "linear {n}: {dl:e}");
        assert!(relative_error(back.angular[n], physical.angular[n]) < 4e-16, "angular {n}");
    }
    assert_eq!(state.velocity(&ts), back.linear[1]);
    assert_eq!(state.acceleration(&ts), back.linear[2]);
    assert_eq!(state.angular_velocity(&ts), back.angular[1]);
    assert_eq!(state.angular_acceleration(&ts), back.angular[2]);

    let simple = GearState::from_physical(
        physical.linear[0],
        physical.linear[1],
        physical.linear[2],
        physical.angular[0],
        physical.angular[1],
        physical.angular[2],
        &ts,
    );
    assert_eq!(simple.linear[..3], state.linear[..3]);
    assert_eq!(simple.angular[..3], state.angular[..3]);
    assert_eq!(simple.linear[3..], [DVec2::ZERO; 3]);
    assert_eq!(simple.angular[3..], [0.0; 3]);
}

#[test]
fn rescale_keeps_the_physical_derivatives() {
    let physical = PhysicalDerivatives {
        linear: std::array::from_fn(|n| DVec2::new(1.0 + n as f64, -0.5 * n as f64)),
        angular: std::array::from_fn(|n| 0.25 - n as f64),
    };
    let old = TimeStep::new(3e-6).unwrap();
    // A power-of-two ratio is exact bit for bit, in both directions.
    let half = TimeStep::new(1.5e-6).unwrap();
    let mut state = GearState::from_physical_derivatives(&physical, &old);
    state.rescale(&old, &half);
    assert_eq!(state, GearState::from_physical_derivatives(&physical, &half));
    state.rescale(&half, &old);
    assert_eq!(state, GearState::from_physical_derivatives(&physical, &old));
    // Any other ratio is exact to round-off (observed ≤ 4.4e-16 relative).
    let odd = TimeStep::new(3e-6 * 3.0 / 7.0).unwrap();
    let mut state = GearState::from_physical_derivatives(&physical, &old);
    state.rescale(&old, &odd);
    let physical_after = state.physical_derivatives(&odd);
    for n in 0..GEAR_ORDER {
        assert!(relative_error(physical_after.angular[n], physical.angular[n]) < 1e-15, "angular {n}");
        assert!(relative_error(physical_after.linear[n].x, physical.linear[n].x) < 1e-15, "linear {n}");
    }
}

#[test]
fn changing_the_time_step_mid_run_keeps_free_fall_exact() {
    let g = DVec2::new(0.5, -9.81);
    let v0 = DVec2::new(1.0, 3.0);
    let mut gear = Gear6::new(TimeStep::new(1e-3).unwrap(), GearC0::default());
    let mut states = [GearState::from_physical(DVec2::ZERO, v0, g, 0.0, 0.0, 0.0, gear.time_step())];
    let run = |gear: &Gear6, states: &mut [GearState], steps: usize| {
        for _ in 0..steps {
            gear.predict(states);
            gear.correct(states, &[g], &[0.0]);
        }
    };
    run(&gear, &mut states, 300);
    gear.set_time_step(TimeStep::new(0.25e-3).unwrap(), &mut states);
    run(&gear, &mut states, 400);
    assert_eq!(gear.time_step().dt(), 0.25e-3);
    let t = 0.4;
    assert!((states[0].position() - (v0 * t + 0.5 * g * t * t)).length() < 1e-13);
    assert!((states[0].velocity(gear.time_step()) - (v0 + g * t)).length() < 1e-13);
}

#[test]
fn bodies_outside_the_passed_slice_are_not_touched() {
    let ts = TimeStep::new(1e-3).unwrap();
    let gear = Gear6::new(ts, GearC0::default());
    let moving = GearState::from_physical(DVec2::ZERO, DVec2::new(1.0, 0.0), DVec2::ZERO, 0.0, 2.0, 0.0, &ts);
    let mut states = [moving; 4];
    // Bodies 0 and 3 are fixed: the engine passes only 1..3.
    gear.predict(&mut states[1..3]);
    gear.correct(&mut states[1..3], &[DVec2::ZERO; 2], &[0.0; 2]);
    assert_eq!(states[0], moving);
    assert_eq!(states[3], moving);
    assert_eq!(states[1].position(), DVec2::new(1e-3, 0.0));
    assert_eq!(states[2].angle(), 2e-3);
}

#[test]
fn time_step_bound_matches_the_reference_examples() {
    // §3.6: ρ = 5000 kg/m², E = 1e7 N/m; r = 1.5 mm → m = 0.0353 kg, Δt ≈ 1.87e-5 s; r = 1 mm → 1.25e-5 s.
    let (rho, e) = (5000.0, 1e7);
    for (radius, expected) in [(1.5e-3, 1.87e-5), (1e-3, 1.25e-5), (0.64e-3, 8.0e-6)] {
        let bound = max_stable_time_step_elongated(radius, rho, e).unwrap();
        assert!(relative_error(bound, expected) < 5e-3, "r = {radius}: {bound:e}");
        assert_eq!(bound, max_stable_time_step(PI * radius * radius * rho, e).unwrap());
    }
    // The closed form itself: a unit mass on a unit spring has a half period π, and the bound is a tenth of it.
    assert!(relative_error(max_stable_time_step(1.0, 1.0).unwrap(), PI / 10.0) < 1e-15);
    for (m, e) in [(0.0, 1e7), (-1.0, 1e7), (1.0, 0.0), (f64::NAN, 1.0), (1.0, f64::INFINITY)] {
        assert_eq!(max_stable_time_step(m, e), None, "m = {m}, E = {e}");
    }
    assert_eq!(max_stable_time_step_elongated(-1e-3, rho, e), None);
    assert_eq!(max_stable_time_step_elongated(1e-3, f64::NAN, e), None);
}

/// Velocity ratio |v_out/v_in| of a body hitting a one-sided linear spring (a = −x for x > 0, ω = 1) at unit speed,
/// resolved with `steps_per_contact` steps over the contact time π; the body starts `phase` steps before the spring.
fn one_sided_spring_restitution(c0: GearC0, steps_per_contact: usize, phase: f64) -> f64 {
    let ts = TimeStep::new(PI / steps_per_contact as f64).unwrap();
    let gear = Gear6::new(ts, c0);
    let x0 = -phase * ts.dt();
    let mut states = [GearState::from_physical(DVec2::new(x0, 0.0), DVec2::X, DVec2::ZERO, 0.0, 0.0, 0.0, &ts)];
    for _ in 0..4 * steps_per_contact {
        gear.predict(&mut states);
        let x = states[0].position().x;
        gear.correct(&mut states, &[DVec2::new(if x > 0.0 { -x } else { 0.0 }, 0.0)], &[0.0]);
    }
    -states[0].velocity(&ts).x
}

#[test]
fn one_sided_spring_contact_keeps_the_restitution_near_one() {
    // The shape of a DEM contact: free flight, then a force that switches on continuously at first touch (the jerk
    // jumps), then free flight again. |e − 1| over onset phases 0, 0.1, …, 0.9 of a step, observed:
    //   10 steps per contact (the §3.6 rule): 3/20 → +1.14e-4 … +1.22e-4, 3/16 → +1.17e-4 … +1.46e-4;
    //   32 steps per contact: 3/20 → −2.4e-7, 3/16 → −4.4e-7.
    for c0 in BOTH_C0 {
        for (steps_per_contact, tolerance) in [(10, 1.6e-4), (32, 5e-7)] {
            for phase in (0..10).map(|k| k as f64 / 10.0) {
                let deviation = one_sided_spring_restitution(c0, steps_per_contact, phase) - 1.0;
                assert!(deviation.abs() < tolerance, "{c0:?}, {steps_per_contact} steps, phase {phase}: {deviation:e}");
            }
        }
    }
}

/// True when any of the state's eighteen values is subnormal.
fn has_subnormal(state: &GearState) -> bool {
    state.linear.iter().any(|d| d.x.is_subnormal() || d.y.is_subnormal())
        || state.angular.iter().any(|a| a.is_subnormal())
}

/// A particle that has just left a contact flies on with a constant acceleration: its third to fifth derivatives
/// decay, and without the flush they end up as subnormal numbers for good (slow on Intel CPUs). With it they become
/// zero, and the particle's positions, angles and velocities are bit for bit those of the corrector without the flush.
#[test]
fn a_particle_in_free_flight_keeps_no_subnormal_derivatives_and_moves_as_without_the_flush() {
    let ts = TimeStep::new(3e-6).unwrap();
    let g = DVec2::new(0.0, -9.81);
    for c0 in BOTH_C0 {
        let gear = Gear6::new(ts, c0);
        // Leftovers of the last contact in the higher derivatives (scaled, m and rad), as a settled pile holds them.
        let mut flushed =
            GearState::from_physical(DVec2::new(0.4, 0.01), DVec2::new(3e-3, -2e-2), g, 1.5, 2.0, 0.0, &ts);
        flushed.linear[3] = DVec2::new(2e-27, -3e-28);
        flushed.linear[4] = DVec2::new(-5e-28, 4e-29);
        flushed.linear[5] = DVec2::new(7e-29, 1e-29);
        flushed.angular[3..].copy_from_slice(&[3e-27, -8e-28, 6e-29]);
        let mut plain = flushed;
        let mut plain_had_subnormals = false;
        for _ in 0..20_000 {
            gear.predict_body(&mut flushed);
            gear.correct_body(&mut flushed, g, 0.0);
            gear.predict_body(&mut plain);
            correct_scaled(&mut plain.linear, g * ts.scale[2], &c0.coefficients());
            correct_scaled(&mut plain.angular, 0.0, &c0.coefficients());
            plain_had_subnormals |= has_subnormal(&plain);
            assert!(!has_subnormal(&flushed), "{c0:?}: {flushed:?}");
            for n in 0..2 {
                assert_eq!(
                    flushed.linear[n].to_array().map(f64::to_bits),
                    plain.linear[n].to_array().map(f64::to_bits)
                );
                assert_eq!(flushed.angular[n].to_bits(), plain.angular[n].to_bits());
            }
        }
        assert!(plain_had_subnormals, "{c0:?}: the case does not reach the subnormal range");
    }
}
