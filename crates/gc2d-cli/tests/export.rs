//! `gc2d-rs export` (issue 16 item 1): the particle and contact tables against the World's own state, read back from
//! CSV, from Parquet with the parquet crate's reader and with polars in the project's venv (the docs' example), the
//! VTK files' structure, and located refusals.

mod common;

use assert_cmd::Command;
use gc2d_engine::World;
use parquet::file::reader::{FileReader, SerializedFileReader};
use parquet::record::RowAccessor;
use std::path::{Path, PathBuf};

/// Disks of two materials and 7-gons dropped into a box: they touch the floor and each other within 0.15 s.
const SCENE: &str = r#"Scene(
    run: (end_time_s: 0.15, checkpoint_interval_s: 0.05),
    materials: [(name: "glass", density_kg_m2: 2500), (name: "sand", density_kg_m2: 2600)],
    walls: [Box(x_range_m: (-0.03, 0.03), y_range_m: (0.0, 0.08), thickness_m: 0.005)],
    blocks: [
        (x_range_m: (-0.02, 0.02), y_range_m: (0.005, 0.02), grid_spacing_m: (0.0085, 0.0085),
         shape: (semi_axes_m: (0.004, 0.004), disk: true), material: "glass"),
        (x_range_m: (-0.02, 0.02), y_range_m: (0.03, 0.04), grid_spacing_m: (0.0095, 0.0095),
         shape: (semi_axes_m: (0.004, 0.004), corners: 7), material: "sand"),
    ],
)"#;

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A finished run of [`SCENE`] in a fresh folder.
fn run() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("drop.ron");
    std::fs::write(&scene, SCENE).unwrap();
    let out = dir.path().join("run");
    Command::cargo_bin("gc2d-rs")
        .unwrap()
        .arg("run")
        .arg(&scene)
        .arg("--quiet")
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    (dir, out)
}

fn csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(str::to_owned).collect();
    (header, lines.map(|l| l.split(',').map(str::to_owned).collect()).collect())
}

#[test]
fn exported_rows_are_the_worlds_state_in_every_format() {
    let (_dir, run_dir) = run();
    Command::cargo_bin("gc2d-rs").unwrap().args(["export", run_dir.to_str().unwrap()]).assert().success();
    let export = run_dir.join("export");
    let world = World::load_checkpoint_file(run_dir.join("final.ckpt")).unwrap();
    let bodies = world.bodies();

    // Particles: every living particle once, in id order, with its state bit for bit (CSV floats round-trip).
    let (header, rows) = csv(&export.join("particles.csv"));
    assert_eq!(header, gc2d_cli::export::PARTICLE_COLUMNS);
    let column = |name: &str| header.iter().position(|h| h == name).unwrap();
    let ids: Vec<u32> = bodies.particles().map(|id| id.0).collect();
    assert_eq!(rows.len(), ids.len());
    for (row, &id) in rows.iter().zip(&ids) {
        let i = id as usize;
        assert_eq!(row[column("id")].parse::<u32>().unwrap(), id);
        let value = |name: &str| row[column(name)].parse::<f64>().unwrap();
        assert_eq!(value("x_m"), bodies.pose[i].position.x);
        assert_eq!(value("y_m"), bodies.pose[i].position.y);
        assert_eq!(value("vy_m_s"), bodies.velocity[i].y);
        assert_eq!(value("fx_n"), bodies.force[i].x);
        assert_eq!(value("torque_n_m"), bodies.torque[i]);
        let (material, shape, origin) = (&row[column("material")], &row[column("shape")], &row[column("origin")]);
        if shape == "disk" {
            assert_eq!((material.as_str(), origin.starts_with("blocks[0] #")), ("glass", true), "{row:?}");
        } else {
            assert_eq!((material.as_str(), origin.starts_with("blocks[1] #")), ("sand", true), "{row:?}");
            assert_eq!(row[column("corners")], "7");
        }
    }

    // Contacts: every touching pair, its force split along the normal and the tangent.
    let (header, rows) = csv(&export.join("contacts.csv"));
    assert_eq!(header, gc2d_cli::export::CONTACT_COLUMNS);
    let column = |name: &str| header.iter().position(|h| h == name).unwrap();
    let pairs: Vec<_> = world.contacts().collect();
    assert!(pairs.len() > 10, "the drop makes contacts: {}", pairs.len());
    assert_eq!(rows.len(), pairs.len());
    for (row, (a, b, contact)) in rows.iter().zip(&pairs) {
        let value = |name: &str| row[column(name)].parse::<f64>().unwrap();
        assert_eq!((value("a") as u32, value("b") as u32), (a.0, b.0));
        assert_eq!((value("fx_on_a_n"), value("fy_on_a_n")), (contact.force_on_a.x, contact.force_on_a.y));
        let normal = world.contact_normal(*a, *b).unwrap();
        assert!((normal.length() - 1.0).abs() < 1e-12);
        let (fn_, ft) = (value("normal_force_n"), value("tangential_force_n"));
        assert!((fn_.hypot(ft) - contact.force_on_a.length()).abs() <= 1e-9 * contact.force_on_a.length());
        assert!(fn_ > 0.0, "a soft contact pushes the bodies apart: {row:?}");
        assert_eq!(value("overlap_fraction"), world.overlap_fraction(*a, *b, contact));
    }

    // Parquet: the same rows, read with the parquet crate's own reader.
    for (name, count, columns) in [
        ("particles", ids.len(), gc2d_cli::export::PARTICLE_COLUMNS.len()),
        ("contacts", pairs.len(), gc2d_cli::export::CONTACT_COLUMNS.len()),
    ] {
        let reader =
            SerializedFileReader::new(std::fs::File::open(export.join(format!("{name}.parquet"))).unwrap()).unwrap();
        let metadata = reader.metadata().file_metadata();
        assert_eq!(metadata.num_rows() as usize, count, "{name}");
        assert_eq!(metadata.schema_descr().num_columns(), columns, "{name}");
    }
    let reader = SerializedFileReader::new(std::fs::File::open(export.join("particles.parquet")).unwrap()).unwrap();
    let first = reader.get_row_iter(None).unwrap().next().unwrap().unwrap();
    assert_eq!(first.get_ulong(1).unwrap(), u64::from(ids[0]));
    assert_eq!(first.get_double(7).unwrap(), bodies.pose[ids[0] as usize].position.x);

    // VTK: one polygon cell per particle with its outline's corners (a disk traced with 48), and a collection.
    let vtu_name = format!("particles_{}.vtu", world.steps());
    let vtu = std::fs::read_to_string(export.join(&vtu_name)).unwrap();
    let corners: usize =
        ids.iter().map(|&id| if bodies.shape[id as usize] == gc2d_engine::ShapeKind::Disk { 48 } else { 7 }).sum();
    assert!(vtu.contains(&format!(r#"NumberOfPoints="{corners}" NumberOfCells="{}""#, ids.len())), "{}", &vtu[..300]);
    let pvd = std::fs::read_to_string(export.join("particles.pvd")).unwrap();
    assert!(pvd.contains(&format!(r#"file="{vtu_name}""#)), "{pvd}");
}

#[test]
fn the_python_example_of_the_docs_reads_the_export() {
    // The docs show docs/examples/export_summary.py verbatim.
    let example = std::fs::read_to_string(repo_root().join("docs/examples/export_summary.py")).unwrap();
    let docs = std::fs::read_to_string(repo_root().join("docs/export.md")).unwrap();
    assert!(docs.contains(&format!("```python\n{example}```")), "docs/export.md must show the example verbatim");
    if std::process::Command::new("python3").arg("--version").output().is_err() {
        eprintln!("SKIPPED: python3 is not installed, so the export cannot be read by polars");
        return;
    }
    let setup = std::process::Command::new("bash").arg(repo_root().join("tools/setup-python.sh")).output().unwrap();
    assert!(setup.status.success(), "setup-python.sh failed: {}", String::from_utf8_lossy(&setup.stderr));
    let python = String::from_utf8(setup.stdout).unwrap().lines().last().unwrap().trim().to_string();
    let (_dir, run_dir) = run();
    Command::cargo_bin("gc2d-rs")
        .unwrap()
        .args(["export", run_dir.to_str().unwrap(), "--format", "parquet"])
        .assert()
        .success();
    let output = std::process::Command::new(python)
        .arg(repo_root().join("docs/examples/export_summary.py"))
        .current_dir(&run_dir)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{stdout}{}", String::from_utf8_lossy(&output.stderr));
    let world = World::load_checkpoint_file(run_dir.join("final.ckpt")).unwrap();
    let glass = world
        .bodies()
        .particles()
        .filter(|id| world.bodies().shape[id.index()] == gc2d_engine::ShapeKind::Disk)
        .count();
    let glass_line = stdout.lines().find(|l| l.contains("glass")).unwrap_or_else(|| panic!("{stdout}"));
    assert!(glass_line.contains(&format!("│ {glass} ")) || glass_line.contains(&format!(" {glass} ")), "{stdout}");
    assert!(stdout.contains("mean normal force:"), "{stdout}");
}

#[test]
fn refusals_name_the_problem() {
    let dir = tempfile::tempdir().unwrap();
    let failure = |args: &[&str]| {
        let assert = Command::cargo_bin("gc2d-rs").unwrap().args(args).assert().failure();
        String::from_utf8_lossy(&assert.get_output().stderr).to_string()
    };
    let not_a_run = failure(&["export", dir.path().to_str().unwrap()]);
    assert!(not_a_run.contains("holds no checkpoint"), "{not_a_run}");
    let (_keep, run_dir) = run();
    let too_early = failure(&["export", run_dir.to_str().unwrap(), "--at=-1"]);
    assert!(too_early.contains("no checkpoint at or before t = -1 s") && too_early.contains("0.05"), "{too_early}");
    let blocked = dir.path().join("file");
    std::fs::write(&blocked, "").unwrap();
    let unwritable = failure(&["export", run_dir.to_str().unwrap(), "--out", blocked.join("x").to_str().unwrap()]);
    assert!(unwritable.contains("cannot create"), "{unwritable}");
}

/// A second export into the same folder replaces the first one's files, as its manifest lists them: a Parquet table of
/// one time stayed beside a CSV of another, and outlines of an earlier step beside a collection that no longer lists
/// them. Other files stay, also outlines of the same pattern that the export did not write (a run's VTK dumps).
#[test]
fn a_second_export_replaces_the_first() {
    let (_dir, run_dir) = run();
    let export = |args: &[&str]| {
        Command::cargo_bin("gc2d-rs").unwrap().arg("export").arg(&run_dir).args(args).assert().success();
    };
    export(&["--at", "0.05"]);
    let folder = run_dir.join("export");
    std::fs::write(folder.join("notes.txt"), "mine").unwrap();
    std::fs::write(folder.join("particles_000000.vtu"), "a dump").unwrap();
    export(&["--format", "csv"]);
    let mut names: Vec<String> =
        std::fs::read_dir(&folder).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
    names.sort();
    assert_eq!(names, [".gc2d-export", "contacts.csv", "notes.txt", "particles.csv", "particles_000000.vtu"]);
    let (_, rows) = csv(&folder.join("particles.csv"));
    let time: f64 = rows[0][0].parse().unwrap();
    assert!((time - 0.15).abs() < 1e-9, "the latest checkpoint's time, not 0.05: {time}");
}

/// A run directory's scene.ron names the files its scene reads by absolute paths: `export` builds it to name the
/// bodies, and a fluid's VTK field named relative to the scene's own folder was not found from the run directory (the
/// `origin` column came out empty). Resuming with the original scene still finds it the same scene.
#[test]
fn the_scene_copy_of_a_run_with_a_vtk_field_finds_the_field() {
    let dir = tempfile::tempdir().unwrap();
    common::scene_with_a_vtk_field(dir.path());
    let gc2d = |args: &[&str]| Command::cargo_bin("gc2d-rs").unwrap().current_dir(dir.path()).args(args).assert();
    gc2d(&["run", "scenes/air.ron", "--quiet", "--out", "run"]).success();
    gc2d(&["export", "run", "--format", "csv"]).success();
    let (header, rows) = csv(&dir.path().join("run/export/particles.csv"));
    let origin = header.iter().position(|h| h == "origin").unwrap();
    assert_eq!(rows[0][origin], "particles[0]");
    gc2d(&["run", "scenes/air.ron", "--quiet", "--resume", "run", "--until", "0.003"]).success();
    // The same scene by another path to the same file is the same scene.
    gc2d(&["run", "scenes/../scenes/air.ron", "--quiet", "--resume", "run", "--until", "0.004"]).success();
}

/// An export into a folder holding files of the same names that no export wrote (a run's `dumps/`, with its own
/// `particles.pvd`) replaced them; it is refused, and the folder is left as it was.
#[test]
fn an_export_does_not_replace_files_it_did_not_write() {
    let (dir, run_dir) = run();
    let folder = dir.path().join("dumps");
    std::fs::create_dir_all(&folder).unwrap();
    std::fs::write(folder.join("particles.pvd"), "the dumps' collection").unwrap();
    let refused = Command::cargo_bin("gc2d-rs").unwrap().arg("export").arg(&run_dir).arg("--out").arg(&folder).assert();
    let stderr = String::from_utf8_lossy(&refused.code(2).get_output().stderr).to_string();
    assert!(stderr.contains("holds particles.pvd, which no export wrote"), "{stderr}");
    assert_eq!(std::fs::read_to_string(folder.join("particles.pvd")).unwrap(), "the dumps' collection");
    assert_eq!(std::fs::read_dir(&folder).unwrap().count(), 1);
    // A format named twice is written, and listed, once.
    let csv_twice = dir.path().join("twice");
    Command::cargo_bin("gc2d-rs")
        .unwrap()
        .arg("export")
        .arg(&run_dir)
        .args(["--format", "csv,csv", "--out"])
        .arg(&csv_twice)
        .assert()
        .success();
    let manifest = std::fs::read_to_string(csv_twice.join(".gc2d-export")).unwrap();
    assert_eq!(manifest, "particles.csv\ncontacts.csv\n");
}

/// The particles are named from the run's `scene.ron`: a scene.ron of another run (copied over, or edited) named the
/// pile's poured sand as steel balls of another scene's block. Where the file is not the checkpoint's scene, or is
/// missing, the names are left empty and the export says why.
#[test]
fn an_export_names_no_particle_from_a_scene_that_is_not_the_runs() {
    let (_dir, run_dir) = run();
    let export = || {
        let assert =
            Command::cargo_bin("gc2d-rs").unwrap().arg("export").arg(&run_dir).args(["--format", "csv"]).assert();
        let stderr = String::from_utf8_lossy(&assert.success().get_output().stderr).to_string();
        let (header, rows) = csv(&run_dir.join("export/particles.csv"));
        let column = |name: &str| header.iter().position(|h| h == name).unwrap();
        let (origin, material) = (column("origin"), column("material"));
        (stderr, rows[0][origin].clone(), rows[0][material].clone())
    };
    let (stderr, origin, material) = export();
    assert!(!stderr.contains("warning"), "{stderr}");
    assert_eq!((origin.as_str(), material.as_str()), ("blocks[0] #0", "glass"));
    let balls = std::fs::read_to_string(repo_root().join("scenes/balls.ron")).unwrap();
    std::fs::write(run_dir.join("scene.ron"), balls).unwrap();
    let (stderr, origin, material) = export();
    assert!(stderr.contains("is not the scene of") && stderr.contains("left empty"), "{stderr}");
    assert_eq!((origin.as_str(), material.as_str()), ("", ""));
    std::fs::remove_file(run_dir.join("scene.ron")).unwrap();
    let (stderr, origin, material) = export();
    assert!(stderr.contains("has no scene.ron"), "{stderr}");
    assert_eq!((origin.as_str(), material.as_str()), ("", ""));
}

/// A damaged final.ckpt made `export --at T` fail although T's periodic checkpoint was intact (the final one only
/// gives the time step); it is left out with a warning. And `snapshot` drew a checkpoint of another run, copied into
/// the run's `checkpoints/` with a higher step, without a word; it now warns that it is not a state of the run.
#[test]
fn a_damaged_final_checkpoint_or_a_foreign_one_is_named_not_silently_used() {
    let (_keep, run_dir) = run();
    let gc2d = || Command::cargo_bin("gc2d-rs").unwrap();
    let final_checkpoint = run_dir.join("final.ckpt");
    let intact = std::fs::read(&final_checkpoint).unwrap();
    std::fs::write(&final_checkpoint, &intact[..100]).unwrap();
    let exported = gc2d().arg("export").arg(&run_dir).args(["--at", "0.05", "--format", "csv"]).output().unwrap();
    let stderr = String::from_utf8_lossy(&exported.stderr);
    assert!(exported.status.success(), "{stderr}");
    assert!(stderr.contains("warning: cannot read") && stderr.contains("it is left out"), "{stderr}");
    assert!(stderr.contains("Exported t = 0.05") && stderr.contains("checkpoint-0000010417.ckpt"), "{stderr}");
    std::fs::write(&final_checkpoint, &intact).unwrap();

    let other_dir = tempfile::tempdir().unwrap();
    let other_scene = other_dir.path().join("other.ron");
    std::fs::write(&other_scene, SCENE.replace("density_kg_m2: 2500", "density_kg_m2: 3000")).unwrap();
    let other_run = other_dir.path().join("run");
    gc2d()
        .arg("run")
        .arg(&other_scene)
        .args(["--quiet", "--until", "0.01", "--out"])
        .arg(&other_run)
        .assert()
        .success();
    let foreign = run_dir.join("checkpoints/checkpoint-9999999999.ckpt");
    std::fs::copy(other_run.join("final.ckpt"), &foreign).unwrap();
    let drawn = gc2d().arg("snapshot").arg(&run_dir).output().unwrap();
    let stderr = String::from_utf8_lossy(&drawn.stderr);
    assert!(drawn.status.success(), "{stderr}");
    assert!(stderr.contains("later than its final.ckpt") && stderr.contains("is not a state of the run's"), "{stderr}");
    std::fs::remove_file(&foreign).unwrap();
    let drawn = gc2d().arg("snapshot").arg(&run_dir).output().unwrap();
    assert!(drawn.stderr.is_empty() || !String::from_utf8_lossy(&drawn.stderr).contains("warning"));
}
