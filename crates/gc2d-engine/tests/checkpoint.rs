//! Checkpoints: a run split at a checkpoint ends bitwise identical to the unsplit run (reference §10.1 item 19), and
//! damaged or foreign files are refused with a clear error.

use gc2d_contact::{Cohesion, ContactLaw, CundallStrack, NormalDamping, NormalElastic};
use gc2d_engine::checkpoint::{CHECKPOINT_FORMAT_VERSION, CHECKPOINT_MAGIC, PROGRAM_VERSION};
use gc2d_engine::motion::{Piston, Vibration, Waveform};
use gc2d_engine::schedules::{DragSpring, GravityProfile, GravitySchedule, HeatingSchedule};
use gc2d_engine::{
    CheckpointError, DropHeight, DropSource, GearC0, Integrator, InteractionTable, MassModel, MaterialId,
    ParticleRecipe, SafetyLimits, TimeWindow, WallMotion, World, WorldConfig,
};
use gc2d_geometry::{Aabb, AngleMode, DVec2, Pose, Randomization, ShapeRecipe, rectangle, regular_polygon, square};

const DT: f64 = 1e-4;
/// Steps of the unsplit run; the split run checkpoints after half of them.
const STEPS: u64 = 3000;

/// A small box of particles exercising every kind of state a checkpoint must carry: a vibrating floor, a static
/// wall, a force-controlled piston wall, a drop source (random numbers, next insertion time), a drag spring,
/// variable gravity, heating, a domain, and a contact law with damping, friction and cohesion.
fn scene() -> World {
    let config = WorldConfig {
        time_step: DT,
        integrator: Integrator::Gear6(GearC0::VelocityDependent),
        interactions: InteractionTable::uniform(ContactLaw {
            elastic: NormalElastic::thesis(1e5),
            damping: Some(NormalDamping { gamma: 0.3 }),
            friction: Some(CundallStrack { mu: 0.5 }),
            cohesion: Some(Cohesion { k_coh: 2.0 }),
        }),
        mass_model: MassModel::PerUnitThickness,
        gravity: GravitySchedule {
            profile: GravityProfile::Linear,
            start_value: 9.81,
            end_value: 8.0,
            window: TimeWindow::new(0.0, 10.0),
            steps: 5,
            ramp_fraction: 0.5,
        },
        heating: Some(HeatingSchedule {
            window: TimeWindow::new(0.0, 10.0),
            amplitude: 0.02,
            frequency: 3.0,
            slope: HeatingSchedule::DEFAULT_SLOPE,
        }),
        safety: SafetyLimits::default(),
        domain: Some(Aabb { min: DVec2::new(-1.0, -1.0), max: DVec2::new(1.0, 1.0) }),
        seed: 7,
    };
    let mut world = World::new(config).unwrap();
    let floor = rectangle(0.3, 0.02).unwrap();
    let side = rectangle(0.02, 0.3).unwrap();
    let vibration = Vibration {
        direction_angle: std::f64::consts::FRAC_PI_2,
        window: TimeWindow::new(0.0, f64::INFINITY),
        amplitude: 5e-4,
        frequency: 20.0,
        waveform: Waveform::Cosine,
    };
    world.add_wall(&floor, Pose::new(DVec2::new(0.0, -0.01), 0.0), DVec2::ZERO, WallMotion::Vibrating(vibration));
    world.add_wall(&side, Pose::new(DVec2::new(-0.11, 0.15), 0.0), DVec2::ZERO, WallMotion::Static);
    let piston = Piston::new(std::f64::consts::PI, 0.5, 0.05);
    world.add_wall(&side, Pose::new(DVec2::new(0.105, 0.15), 0.0), DVec2::ZERO, WallMotion::Piston(piston));
    let hexagon = regular_polygon(6, 0.009).unwrap();
    let small = square(0.012).unwrap();
    let mut first = None;
    for row in 0..4 {
        for column in 0..7 {
            let shape = if (row + column) % 2 == 0 { &hexagon } else { &small };
            let position = DVec2::new(-0.08 + 0.024 * f64::from(column), 0.0095 + 0.0195 * f64::from(row));
            let spin = 0.3 * f64::from(column - 3);
            let id = world.add_particle(shape, Pose::new(position, 0.1 * f64::from(row)), 800.0, DVec2::ZERO, spin);
            first.get_or_insert(id.unwrap());
        }
    }
    let pulled = first.unwrap();
    let spring = DragSpring {
        stiffness: 20.0,
        fixing_point: DVec2::new(0.003, 0.0),
        pulling_start: world.bodies().pose[pulled.index()].position,
        direction_angle: 0.3,
        speed: 0.1,
        window: TimeWindow::new(0.0, 1.0),
    };
    world.add_drag_spring(pulled, spring).unwrap();
    world
        .add_source(DropSource {
            position: DVec2::new(0.0, 0.05),
            width: 0.12,
            height: DropHeight::AboveHighest,
            window: TimeWindow::new(0.0, 1.0),
            interval: 0.02,
            recipe: ParticleRecipe::Polygon(ShapeRecipe {
                semi_axes: DVec2::new(0.006, 0.005),
                size_variation: 0.2,
                size_randomization: Randomization::Equal,
                corners: 6,
                corner_variation: 2,
                corner_randomization: Randomization::Equal,
                angle_mode: AngleMode::Rand1,
                rotation: 0.0,
                rotation_randomization: Randomization::Equal,
            }),
            density: 800.0,
            material: MaterialId::default(),
        })
        .unwrap();
    world
}

fn run(world: &mut World, steps: u64) {
    for _ in 0..steps {
        world.step().unwrap();
    }
}

fn checkpoint_bytes(world: &World) -> Vec<u8> {
    let mut bytes = Vec::new();
    world.save_checkpoint(&mut bytes).unwrap();
    bytes
}

/// The bit patterns of every body's position and angle.
fn position_bits(world: &World) -> Vec<u64> {
    let poses = &world.bodies().pose;
    poses.iter().flat_map(|p| [p.position.x, p.position.y, p.angle].map(f64::to_bits)).collect()
}

/// The first index where two bit lists differ, with both values (or the two lengths).
fn first_difference(a: &[u64], b: &[u64]) -> Option<(usize, u64, u64)> {
    if a.len() != b.len() {
        return Some((usize::MAX, a.len() as u64, b.len() as u64));
    }
    a.iter().zip(b).enumerate().find(|(_, (x, y))| x != y).map(|(i, (x, y))| (i, *x, *y))
}

/// The bit patterns of everything a step reads or a user observes, body by body and contact by contact.
fn observed_bits(world: &World) -> Vec<u64> {
    let b = world.bodies();
    let mut bits = Vec::new();
    for i in 0..b.len() {
        let gear = &b.gear[i];
        let vectors = [b.pose[i].position, b.velocity[i], b.force[i]].into_iter().chain(gear.linear);
        bits.extend(vectors.flat_map(|v| [v.x.to_bits(), v.y.to_bits()]));
        let scalars = [b.pose[i].angle, b.pose[i].scale, b.angular_velocity[i], b.torque[i], b.inverse_inertia[i]];
        bits.extend(scalars.into_iter().chain(gear.angular).map(f64::to_bits));
        bits.push(u64::from(b.alive[i]));
    }
    for (a, bb, c) in world.pairs() {
        bits.extend([u64::from(a.0), u64::from(bb.0), u64::from(c.touching), c.clearance.metres().to_bits()]);
        let s = c.state.overlap_area();
        let constants = s.constants.map_or([0.0; 3], |k| [k.length, k.normal_mass, k.tangential_mass]);
        let scalars = [s.previous_area, s.previous_chord, s.spring, s.normal_energy, c.torque_on_a, c.torque_on_b]
            .into_iter()
            .chain(constants)
            .chain([c.force_on_a.x, c.force_on_a.y, c.point.x, c.point.y, world.overlap_fraction(a, bb, c)])
            .chain([c.dissipated]);
        bits.extend(scalars.map(f64::to_bits));
    }
    let l = world.ledger();
    let ledger = [
        l.kinetic_translational,
        l.kinetic_rotational,
        l.potential,
        l.contact_stored,
        l.drag_stored,
        l.dissipated_normal_damping,
        l.dissipated_tangential_damping,
        l.dissipated_sliding,
        l.opening_residual,
        l.work_walls,
        l.work_drag,
        l.work_gravity_change,
        l.work_heating,
        l.work_insertions,
        l.energy_removed,
        l.initial_total,
    ];
    bits.extend(ledger.map(f64::to_bits));
    bits.extend([world.time().to_bits(), world.steps(), world.stats().inserted, world.stats().contacts as u64]);
    bits
}

#[test]
fn a_run_split_at_a_checkpoint_ends_bitwise_identical_to_the_unsplit_run() {
    let mut unsplit = scene();
    run(&mut unsplit, STEPS);

    let mut first_half = scene();
    run(&mut first_half, STEPS / 2);
    // The split falls in the middle of the action, so every kind of history is live.
    let springs = first_half.contacts().filter(|(_, _, c)| c.state.overlap_area().spring != 0.0).count();
    assert!(springs >= 5, "only {springs} contacts carry a tangential spring at the split");
    assert!(first_half.stats().inserted >= 5, "the source inserted {} particles", first_half.stats().inserted);
    let piston_x = first_half.bodies().pose[2].position.x;
    assert!(piston_x < 0.105 - 1e-3, "the piston has not moved (x = {piston_x})");
    assert!(first_half.ledger().dissipated() > 0.0 && first_half.ledger().work_drag != 0.0);
    assert!(first_half.ledger().work_heating != 0.0, "the heating's work is part of the split");

    let saved = checkpoint_bytes(&first_half);
    drop(first_half);
    let mut resumed = World::load_checkpoint(saved.as_slice()).unwrap();
    run(&mut resumed, STEPS / 2);

    assert_eq!(resumed.steps(), STEPS);
    assert_eq!(first_difference(&position_bits(&resumed), &position_bits(&unsplit)), None, "positions differ");
    let pairs = |w: &World| w.pairs().map(|(a, b, _)| (a, b)).collect::<Vec<_>>();
    assert_eq!(pairs(&resumed), pairs(&unsplit), "pair list order differs");
    assert_eq!(first_difference(&observed_bits(&resumed), &observed_bits(&unsplit)), None);
    assert!(checkpoint_bytes(&resumed) == checkpoint_bytes(&unsplit), "the final states serialize differently");
}

#[test]
fn the_force_alternation_is_measured_again_from_the_second_step_after_loading() {
    // The pairs' force history is not saved (the format stays): a loaded World knows each pair's last force but
    // not the one before, so its first step reports NaN and its second agrees bit for bit with the unsplit run.
    let mut unsplit = scene();
    run(&mut unsplit, 700);
    let mut loaded = World::load_checkpoint(checkpoint_bytes(&unsplit).as_slice()).unwrap();
    assert!(loaded.force_alternation().ratio().is_nan(), "not measured before a step");
    run(&mut unsplit, 1);
    run(&mut loaded, 1);
    assert!(loaded.force_alternation().ratio().is_nan(), "the first step lacks F(n−2)");
    assert!(unsplit.force_alternation().scale > 0.0, "the box has contacts");
    run(&mut unsplit, 1);
    run(&mut loaded, 1);
    assert_eq!(loaded.force_alternation(), unsplit.force_alternation());
}

#[test]
fn a_checkpoint_round_trip_preserves_every_byte() {
    let mut world = scene();
    // Before the first step: bodies still pending in the broadphase, ledger not opened.
    let fresh = checkpoint_bytes(&world);
    assert_eq!(checkpoint_bytes(&World::load_checkpoint(fresh.as_slice()).unwrap()), fresh);
    run(&mut world, 700);
    let bytes = checkpoint_bytes(&world);
    let loaded = World::load_checkpoint(bytes.as_slice()).unwrap();
    assert!(checkpoint_bytes(&loaded) == bytes);
    assert_eq!(first_difference(&observed_bits(&loaded), &observed_bits(&world)), None);
    assert_eq!(loaded.config(), world.config());
}

#[test]
fn checkpoint_files_are_written_atomically_and_read_back() {
    let mut world = scene();
    run(&mut world, 100);
    let directory = std::env::temp_dir().join(format!("gc2d-checkpoint-test-{}", std::process::id()));
    std::fs::create_dir_all(&directory).unwrap();
    let path = directory.join("run.ckpt");
    world.save_checkpoint_file(&path).unwrap();
    assert!(!directory.join("run.ckpt.tmp").exists());
    let loaded = World::load_checkpoint_file(&path).unwrap();
    assert!(checkpoint_bytes(&loaded) == checkpoint_bytes(&world));
    let missing = World::load_checkpoint_file(directory.join("missing.ckpt"));
    assert!(matches!(missing, Err(CheckpointError::Io(_))));
    std::fs::remove_dir_all(&directory).unwrap();
}

/// Byte offset of the payload: magic, format version, version length and string, payload length, checksum.
fn payload_offset() -> usize {
    8 + 4 + 2 + PROGRAM_VERSION.len() + 8 + 8
}

#[test]
fn truncated_checkpoints_are_refused_at_every_length() {
    let mut world = scene();
    run(&mut world, 50);
    let bytes = checkpoint_bytes(&world);
    let header = payload_offset();
    for cut in (0..header).chain([header, header + 1, bytes.len() / 2, bytes.len() - 1]) {
        match World::load_checkpoint(&bytes[..cut]) {
            Err(CheckpointError::Truncated { expected, found, .. }) => assert!(found < expected, "cut at {cut}"),
            other => panic!("cut at {cut} of {}: expected Truncated, got {:?}", bytes.len(), other.err()),
        }
    }
    let message = World::load_checkpoint(&bytes[..bytes.len() - 1]).err().unwrap().to_string();
    assert!(message.contains("truncated") && message.contains("payload"), "{message}");
}

#[test]
fn foreign_and_corrupted_checkpoints_are_refused() {
    let world = scene();
    let bytes = checkpoint_bytes(&world);
    assert_eq!(bytes[..8], CHECKPOINT_MAGIC);

    let mut wrong_magic = bytes.clone();
    wrong_magic[..8].copy_from_slice(b"GC2DCKPX");
    assert!(matches!(World::load_checkpoint(wrong_magic.as_slice()), Err(CheckpointError::NotACheckpoint)));
    assert!(matches!(World::load_checkpoint(&b"PARAMETER v1.4\n"[..]), Err(CheckpointError::NotACheckpoint)));

    let mut newer_format = bytes.clone();
    newer_format[8..12].copy_from_slice(&(CHECKPOINT_FORMAT_VERSION + 1).to_le_bytes());
    match World::load_checkpoint(newer_format.as_slice()) {
        Err(CheckpointError::FormatVersion { found, expected }) => {
            assert_eq!((found, expected), (CHECKPOINT_FORMAT_VERSION + 1, CHECKPOINT_FORMAT_VERSION));
        }
        other => panic!("expected FormatVersion, got {:?}", other.err()),
    }

    let mut other_program = bytes.clone();
    let version = 14..14 + PROGRAM_VERSION.len();
    assert_eq!(&other_program[version.clone()], PROGRAM_VERSION.as_bytes());
    other_program[version.start] = b'9';
    match World::load_checkpoint(other_program.as_slice()) {
        Err(error @ CheckpointError::ProgramVersion { .. }) => {
            assert!(error.to_string().contains(PROGRAM_VERSION), "{error}");
        }
        other => panic!("expected ProgramVersion, got {:?}", other.err()),
    }

    // Any single flipped bit in the payload is caught by the checksum before decoding.
    for position in [payload_offset(), payload_offset() + 100, bytes.len() - 1] {
        let mut flipped = bytes.clone();
        flipped[position] ^= 0x10;
        assert!(
            matches!(World::load_checkpoint(flipped.as_slice()), Err(CheckpointError::Corrupted { .. })),
            "flip at {position}"
        );
    }
}

/// The header is not covered by the checksum: a damaged byte in the program version or its length is a corrupted
/// header, named as such, not "another program version", and the file's bytes are never shown raw (a length of
/// 16,901 printed 28 kB of payload, control characters included).
#[test]
fn a_damaged_program_version_is_a_corrupted_header_shown_without_raw_bytes() {
    let bytes = checkpoint_bytes(&scene());
    let version_end = 14 + PROGRAM_VERSION.len();
    let check = |position: usize, value: u8| {
        let mut damaged = bytes.clone();
        damaged[position] = value;
        match World::load_checkpoint(damaged.as_slice()) {
            Err(error @ CheckpointError::CorruptedHeader { .. }) => {
                let message = error.to_string();
                assert!(message.starts_with("checkpoint is corrupted (header): "), "{message}");
                assert!(message.len() < 200 && !message.chars().any(char::is_control), "{position}: {message:?}");
                message
            }
            other => panic!("byte {position} set to {value:#04x}: expected CorruptedHeader, got {:?}", other.err()),
        }
    };
    // The reported cases: one byte set to 0x42 in the length (16,901 or 66 bytes) or in the version ("B.1.0").
    assert!(check(13, 0x42).contains("the program version length is 16901 bytes"));
    assert!(check(12, 0x42).contains("the program version length is 66 bytes"));
    assert!(check(14, 0x42).contains("the program version \"B"));
    assert!(check(17, 0x42).contains("is not a version number"));
    for (position, &original) in bytes.iter().enumerate().take(version_end).skip(12) {
        for value in [0x00, 0x1b, 0xff].into_iter().filter(|&value| value != original) {
            check(position, value);
        }
    }
    // A shorter length cuts the version to something that is not a number.
    for length in [0u16, 3, 4] {
        let mut damaged = bytes.clone();
        damaged[12..14].copy_from_slice(&length.to_le_bytes());
        let result = World::load_checkpoint(damaged.as_slice());
        assert!(matches!(result, Err(CheckpointError::CorruptedHeader { .. })), "{length}: {:?}", result.err());
    }
}

/// The header gives the payload's length, so bytes after it are detectable: a file with anything appended is refused.
#[test]
fn bytes_after_the_payload_are_refused() {
    let bytes = checkpoint_bytes(&scene());
    for tail in [&b"garbage\n"[..], &[0][..], &bytes[..]] {
        let mut appended = bytes.clone();
        appended.extend_from_slice(tail);
        match World::load_checkpoint(appended.as_slice()) {
            Err(error @ CheckpointError::TrailingBytes { .. }) => {
                assert!(error.to_string().contains(&format!("{} bytes follow the payload", tail.len())), "{error}");
            }
            other => panic!("{} bytes appended: expected TrailingBytes, got {:?}", tail.len(), other.err()),
        }
    }
}

#[test]
fn a_payload_that_passes_the_checksum_but_is_not_a_world_is_an_error() {
    let garbage: Vec<u8> = (0..200u32).map(|i| (i.wrapping_mul(2_654_435_761) >> 24) as u8).collect();
    let mut file = Vec::new();
    file.extend_from_slice(&CHECKPOINT_MAGIC);
    file.extend_from_slice(&CHECKPOINT_FORMAT_VERSION.to_le_bytes());
    file.extend_from_slice(&(PROGRAM_VERSION.len() as u16).to_le_bytes());
    file.extend_from_slice(PROGRAM_VERSION.as_bytes());
    file.extend_from_slice(&(garbage.len() as u64).to_le_bytes());
    let checksum =
        garbage.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3));
    file.extend_from_slice(&checksum.to_le_bytes());
    file.extend_from_slice(&garbage);
    let result = World::load_checkpoint(file.as_slice());
    assert!(
        matches!(result, Err(CheckpointError::Encoding(_) | CheckpointError::Inconsistent(_))),
        "{:?}",
        result.err()
    );
}

/// The payload length of a fixed scene pins the serialized layout: a field added to, removed from or retyped in any
/// type of the World changes it. When this fails, bump `CHECKPOINT_FORMAT_VERSION` and update the length. The scene
/// runs until it has a touching pair, so that the pair records are in the payload too (after one step it had none,
/// and format 12's smaller record passed the pin unseen). The length also follows what the columns hold: 21,435
/// bytes became 20,923 when the wall surface-velocity column stopped at the last wall that has one (the scene's 32
/// bodies without one no longer write 16 zero bytes each), a change of content, not of layout, so format 12 stayed
/// (files with the full column still load). Format 13 dropped the broadphase's previous boxes (32 bytes per body
/// written), the pair list's index table, which loading rebuilds from the entries, and the bodies' box column
/// (the broadphase's boxes are the only ones now): 18,567 bytes. Format 14 dropped the pair record's overlap
/// fraction, which is read from the contact's history now: 18,535 bytes. Format 15 added the broadphase's bands of
/// the y axis (`None` here, one byte): 18,536 bytes. Format 16 added the bodies' travel bounds (4 bytes each and the
/// column's length) and put the pair record's clearance (two bytes, a varint like the pass count it replaced) in
/// place of its closest-feature passes, and the step's flag that the travel is tracked (one byte): 18,666 bytes.
#[test]
fn checkpoint_layout_is_pinned() {
    let mut world = scene();
    run(&mut world, 200);
    assert!(world.contacts().count() > 0, "the pin must cover a pair record");
    let payload = checkpoint_bytes(&world).len() - payload_offset();
    assert_eq!(
        payload, 18690,
        "the checkpoint layout changed: bump CHECKPOINT_FORMAT_VERSION (now {CHECKPOINT_FORMAT_VERSION}) and pin the \
         new payload length"
    );
}
