//! Scene files (RON): any bytes are loaded (parsed and validated) as `fuzz.ron`; a rejected input must be located
//! at a line and column and render as a report, and an accepted scene with at most 3,000 particles at the start is
//! built (overlap and time-step checks). A panic or a hang is a finding.
#![no_main]

use gc2d_scene::Scene;
use libfuzzer_sys::fuzz_target;

/// Scenes larger than this are loaded and validated but not built, to keep each input quick.
const MAX_BUILT_PARTICLES: usize = 3_000;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data).into_owned();
    let rejected = match Scene::from_bytes(data.to_vec(), "fuzz.ron") {
        Err(error) => Some(error),
        Ok(scene) if scene.initial_particle_count() <= MAX_BUILT_PARTICLES => scene.build().err(),
        Ok(_) => None,
    };
    if let Some(error) = rejected {
        let location = error.location().expect("every rejected scene is located");
        assert!(location.line >= 1 && location.column >= 1 && location.line <= text.split('\n').count());
        assert!(!error.render_plain().is_empty());
    }
});
