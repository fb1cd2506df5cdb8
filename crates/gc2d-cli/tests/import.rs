//! `gc2d-rs import-gsi` on the thesis's example file (App. B.1.8) and on a broken one.

use assert_cmd::Command;
use gc2d_scene::Scene;
use predicates::prelude::*;
use predicates::str::contains;
use std::path::{Path, PathBuf};

fn piston_gsi() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/piston.gsi")
}

fn gc2d() -> Command {
    Command::cargo_bin("gc2d-rs").unwrap()
}

#[test]
fn the_piston_file_imports_warns_about_part_size_and_the_scene_builds_and_runs() {
    let dir = tempfile::tempdir().unwrap();
    let gsi = dir.path().join("piston.gsi");
    std::fs::copy(piston_gsi(), &gsi).unwrap();
    gc2d()
        .arg("import-gsi")
        .arg(&gsi)
        .assert()
        .success()
        .stderr(contains("piston.gsi:58: warning: read as semi-axes, PART_SIZE"))
        .stderr(contains("piston.gsi:4: warning: DELTA_T is not converted"))
        .stderr(contains("piston.gsi:10: warning: BASENAME is not converted"))
        .stderr(contains("1251 particles"));
    // The default output sits next to the input, named after it.
    let ron = dir.path().join("piston.ron");
    let text = std::fs::read_to_string(&ron).unwrap();
    assert!(text.starts_with("// piston.ron: imported from "));
    let scene = Scene::from_str(&text, "piston.ron").unwrap_or_else(|e| panic!("{}", e.render_plain()));
    assert_eq!(scene.name, "piston");
    let summary = scene.summary().unwrap();
    assert_eq!((summary.wall_bodies, summary.moving_walls, summary.particles), (4, 1, 1251));
    assert!(summary.time_step_is_automatic);
    // A second import does not replace the scene (it may have been edited since) unless asked to.
    std::fs::write(&ron, format!("{text}// edited\n")).unwrap();
    gc2d().arg("import-gsi").arg(&gsi).assert().code(2).stderr(contains("piston.ron exists").and(contains("--force")));
    assert!(std::fs::read_to_string(&ron).unwrap().ends_with("// edited\n"));
    gc2d().arg("import-gsi").arg(&gsi).arg("--force").assert().success();
    assert_eq!(std::fs::read_to_string(&ron).unwrap(), text);
    let out = dir.path().join("out");
    gc2d()
        .args(["run", ron.to_str().unwrap(), "--quiet", "--until", "0.002", "--out"])
        .arg(&out)
        .assert()
        .success()
        .stderr(contains("Finished at t = 0.002"));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["outcome"]["status"], "completed");
}

#[test]
fn output_path_and_part_size_convention_are_honoured() {
    let dir = tempfile::tempdir().unwrap();
    let ron = dir.path().join("semi.ron");
    gc2d()
        .arg("import-gsi")
        .arg(piston_gsi())
        .args(["--part-size", "semi-axes", "-o"])
        .arg(&ron)
        .assert()
        .code(2)
        .stderr(contains("piston.gsi:58: warning: particles of this GENERATE_BLOCK are up to 6.000 mm across"))
        .stderr(contains("semi.ron was written but is not a valid scene"));
    // Read as semi-axes the lattice starts 17 % overlapped: the scene is written (for inspection) but refused.
    let scene = Scene::from_path(&ron).unwrap();
    assert_eq!(scene.blocks[0].shape.semi_axes_m, [0.003, 0.003]);
    assert_eq!(scene.name, "semi");
}

#[test]
fn a_broken_gsi_file_exits_with_2_and_names_each_bad_line() {
    let dir = tempfile::tempdir().unwrap();
    let gsi = dir.path().join("broken.gsi");
    let text = std::fs::read_to_string(piston_gsi())
        .unwrap()
        .replace("E_Modul ", "E_Modulus ")
        .replace("Grid_Type           FCC", "Grid_Type           HEX");
    std::fs::write(&gsi, text).unwrap();
    let assert = gc2d().arg("import-gsi").arg(&gsi).assert().code(2);
    let stderr = String::from_utf8(assert.get_output().stderr.clone()).unwrap();
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 2, "{stderr}");
    assert!(lines[0].contains("broken.gsi:6: unknown keyword `E_Modulus`"), "{stderr}");
    assert!(lines[1].contains("broken.gsi:66: GRID_TYPE"), "{stderr}");
    assert!(!dir.path().join("broken.ron").exists());
}

#[test]
fn dollar_comments_are_printed_with_their_line() {
    let dir = tempfile::tempdir().unwrap();
    let gsi = dir.path().join("note.gsi");
    let text = "PARAMETER v1.4\nA box\n$ compressing, please wait\nDelta_T 1e-5\nWALL\nCorners\n0 0\n1 0\n1 1\nEND\nEND_OF_FILE\n";
    std::fs::write(&gsi, text).unwrap();
    gc2d().arg("import-gsi").arg(&gsi).assert().success().stdout(contains("note.gsi:3: $ compressing, please wait"));
    let scene = Scene::from_path(dir.path().join("note.ron")).unwrap();
    assert_eq!(scene.description, "A box (imported from a gc2d gsi file)");
    assert_eq!(scene.run.time_step_s, Some(1e-5));
}

#[test]
fn a_wall_overlapping_the_particles_is_blamed_not_the_time_step() {
    // The piston's floor moved up 3 cm into the block: DELTA_T is above the particles' bound as before, so the
    // import leaves the time step automatic (it used to keep DELTA_T once the overlap stopped the scene from building,
    // and the load-back check then blamed the time step).
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(piston_gsi()).unwrap();
    let floor = "WALL\n        Offset              0.0        0.0\n        Corners\n                -0.3    -0.01";
    assert!(text.contains(floor));
    let gsi = dir.path().join("overlap.gsi");
    std::fs::write(&gsi, text.replacen(floor, &floor.replace("0.0        0.0", "0.0        0.03"), 1)).unwrap();
    let output = gc2d().env("NO_COLOR", "1").arg("import-gsi").arg(&gsi).output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("overlap.gsi:4: warning: DELTA_T is not converted"), "{stderr}");
    assert!(stderr.contains("overlap.ron was written but is not a valid scene"), "{stderr}");
    assert!(stderr.contains("gc2d_scene::overlap"), "{stderr}");
    assert!(stderr.contains("`blocks[0]`: a particle and a wall"), "{stderr}");
    assert!(!stderr.contains("gc2d_scene::time_step"), "{stderr}");
}

/// The piston file with each `(from, to)` replaced once, written as `name` in `dir`.
fn piston_variant(dir: &Path, name: &str, replacements: &[(&str, &str)]) -> PathBuf {
    let mut text = std::fs::read_to_string(piston_gsi()).unwrap();
    for (from, to) in replacements {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    let gsi = dir.join(name);
    std::fs::write(&gsi, text).unwrap();
    gsi
}

#[test]
fn missing_and_extra_values_are_refused_at_their_gsi_line() {
    // QA report 1, section 2: these used to be read as 0, dropped, or (GRID_DISTANCE) reported with an invented 0.
    let dir = tempfile::tempdir().unwrap();
    let gsi = piston_variant(
        dir.path(),
        "counts.gsi",
        &[
            ("Time                0          0.2", "Time                0"),
            ("Gamma               0.5", "Gamma               0.5 0.9"),
            ("Offset              0.0        0.11", "Offset              0.11"),
            ("Grid_Distance       0.005      0.005", "Grid_Distance       0.005"),
        ],
    );
    let assert = gc2d().arg("import-gsi").arg(&gsi).assert().code(2);
    let stderr = String::from_utf8(assert.get_output().stderr.clone()).unwrap();
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(
        lines,
        [
            format!("{}:5: TIME: expected 2 values (start end, s), found 1: `0`", gsi.display()),
            format!("{}:7: GAMMA: expected 1 value, found 2: `0.5 0.9`", gsi.display()),
            format!("{}:41: OFFSET: expected 2 values (x y, m), found 1: `0.11`", gsi.display()),
            format!("{}:61: GRID_DISTANCE: expected 2 values (Δx Δy, m), found 1: `0.005`", gsi.display()),
        ],
        "{stderr}"
    );
    assert!(!dir.path().join("counts.ron").exists());
}

#[test]
fn missing_time_and_piston_force_warn_with_the_default_and_comments_without_hash_warn() {
    let dir = tempfile::tempdir().unwrap();
    let gsi = piston_variant(
        dir.path(),
        "defaults.gsi",
        &[
            ("        Time                0          0.2\n", ""),
            ("        Piston_Force        10000\n", ""),
            ("E_Modul             1E7", "E_Modul             1E7  Steifigkeit"),
        ],
    );
    gc2d()
        .arg("import-gsi")
        .arg(&gsi)
        .assert()
        .success()
        .stderr(contains("defaults.gsi:1: warning: GENERAL has no TIME: gc2d's default 0 1 (s) is used"))
        .stderr(contains("defaults.gsi:5: warning: E_MODUL: the text after the parameters, `Steifigkeit`, is ignored"))
        .stderr(contains("defaults.gsi:18: warning: WALL has no PISTON_FORCE: gc2d's default 0 (N) is used"));
    let scene = Scene::from_path(dir.path().join("defaults.ron")).unwrap();
    assert_eq!(scene.run.end_time_s, 1.0);
}

#[test]
fn values_the_scene_refuses_are_named_at_their_gsi_line() {
    // QA report 1, section 10: these used to be reported at lines of the written .ron.
    let dir = tempfile::tempdir().unwrap();
    let gsi = piston_variant(
        dir.path(),
        "ranges.gsi",
        &[
            ("Gamma               0.5", "Gamma               -0.5"),
            ("Part_Num_Corners    8", "Part_Num_Corners    100"),
        ],
    );
    let assert = gc2d().arg("import-gsi").arg(&gsi).assert().code(2);
    let stderr = String::from_utf8(assert.get_output().stderr.clone()).unwrap();
    assert!(
        stderr.contains("ranges.gsi:7: GAMMA: -0.5: must be a finite number ≥ 0 (scene field `materials[0].gamma`)"),
        "{stderr}"
    );
    assert!(stderr.contains("ranges.gsi:63: PART_NUM_CORNERS: 100 is not allowed"), "{stderr}");
    assert!(!stderr.contains("ranges.ron"), "{stderr}");
    assert!(!dir.path().join("ranges.ron").exists());
    let gsi = piston_variant(dir.path(), "steps.gsi", &[("Steps_Data          1000", "Steps_Data          0")]);
    gc2d().arg("import-gsi").arg(&gsi).assert().code(2).stderr(contains("steps.gsi:8: STEPS_DATA"));
}

/// An old gc2d file with a Latin-1 umlaut in a comment was refused as a whole, without a line (QA report 1, section
/// 6): it is read as Latin-1, with a warning at the line of the first byte that is not UTF-8.
#[test]
fn a_latin1_file_is_read_with_a_warning_at_its_first_non_utf8_byte() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(piston_gsi()).unwrap();
    let (first, rest) = text.split_once('\n').unwrap();
    let mut bytes = format!("{first}\n# Kolben mit Gr").into_bytes();
    bytes.push(0xFC); // ü in Latin-1
    bytes.extend_from_slice(format!("n\n{rest}").as_bytes());
    let gsi = dir.path().join("latin1.gsi");
    std::fs::write(&gsi, bytes).unwrap();
    gc2d()
        .arg("import-gsi")
        .arg(&gsi)
        .assert()
        .success()
        .stderr(contains("latin1.gsi:2: warning: the file is not UTF-8 (byte 0xfc at column 16").and(contains("`ü`")));
    assert!(Scene::from_path(dir.path().join("latin1.ron")).is_ok());
}
