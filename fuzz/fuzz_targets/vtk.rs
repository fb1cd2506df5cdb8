//! Legacy ASCII VTK files (OpenFOAM's foamToVTK exports, read by gc2d-fluid for a scene's `fluid` field): any bytes
//! are parsed; a refusal must name a line of the file; a file that parses is turned into velocity fields (points and
//! cells, bilinear where the nodes form a lattice and Shepard) and sampled. A panic or a hang is a finding.
#![no_main]

use gc2d_fluid::vtk::{DataLocation, VtkError, VtkFile};
use gc2d_fluid::{Interpolation, Outside, SampledField};
use gc2d_geometry::DVec2;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let lines = data.split(|&b| b == b'\n').count();
    let file = match VtkFile::parse(data, "fuzz.vtk") {
        Ok(file) => file,
        Err(VtkError::Syntax { line, .. }) => {
            assert!(line >= 1 && line <= lines + 1, "line {line} of {lines}");
            return;
        }
        Err(error) => panic!("parsing bytes cannot fail to read a file: {error}"),
    };
    for location in [DataLocation::Points, DataLocation::Cells] {
        let Ok(samples) = file.velocity_samples("U", location) else { continue };
        for interpolation in [Interpolation::Bilinear, Interpolation::SHEPARD_THESIS] {
            if let Ok(field) = SampledField::new(&samples, interpolation, Outside::Nearest) {
                for p in [DVec2::ZERO, DVec2::new(0.5, 0.25), DVec2::new(-1e3, 1e3)] {
                    let _ = field.velocity(p);
                }
            }
        }
    }
});
