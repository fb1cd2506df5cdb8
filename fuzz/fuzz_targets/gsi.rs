//! Legacy gc2d input files (.gsi): any UTF-8 text is imported as `gc2d-rs import-gsi` does (read, convert, write
//! RON, load the RON back); every error must name a line of the file, and the written scene must load or be rejected
//! at a line and column. A panic or a hang is a finding.
#![no_main]

use gc2d_scene::Scene;
use gc2d_scene::gsi::{GsiErrors, ImportOptions, parse_gsi, to_scene};
use libfuzzer_sys::fuzz_target;

fn assert_lines(errors: &GsiErrors, lines: usize) {
    assert!(!errors.0.is_empty());
    for error in &errors.0 {
        assert!(error.line >= 1 && error.line <= lines, "line {} of {lines}", error.line);
    }
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let lines = text.split('\n').count() + 1;
    let import = match parse_gsi(text, &ImportOptions::default()) {
        Ok(import) => import,
        Err(errors) => return assert_lines(&errors, lines),
    };
    let conversion = match to_scene(&import, "fuzz") {
        Ok(conversion) => conversion,
        Err(errors) => return assert_lines(&errors, lines),
    };
    let ron = conversion.scene.to_ron_string().expect("a converted scene writes as RON");
    if let Err(error) = Scene::from_str(&ron, "fuzz.ron") {
        assert!(error.location().is_some(), "{error}");
    }
});
