//! A fluid as a body force through the whole engine (issue 15 item 2): quadratic-drag settling against the closed
//! form, levitation at the terminal speed, the ledger's balance with the fluid's work, and free fall without a fluid
//! unchanged bitwise.

mod common;

use common::{G, law, sphere_world, step};
use gc2d_engine::{BodyId, BodyShape, Fluid, World};
use gc2d_fluid::drag::terminal_speed;
use gc2d_fluid::{DragCoefficient, FluidField, FluidProperties, ImmersedBody};
use gc2d_geometry::{DVec2, Pose};

/// The thesis's styrofoam ball (feedpipe.md §7.2): radius 0.02 m, 15 kg/m³.
const RADIUS: f64 = 0.02;
const STYROFOAM: f64 = 15.0;
/// Air, kg/m³.
const AIR: f64 = 1.25;
const C_W: f64 = 0.47;

/// Air moving with `u` everywhere, constant c_w 0.47, buoyancy on.
fn air(u: DVec2) -> Fluid {
    Fluid {
        field: FluidField::Uniform(u),
        properties: FluidProperties { density_kg_m3: AIR, dynamic_viscosity_pa_s: 1.8e-5 },
        drag: DragCoefficient::Constant(C_W),
        buoyancy: true,
    }
}

/// A World of spheres at Δt `dt` with one styrofoam ball at the origin moving with `velocity`.
fn ball_world(dt: f64, velocity: DVec2) -> (World, BodyId) {
    let mut world = sphere_world(law(1.0, 0.0, 0.0), dt, G);
    let pose = Pose::new(DVec2::ZERO, 0.0);
    let id = world.add_particle(BodyShape::Disk { radius: RADIUS }, pose, STYROFOAM, velocity, 0.0).unwrap();
    (world, id)
}

/// The ball's terminal speed in still air, m/s.
fn ball_terminal_speed() -> f64 {
    let body = ImmersedBody::sphere_equivalent(RADIUS);
    terminal_speed(AIR, STYROFOAM * body.volume_m3, &body, C_W, G)
}

#[test]
fn a_styrofoam_ball_settles_in_still_air_as_the_closed_form_says() {
    let dt = 1e-4;
    let (mut world, id) = ball_world(dt, DVec2::ZERO);
    world.set_fluid(air(DVec2::ZERO)).unwrap();
    let w_t = ball_terminal_speed();
    assert!((w_t - 3.4993).abs() < 1e-4, "w_t = {w_t}");
    let g_reduced = G * (STYROFOAM - AIR) / STYROFOAM;
    let mut worst = (0.0f64, 0.0f64);
    for n in 1..=15_000u32 {
        step(&mut world);
        if n % 500 != 0 {
            continue;
        }
        let t = world.time();
        let x = g_reduced * t / w_t;
        let speed = w_t * x.tanh();
        let fallen = w_t * w_t / g_reduced * x.cosh().ln();
        let b = world.bodies();
        let (v, y) = (b.velocity[id.index()], b.pose[id.index()].position.y);
        assert_eq!(v.x, 0.0);
        let (ev, es) = (((-v.y) - speed).abs() / speed, ((-y) - fallen).abs() / fallen);
        worst = (worst.0.max(ev), worst.1.max(es));
        assert!(ev < 1e-4 && es < 1e-4, "t = {t} s: v = {} against {speed}, s = {} against {fallen}", -v.y, -y);
    }
    // The ball is at its terminal speed by the end (1.5 s is almost four time constants w_t/g′).
    let v_end = -world.bodies().velocity[id.index()].y;
    assert!((v_end - w_t).abs() / w_t < 2e-3, "v(1.5 s) = {v_end}, w_t = {w_t}, worst {worst:?}");
}

#[test]
fn a_ball_released_at_rest_in_an_upward_stream_at_its_terminal_speed_stays_at_rest() {
    let (mut world, id) = ball_world(1e-4, DVec2::ZERO);
    world.set_fluid(air(DVec2::new(0.0, ball_terminal_speed()))).unwrap();
    for _ in 0..10_000 {
        step(&mut world);
        let v = world.bodies().velocity[id.index()];
        assert!(v.length() < 1e-9, "t = {} s: v = {v}", world.time());
    }
    assert!(world.bodies().pose[id.index()].position.length() < 1e-9);
}

#[test]
fn a_ball_released_moving_in_the_levitating_stream_relaxes_to_rest() {
    let (mut world, id) = ball_world(1e-4, DVec2::new(0.0, 2.0));
    world.set_fluid(air(DVec2::new(0.0, ball_terminal_speed()))).unwrap();
    common::run_until(&mut world, 3.0);
    let v = world.bodies().velocity[id.index()];
    assert!(v.length() < 1e-3, "v(3 s) = {v}");
}

#[test]
fn the_ledger_balances_with_the_fluids_work() {
    // Braked by still air and driven by a sideways stream: the fluid's work is booked as work in either way. The
    // balance error is the integration error of a velocity-dependent force, first order in Δt (about 5e-5 of the
    // energies moved per second of flight at Δt = 1e-4 s, twice that at 2e-4 s).
    for u in [DVec2::ZERO, DVec2::new(5.0, 1.0)] {
        let (mut world, _) = ball_world(1e-4, DVec2::new(-1.0, 2.0));
        world.set_fluid(air(u)).unwrap();
        common::run_until(&mut world, 1.0);
        let l = world.ledger();
        let scale = l.energy_scale();
        if u == DVec2::ZERO {
            assert!(l.work_fluid < -0.1 * scale, "still air only takes energy: {} of {scale}", l.work_fluid);
        } else {
            assert!(l.work_fluid > 0.0, "the stream drives the ball: {}", l.work_fluid);
        }
        assert!(l.balance_error().abs() < 1e-4 * scale, "u = {u}: balance error {} of {scale}", l.balance_error());
    }
}

#[test]
fn free_fall_without_a_fluid_is_unchanged_bitwise_and_exact() {
    // A World with no fluid and one with a fluid of zero density and zero c_w without buoyancy both fall freely,
    // and the closed form holds to round-off.
    let dt = 1e-3;
    let (mut plain, a) = ball_world(dt, DVec2::new(0.5, 0.0));
    let (mut still, b) = ball_world(dt, DVec2::new(0.5, 0.0));
    let mut nothing = air(DVec2::ZERO);
    nothing.properties.density_kg_m3 = 0.0;
    nothing.buoyancy = false;
    still.set_fluid(nothing).unwrap();
    for _ in 0..1000 {
        step(&mut plain);
        step(&mut still);
    }
    let (pa, pb) = (plain.bodies(), still.bodies());
    assert_eq!(pa.pose[a.index()].position.to_array(), pb.pose[b.index()].position.to_array());
    assert_eq!(pa.velocity[a.index()].to_array(), pb.velocity[b.index()].to_array());
    let t = plain.time();
    let p = pa.pose[a.index()].position;
    assert!((p.y + 0.5 * G * t * t).abs() < 1e-12 && (p.x - 0.5 * t).abs() < 1e-12, "p = {p}");
    assert_eq!(plain.ledger().work_fluid, 0.0);
}

#[test]
fn bad_fluid_numbers_are_refused_with_the_field_named() {
    let (mut world, _) = ball_world(1e-4, DVec2::ZERO);
    let mut negative = air(DVec2::ZERO);
    negative.properties.density_kg_m3 = -1.0;
    assert!(world.set_fluid(negative).unwrap_err().to_string().contains("density_kg_m3"));
    let mut no_viscosity = air(DVec2::ZERO);
    no_viscosity.drag = DragCoefficient::SchillerNaumann;
    no_viscosity.properties.dynamic_viscosity_pa_s = 0.0;
    assert!(world.set_fluid(no_viscosity).unwrap_err().to_string().contains("viscosity_pa_s"));
}

/// The time a ball starting at `v0` upward takes to rise `height` in plug flow `u` > w_t, from
/// dv/dt = g′·((u − v)²/w_t² − 1) (drag and buoyancy balance the weight at slip w_t), by RK4 in fine steps.
fn rise_time(u: f64, v0: f64, height: f64) -> f64 {
    let w_t = ball_terminal_speed();
    let g_net = G * (STYROFOAM - AIR) / STYROFOAM;
    let accel = |v: f64| g_net * ((u - v).powi(2) / (w_t * w_t) - 1.0);
    let h = 1e-6;
    let (mut t, mut y, mut v) = (0.0, 0.0, v0);
    loop {
        let (k1v, k1y) = (accel(v), v);
        let (k2v, k2y) = (accel(v + 0.5 * h * k1v), v + 0.5 * h * k1v);
        let (k3v, k3y) = (accel(v + 0.5 * h * k2v), v + 0.5 * h * k2v);
        let (k4v, k4y) = (accel(v + h * k3v), v + h * k3v);
        let y_next = y + h / 6.0 * (k1y + 2.0 * k2y + 2.0 * k3y + k4y);
        if y_next >= height {
            return t + h * (height - y) / (y_next - y);
        }
        (y, v, t) = (y_next, v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v), t + h);
    }
}

#[test]
fn a_ball_fed_into_plug_flow_crosses_the_riser_in_the_time_the_drag_law_gives() {
    use gc2d_engine::{DiskRecipe, Inlet, MaterialId, Outlet, ParticleRecipe};
    use gc2d_geometry::Randomization;
    // An inlet across the floor feeds one styrofoam ball at 0.5 m/s upward into air rising at U = 5 m/s
    // (w_t = 3.4993 m/s); an outlet 2 m up removes it. Its transit record must give the time the drag law gives:
    // about 2 m / (U − w_t) = 1.33 s plus the start transient.
    let (dt, u, height, v0) = (1e-4, 5.0, 2.0, 0.5);
    let mut world = sphere_world(law(1.0, 0.0, 0.0), dt, G);
    world.set_fluid(air(DVec2::new(0.0, u))).unwrap();
    let recipe = ParticleRecipe::Disk(DiskRecipe {
        radius: RADIUS,
        size_randomization: Randomization::Const,
        size_variation: 0.0,
    });
    let mut transits = Vec::new();
    world
        .add_inlet(Inlet {
            name: "feed".into(),
            // Walking from `from` to `to` the domain lies on the left: above the floor.
            from: DVec2::new(-0.1, 0.0),
            to: DVec2::new(0.1, 0.0),
            rate: 1.0,
            start: 0.0,
            stop: 0.5,
            velocity: DVec2::new(0.0, v0),
            angular_velocity: 0.0,
            recipe,
            density: STYROFOAM,
            material: MaterialId(0),
        })
        .unwrap();
    world
        .add_outlet(Outlet { name: "top".into(), from: DVec2::new(0.1, height), to: DVec2::new(-0.1, height) })
        .unwrap();
    while world.time() < 2.0 {
        world.step().unwrap();
        transits.extend_from_slice(world.transits());
    }
    assert_eq!(transits.len(), 1);
    let transit = transits[0];
    let entry = transit.entry.expect("it came through the inlet");
    assert_eq!((entry.inlet, transit.outlet), (0, 0));
    assert!((entry.time - dt).abs() < 1e-12, "inserted at the end of the first step: {}", entry.time);
    let expected = rise_time(u, v0, height);
    let measured = transit.transit_time().unwrap();
    // The record is taken at the end of the crossing step: within one step of the crossing.
    assert!((measured - expected).abs() < 2.0 * dt, "{measured} s against {expected} s");
    let asymptotic = height / (u - ball_terminal_speed());
    assert!(measured > asymptotic && measured < 1.2 * asymptotic, "{measured} against {asymptotic}");
}
