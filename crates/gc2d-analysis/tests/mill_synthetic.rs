//! `analyze_mill` on a hand-made run directory with known answers: a World of a chamber, a turning blade, a hub, two
//! balls and two ore grains saved as `final.ckpt`, and written `events.csv`, `timeseries.csv` and state dumps.

use gc2d_analysis::particle_state::csv::{dump_file_name, write_csv};
use gc2d_analysis::particle_states;
use gc2d_analysis::{AnalysisError, MillOptions, analyze_mill};
use gc2d_contact::{ContactLaw, NormalElastic};
use gc2d_engine::motion::Rotation;
use gc2d_engine::schedules::GravitySchedule;
use gc2d_engine::{BodyShape, InteractionTable, MassModel, TimeWindow, WallMotion, World, WorldConfig};
use gc2d_geometry::{DVec2, Pose, regular_polygon};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Chamber radius and ball diameter, m.
const R: f64 = 0.05;
const D: f64 = 0.005;
/// Rotor speed, rad/s (10 revolutions per second).
const OMEGA: f64 = 20.0 * std::f64::consts::PI;

/// Bodies 0 chamber, 1 blade, 2 hub, 3 and 4 balls, 5 and 6 ore grains; nothing touches. The blade turns at
/// [`OMEGA`] after a linear spin-up of `spin_up` s from rest. The chamber is an inner circle of radius [`R`], or with
/// `circular` false a square wall far away (as a wavy chamber, a wall without a radius).
fn world(spin_up: f64, circular: bool) -> World {
    let config = WorldConfig {
        time_step: 1e-3,
        integrator: Default::default(),
        interactions: InteractionTable::uniform(ContactLaw {
            elastic: NormalElastic::thesis(100.0),
            damping: None,
            friction: None,
            cohesion: None,
        }),
        mass_model: MassModel::PerUnitThickness,
        gravity: GravitySchedule::constant(0.0),
        heating: None,
        safety: Default::default(),
        domain: None,
        seed: 1,
    };
    let mut world = World::new(config).unwrap();
    let origin = Pose::new(DVec2::ZERO, 0.0);
    if circular {
        world.add_wall(BodyShape::InnerCircle { radius: R }, origin, DVec2::ZERO, WallMotion::Static);
    } else {
        let far = Pose::new(DVec2::new(1.0, 0.0), 0.0);
        world.add_wall(regular_polygon(4, 0.01).unwrap(), far, DVec2::ZERO, WallMotion::Static);
    }
    let rotation =
        Rotation { pivot: DVec2::ZERO, angular_velocity: OMEGA, window: TimeWindow::new(0.0, f64::INFINITY), spin_up };
    world.add_wall(
        BodyShape::Capsule { half_length: 0.004, radius: 0.001 },
        origin,
        DVec2::ZERO,
        WallMotion::Rotating(rotation),
    );
    world.add_wall(BodyShape::Disk { radius: 0.002 }, origin, DVec2::ZERO, WallMotion::Static);
    for y in [0.046, -0.046] {
        world
            .add_particle(
                BodyShape::Disk { radius: 0.5 * D },
                Pose::new(DVec2::new(0.0, y), 0.0),
                7800.0,
                DVec2::ZERO,
                0.0,
            )
            .unwrap();
    }
    let grain = regular_polygon(4, 0.002).unwrap();
    for x in [0.03, -0.03] {
        world.add_particle(&grain, Pose::new(DVec2::new(x, 0.0), 0.0), 3000.0, DVec2::ZERO, 0.0).unwrap();
    }
    world
}

/// One events.csv row: begin time, bodies, impact normal speed and begin point.
fn event(text: &mut String, begin: f64, a: u32, b: u32, speed: f64, at: DVec2) {
    let _ = writeln!(text, "{begin},{begin},{a},{b},x,x,m,m,{speed:e},0,0,0,0,0,,0,{:e},{:e}", at.x, at.y);
}

/// A run directory `gc2d-mill-synthetic-<name>-<pid>` of [`world`]`(spin_up, true)` run to 1 s.
fn run_dir(name: &str, spin_up: f64) -> (PathBuf, World) {
    let mut world = world(spin_up, true);
    world.run_until(1.0).unwrap();
    let dir = std::env::temp_dir().join(format!("gc2d-mill-synthetic-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("dumps")).unwrap();
    world.save_checkpoint_file(dir.join("final.ckpt")).unwrap();

    let frames: Vec<f64> = (0..=100).map(|k| k as f64 * 0.01).collect();
    write_dumps(&dir, &world, &frames);
    write_series(&dir, &frames, |t| 2.0 * t);

    let mut events = String::from(
        "begin_time_s,end_time_s,a,b,kind_a,kind_b,material_a,material_b,impact_normal_speed_m_s,\
         impact_tangential_speed_m_s,max_overlap_fraction,dissipated_j,impulse_on_a_x_n_s,impulse_on_a_y_n_s,\
         wall_angular_impulse_n_m_s,duration_s,begin_x_m,begin_y_m\n",
    );
    let at = |r: f64, degrees: f64| r * DVec2::from_angle(degrees.to_radians());
    event(&mut events, 0.1, 1, 4, 9.0, at(0.004, 10.0)); // in the warm-up: left out
    event(&mut events, 0.4, 1, 4, 4.0, at(0.004, 10.0)); // ball–blade
    event(&mut events, 0.5, 3, 4, 2.0, at(0.048, 95.0)); // ball–ball
    event(&mut events, 0.6, 3, 5, 1.0, at(0.048, 100.0)); // ball–ore
    event(&mut events, 0.7, 5, 6, 2.0, at(0.03, 180.0)); // ore–ore
    event(&mut events, 0.8, 0, 5, 1.0, at(0.049, 0.0)); // ore–chamber
    event(&mut events, 0.9, 2, 3, 0.5, at(0.001, 270.0)); // ball–hub
    std::fs::write(dir.join("events.csv"), events).unwrap();
    (dir, world)
}

/// Dumps at `times` (one every 10 ms, 101 of them): both balls at 5 m/s in the first 30, then ball 3 at 1 m/s in the
/// upper and ball 4 at 3 m/s in the lower half of the outer ring (r = 46 mm > R − 2d = 40 mm).
fn write_dumps(dir: &Path, world: &World, times: &[f64]) {
    let template = particle_states(world, &["m".to_string()]);
    for (k, &t) in times.iter().enumerate() {
        let rows: Vec<_> = template
            .iter()
            .map(|row| {
                let speed = match (row.id, k < 30) {
                    (3 | 4, true) => 5.0,
                    (3, false) => 1.0,
                    (4, false) => 3.0,
                    _ => 7.0,
                };
                gc2d_analysis::ParticleState { time_s: t, vx_m_s: speed, vy_m_s: 0.0, ..row.clone() }
            })
            .collect();
        let mut bytes = Vec::new();
        write_csv(&rows, &mut bytes).unwrap();
        std::fs::write(dir.join("dumps").join(dump_file_name(k as u64)), bytes).unwrap();
    }
}

/// A time series with rows at `times`: ω·τ and Σ F·v and the walls' work sum to `work(t)` over the steps (their
/// instantaneous rows alternate 7 and −3 W, which the means must not use), and 1.9 J/s is dissipated.
fn write_series(dir: &Path, times: &[f64], work: impl Fn(f64) -> f64) {
    let mut series = String::from(
        "time_s,median_speed_m_s,rotor_power_torque_w,rotor_power_work_w,work_in_j,dissipated_normal_damping_j,\
         dissipated_tangential_damping_j,dissipated_sliding_j,rotor_work_torque_j,rotor_work_j\n",
    );
    for (k, &t) in times.iter().enumerate() {
        let (work, noise) = (work(t), if k % 2 == 0 { 7.0 } else { -3.0 });
        let _ = writeln!(series, "{t},0,{noise},{noise},{work},{},{},{},{work},{work}", 1.0 * t, 0.5 * t, 0.4 * t);
    }
    std::fs::write(dir.join("timeseries.csv"), series).unwrap();
}

#[test]
fn a_hand_made_mill_run_gives_the_known_statistics() {
    let (dir, world) = run_dir("known", 0.0);
    let report = analyze_mill(&dir, &MillOptions::default()).unwrap();
    let mass = |i: usize| world.bodies().mass[i];

    // The warm-up: 101 samples in 20 blocks of 5; the step at sample 30 ends it.
    let cut = report.warm_up.automatic.unwrap();
    assert_eq!((cut.blocks, cut.block_samples, cut.reference_mean_m_s), (20, 5, 2.0));
    let end = world.time();
    assert_eq!(report.window_s, [30.0 * 0.01, end]);
    assert!(!report.warm_up.given && report.warm_up.series == "dumps");
    let span = end - 30.0 * 0.01;
    assert_eq!((report.balls, report.ore_grains), (2, 2));

    // Classes in the window, one collision each; the blade hit before the cut is left out.
    let names: Vec<&str> = report.classes.iter().map(|c| c.class.as_str()).collect();
    assert_eq!(names, ["ball–ball", "ball–blade", "ball–hub", "ball–ore", "ore–chamber", "ore–ore"]);
    assert!(report.classes.iter().all(|c| c.collisions == 1));
    let class = |name: &str| report.classes.iter().find(|c| c.class == name).unwrap();
    assert!((class("ore–ore").per_ball_per_second - 1.0 / span / 2.0).abs() < 1e-12);
    // ΣE_n with the ball's mass for ball–ore (body 5 is the grain), the grain's for ore–chamber.
    assert!((class("ball–ore").normal_energy_per_second_w - 0.5 * mass(3) / span).abs() < 1e-15);
    assert!((class("ore–chamber").normal_energy_per_second_w - 0.5 * mass(5) / span).abs() < 1e-15);
    assert_eq!(report.all_classes.collisions, 6);
    assert_eq!(report.all_classes.fractions_above, [5.0 / 6.0, 3.0 / 6.0, 1.0 / 6.0]);
    // 10 revolutions a second over 0.7 s, one blade hit.
    assert!((report.revolutions - 7.0).abs() < 1e-12);
    assert!((report.blade_hits_per_revolution - 1.0 / 7.0).abs() < 1e-12);

    // Stress energy on ore: ball–ore ½ m* 1², ore–ore ½ (m/2) 2², ore–chamber ½ m 1².
    let s = report.stress_energy.as_ref().unwrap();
    let reduced = mass(3) * mass(5) / (mass(3) + mass(5));
    let mut expected = [0.5 * reduced, 0.5 * 0.5 * mass(5) * 4.0, 0.5 * mass(5)];
    expected.sort_by(f64::total_cmp);
    assert_eq!((s.events, s.without_impact, s.counts.iter().sum::<usize>()), (3, 0, 3));
    assert!((s.median_j - expected[1]).abs() < 1e-15 * expected[1].max(1.0));
    assert!((s.energy_per_second_w - expected.iter().sum::<f64>() / span).abs() < 1e-12);
    assert!((s.bin_edges_j[0] / expected[0] - 1.0).abs() < 1e-12);
    assert!((s.bin_edges_j.last().unwrap() / expected[2] - 1.0).abs() < 1e-12);

    // Power: 2 W in by both methods, 1.9 W dissipated.
    let p = report.power;
    assert_eq!((p.mean_power_torque_w, p.mean_power_work_w, p.relative_torque_work), (2.0, 2.0, 0.0));
    assert!((p.dissipation_w - 1.9).abs() < 1e-9 && (p.relative_torque_dissipation - 0.05).abs() < 1e-9);

    // Ball speeds: 71 dumps in the window, half the samples at 1 m/s (upper), half at 3 m/s (lower).
    let speeds = report.ball_speeds.as_ref().unwrap();
    assert_eq!((speeds.dumps, speeds.all.samples), (71, 142));
    assert_eq!((speeds.all.median_m_s, speeds.all.mean_m_s, speeds.all.p90_m_s), (2.0, 2.0, 3.0));
    let (upper, lower) = (speeds.upper_outer.as_ref().unwrap(), speeds.lower_outer.as_ref().unwrap());
    assert_eq!((upper.samples, upper.median_m_s, lower.samples, lower.median_m_s), (71, 1.0, 71, 3.0));
    assert_eq!(report.median_speed_m_s, [2.0, 0.0]);
    assert!(report.autocorrelation.is_none(), "a constant series has no autocorrelation");

    // Where: every ball sample at r = 46 mm, in the outer ring and the ring 45–50 mm.
    let chamber = report.chamber.unwrap();
    assert_eq!((chamber.radius_m, chamber.ball_diameter_m), (R, D));
    let profile = report.radial_profile.as_ref().unwrap();
    assert_eq!(profile.outer_ring_share, 1.0);
    assert_eq!(profile.rings.last().unwrap().share, 1.0);
    assert_eq!(profile.rings.len(), 10);
    // Sector cells of 22.5°, rings at R √(k/5): the ball at 90° (upper) in ring 4, sector 4, at 1 m/s; the
    // ball–ball and ball–ore collisions began in the same cell.
    assert!(report.collision_points_known);
    let cell = |ring: usize, sector: usize| &report.sectors[ring * 16 + sector];
    assert_eq!((cell(4, 4).ball_share, cell(4, 4).mean_speed_m_s, cell(4, 4).collisions), (0.5, 1.0, 2));
    assert_eq!((cell(4, 12).ball_share, cell(4, 12).mean_speed_m_s), (0.5, 3.0));
    assert_eq!(report.sectors.iter().map(|c| c.collisions).sum::<usize>(), 6);

    // A given start replaces the cut and keeps the blade hit at 0.1 s.
    let given = analyze_mill(&dir, &MillOptions { warm_up_s: Some(0.0), ..MillOptions::default() }).unwrap();
    assert!(given.warm_up.given && given.window_s[0] == 0.0);
    assert_eq!(given.classes.iter().find(|c| c.class == "ball–blade").unwrap().collisions, 2);
    let summary = given.summary();
    assert!(summary.contains("median ball speed") && summary.contains(" blade hits per revolution;"), "{summary}");
    // A rotor at rest has no revolutions to count hits per (the line said `NaN blade hits per revolution`), and a
    // mill without balls no ball speed to take the median of.
    let mut still = given.clone();
    (still.blade_hits_per_revolution, still.balls) = (f64::NAN, 0);
    let summary = still.summary();
    assert!(summary.contains("blade hits per revolution undefined (the rotor stands)") && summary.contains("no balls"));
    assert!(!summary.contains("NaN"), "{summary}");
    for file in [
        "mill.json",
        "mill_collisions.csv",
        "mill_ball_speeds.csv",
        "mill_median_speed.csv",
        "mill_radial_profile.csv",
        "mill_sectors.csv",
        "mill_stress_energy.csv",
        "mill_sector_speed.svg",
        "mill_sector_collisions.svg",
        "mill_median_speed.svg",
        "mill_stress_energy.svg",
    ] {
        assert!(dir.join("analysis").join(file).exists(), "{file} is missing");
    }
    // The radial profile's figure draws the ring's share of the area beside the balls' (it drew only the balls').
    let figure = analysis_file(&dir, "mill_radial_profile.svg");
    let texts: Vec<&str> = figure.lines().map(str::trim).collect();
    assert!(texts.contains(&"share of ball samples") && texts.contains(&"share of the area"), "{figure}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// QA P2-2: a row's time is a sum of steps, a hair off its frame's multiple. `--warm-up T` at a frame whose row and
/// dump lie 1 ns below T left them out: the power was taken from the next row while `window_s` named T, and a start at
/// the last row but one had "fewer than two rows". A start between two rows moves to the next row.
#[test]
fn a_start_at_a_frame_takes_the_frame_whose_time_is_a_hair_below_it() {
    let (dir, world) = run_dir("hair", 0.0);
    let end = world.time();
    // Rows and dumps every 10 ms, 1 ns early (a Δt is 1 ms), the last at the run's end; the work is t², so the mean
    // power from a row at a to the end is (end² − a²)/(end − a) = end + a.
    let frames: Vec<f64> = (0..=100).map(|k| if k == 100 { end } else { (k as f64 * 0.01 - 1e-9).max(0.0) }).collect();
    write_dumps(&dir, &world, &frames);
    write_series(&dir, &frames, |t| t * t);
    let mut events = std::fs::read_to_string(dir.join("events.csv")).unwrap();
    event(&mut events, frames[30], 1, 3, 1.0, DVec2::new(0.004, 0.0)); // a blade hit at the 0.3 s step
    std::fs::write(dir.join("events.csv"), events).unwrap();

    let analyse =
        |warm_up: f64| analyze_mill(&dir, &MillOptions { warm_up_s: Some(warm_up), ..MillOptions::default() });
    let blade = |r: &gc2d_analysis::MillReport| r.classes.iter().find(|c| c.class == "ball–blade").unwrap().collisions;
    let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
    let at_frame = analyse(0.3).unwrap();
    assert_eq!(at_frame.window_s, [0.3, end]);
    assert!(close(at_frame.power.mean_power_torque_w, end + frames[30]), "{:?}", at_frame.power);
    assert_eq!(at_frame.ball_speeds.as_ref().unwrap().dumps, 71);
    assert_eq!(blade(&at_frame), 2, "the hits at 0.3 s and 0.4 s");
    assert_eq!(at_frame.warm_up.tolerance_s, 0.5 * world.time_step());
    let median = std::fs::read_to_string(dir.join("analysis/mill_median_speed.csv")).unwrap();
    assert_eq!(median.lines().filter(|l| l.ends_with(",1")).count(), 71, "{median}");

    // Between two frames: the window starts at the next row, and says so.
    let between = analyse(0.305).unwrap();
    assert_eq!(between.window_s, [frames[31], end]);
    assert!(close(between.power.mean_power_torque_w, end + frames[31]), "{:?}", between.power);
    assert_eq!((between.ball_speeds.as_ref().unwrap().dumps, blade(&between)), (70, 1));

    // The last frame but one leaves two rows; after it, one, and the message says where the rows are.
    let last = analyse(0.99).unwrap();
    assert!(close(last.power.mean_power_torque_w, end + frames[99]), "{:?}", last.power);
    assert_eq!(last.ball_speeds.as_ref().unwrap().dumps, 2);
    let refused = analyse(0.995).unwrap_err().to_string();
    assert!(
        refused.contains("fewer than two rows in the window from 0.995 s")
            && refused.contains("its last two rows are at 0.99 s and 1 s: give a warm-up at or before 0.99 s"),
        "{refused}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// QA P2-8: the revolutions in the window were the rotor's angular velocity at the end times the window's length, 2×
/// too many over a linear spin-up. With ω reached after T = 0.5 s the rotor has turned ω·t²/(2T) at t ≤ T and
/// ω·(t − T/2) after it.
#[test]
fn revolutions_count_the_turns_the_rotor_made_during_its_spin_up() {
    let (dir, world) = run_dir("spin-up", 0.5);
    let end = world.time();
    let turns = |t: f64| OMEGA / std::f64::consts::TAU * if t <= 0.5 { t * t } else { t - 0.25 };
    for (warm_up, blade_hits) in [(0.0, 2.0), (0.3, 1.0), (0.6, 0.0)] {
        let report = analyze_mill(&dir, &MillOptions { warm_up_s: Some(warm_up), ..MillOptions::default() }).unwrap();
        let expected = turns(end) - turns(warm_up);
        assert!(
            (report.revolutions - expected).abs() < 1e-9,
            "from {warm_up} s: {} against {expected}",
            report.revolutions
        );
        assert!((report.blade_hits_per_revolution - blade_hits / expected).abs() < 1e-9, "from {warm_up} s");
    }
    // From 0: 7.5 turns, not the 10 of ω_end × 1 s; from 0.3 s: 6.6, not 7.
    let from_zero = turns(end) - turns(0.0);
    assert!((from_zero - 7.5).abs() < 1e-9 && (turns(end) - turns(0.3) - 6.6).abs() < 1e-9);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The analysis directory's `name` as text.
fn analysis_file(dir: &Path, name: &str) -> String {
    std::fs::read_to_string(dir.join("analysis").join(name)).unwrap()
}

/// QA P2-10 d: a run whose dumps are only Parquet (`--dump-format parquet`) gave `"ball_speeds": null` without a word.
#[test]
fn dumps_in_formats_the_analysis_cannot_read_are_warned_about() {
    let (dir, _) = run_dir("parquet", 0.0);
    let dumps = dir.join("dumps");
    for (_, path) in gc2d_analysis::particle_state::csv::dump_files(&dumps).unwrap() {
        std::fs::rename(&path, path.with_extension("parquet")).unwrap();
    }
    let report = analyze_mill(&dir, &MillOptions::default()).unwrap();
    assert!(report.ball_speeds.is_none());
    assert_eq!(report.warnings.len(), 1, "{:?}", report.warnings);
    let warning = &report.warnings[0];
    assert!(
        warning.contains("dumps in formats the analysis cannot read (101 in parquet, without a CSV copy)")
            && warning.contains("run with `--dump-format csv` (csv is what `analyze` reads"),
        "{warning}"
    );
    let json: serde_json::Value = serde_json::from_str(&analysis_file(&dir, "mill.json")).unwrap();
    assert_eq!(json["warnings"][0].as_str(), Some(warning.as_str()));
    // With a CSV copy of every dump there is nothing to say.
    let (both, _) = run_dir("parquet-and-csv", 0.0);
    std::fs::write(both.join("dumps/particles_000003.parquet"), "").unwrap();
    assert_eq!(analyze_mill(&both, &MillOptions::default()).unwrap().warnings, Vec::<String>::new());
    std::fs::remove_dir_all(&dir).unwrap();
    std::fs::remove_dir_all(&both).unwrap();
}

/// QA P2-10 h: a dump file deleted from the numbered sequence was skipped without a word.
#[test]
fn dumps_missing_from_the_numbering_are_named() {
    let (dir, _) = run_dir("missing", 0.0);
    std::fs::remove_file(dir.join("dumps").join(dump_file_name(50))).unwrap();
    let report = analyze_mill(&dir, &MillOptions::default()).unwrap();
    assert_eq!(
        report.warnings,
        ["dumps/particles_000050.csv is missing from the numbered dumps (deleted, or lost): the dump-based \
          statistics use the 100 others"]
    );
    assert_eq!(report.ball_speeds.as_ref().unwrap().dumps, 70);
    // Several: counted, the first few named.
    for k in [40, 41, 42, 43, 44, 45, 60] {
        std::fs::remove_file(dir.join("dumps").join(dump_file_name(k))).unwrap();
    }
    let report = analyze_mill(&dir, &MillOptions::default()).unwrap();
    let warning = &report.warnings[0];
    assert!(
        warning.starts_with(
            "8 dump files are missing from the numbered dumps (deleted, or lost): dumps/particles_000040.csv, \
             dumps/particles_000041.csv, dumps/particles_000042.csv, dumps/particles_000043.csv, \
             dumps/particles_000044.csv, …; the dump-based statistics use the 93 others"
        ),
        "{warning}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// QA P2-10 j: a window without collisions wrote a 330-character mode and NaN quartiles into `mill_collisions.csv`
/// and 2.2e-308 bin edges into `mill.json`; an empty stress-energy spectrum had bins from 1 J to 10 J. The shares above
/// 0.5, 1 and 3 m/s of no collisions were 0 ("0 % of no impacts"): null and empty fields too, and the summary says
/// that there were no collisions.
#[test]
fn empty_classes_give_null_and_empty_fields_not_sentinels() {
    let (dir, _) = run_dir("no-collisions", 0.0);
    let header = std::fs::read_to_string(dir.join("events.csv")).unwrap().lines().next().unwrap().to_owned();
    std::fs::write(dir.join("events.csv"), header + "\n").unwrap();
    let report = analyze_mill(&dir, &MillOptions::default()).unwrap();
    assert!(report.classes.is_empty() && report.all_classes.collisions == 0);
    assert!(report.all_classes.fractions_above.iter().all(|f| f.is_nan()), "{:?}", report.all_classes);
    let collisions = analysis_file(&dir, "mill_collisions.csv");
    assert_eq!(collisions.lines().nth(1), Some("all,0,0,0,,,,,,,,0"), "{collisions}");
    let json: serde_json::Value = serde_json::from_str(&analysis_file(&dir, "mill.json")).unwrap();
    let all = &json["all_classes"];
    assert!(all["mode_m_s"].is_null() && all["quartiles_m_s"].as_array().unwrap().iter().all(|q| q.is_null()));
    assert_eq!(all["fractions_above"], serde_json::json!([null, null, null]));
    let summary = report.summary();
    assert!(summary.ends_with("; no collisions in the window.") && !summary.contains("NaN"), "{summary}");
    assert_eq!(
        (all["bin_edges_m_s"].as_array().map(Vec::len), all["densities"].as_array().map(Vec::len)),
        (Some(0), Some(0))
    );
    let stress = &json["stress_energy"];
    assert_eq!((stress["events"].as_u64(), stress["bin_edges_j"].as_array().map(Vec::len)), (Some(0), Some(0)));
    assert!(stress["median_j"].is_null());
    assert!(!analysis_file(&dir, "mill.json").contains("e-308"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An all-zero sample (balls at rest, contacts without approach) had bin edges [0, 2.2e-308] and a mode of 1.1e-308:
/// it has no bins, a mode of 0, and a warning says why.
#[test]
fn samples_whose_every_speed_is_zero_have_no_bins_mode_zero_and_a_warning() {
    let (dir, _) = run_dir("all-zero", 0.0);
    for (_, path) in gc2d_analysis::particle_state::csv::dump_files(&dir.join("dumps")).unwrap() {
        let rows: Vec<_> = gc2d_analysis::particle_state::csv::read_csv(&path)
            .unwrap()
            .into_iter()
            .map(|row| gc2d_analysis::ParticleState { vx_m_s: 0.0, vy_m_s: 0.0, ..row })
            .collect();
        let mut bytes = Vec::new();
        write_csv(&rows, &mut bytes).unwrap();
        std::fs::write(&path, bytes).unwrap();
    }
    let events = std::fs::read_to_string(dir.join("events.csv")).unwrap();
    let mut rest = events.lines().next().unwrap().to_owned() + "\n";
    event(&mut rest, 0.4, 1, 4, 0.0, DVec2::new(0.004, 0.0)); // ball–blade
    event(&mut rest, 0.5, 3, 4, 0.0, DVec2::new(0.0, 0.048)); // ball–ball
    std::fs::write(dir.join("events.csv"), rest).unwrap();
    let report = analyze_mill(&dir, &MillOptions { warm_up_s: Some(0.0), ..MillOptions::default() }).unwrap();
    let speeds = report.ball_speeds.as_ref().unwrap();
    assert_eq!((speeds.all.samples, speeds.all.mode_m_s, speeds.all.median_m_s), (202, 0.0, 0.0));
    assert!(speeds.all.histogram.bin_edges.is_empty() && speeds.all.histogram.densities.is_empty());
    assert_eq!((report.all_classes.collisions, report.all_classes.mode_m_s), (2, 0.0));
    assert!(report.all_classes.bin_edges_m_s.is_empty());
    assert_eq!(report.all_classes.fractions_above, [0.0; 3]);
    assert_eq!(
        report.warnings,
        [
            "all 2 impact normal speeds of class all are 0: no histogram bins (a sample at one value has no density); \
             mode and quartiles 0",
            "all 202 ball speeds (all) in the window are 0 (the balls are at rest): no histogram bins (a sample at one \
             value has no density); mode, median, P90 and mean 0",
        ]
    );
    let json = analysis_file(&dir, "mill.json");
    assert!(!json.contains("e-308"), "{json}");
    assert_eq!(analysis_file(&dir, "mill_ball_speeds.csv"), "part,from_m_s,to_m_s,density_s_m\n\n");
    assert_eq!(analysis_file(&dir, "mill_speed_histograms.csv"), "class,from_m_s,to_m_s,density_s_m\n\n");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// QA P2-10 j: a wavy chamber (no inner circle in the final state) gave outer-ring speeds of 0 samples with sentinel
/// bins and no word; they are not defined without the chamber's radius: null, with a warning that says why.
#[test]
fn a_chamber_that_is_not_a_circle_has_no_outer_ring_and_says_so() {
    let (dir, _) = run_dir("not-circular", 0.0);
    let mut world = world(0.0, false);
    world.run_until(1.0).unwrap();
    world.save_checkpoint_file(dir.join("final.ckpt")).unwrap();
    let report = analyze_mill(&dir, &MillOptions::default()).unwrap();
    let speeds = report.ball_speeds.as_ref().unwrap();
    assert_eq!(speeds.all.samples, 142);
    assert!(speeds.upper_outer.is_none() && speeds.lower_outer.is_none());
    assert!(report.chamber.is_none() && report.radial_profile.is_none());
    assert_eq!(report.warnings.len(), 1, "{:?}", report.warnings);
    assert!(report.warnings[0].starts_with("the chamber is not a circle"), "{}", report.warnings[0]);
    let json: serde_json::Value = serde_json::from_str(&analysis_file(&dir, "mill.json")).unwrap();
    assert!(json["ball_speeds"]["upper_outer"].is_null() && json["ball_speeds"]["lower_outer"].is_null());
    let rows = analysis_file(&dir, "mill_ball_speeds.csv");
    assert!(rows.lines().skip(1).all(|l| l.starts_with("all,")), "{rows}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// QA docs 11: a field that is not a number in a column of `events.csv` the analysis does not read passed unseen, and
/// a damaged file was labelled "not enough data".
#[test]
fn a_damaged_events_file_is_named_damaged_in_every_numeric_column() {
    let (dir, _) = run_dir("damaged-events", 0.0);
    let path = dir.join("events.csv");
    let original = std::fs::read_to_string(&path).unwrap();
    let mut lines: Vec<String> = original.lines().map(str::to_owned).collect();
    let good = lines[2].clone();
    for (column, bad) in [(1, "x0.4"), (11, "abc"), (0, "y0.4")] {
        let mut fields: Vec<&str> = good.split(',').collect();
        fields[column] = bad;
        lines[2] = fields.join(",");
        std::fs::write(&path, lines.join("\n") + "\n").unwrap();
        let name = lines[0].split(',').nth(column).unwrap();
        match analyze_mill(&dir, &MillOptions::default()) {
            Err(error @ AnalysisError::DamagedFile(_)) => {
                let message = error.to_string();
                assert!(message.starts_with("damaged file: "), "{message}");
                assert!(
                    message.contains(&format!("events.csv:3: `{bad}` in column `{name}` is not a number")),
                    "{message}"
                );
            }
            other => panic!("`{bad}` in `{name}`: {other:?}"),
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
