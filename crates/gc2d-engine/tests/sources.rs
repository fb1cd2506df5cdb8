//! Drop sources (gc2d's DROPSOURCE, reference §9.8): one insertion per interval inside the window, never on top of
//! another body, skipped and counted when no free spot is found, and REL heights above the highest particle.

mod common;

use common::*;
use gc2d_engine::{DropHeight, DropSource, MaterialId, ParticleRecipe, TimeWindow, World};
use gc2d_geometry::{AngleMode, DVec2, Pose, Randomization, ShapeRecipe, contact_geometry, rectangle};

const DT: f64 = 5e-6;

/// Random 7-gons of semi-axes 2 mm ± 10 %.
fn recipe() -> ShapeRecipe {
    ShapeRecipe {
        semi_axes: DVec2::splat(2e-3),
        size_variation: 0.1,
        size_randomization: Randomization::Equal,
        corners: 7,
        corner_variation: 0,
        corner_randomization: Randomization::Const,
        angle_mode: AngleMode::Rand1,
        rotation: 0.0,
        rotation_randomization: Randomization::Equal,
    }
}

fn source(position: DVec2, width: f64, height: DropHeight, window: TimeWindow, interval: f64) -> DropSource {
    DropSource {
        position,
        width,
        height,
        window,
        interval,
        recipe: ParticleRecipe::Polygon(recipe()),
        density: RHO_THESIS,
        material: MaterialId::default(),
    }
}

/// World vertices of body `i` at its current pose (the World's own copy is at the last predicted pose).
fn vertices_now(world: &World, i: usize) -> Vec<DVec2> {
    let b = world.bodies();
    let body = b.body_vertices_of(gc2d_engine::BodyId(i as u32));
    let mut out = vec![DVec2::ZERO; body.len()];
    b.pose[i].transform_into(body, &mut out);
    out
}

/// Steps to `t_end` and returns, for every insertion, the time and the new body's slot; asserts that no inserted
/// particle overlaps any other living body at the step of its insertion.
fn run_recording_insertions(world: &mut World, t_end: f64) -> Vec<(f64, usize)> {
    let mut insertions = Vec::new();
    while world.time() < t_end {
        let (before, bodies_before) = (world.stats().inserted, world.bodies().len());
        step(world);
        let new = (world.stats().inserted - before) as usize;
        assert!(new <= 1, "one insertion per interval, got {new} in one step");
        for i in bodies_before..bodies_before + new {
            insertions.push((world.time(), i));
            let inserted = vertices_now(world, i);
            for other in (0..bodies_before).filter(|&k| world.bodies().alive[k]) {
                let overlap = contact_geometry(&inserted, &vertices_now(world, other));
                assert!(overlap.is_none(), "particle {i} inserted at t = {} overlaps body {other}", world.time());
            }
        }
    }
    insertions
}

#[test]
fn absolute_source_inserts_at_its_interval_inside_its_window_and_only_in_free_space() {
    let mut world = world(config(DT, law(E_THESIS, 0.5, 0.5), G));
    add_static_wall(&mut world, &rectangle(0.2, 0.01).unwrap(), Pose::new(DVec2::new(0.0, -0.005), 0.0));
    // A block covering the left half of the insertion line: insertions must land in the right half.
    add_static_wall(&mut world, &rectangle(0.02, 0.01).unwrap(), Pose::new(DVec2::new(-0.01, 0.05), 0.0));
    let (start, interval) = (0.02, 0.01);
    let window = TimeWindow::new(start, 0.095);
    world.add_source(source(DVec2::new(0.0, 0.05), 0.04, DropHeight::Absolute, window, interval)).unwrap();
    let insertions = run_recording_insertions(&mut world, 0.15);
    let stats = world.stats();
    // Due at 0.02, 0.03, …, 0.09: eight insertions, each made or skipped for want of a free spot.
    assert_eq!(stats.inserted + stats.insertions_skipped, 8, "{stats:?}");
    // Measured: all eight found a free spot within the 10 attempts.
    assert!(stats.inserted >= 6, "most insertions find a free spot in the right half: {stats:?}");
    let mut due = start;
    for &(time, i) in &insertions {
        while time >= due + interval {
            due += interval; // a skipped insertion
        }
        assert!(time >= due && time < due + DT * 1.5, "insertion at t = {time}, due at {due}");
        let p = world.bodies().pose[i].position;
        assert!((0.0..=0.02).contains(&p.x), "x = {} outside the free half of the source's width", p.x);
        due += interval;
    }
}

#[test]
fn source_with_no_free_spot_skips_and_counts_every_insertion() {
    let mut world = world(config(DT, law(E_THESIS, 0.5, 0.5), G));
    add_static_wall(&mut world, &rectangle(0.1, 0.02).unwrap(), Pose::new(DVec2::ZERO, 0.0));
    let window = TimeWindow::new(0.0, 0.0345);
    world.add_source(source(DVec2::ZERO, 0.05, DropHeight::Absolute, window, 0.005)).unwrap();
    let insertions = run_recording_insertions(&mut world, 0.05);
    assert!(insertions.is_empty());
    assert_eq!((world.stats().inserted, world.stats().insertions_skipped), (0, 7), "due at 0, 0.005, …, 0.03");
    assert_eq!(world.bodies().particles().count(), 0);
}

#[test]
fn relative_source_inserts_above_the_highest_particle_within_its_width() {
    // Without gravity every particle stays where it is put, so each REL insertion lands 2 cm above the previous
    // one; a particle outside the source's width is higher still and must be ignored.
    let mut world = world(config(DT, law(E_THESIS, 0.5, 0.5), 0.0));
    let shape = rectangle(0.004, 0.004).unwrap();
    for (x, y) in [(0.0, 0.01), (0.005, 0.03), (0.1, 0.5)] {
        world.add_particle(&shape, Pose::new(DVec2::new(x, y), 0.0), RHO_THESIS, DVec2::ZERO, 0.0).unwrap();
    }
    let offset = 0.02;
    let window = TimeWindow::new(0.0, 0.035);
    world.add_source(source(DVec2::new(0.0, offset), 0.02, DropHeight::AboveHighest, window, 0.01)).unwrap();
    let insertions = run_recording_insertions(&mut world, 0.05);
    assert_eq!(insertions.len(), 4, "due at 0, 0.01, 0.02, 0.03");
    let mut highest = 0.03;
    for &(_, i) in &insertions {
        let y = world.bodies().pose[i].position.y;
        assert!((y - (highest + offset)).abs() < 1e-12, "inserted at y = {y}, expected {}", highest + offset);
        highest = y;
    }
}
