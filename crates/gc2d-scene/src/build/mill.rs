//! The ball mill section to walls and particles: the chamber (an inner-circle wall; with two triangular ramp walls on
//! it; or a wavy outline traced by thin quadrilateral walls), the rotor as a hub disk and one capsule per blade arm,
//! all turning about the chamber's centre, the balls placed at random without overlap (ballmill.md §7.2: r = R·√u,
//! φ = 2π·u', overlaps with balls, walls, hub and blades rejected) or in a bed at rest, and the ore grains placed at
//! random among them.

use super::PlannedParticle;
use super::shapes::{particle_recipe, polygon_error};
use super::walls::PlacedWall;
use crate::checks::{finite, finite_pair, non_negative, number, positive, significant_digits};
use crate::error::SceneError;
use crate::schema::{BallPlacement, Chamber, MassModel, Mill};
use crate::spans::field_path;
use crate::validate::Materials;
use gc2d_engine::motion::Rotation;
use gc2d_engine::{BodyShape, MaterialId, ShapeKind, TimeWindow, WallMotion, shape_view};
use gc2d_geometry::{ConvexPolygon, DVec2, Pose, area_contact};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use std::f64::consts::{FRAC_PI_2, TAU};

/// Placement attempts per ball or ore grain before the mill is declared too full.
const PLACEMENT_ATTEMPTS_PER_BALL: usize = 1000;
/// Fewest straight pieces of a wavy chamber (ballmill.md §7.2: a faceted chamber needs ≥ 256 so that a piece is much
/// shorter than a ball's radius).
pub const MIN_CHAMBER_SEGMENTS: usize = 256;
/// Most straight pieces of a wavy chamber.
pub const MAX_CHAMBER_SEGMENTS: usize = 10_000;
/// The longest piece of a wavy chamber, in ball radii.
const MAX_SEGMENT_PER_BALL_RADIUS: f64 = 1.0;
/// The gap between neighbouring balls of a bed, as a fraction of the ball diameter (a loose packing).
const BED_GAP: f64 = 0.01;
/// The farthest a mill's centre may lie from the origin, in chamber radii (see `check`).
const MAX_CENTRE_OFFSET_RADII: f64 = 1e6;
/// Samples of one wave when the wavy wall's curvature is checked.
const CURVATURE_SAMPLES_PER_LOBE: usize = 4096;
/// Two blades whose angles agree modulo 2π to within this share of a blade's angular width at its tip
/// (`blade_width_m / tip_radius_m`) are one blade given twice: their tips lie less than this share of the width apart.
const SAME_ARM_WIDTH_SHARE: f64 = 0.01;

/// A number the checks computed (a gap, a bound, a ratio), rounded for a message to 4 significant digits: 0.015 m, not
/// 0.014999999999999993 m.
fn derived(x: f64) -> String {
    significant_digits(x, 4)
}

/// The speed of the blade tips at the rotor's full speed, m/s.
pub(crate) fn tip_speed(mill: &Mill) -> f64 {
    (mill.rotor.rpm * TAU / 60.0 * mill.rotor.tip_radius_m).abs()
}

/// The farthest the chamber's wall gets from the centre, m.
pub(crate) fn outer_radius(mill: &Mill) -> f64 {
    match mill.chamber {
        Chamber::Wavy { amplitude_m, .. } => mill.chamber_radius_m + amplitude_m.abs(),
        Chamber::Circle | Chamber::Ramps { .. } => mill.chamber_radius_m,
    }
}

/// The distance of the chamber's curve from the centre in direction φ (rad from +x), m; ramps are walls of their own
/// and not part of it.
fn outline_radius(mill: &Mill, phi: f64) -> f64 {
    match mill.chamber {
        Chamber::Wavy { amplitude_m, lobes, .. } => {
            mill.chamber_radius_m + amplitude_m * (f64::from(lobes) * phi).cos()
        }
        Chamber::Circle | Chamber::Ramps { .. } => mill.chamber_radius_m,
    }
}

/// Checks the mill's numbers, each at its field.
pub(crate) fn check(mill: &Mill, path: &str) -> Result<(), SceneError> {
    let at = |field: &str| field_path(path, field);
    let rotor = |field: &str| field_path(&at("rotor"), field);
    let balls = |field: &str| field_path(&at("balls"), field);
    finite_pair(&at("centre_m"), mill.centre_m)?;
    positive(&at("chamber_radius_m"), mill.chamber_radius_m)?;
    // Far from the origin, f64 coordinates keep too few digits for the contacts of balls a fraction of the chamber's
    // size (at 1e6 radii, about 1e-10 of a radius; further out, the blades' ends and the balls' overlaps blur).
    let offset = mill.centre_m[0].abs().max(mill.centre_m[1].abs());
    if offset > MAX_CENTRE_OFFSET_RADII * mill.chamber_radius_m {
        return Err(SceneError::value(
            at("centre_m"),
            format!(
                "({}, {}): the mill's centre lies {} chamber radii from the origin, beyond the {} at which \
                 coordinates keep enough digits for its contacts",
                number(mill.centre_m[0]),
                number(mill.centre_m[1]),
                derived(offset / mill.chamber_radius_m),
                number(MAX_CENTRE_OFFSET_RADII)
            ),
        )
        .with_help("place the mill near the origin, e.g. `centre_m: (0, 0)`"));
    }
    finite(&rotor("rpm"), mill.rotor.rpm)?;
    non_negative(&rotor("spin_up_s"), mill.rotor.spin_up_s)?;
    positive(&rotor("hub_radius_m"), mill.rotor.hub_radius_m)?;
    positive(&rotor("blade_width_m"), mill.rotor.blade_width_m)?;
    if mill.rotor.hub_radius_m >= mill.chamber_radius_m {
        return Err(SceneError::value(
            rotor("hub_radius_m"),
            format!(
                "{}: the hub must lie inside the chamber (radius {} m)",
                number(mill.rotor.hub_radius_m),
                number(mill.chamber_radius_m)
            ),
        ));
    }
    let tip = mill.rotor.tip_radius_m;
    if !(tip.is_finite() && tip > mill.rotor.hub_radius_m && tip < mill.chamber_radius_m) {
        return Err(SceneError::value(
            rotor("tip_radius_m"),
            format!("{}: the blade tips must reach beyond the hub and stay inside the chamber", number(tip)),
        ));
    }
    // An arm is a capsule from the hub's centre whose round end reaches the tip: it needs a straight part, and one of
    // round-off's length (a width a few ulps below twice the tip) made two opposite arms one wall.
    let width = mill.rotor.blade_width_m;
    if tip - 0.5 * width <= 1e-6 * tip {
        return Err(SceneError::value(
            rotor("blade_width_m"),
            format!(
                "{}: a blade must be narrower than twice the tip radius ({} m), so that its round end reaches the tip \
                 from the rotor's centre along a straight part (of at least a millionth of the tip radius)",
                number(width),
                number(2.0 * tip)
            ),
        ));
    }
    for (k, &arm) in mill.rotor.arms_rad.iter().enumerate() {
        finite(&format!("{}[{k}]", rotor("arms_rad")), arm)?;
    }
    check_arms_distinct(mill, &rotor("arms_rad"))?;
    positive(&balls("radius_m"), mill.balls.radius_m)?;
    if let Some(speed) = mill.balls.speed_m_s {
        non_negative(&balls("speed_m_s"), speed)?;
        if mill.balls.placement == BallPlacement::Bed && speed != 0.0 {
            return Err(SceneError::value(balls("speed_m_s"), format!("{}: a bed starts at rest", number(speed)))
                .with_help("leave `speed_m_s` out, or use `placement: Random` for moving balls"));
        }
    }
    if 2.0 * mill.balls.radius_m >= mill.chamber_radius_m - tip {
        return Err(SceneError::value(
            balls("radius_m"),
            format!(
                "{}: a ball must fit between the blade tips and the chamber ({} m)",
                number(mill.balls.radius_m),
                derived(mill.chamber_radius_m - tip)
            ),
        ));
    }
    check_chamber(mill, &at("chamber"))?;
    if let Some(ore) = &mill.ore {
        particle_recipe(&ore.shape, &field_path(&at("ore"), "shape"))?;
    }
    Ok(())
}

/// Refuses two blades whose angles agree modulo 2π to within [`SAME_ARM_WIDTH_SHARE`] of a blade's angular width: 2π
/// written as 6.2831853 is the same blade as 0, and a particle touching one touches both, at twice the stiffness.
fn check_arms_distinct(mill: &Mill, path: &str) -> Result<(), SceneError> {
    let arms = &mill.rotor.arms_rad;
    let angular_width = mill.rotor.blade_width_m / mill.rotor.tip_radius_m;
    let tolerance = SAME_ARM_WIDTH_SHARE * angular_width;
    for (k, &arm) in arms.iter().enumerate() {
        for (j, &earlier) in arms[..k].iter().enumerate() {
            let turn = (arm - earlier).rem_euclid(TAU);
            let apart = turn.min(TAU - turn);
            if apart <= tolerance {
                return Err(SceneError::value(
                    format!("{path}[{k}]"),
                    format!(
                        "{}: this blade (`{path}[{k}]`) points {} rad from `{path}[{j}]` ({}) modulo 2π, within {} rad \
                         ({} % of a blade's angular width, blade_width_m / tip_radius_m = {} rad): the two are one \
                         blade given twice, and a particle touching one touches both and feels twice the contact \
                         stiffness and damping",
                        number(arm),
                        significant_digits(apart, 2),
                        number(earlier),
                        significant_digits(tolerance, 2),
                        number(100.0 * SAME_ARM_WIDTH_SHARE),
                        significant_digits(angular_width, 3)
                    ),
                )
                .with_help("give each blade's angle once (angles a whole turn, 2π, apart are the same blade)")
                .with_label("the same blade again"));
            }
        }
    }
    Ok(())
}

/// Checks a ramp or wavy chamber against the rotor and the balls.
fn check_chamber(mill: &Mill, path: &str) -> Result<(), SceneError> {
    let at = |field: &str| field_path(path, field);
    let radius = mill.chamber_radius_m;
    let ball = mill.balls.radius_m;
    let free = mill.rotor.tip_radius_m + 2.0 * ball;
    match mill.chamber {
        Chamber::Circle => {}
        Chamber::Ramps { tilt_rad, height_m } => {
            if !(tilt_rad > 0.0 && tilt_rad < FRAC_PI_2) {
                return Err(SceneError::value(
                    at("tilt_rad"),
                    format!("{}: the tilt must lie in (0, π/2) (radians from the wall's tangent)", number(tilt_rad)),
                ));
            }
            positive(&at("height_m"), height_m)?;
            let deepest = radius * (1.0 - tilt_rad.cos());
            if height_m >= deepest {
                return Err(SceneError::value(
                    at("height_m"),
                    format!(
                        "{}: a ramp at {} rad leaving a circle of radius {} m stays within {} m of it",
                        number(height_m),
                        number(tilt_rad),
                        number(radius),
                        derived(deepest)
                    ),
                )
                .with_help("use a lower ramp or a steeper tilt"));
            }
            if radius - height_m <= free {
                return Err(SceneError::value(
                    at("height_m"),
                    format!(
                        "{}: a ball must fit between the blade tips and a ramp's crest (at most {} m high)",
                        number(height_m),
                        derived(radius - free)
                    ),
                ));
            }
        }
        Chamber::Wavy { amplitude_m, lobes, segments } => {
            positive(&at("amplitude_m"), amplitude_m)?;
            if lobes == 0 {
                return Err(SceneError::value(at("lobes"), "0: the wall needs at least one wave"));
            }
            if !(MIN_CHAMBER_SEGMENTS..=MAX_CHAMBER_SEGMENTS).contains(&segments) {
                return Err(SceneError::value(
                    at("segments"),
                    format!(
                        "{segments} segments: a wavy chamber needs {MIN_CHAMBER_SEGMENTS} to {MAX_CHAMBER_SEGMENTS}"
                    ),
                ));
            }
            if radius - amplitude_m <= free {
                return Err(SceneError::value(
                    at("amplitude_m"),
                    format!(
                        "{}: the wall's smallest radius R − A = {} m must exceed the blade tips plus a ball diameter \
                         ({} m)",
                        number(amplitude_m),
                        derived(radius - amplitude_m),
                        derived(free)
                    ),
                ));
            }
            let curvature = wavy_max_curvature(radius, amplitude_m, lobes);
            if curvature * ball >= 1.0 {
                return Err(SceneError::value(
                    at("amplitude_m"),
                    format!(
                        "{}: the wall's tightest bend has a radius of {} m, not more than the ball radius {} m",
                        number(amplitude_m),
                        derived(1.0 / curvature),
                        number(ball)
                    ),
                )
                .with_help("use a smaller amplitude or fewer waves"));
            }
            let outline = wavy_outline(mill, segments);
            let longest = (0..segments).map(|k| outline[k].distance(outline[(k + 1) % segments])).fold(0.0, f64::max);
            let limit = MAX_SEGMENT_PER_BALL_RADIUS * ball;
            if longest > limit {
                let needed = (segments as f64 * longest / limit).ceil();
                return Err(SceneError::value(
                    at("segments"),
                    format!(
                        "{segments} segments: the pieces are up to {} m long, longer than the ball radius ({} m)",
                        derived(longest),
                        number(limit)
                    ),
                )
                .with_help(format!("use at least {needed} segments")));
            }
        }
    }
    Ok(())
}

/// The largest curvature (1/m, positive where the wall bends around the chamber like a circle) of ρ(φ) = R + A·cos(nφ),
/// sampled over one wave.
fn wavy_max_curvature(radius: f64, amplitude: f64, lobes: u32) -> f64 {
    let n = f64::from(lobes);
    (0..CURVATURE_SAMPLES_PER_LOBE)
        .map(|k| {
            let phi = TAU / n * k as f64 / CURVATURE_SAMPLES_PER_LOBE as f64;
            let (sin, cos) = (n * phi).sin_cos();
            let (rho, d1, d2) = (radius + amplitude * cos, -amplitude * n * sin, -amplitude * n * n * cos);
            (rho * rho + 2.0 * d1 * d1 - rho * d2) / (rho * rho + d1 * d1).powf(1.5)
        })
        .fold(f64::MIN, f64::max)
}

/// The `segments` corners of a wavy chamber's outline, counter-clockwise from +x, about the mill's centre.
fn wavy_outline(mill: &Mill, segments: usize) -> Vec<DVec2> {
    let centre = DVec2::from_array(mill.centre_m);
    (0..segments)
        .map(|k| {
            let phi = TAU * k as f64 / segments as f64;
            centre + outline_radius(mill, phi) * DVec2::from_angle(phi)
        })
        .collect()
}

/// The chamber's walls, then the hub and the blades, at their poses at t = 0; the rotor parts turn at the rotor's
/// speed.
pub(crate) fn walls(mill: &Mill, path: &str) -> Result<Vec<PlacedWall>, SceneError> {
    let centre = DVec2::from_array(mill.centre_m);
    let rotor = &mill.rotor;
    let motion = WallMotion::Rotating(Rotation {
        pivot: centre,
        angular_velocity: rotor.rpm * TAU / 60.0,
        window: TimeWindow::new(0.0, f64::INFINITY),
        spin_up: rotor.spin_up_s,
    });
    let placed = |shape, pose, motion, material: &Option<String>, part: &str| PlacedWall {
        shape,
        pose,
        surface_velocity: DVec2::ZERO,
        motion,
        material: material.clone(),
        path: field_path(path, part),
    };
    let fixed = |corners: &[DVec2]| -> Result<PlacedWall, SceneError> {
        let chamber_path = field_path(path, "chamber");
        let (polygon, centroid) = ConvexPolygon::new(corners).map_err(|e| {
            SceneError::value(
                &chamber_path,
                format!("a chamber wall is degenerate: {}", polygon_error(&e, "").message()),
            )
        })?;
        Ok(placed(polygon.into(), Pose::new(centroid, 0.0), WallMotion::Static, &mill.chamber_material, "chamber"))
    };
    let circle = || {
        placed(
            BodyShape::InnerCircle { radius: mill.chamber_radius_m },
            Pose::new(centre, 0.0),
            WallMotion::Static,
            &mill.chamber_material,
            "chamber_radius_m",
        )
    };
    let mut walls = Vec::new();
    match mill.chamber {
        Chamber::Circle => walls.push(circle()),
        Chamber::Ramps { tilt_rad, height_m } => {
            walls.push(circle());
            // Against the rotor's turning: balls carried along the wall run up the ramp.
            let turning = if rotor.rpm < 0.0 { -1.0 } else { 1.0 };
            for middle in [FRAC_PI_2, 3.0 * FRAC_PI_2] {
                walls.push(fixed(&ramp_corners(mill, tilt_rad, height_m, middle, turning))?);
            }
        }
        Chamber::Wavy { segments, .. } => {
            // One quadrilateral per piece, the piece and its copy one ball diameter further out along the rays
            // through its ends: neighbours share that radial edge, so the wall has no gap to slip through.
            let thickness = 2.0 * mill.balls.radius_m;
            let inner = wavy_outline(mill, segments);
            let outer: Vec<DVec2> = inner.iter().map(|&p| p + thickness * (p - centre).normalize_or_zero()).collect();
            for k in 0..segments {
                let next = (k + 1) % segments;
                walls.push(fixed(&[inner[k], outer[k], outer[next], inner[next]])?);
            }
        }
    }
    walls.push(placed(
        BodyShape::Disk { radius: rotor.hub_radius_m },
        Pose::new(centre, 0.0),
        motion,
        &mill.rotor_material,
        "rotor",
    ));
    // Each arm: a capsule from the hub's centre out to the tip, its round end reaching the tip radius.
    let radius = 0.5 * rotor.blade_width_m;
    let outer = rotor.tip_radius_m - radius;
    for &arm in &rotor.arms_rad {
        let direction = DVec2::from_angle(arm);
        let shape = BodyShape::Capsule { half_length: 0.5 * outer, radius };
        let pose = Pose::new(centre + 0.5 * outer * direction, arm);
        walls.push(placed(shape, pose, motion, &mill.rotor_material, "rotor.arms_rad"));
    }
    Ok(walls)
}

/// The corners of one ramp centred on direction `middle` (rad): its foot on the circle, its crest `height` inside the
/// circle, reached along a line at `tilt` to the circle's tangent at the foot going in the direction `turning` (+1
/// counter-clockwise), and the point on the circle radially behind the crest.
fn ramp_corners(mill: &Mill, tilt: f64, height: f64, middle: f64, turning: f64) -> [DVec2; 3] {
    let centre = DVec2::from_array(mill.centre_m);
    let radius = mill.chamber_radius_m;
    let (sin, cos) = tilt.sin_cos();
    // The distance s along the ramp at which |foot + s·direction| = R − height.
    let along = radius * sin - ((radius * sin).powi(2) - (2.0 * radius - height) * height).sqrt();
    let span = (along * cos).atan2(radius - along * sin);
    let foot = middle - 0.5 * turning * span;
    let top = foot + turning * span;
    [
        centre + radius * DVec2::from_angle(foot),
        centre + (radius - height) * DVec2::from_angle(top),
        centre + radius * DVec2::from_angle(top),
    ]
}

/// A body already placed, as the placement's overlap test sees it.
struct Occupied {
    kind: ShapeKind,
    points: Vec<DVec2>,
    radius: f64,
    /// Centre and radius of a circle around the body (infinite for a chamber circle).
    centre: DVec2,
    reach: f64,
}

impl Occupied {
    fn new(shape: &BodyShape, pose: Pose) -> Self {
        let points: Vec<DVec2> = shape.body_points().iter().map(|&p| pose.apply(p)).collect();
        let radius = shape.radius() * pose.scale;
        let reach = match shape {
            BodyShape::InnerCircle { .. } => f64::INFINITY,
            _ => points.iter().map(|p| p.distance(pose.position)).fold(0.0, f64::max) + radius,
        };
        Self { kind: shape.kind(), points, radius, centre: pose.position, reach }
    }

    /// True if the two bodies overlap.
    fn overlaps(&self, other: &Occupied) -> bool {
        self.centre.distance(other.centre) < self.reach + other.reach
            && area_contact(
                shape_view(self.kind, &self.points, self.radius),
                shape_view(other.kind, &other.points, other.radius),
            )
            .is_some()
    }

    /// True if every point of the body lies inside the chamber's curve and the body overlaps none of `others`.
    fn fits(&self, mill: &Mill, others: &[Occupied]) -> bool {
        let centre = DVec2::from_array(mill.centre_m);
        let inside = self.points.iter().all(|&p| {
            let offset = p - centre;
            offset.length() < outline_radius(mill, offset.y.atan2(offset.x))
        });
        inside && others.iter().all(|other| !self.overlaps(other))
    }
}

/// The balls, then the ore grains. Balls placed at `Random` draw from `rng` in a fixed order (position, then
/// direction, per ball), a `Bed` draws nothing; each grain then draws its shape, its positions until one is free, and
/// its direction. The same seed places the same particles.
pub(crate) fn particles(
    mill: &Mill,
    walls: &[PlacedWall],
    others: &[(&BodyShape, Pose)],
    materials: &Materials,
    mass_model: MassModel,
    rng: &mut ChaCha8Rng,
    path: &str,
) -> Result<Vec<PlannedParticle>, SceneError> {
    let balls = &mill.balls;
    let balls_path = field_path(path, "balls");
    let material_path = field_path(&balls_path, "material");
    let material = materials.resolve(balls.material.as_deref(), &material_path)?;
    let material_id = MaterialId(materials.index_of(balls.material.as_deref(), &material_path)? as u16);
    let density = Materials::density(material, mass_model);
    let speed = balls.start_speed();
    // The mill's walls, and the scene's own walls and particles (a baffle, a tracer): no ball or grain is placed on one.
    let mut occupied: Vec<Occupied> = walls.iter().map(|w| Occupied::new(&w.shape, w.pose)).collect();
    occupied.extend(others.iter().map(|(shape, pose)| Occupied::new(shape, *pose)));
    let ball = BodyShape::Disk { radius: balls.radius_m };
    let positions = match balls.placement {
        BallPlacement::Random => random_balls(mill, &mut occupied, rng, &balls_path)?,
        BallPlacement::Bed => bed(mill, &mut occupied, &balls_path)?,
    };
    let mut planned: Vec<PlannedParticle> = positions
        .into_iter()
        .map(|(position, velocity)| PlannedParticle {
            shape: ball.clone(),
            pose: Pose::new(position, 0.0),
            velocity,
            angular_velocity: 0.0,
            density,
            material: material_id,
            drag_spring: None,
            path: balls_path.clone(),
        })
        .collect();
    let Some(ore) = &mill.ore else { return Ok(planned) };
    let ore_path = field_path(path, "ore");
    let material_path = field_path(&ore_path, "material");
    let material = materials.resolve(ore.material.as_deref(), &material_path)?;
    let material_id = MaterialId(materials.index_of(ore.material.as_deref(), &material_path)? as u16);
    let density = Materials::density(material, mass_model);
    let recipe = particle_recipe(&ore.shape, &field_path(&ore_path, "shape"))?;
    let centre = DVec2::from_array(mill.centre_m);
    for placed in 0..ore.count {
        let (shape, angle) =
            recipe.draw(rng).map_err(|e| SceneError::value(field_path(&ore_path, "shape"), e.to_string()))?;
        let size = Occupied::new(&shape, Pose::new(DVec2::ZERO, angle)).reach;
        let reach = (outer_radius(mill) - size).max(0.0);
        let mut attempts = 0;
        let grain = loop {
            attempts += 1;
            if attempts > PLACEMENT_ATTEMPTS_PER_BALL {
                return Err(SceneError::value(
                    field_path(&ore_path, "count"),
                    format!(
                        "only {placed} of {} ore grains found room among the balls ({PLACEMENT_ATTEMPTS_PER_BALL} \
                         attempts for the next)",
                        ore.count
                    ),
                )
                .with_help("use fewer or smaller grains or balls"));
            }
            let position = centre + reach * rng.random::<f64>().sqrt() * DVec2::from_angle(TAU * rng.random::<f64>());
            let pose = Pose::new(position, angle);
            let grain = Occupied::new(&shape, pose);
            if grain.fits(mill, &occupied) {
                occupied.push(grain);
                break pose;
            }
        };
        planned.push(PlannedParticle {
            shape,
            pose: grain,
            velocity: speed * DVec2::from_angle(TAU * rng.random::<f64>()),
            angular_velocity: 0.0,
            density,
            material: material_id,
            drag_spring: None,
            path: ore_path.clone(),
        });
    }
    Ok(planned)
}

/// Positions and velocities of balls placed uniformly at random in the chamber, each added to `occupied`; refused
/// where the chamber could not hold them even densely packed, or where a ball finds no room in
/// [`PLACEMENT_ATTEMPTS_PER_BALL`] attempts (the ones before it placed).
fn random_balls(
    mill: &Mill,
    occupied: &mut Vec<Occupied>,
    rng: &mut ChaCha8Rng,
    path: &str,
) -> Result<Vec<(DVec2, DVec2)>, SceneError> {
    let balls = &mill.balls;
    let (r, speed) = (balls.radius_m, balls.start_speed());
    let centre = DVec2::from_array(mill.centre_m);
    let chamber = outer_radius(mill);
    let reach = chamber - r;
    let most = densest_disk_count(chamber, r);
    if balls.count as f64 > most {
        return Err(SceneError::value(
            field_path(path, "count"),
            format!(
                "{} balls of radius {} m cannot fit in a chamber of radius {} m: packed as densely as disks can be, it \
                 would hold at most {}",
                balls.count,
                number(r),
                number(chamber),
                most.floor()
            ),
        )
        .with_help("use fewer or smaller balls, or a larger chamber"));
    }
    let walls = occupied.len();
    let mut attempts = 0;
    let mut placed = Vec::with_capacity(balls.count);
    while placed.len() < balls.count {
        attempts += 1;
        if attempts > PLACEMENT_ATTEMPTS_PER_BALL {
            return Err(SceneError::value(
                field_path(path, "count"),
                format!(
                    "only {} of {} balls found room in the chamber ({PLACEMENT_ATTEMPTS_PER_BALL} attempts for the \
                     next)",
                    placed.len(),
                    balls.count
                ),
            )
            .with_help("use fewer or smaller balls, or a larger chamber"));
        }
        let radial = reach * rng.random::<f64>().sqrt();
        let position = centre + radial * DVec2::from_angle(TAU * rng.random::<f64>());
        let free_of_balls = occupied[walls..].iter().all(|other| other.centre.distance(position) >= 2.0 * r);
        let candidate = Occupied::new(&BodyShape::Disk { radius: r }, Pose::new(position, 0.0));
        if !(free_of_balls && candidate.fits(mill, &occupied[..walls])) {
            continue;
        }
        occupied.push(candidate);
        placed.push((position, speed * DVec2::from_angle(TAU * rng.random::<f64>())));
        attempts = 0;
    }
    Ok(placed)
}

/// The most disks of radius `r` that a circle of radius `radius` could hold at the density of the densest packing of
/// equal disks in the plane, π/(2√3) ≈ 0.907 of the area: an upper bound (the rim and the rotor leave less), so that a
/// ball count far beyond it is refused at once instead of after a thousand futile attempts for each ball.
fn densest_disk_count(radius: f64, r: f64) -> f64 {
    let densest_packing = std::f64::consts::PI / (2.0 * 3f64.sqrt());
    densest_packing * (radius / r).powi(2)
}

/// Positions of balls at rest in a loose triangular packing (neighbours 1 % of a diameter apart), rows from the
/// chamber's bottom up, each row from the middle outwards, leaving out places that overlap a wall or the rotor; each
/// ball is added to `occupied`.
fn bed(mill: &Mill, occupied: &mut Vec<Occupied>, path: &str) -> Result<Vec<(DVec2, DVec2)>, SceneError> {
    let balls = &mill.balls;
    let r = balls.radius_m;
    let centre = DVec2::from_array(mill.centre_m);
    let spacing = 2.0 * r * (1.0 + BED_GAP);
    let rise = spacing * 0.75f64.sqrt();
    let outer = outer_radius(mill);
    // The lattice keeps the balls apart; only the walls need testing.
    let walls = occupied.len();
    // Places per row in half spacings k from the middle: even k on even rows, odd k on odd rows.
    let half_width = (outer / (0.5 * spacing)).ceil() as i64 + 1;
    let mut placed = Vec::with_capacity(balls.count);
    let mut row = 0;
    while placed.len() < balls.count {
        let y = centre.y - outer + r + row as f64 * rise;
        if y > centre.y + outer - r {
            return Err(SceneError::value(
                field_path(path, "count"),
                format!("only {} of {} balls fit in a bed in the chamber", placed.len(), balls.count),
            )
            .with_help("use fewer or smaller balls, or `placement: Random`"));
        }
        let mut places: Vec<i64> = (-half_width..=half_width).filter(|k| (k + row).rem_euclid(2) == 0).collect();
        places.sort_by_key(|&k| (k.abs(), k));
        for k in places {
            if placed.len() == balls.count {
                break;
            }
            let position = DVec2::new(centre.x + k as f64 * 0.5 * spacing, y);
            let candidate = Occupied::new(&BodyShape::Disk { radius: r }, Pose::new(position, 0.0));
            if candidate.fits(mill, &occupied[..walls]) {
                occupied.push(candidate);
                placed.push((position, DVec2::ZERO));
            }
        }
        row += 1;
    }
    Ok(placed)
}
