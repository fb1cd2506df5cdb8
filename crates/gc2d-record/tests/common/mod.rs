//! Small Worlds for the recording tests: 7-gons falling into a box.
// Each test crate uses a different part of these helpers.
#![allow(dead_code)]

use gc2d_contact::{ContactLaw, CundallStrack, NormalDamping};
use gc2d_engine::schedules::GravitySchedule;
use gc2d_engine::{
    DropHeight, DropSource, InteractionTable, MassModel, MaterialId, ParticleRecipe, SafetyLimits, TimeWindow,
    WallMotion, World, WorldConfig,
};
use gc2d_geometry::{AngleMode, DVec2, Pose, Randomization, ShapeRecipe, rectangle, regular_polygon};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Circumradius of the test particles, m.
pub const RADIUS: f64 = 0.01;
/// Area density of the test particles, kg/m².
pub const DENSITY: f64 = 1000.0;
/// Δt, s: a fifth of the stable bound (π/10)·sqrt(m/E) ≈ 5e-4 s of these particles.
pub const TIME_STEP: f64 = 1e-4;
/// Inner width of the box, m.
pub const BOX_WIDTH: f64 = 0.3;

/// A damped, frictional law with E = 1e5 N/m.
pub fn contact_law() -> ContactLaw {
    ContactLaw {
        damping: Some(NormalDamping { gamma: 0.3 }),
        friction: Some(CundallStrack { mu: 0.5 }),
        ..ContactLaw::elastic(1e5)
    }
}

/// An empty World with gravity 9.81 m/s² along −y.
pub fn empty_world() -> World {
    World::new(WorldConfig {
        time_step: TIME_STEP,
        integrator: Default::default(),
        interactions: InteractionTable::uniform(contact_law()),
        mass_model: MassModel::PerUnitThickness,
        gravity: GravitySchedule::default(),
        heating: None,
        safety: SafetyLimits::default(),
        domain: None,
        seed: 7,
    })
    .unwrap()
}

/// A floor (top at y = 0) and two side walls `BOX_WIDTH` apart; `floor_motion` moves the floor.
pub fn add_box(world: &mut World, floor_motion: WallMotion) {
    let floor = rectangle(BOX_WIDTH + 0.1, 0.05).unwrap();
    world.add_wall(&floor, Pose::new(DVec2::new(0.0, -0.025), 0.0), DVec2::ZERO, floor_motion);
    let side = rectangle(0.05, 0.6).unwrap();
    for x in [-1.0, 1.0] {
        let centre = DVec2::new(x * (0.5 * BOX_WIDTH + 0.025), 0.3);
        world.add_wall(&side, Pose::new(centre, 0.0), DVec2::ZERO, WallMotion::Static);
    }
}

/// Adds a 7-gon at `position`, turned by `angle`, at rest.
pub fn add_heptagon(world: &mut World, position: DVec2, angle: f64) {
    let shape = regular_polygon(7, RADIUS).unwrap();
    world.add_particle(&shape, Pose::new(position, angle), DENSITY, DVec2::ZERO, 0.0).unwrap();
}

/// `count` 7-gons on a staggered grid 2.5 radii apart, starting 2 radii above the floor.
pub fn falling_heptagons(count: usize) -> World {
    let mut world = empty_world();
    add_box(&mut world, WallMotion::Static);
    let spacing = 2.5 * RADIUS;
    let per_row = ((BOX_WIDTH - 2.0 * RADIUS) / spacing).floor() as usize;
    for k in 0..count {
        let (row, column) = (k / per_row, k % per_row);
        let stagger = if row % 2 == 1 { 0.5 * spacing } else { 0.0 };
        let x = -0.5 * BOX_WIDTH + 1.5 * RADIUS + stagger + column as f64 * spacing;
        let y = 2.0 * RADIUS + row as f64 * spacing;
        add_heptagon(&mut world, DVec2::new(x, y), 0.37 * k as f64);
    }
    world
}

/// Seconds between two insertions of [`add_heptagon_source`].
pub const SOURCE_INTERVAL: f64 = 0.15;

/// A source that drops a 7-gon of the test size every [`SOURCE_INTERVAL`] from t = 0 on, 5 cm above the highest
/// particle, so the particle count changes during a run (and the ledger books the inserted energy).
pub fn add_heptagon_source(world: &mut World) {
    let recipe = ShapeRecipe {
        semi_axes: DVec2::splat(RADIUS),
        size_variation: 0.0,
        size_randomization: Randomization::Const,
        corners: 7,
        corner_variation: 0,
        corner_randomization: Randomization::Const,
        angle_mode: AngleMode::Regular,
        rotation: 0.0,
        rotation_randomization: Randomization::Const,
    };
    world
        .add_source(DropSource {
            position: DVec2::new(0.0, 0.05),
            width: 0.2,
            height: DropHeight::AboveHighest,
            window: TimeWindow::new(0.0, f64::INFINITY),
            interval: SOURCE_INTERVAL,
            recipe: ParticleRecipe::Polygon(recipe),
            density: DENSITY,
            material: MaterialId::default(),
        })
        .unwrap();
}

/// One 7-gon resting on a face on the floor of the box (bottom face horizontal, 0.1 mm above the floor), at x = 0.
pub fn heptagon_on_the_floor() -> World {
    let mut world = empty_world();
    add_box(&mut world, WallMotion::Static);
    let inscribed = RADIUS * (std::f64::consts::PI / 7.0).cos();
    // Face k = 5 (between corners 5 and 6) has its outward normal at 2π·5.5/7; turning by −π/14 points it down.
    add_heptagon(&mut world, DVec2::new(0.0, inscribed + 1e-4), -std::f64::consts::PI / 14.0);
    world
}

/// The repository root (two levels above this crate).
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The venv python with the reference reader, or `None` (with a message) when python3 is not installed.
pub fn checker_python() -> Option<PathBuf> {
    if Command::new("python3").arg("--version").output().is_err() {
        eprintln!("SKIPPED: python3 is not installed, so the recording cannot be checked by the reference reader");
        return None;
    }
    let setup = repo_root().join("tools/setup-python.sh");
    let output = Command::new("bash").arg(&setup).output().expect("run tools/setup-python.sh");
    assert!(output.status.success(), "setup-python.sh failed: {}", String::from_utf8_lossy(&output.stderr));
    let python = String::from_utf8(output.stdout).unwrap().lines().last().unwrap().trim().to_string();
    Some(PathBuf::from(python))
}

/// Runs tools/check_mcap.py on `recording` with the expectations `expect`; panics with its report on failure.
pub fn check_with_reference_reader(python: &Path, recording: &Path, expect: &serde_json::Value) {
    let expect_path = recording.with_extension("expect.json");
    std::fs::write(&expect_path, serde_json::to_string_pretty(expect).unwrap()).unwrap();
    let output = Command::new(python)
        .arg(repo_root().join("tools/check_mcap.py"))
        .arg(recording)
        .arg(&expect_path)
        .output()
        .expect("run tools/check_mcap.py");
    let report = String::from_utf8_lossy(&output.stdout);
    eprintln!("{report}{}", String::from_utf8_lossy(&output.stderr));
    assert!(output.status.success(), "check_mcap.py found problems:\n{report}");
}
