//! The ball mill section: chamber, rotor and balls as the scene builds them, and its located errors.

use gc2d_engine::{BodyId, BodyKind, ShapeKind};
use gc2d_geometry::{DVec2, area_contact, cross};
use gc2d_scene::{ErrorKind, Scene};
use std::f64::consts::{FRAC_PI_2, TAU};
use std::path::PathBuf;

fn mill_scene() -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/mill.ron");
    Scene::from_path(path).unwrap()
}

#[test]
fn the_mill_builds_a_chamber_a_turning_rotor_and_scattered_moving_balls() {
    let world = mill_scene().build().unwrap();
    let b = world.bodies();
    let walls: Vec<usize> = (0..b.len()).filter(|&i| b.kind[i] == BodyKind::Wall).collect();
    let shapes: Vec<ShapeKind> = walls.iter().map(|&i| b.shape[i]).collect();
    assert_eq!(shapes, [ShapeKind::InnerCircle, ShapeKind::Disk, ShapeKind::Capsule, ShapeKind::Capsule]);
    let balls: Vec<usize> = b.particles().map(|id| id.index()).collect();
    assert_eq!(balls.len(), 130);
    for (k, &i) in balls.iter().enumerate() {
        let p = b.pose[i].position;
        assert!(p.length() + 0.0025 <= 0.073, "ball {k} pokes out of the chamber");
        assert!((b.velocity[i].length() - 1.0).abs() < 1e-12, "ball {k} starts at 1 m/s");
        assert!((b.mass[i] - 0.514e-3).abs() < 0.001e-3, "a 5 mm steel ball weighs 0.514 g, not {}", b.mass[i]);
        for &j in &balls[k + 1..] {
            assert!(p.distance(b.pose[j].position) >= 0.005, "balls {i} and {j} overlap");
        }
    }
    // The same seed places the same balls.
    let again = mill_scene().build().unwrap();
    assert!(balls.iter().all(|&i| again.bodies().pose[i] == b.pose[i] && again.bodies().velocity[i] == b.velocity[i]));
}

#[test]
fn the_rotor_turns_at_its_rpm_and_the_chamber_stands() {
    let mut world = mill_scene().build().unwrap();
    let rest: Vec<f64> = (0..4).map(|i| world.bodies().pose[i].angle).collect();
    for _ in 0..100 {
        world.step().unwrap();
    }
    let b = world.bodies();
    let omega = 1700.0 * std::f64::consts::TAU / 60.0;
    assert_eq!(b.angular_velocity[0], 0.0, "the chamber stands");
    for (rotor, rest_angle) in rest.iter().enumerate().skip(1) {
        assert!((b.angular_velocity[rotor] - omega).abs() < 1e-9 * omega, "rotor part {rotor}");
        let turned = b.pose[rotor].angle - rest_angle;
        assert!((turned - omega * world.time()).abs() < 1e-9, "rotor part {rotor} turned {turned} rad");
    }
}

#[test]
fn mill_errors_name_the_field() {
    let scene = |rotor: &str, balls: &str| {
        format!(
            "Scene(mass_model: SphereEquivalent, materials: [(name: \"steel\", density_kg_m3: 7850)], mill: (rotor: ({rotor}), balls: ({balls})))"
        )
    };
    let error = |text: String| Scene::from_str(&text, "bad.ron").and_then(|s| s.build().map(drop)).unwrap_err();
    let e = error(scene("rpm: 1000, tip_radius_m: 0.08", "count: 10"));
    assert_eq!((e.kind(), e.path()), (ErrorKind::Value, "mill.rotor.tip_radius_m"), "{}", e.render_plain());
    // A hub larger than the chamber was reported at the tip radius, which lay inside the chamber.
    let e = error(scene("rpm: 1000, hub_radius_m: 0.08", "count: 10"));
    assert_eq!((e.kind(), e.path()), (ErrorKind::Value, "mill.rotor.hub_radius_m"), "{}", e.render_plain());
    assert!(e.message().contains("0.08: the hub must lie inside the chamber (radius 0.073 m)"), "{}", e.message());
    // A blade as wide as twice its tip radius leaves its capsule no straight part: it panicked the engine, and at
    // exactly twice the two arms became one disk, reported as an arm given twice.
    for (tip, width, twice) in
        [("0.012", "0.03", "0.024"), ("0.058", "0.116", "0.116"), ("0.058", "0.11599999999999999", "0.116")]
    {
        let rotor = format!("rpm: 1000, hub_radius_m: 0.008, tip_radius_m: {tip}, blade_width_m: {width}");
        let e = error(scene(&rotor, "count: 0"));
        assert_eq!((e.kind(), e.path()), (ErrorKind::Value, "mill.rotor.blade_width_m"), "{}", e.render_plain());
        assert!(e.message().contains(&format!("narrower than twice the tip radius ({twice} m)")), "{}", e.message());
    }
    // More than the densest packing could hold (773 of the default 5 mm balls in the 146 mm chamber): refused at
    // once. Below that but more than random placement finds room for (about 410): refused after the thousand
    // attempts of the first ball without room, not after a thousand per ball asked for (a count of 999,999 took
    // `check` some ten minutes).
    let e = error(scene("rpm: 1000", "count: 999999"));
    assert_eq!((e.kind(), e.path()), (ErrorKind::Value, "mill.balls.count"), "{}", e.render_plain());
    assert!(e.message().contains("at most 773"), "{}", e.message());
    let e = error(scene("rpm: 1000", "count: 700"));
    assert_eq!((e.kind(), e.path()), (ErrorKind::Value, "mill.balls.count"), "{}", e.render_plain());
    assert!(
        e.message().contains("found room") && e.message().contains("1000 attempts for the next"),
        "{}",
        e.message()
    );
    // Above the million particles a scene may start with: refused at the ball count (it was blamed on `blocks`).
    let e = error(scene("rpm: 1000", "count: 2000000"));
    assert_eq!((e.kind(), e.path()), (ErrorKind::Value, "mill.balls.count"), "{}", e.render_plain());
    assert!(e.message().contains("2000000 from `mill.balls.count`"), "{}", e.message());
    let e = error(scene("rpm: 1000", "count: 10, material: \"stel\""));
    assert_eq!(e.path(), "mill.balls.material", "{}", e.render_plain());
    // A mill far from the origin: its coordinates keep too few digits, which made its two blades look like one wall
    // ("an arm given twice"). Refused at the centre; a kilometre off is still fine.
    let far =
        |centre: &str| scene("rpm: 1000", "count: 10").replace("mill: (", &format!("mill: (centre_m: {centre}, "));
    let e = error(far("(1e12, 0)"));
    assert_eq!((e.kind(), e.path()), (ErrorKind::Value, "mill.centre_m"), "{}", e.render_plain());
    assert!(e.message().contains("chamber radii from the origin"), "{}", e.message());
    assert!(Scene::from_str(&far("(0, -1000)"), "far.ron").unwrap().build().is_ok());
}

#[test]
fn the_rotor_power_from_torque_equals_its_work_on_the_balls_at_every_step() {
    let mut world = mill_scene().build().unwrap();
    let mut driving_steps = 0;
    for _ in 0..20_000 {
        world.step().unwrap();
        let drive = world.rotor_power();
        let scale = drive.power_from_work.abs().max(drive.power_from_torque.abs());
        assert!(
            (drive.power_from_torque - drive.power_from_work).abs() <= 1e-9 * scale,
            "t = {}: ω·τ = {} W, Σ F·v = {} W",
            world.time(),
            drive.power_from_torque,
            drive.power_from_work
        );
        driving_steps += usize::from(scale > 0.0);
    }
    assert!(driving_steps > 100, "the rotor hit balls on {driving_steps} steps");
}

/// A scene file from scenes/.
fn preset(name: &str) -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("../../scenes/{name}.ron"));
    Scene::from_path(path).unwrap_or_else(|e| panic!("{}", e.render_plain()))
}

/// A steel mill scene with the given `mill` fields after the rotor, gravity off, and `particles`.
fn steel_mill(rotor: &str, rest: &str, particles: &str) -> Scene {
    let text = format!(
        "Scene(mass_model: SphereEquivalent, gravity: Constant(0.0), run: (max_impact_speed_m_s: 40.0),
         materials: [(name: \"steel\", density_kg_m3: 7850, youngs_modulus_pa: 196.2e9, poisson_ratio: 0.3)],
         interactions: [(materials: (\"steel\", \"steel\"), law: Hertz(damping: SteelReichardt, friction: (mu: 0.2)))],
         mill: (rotor: ({rotor}), {rest}), particles: [{particles}])"
    );
    Scene::from_str(&text, "mill_test.ron").unwrap_or_else(|e| panic!("{}", e.render_plain()))
}

/// The world-frame corners of wall `i`.
fn corners(world: &gc2d_engine::World, i: usize) -> Vec<DVec2> {
    world.bodies().world_vertices_of(BodyId(i as u32)).to_vec()
}

/// True if bodies `i` and `j` overlap.
fn overlap(world: &gc2d_engine::World, i: usize, j: usize) -> bool {
    let b = world.bodies();
    area_contact(b.shape_view(BodyId(i as u32)), b.shape_view(BodyId(j as u32))).is_some()
}

/// Asserts that no particle overlaps a wall or another particle.
fn assert_nothing_overlaps(world: &gc2d_engine::World) {
    let b = world.bodies();
    let particles: Vec<usize> = b.particles().map(|id| id.index()).collect();
    for (k, &i) in particles.iter().enumerate() {
        for j in (0..b.len()).filter(|&j| b.kind[j] == BodyKind::Wall).chain(particles[k + 1..].iter().copied()) {
            assert!(!overlap(world, i, j), "particle {i} overlaps body {j} ({:?})", b.shape[j]);
        }
    }
}

#[test]
fn ramps_rise_at_their_tilt_in_the_rotors_direction_at_the_top_and_the_bottom() {
    let world = preset("mill_ramps").build().unwrap();
    let b = world.bodies();
    let walls: Vec<ShapeKind> = (0..b.len()).filter(|&i| b.kind[i] == BodyKind::Wall).map(|i| b.shape[i]).collect();
    use ShapeKind::{Capsule, Disk, InnerCircle, Polygon};
    assert_eq!(walls, [InnerCircle, Polygon, Polygon, Disk, Capsule, Capsule]);
    let (radius, height, tilt) = (0.073, 0.005, std::f64::consts::FRAC_PI_6);
    for (wall, middle) in [(1, FRAC_PI_2), (2, 3.0 * FRAC_PI_2)] {
        let points = corners(&world, wall);
        assert_eq!(points.len(), 3);
        let crest = *points.iter().min_by(|a, b| a.length().total_cmp(&b.length())).unwrap();
        assert!((crest.length() - (radius - height)).abs() < 1e-12, "the crest is {height} m inside the circle");
        let on_circle: Vec<DVec2> = points.iter().copied().filter(|&p| p != crest).collect();
        assert!(on_circle.iter().all(|p| (p.length() - radius).abs() < 1e-12));
        // The foot is the corner away from the crest's ray; the rotor turns CCW, so the crest lies CCW of the foot.
        let (foot, behind) = if cross(on_circle[0], crest).abs() > cross(on_circle[1], crest).abs() {
            (on_circle[0], on_circle[1])
        } else {
            (on_circle[1], on_circle[0])
        };
        assert!(cross(behind, crest).abs() < 1e-15, "the ramp drops back along the radius");
        assert!(cross(foot, crest) > 0.0, "the ramp rises counter-clockwise, with the rotor");
        let tangent = foot.perp().normalize();
        let up = (crest - foot).normalize();
        assert!((up.dot(tangent).acos() - tilt).abs() < 1e-12, "the ramp leaves the circle at 30°");
        let centre_angle = (foot + behind).to_angle().rem_euclid(TAU);
        assert!((centre_angle - middle).abs() < 1e-12, "the ramp is centred at {middle} rad, not {centre_angle}");
    }
    assert_eq!(b.particles().count(), 130);
    assert_nothing_overlaps(&world);
}

#[test]
fn a_ramp_turns_the_other_way_for_a_clockwise_rotor() {
    let world = steel_mill("rpm: -1000", "chamber: Ramps(), balls: (count: 0)", "").build().unwrap();
    let points = corners(&world, 1);
    let crest = *points.iter().min_by(|a, b| a.length().total_cmp(&b.length())).unwrap();
    let foot = points.iter().copied().max_by(|a, b| cross(*a, crest).abs().total_cmp(&cross(*b, crest).abs())).unwrap();
    assert!(cross(foot, crest) < 0.0, "the ramp rises clockwise, with the rotor");
}

/// Shoots a 5 mm ball from `start` at `velocity` (m/s) and steps until it has bounced and moves away from the wall
/// for 50 µs; asserts it never got further from the centre than `limit` (m) and returns the rebound speed, m/s.
fn shoot(scene_rest: &str, start: DVec2, velocity: DVec2, limit: f64) -> f64 {
    let particle = format!(
        "(shape: Disk(radius_m: 0.0025), position_m: ({}, {}), velocity_m_s: ({}, {}))",
        start.x, start.y, velocity.x, velocity.y
    );
    let mut world = steel_mill("rpm: 0.0", &format!("{scene_rest}, balls: (count: 0)"), &particle).build().unwrap();
    let ball = world.bodies().particles().next().unwrap().index();
    let mut furthest: f64 = 0.0;
    let mut rebound_at = None;
    while rebound_at.is_none_or(|t| world.time() < t + 5e-5) {
        world.step().unwrap();
        let b = world.bodies();
        furthest = furthest.max(b.pose[ball].position.length());
        if rebound_at.is_none() && b.velocity[ball].dot(velocity) < 0.0 && world.contacts().next().is_none() {
            rebound_at = Some(world.time());
        }
        assert!(world.time() < 0.01, "the ball never came back");
    }
    assert!(furthest <= limit, "the ball reached {furthest} m from the centre, beyond {limit} m");
    assert_nothing_overlaps(&world);
    world.bodies().velocity[ball].length()
}

#[test]
fn a_fast_ball_hitting_a_ramps_corner_stays_inside() {
    // At the top ramp's foot, where the ramp leaves the circle: a 30 m/s ball straight at the corner.
    let world = steel_mill("rpm: 0.0", "chamber: Ramps(), balls: (count: 0)", "").build().unwrap();
    let points = corners(&world, 1);
    let crest = *points.iter().min_by(|a, b| a.length().total_cmp(&b.length())).unwrap();
    let foot = points.iter().copied().max_by(|a, b| cross(*a, crest).abs().total_cmp(&cross(*b, crest).abs())).unwrap();
    let direction = foot.normalize();
    let speed = shoot("chamber: Ramps()", foot - 0.01 * direction, 30.0 * direction, 0.073 - 0.0025 + 2e-4);
    assert!(speed > 5.0 && speed < 30.0, "rebound at {speed} m/s");
}

#[test]
fn the_wavy_chamber_is_a_closed_ring_of_thin_quadrilaterals_on_its_curve() {
    let world = preset("mill_wavy").build().unwrap();
    let b = world.bodies();
    let (radius, amplitude, segments) = (0.073, 0.004, 1024);
    let chamber: Vec<usize> =
        (0..b.len()).filter(|&i| b.kind[i] == BodyKind::Wall && b.shape[i] == ShapeKind::Polygon).collect();
    assert_eq!(chamber, (0..segments).collect::<Vec<_>>());
    let curve = |phi: f64| radius + amplitude * (6.0 * phi).cos();
    for k in 0..segments {
        let quad = corners(&world, k);
        let next = corners(&world, (k + 1) % segments);
        assert_eq!(quad.len(), 4);
        let on_curve = quad.iter().filter(|p| (p.length() - curve(p.to_angle())).abs() < 1e-12).count();
        assert_eq!(on_curve, 2, "piece {k} has two corners on the curve");
        let shared = quad.iter().filter(|p| next.iter().any(|q| p.distance(*q) < 1e-15)).count();
        assert_eq!(shared, 2, "pieces {k} and {} share an edge", (k + 1) % segments);
        for p in &quad {
            let off = p.length() - curve(p.to_angle());
            assert!(off > -1e-12 && off < 0.005 + 1e-12, "piece {k}: a corner {off} m off the curve");
        }
    }
    assert_eq!(b.particles().count(), 130);
    for id in b.particles() {
        let p = b.pose[id.index()].position;
        assert!(p.length() + 0.0025 < curve(p.to_angle()), "ball {} pokes out", id.index());
    }
    assert_nothing_overlaps(&world);
}

#[test]
fn a_fast_ball_hitting_a_joint_of_the_wavy_wall_stays_inside() {
    // 1200 pieces: joint 0 is on a crest of the wall (outermost), 100 in a trough, 50 on a flank.
    let wavy = "chamber: Wavy(amplitude_m: 0.004, segments: 1200)";
    let curve = |phi: f64| 0.073 + 0.004 * (6.0 * phi).cos();
    let steel = |v: f64| 0.985 / (v + 0.9494f64).powf(0.291);
    for joint in [0, 50, 100] {
        let angle = TAU * joint as f64 / 1200.0;
        let direction = DVec2::from_angle(angle);
        let start = (curve(angle) - 0.0025 - 0.005) * direction;
        let speed = shoot(wavy, start, 30.0 * direction, curve(angle) - 0.0025 + 2e-4);
        // Two pieces push at a joint, each with the law's dashpot: more damping than one wall (docs/scene-format.md).
        assert!(speed > 0.1 * 30.0 && speed < steel(30.0) * 30.0, "joint {joint}: rebound at {speed} m/s");
    }
}

#[test]
fn a_slow_ball_bounces_off_a_wavy_piece_as_off_the_circle_and_a_little_softer_at_a_joint() {
    let wavy = "chamber: Wavy(amplitude_m: 0.004, segments: 1200)";
    let steel = 0.985 / (1.0 + 0.9494f64).powf(0.291);
    let middle = DVec2::from_angle(TAU * 0.5 / 1200.0);
    // From 0.2 mm before the wall at its crest (77 mm from the centre).
    let e_piece = shoot(wavy, 0.0743 * middle, middle, 0.08);
    let e_joint = shoot(wavy, 0.0743 * DVec2::X, DVec2::X, 0.08);
    assert!((e_piece - steel).abs() < 1e-3, "off a piece e = {e_piece}, the steel law {steel}");
    assert!(e_joint < e_piece && e_joint > 0.9 * steel, "at a joint e = {e_joint}");
}

#[test]
fn a_bed_is_a_loose_triangular_packing_at_rest_at_the_bottom_and_stays_put() {
    let mut world = preset("mill_spinup").build().unwrap();
    let b = world.bodies();
    let balls: Vec<usize> = b.particles().map(|id| id.index()).collect();
    assert_eq!(balls.len(), 130);
    let spacing = 0.005 * 1.01;
    let start: Vec<DVec2> = balls.iter().map(|&i| b.pose[i].position).collect();
    for (k, &p) in start.iter().enumerate() {
        assert_eq!(b.velocity[balls[k]], DVec2::ZERO, "ball {k} is at rest");
        assert!(p.y < -0.073 / 3.0, "ball {k} at y = {} m is not in the lower part", p.y);
        // Rows 0.866 spacings apart from 2.5 mm above the bottom; places half a spacing apart, alternating.
        let row = (p.y - (-0.073 + 0.0025)) / (spacing * 0.75f64.sqrt());
        assert!((row - row.round()).abs() < 1e-9, "ball {k} is off the rows");
        let place = p.x / (0.5 * spacing);
        assert!((place - place.round()).abs() < 1e-9 && (place.round() + row.round()) % 2.0 == 0.0);
        let neighbours = start.iter().filter(|q| (q.distance(p) - spacing).abs() < 1e-12).count();
        assert!(neighbours >= 1, "ball {k} has no neighbour one spacing away");
        assert!(start[k + 1..].iter().all(|q| q.distance(p) > 0.005), "ball {k} touches another");
    }
    assert_nothing_overlaps(&world);
    // Rows fill from the bottom: the top row is the only partial one, and it is centred.
    let top = start.iter().map(|p| p.y).fold(f64::MIN, f64::max);
    let top_row: Vec<f64> = start.iter().filter(|p| p.y == top).map(|p| p.x).collect();
    let mean = top_row.iter().sum::<f64>() / top_row.len() as f64;
    assert!(mean.abs() <= 0.5 * spacing, "the top row is centred, its mean x is {mean} m");
    // At rest under gravity it settles by less than the gaps: after 2 ms (the rotor barely turning) no ball has moved
    // more than 0.2 mm or is faster than 0.1 m/s.
    world.run_until(0.002).unwrap();
    let b = world.bodies();
    for (k, &i) in balls.iter().enumerate() {
        assert!(b.pose[i].position.distance(start[k]) < 2e-4, "ball {k} moved");
        assert!(b.velocity[i].length() < 0.1, "ball {k} moves at {} m/s", b.velocity[i].length());
    }
}

#[test]
fn ore_grains_are_polygons_of_their_material_placed_among_the_balls_without_overlap() {
    let scene = preset("mill_ore");
    let world = scene.build().unwrap();
    let b = world.bodies();
    let particles: Vec<usize> = b.particles().map(|id| id.index()).collect();
    let (balls, grains): (Vec<usize>, Vec<usize>) = particles.iter().partition(|&&i| b.shape[i] == ShapeKind::Disk);
    assert_eq!((balls.len(), grains.len()), (100, 40));
    let (steel, calcite) = (b.material[balls[0]], b.material[grains[0]]);
    assert_ne!(steel, calcite);
    for &i in &grains {
        assert_eq!(b.shape[i], ShapeKind::Polygon);
        assert_eq!(b.material[i], calcite);
        assert!((b.velocity[i].length() - 1.0).abs() < 1e-12, "a grain starts at the balls' speed");
        let corners = world.bodies().world_vertices_of(BodyId(i as u32));
        assert!(corners.iter().all(|c| c.length() < 0.073), "grain {i} pokes out of the chamber");
    }
    assert!(balls.iter().all(|&i| b.material[i] == steel));
    assert_nothing_overlaps(&world);
    // The same seed places the same grains; the balls come first and are drawn as without ore.
    let again = scene.build().unwrap();
    assert!(
        particles.iter().all(|&i| again.bodies().pose[i] == b.pose[i] && again.bodies().velocity[i] == b.velocity[i])
    );
    let mut without = scene.clone();
    without.mill.as_mut().unwrap().ore = None;
    let without = without.build().unwrap();
    assert!(balls.iter().all(|&i| without.bodies().pose[i] == b.pose[i]));
}

#[test]
fn chamber_placement_and_ore_errors_name_the_field() {
    let scene = |chamber: &str, balls: &str, ore: &str| {
        format!(
            "Scene(mass_model: SphereEquivalent, materials: [(name: \"steel\", density_kg_m3: 7850)],
             mill: (chamber: {chamber}, rotor: (rpm: 1000), balls: ({balls}){ore}))"
        )
    };
    let error = |text: String| Scene::from_str(&text, "bad.ron").and_then(|s| s.build().map(drop)).unwrap_err();
    let cases = [
        (scene("Ramps(tilt_rad: 1.6)", "count: 10", ""), "mill.chamber.tilt_rad", "tilt"),
        (scene("Ramps(height_m: 0.012)", "count: 10", ""), "mill.chamber.height_m", "stays within"),
        (scene("Ramps(tilt_rad: 1.0, height_m: 0.0105)", "count: 10", ""), "mill.chamber.height_m", "crest"),
        (scene("Wavy(amplitude_m: 0.012)", "count: 10", ""), "mill.chamber.amplitude_m", "smallest radius"),
        (scene("Wavy(amplitude_m: 0.004, lobes: 40)", "count: 10", ""), "mill.chamber.amplitude_m", "tightest bend"),
        (scene("Wavy(amplitude_m: 0.004, lobes: 0)", "count: 10", ""), "mill.chamber.lobes", "wave"),
        (scene("Wavy(amplitude_m: 0.004, segments: 100)", "count: 10", ""), "mill.chamber.segments", "256"),
        (
            scene("Wavy(amplitude_m: 0.004, segments: 256)", "count: 10, radius_m: 0.0015", ""),
            "mill.chamber.segments",
            "ball radius",
        ),
        (scene("Circle", "count: 10, placement: Bed, speed_m_s: 1.0", ""), "mill.balls.speed_m_s", "at rest"),
        (scene("Circle", "count: 900, placement: Bed", ""), "mill.balls.count", "bed"),
        (
            scene("Circle", "count: 10", ", ore: (count: 5, shape: (semi_axes_m: (0.002, 0.002), corners: 2))"),
            "mill.ore.shape.corners",
            "",
        ),
        (
            scene("Circle", "count: 10", ", ore: (count: 5, material: \"rock\", shape: (semi_axes_m: (0.002, 0.002)))"),
            "mill.ore.material",
            "",
        ),
        (
            scene("Circle", "count: 10", ", ore: (count: 2000, shape: (semi_axes_m: (0.002, 0.002)))"),
            "mill.ore.count",
            "found room",
        ),
    ];
    for (text, path, words) in cases {
        let e = Scene::from_str(&text, "bad.ron").and_then(|s| s.build().map(drop)).expect_err(path);
        assert_eq!(e.path(), path, "{}", e.render_plain());
        assert!(e.message().contains(words), "{}", e.render_plain());
        assert!(e.location().is_some(), "{path} is located in the file: {}", e.render_plain());
    }
    let e = error(scene("Oval", "count: 10", ""));
    assert_eq!((e.kind(), e.path()), (ErrorKind::UnknownName, "mill.chamber"), "{}", e.render_plain());
}

/// The balls were placed avoiding only the mill's own walls: a baffle or a tracer particle of the scene inside the
/// chamber made the build fail (a ball on it, "move them apart", which random placement does not let a user do).
#[test]
fn balls_are_placed_clear_of_the_scenes_own_walls_and_particles() {
    let text =
        std::fs::read_to_string(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/mill.ron")).unwrap();
    let extra = "    walls: [Wall(shape: Rectangle(width_m: 0.02, height_m: 0.02), position_m: (0.0, -0.06))],\n    \
                 particles: [(shape: Disk(radius_m: 0.003), position_m: (0.03, -0.05))],\n    mill: (";
    assert!(text.contains("    mill: ("));
    let scene = Scene::from_str(&text.replacen("    mill: (", extra, 1), "baffle.ron").unwrap();
    let world = scene.build().unwrap();
    let b = world.bodies();
    let baffle = (0..b.len()).find(|&i| b.kind[i] == BodyKind::Wall).unwrap();
    let balls: Vec<usize> = b.particles().map(|id| id.index()).collect();
    assert_eq!(balls.len(), 131, "130 balls and the tracer");
    let tracer = balls[0];
    for &i in &balls[1..] {
        let p = b.pose[i].position;
        assert!(p.distance(b.pose[tracer].position) >= 0.0025 + 0.003, "ball {i} lies on the tracer");
        let corner = (p - b.pose[baffle].position).abs() - DVec2::splat(0.01);
        assert!(corner.max(DVec2::ZERO).length() >= 0.0025, "ball {i} lies on the baffle");
    }
}

/// A Hertz scene that leaves a pair of its materials out of `interactions` gave that pair the overlap-area law mixed
/// from the materials (E = 1e7 N/m) without a word: a forgotten entry, almost certainly. It is warned about.
#[test]
fn a_pair_left_out_of_a_hertz_scenes_interactions_is_warned_about() {
    let text =
        std::fs::read_to_string(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/mill_ore.ron")).unwrap();
    let entry =
        "        (materials: (\"steel\", \"calcite\"), law: Hertz(damping: Restitution(0.5), friction: (mu: 0.4))),\n";
    assert!(text.contains(entry));
    let complete = Scene::from_str(&text, "mill_ore.ron").unwrap();
    assert!(complete.warnings().is_empty(), "{:?}", complete.warnings());
    let missing = Scene::from_str(&text.replace(entry, ""), "mill_ore.ron").unwrap();
    let warnings = missing.warnings();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(warnings[0].contains("interactions: the pair `steel`–`calcite` has no entry"), "{warnings:?}");
    // One glass particle never meets another: steel–glass and glass–steel-wall pairs are told, glass–glass is not.
    let one_glass = "Scene(\n    mass_model: SphereEquivalent,\n    materials: [(name: \"steel\", density_kg_m3: 7700, \
        youngs_modulus_pa: 2e11), (name: \"glass\", density_kg_m3: 2500, youngs_modulus_pa: 6e10)],\n    interactions: \
        [(materials: (\"steel\", \"steel\"), law: Hertz())],\n    walls: [Wall(shape: Rectangle(width_m: 0.02, \
        height_m: 0.01), position_m: (0, -0.005))],\n    particles: [(shape: Disk(radius_m: 0.0025), position_m: (0, \
        0.003)), (shape: Disk(radius_m: 0.0025), position_m: (0.008, 0.003), material: \"glass\")],\n)";
    let warnings = Scene::from_str(one_glass, "one_glass.ron").unwrap().warnings();
    assert!(warnings.iter().any(|w| w.contains("`steel`–`glass`")), "{warnings:?}");
    assert!(!warnings.iter().any(|w| w.contains("`glass`–`glass`")), "{warnings:?}");
    // Two walls never meet: the feed pipe's `pipe`–`pipe` needs no entry.
    let pipe =
        std::fs::read_to_string(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/feedpipe.ron")).unwrap();
    let pipe = Scene::from_str(&pipe, "feedpipe.ron").unwrap();
    assert!(pipe.warnings().is_empty(), "{:?}", pipe.warnings());
}

/// Two blades were refused only at bit-identical angles: 2π written as 6.2831853, or 0 and 1e-9, gave a silent double
/// blade (every hit on one was a hit on the other). Angles equal modulo 2π to within 1 % of a blade's angular width
/// are refused at the second, naming both; blades a degree apart are two blades.
#[test]
fn a_blade_given_twice_modulo_a_turn_is_refused_naming_both() {
    let scene = |arms: &str| {
        format!(
            "Scene(mass_model: SphereEquivalent, materials: [(name: \"steel\", density_kg_m3: 7850)],
             mill: (rotor: (rpm: 1000, arms_rad: [{arms}]), balls: (count: 10)))"
        )
    };
    let error = |text: String| Scene::from_str(&text, "arms.ron").and_then(|s| s.build().map(drop)).unwrap_err();
    for (arms, second, first) in [
        ("0.0, 3.141592653589793, 6.2831853", "[2]", "[0]"),
        ("0.0, 6.283185307179586", "[1]", "[0]"),
        ("0.0, 1e-9", "[1]", "[0]"),
        ("-3.1415926, 3.141592653589793", "[1]", "[0]"),
        ("1.0, 2.0, 13.566370614359172", "[2]", "[0]"),
    ] {
        let e = error(scene(arms));
        let field = format!("mill.rotor.arms_rad{second}");
        assert_eq!((e.kind(), e.path()), (ErrorKind::Value, field.as_str()), "{arms}: {}", e.render_plain());
        assert!(e.location().is_some(), "{}", e.render_plain());
        let message = e.message();
        assert!(message.contains(&format!("`mill.rotor.arms_rad{first}`")), "{message}");
        assert!(message.contains("modulo 2π") && message.contains("blade_width_m / tip_radius_m"), "{message}");
        assert!(message.contains("0.0014 rad (1 % of a blade's angular width"), "{message}");
    }
    assert!(Scene::from_str(&scene("0.0, 0.0175"), "arms.ron").unwrap().build().is_ok());
}

/// A mill left on the default per-unit-thickness masses with its Hertz law passed `check` without a word and blew up
/// at the first blade hit, advising a stiffer material: the law's force is a sphere's while the masses are per metre
/// of depth. Warned about at the law's entry, naming `mass_model` and the pair.
#[test]
fn a_penetration_law_with_masses_per_unit_thickness_is_warned_about() {
    let text =
        std::fs::read_to_string(PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/mill.ron")).unwrap();
    assert!(Scene::from_str(&text, "mill.ron").unwrap().warnings().is_empty());
    let flat = text.replace("    mass_model: SphereEquivalent,\n", "").replace("density_kg_m3", "density_kg_m2");
    assert_ne!(flat, text);
    let warnings = Scene::from_str(&flat, "mill_2d.ron").unwrap().warnings();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    let warning = &warnings[0];
    assert!(warning.starts_with("mill_2d.ron:") && warning.contains(": interactions[0].law: "), "{warning}");
    assert!(warning.contains("the Hertz law of `steel`–`steel`"), "{warning}");
    assert!(warning.contains("`mass_model` is `PerUnitThickness`"), "{warning}");
    assert!(warning.contains("set `mass_model: SphereEquivalent`"), "{warning}");
    // The overlap-area law is the one made for masses per unit thickness.
    let area = flat.replace("law: Hertz(damping: SteelReichardt, friction: (mu: 0.2))", "law: OverlapArea()");
    assert_ne!(area, flat);
    assert!(Scene::from_str(&area, "mill_area.ron").unwrap().warnings().is_empty());
}

/// The mill's messages printed computed numbers with every digit (0.014999999999999993 m, 1.3698630136986302e7) and
/// a value of 1e300 as 301 digits, and one had a run of stray spaces: numbers read as a scene writes them, derived
/// ones to 4 significant digits.
#[test]
fn mill_messages_write_numbers_short() {
    let scene = |mill: &str| {
        format!(
            "Scene(mass_model: SphereEquivalent, materials: [(name: \"steel\", density_kg_m3: 7850)],
             mill: (chamber_radius_m: 0.073, rotor: (rpm: 1700, hub_radius_m: 0.008, tip_radius_m: 0.058), {mill}))"
        )
    };
    let message = |mill: &str| {
        Scene::from_str(&scene(mill), "short.ron").and_then(|s| s.build().map(drop)).unwrap_err().message().to_owned()
    };
    let cases = [
        ("centre_m: (1e6, 0), balls: (count: 10)", "(1000000, 0): the mill's centre lies 1.37e7 chamber radii"),
        ("centre_m: (1e6, 0), balls: (count: 10)", "beyond the 1000000 at which coordinates keep"),
        (
            "balls: (count: 10, radius_m: 0.08)",
            "0.08: a ball must fit between the blade tips and the chamber (0.015 m)",
        ),
        (
            "balls: (count: 10, radius_m: 1e300)",
            "1e300: a ball must fit between the blade tips and the chamber (0.015 m)",
        ),
        ("chamber: Ramps(tilt_rad: 0.5, height_m: 0.02), balls: (count: 10)", "stays within 0.008936 m of it"),
        ("chamber: Wavy(amplitude_m: 0.02), balls: (count: 10)", "R − A = 0.053 m must exceed"),
        ("chamber: Wavy(amplitude_m: 0.001, lobes: 500, segments: 10000), balls: (count: 10)", "radius of 2.19e-5 m"),
    ];
    for (mill, expected) in cases {
        let message = message(mill);
        assert!(message.contains(expected), "{mill}: {message}");
        assert!(!message.contains("  ") && !message.contains("99999") && !message.contains("0000000000"), "{message}");
    }
}

/// For a penetration law (every mill) `max_overlap_fraction` is the depth over the smaller diameter (docs/model.md),
/// but the docs of the time series and of the run's limit called it a fraction of the area, 19 times larger than the
/// area share of a Hertz impact.
#[test]
fn the_docs_call_a_penetration_contacts_overlap_fraction_a_share_of_the_diameter() {
    let docs = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs");
    for (file, row) in
        [("outputs.md", "| `max_overlap_fraction` | – |"), ("scene-format.md", "| `max_overlap_fraction` | – | 0.05 |")]
    {
        let text = std::fs::read_to_string(docs.join(file)).unwrap();
        let line = text.lines().find(|line| line.starts_with(row)).unwrap_or_else(|| panic!("{file}: no {row}"));
        assert!(line.contains("depth as a fraction of the smaller particle's diameter"), "{file}: {line}");
    }
    let validation = std::fs::read_to_string(docs.join("validation.md")).unwrap();
    assert!(!validation.contains("share of the smaller area"), "validation.md");
}
