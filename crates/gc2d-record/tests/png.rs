//! PNG snapshots: decoded again with tiny-skia and checked pixel by pixel.

mod common;

use common::heptagon_on_the_floor;
use gc2d_geometry::{Aabb, DVec2};
use gc2d_record::colour::{Rgba, WALL_GREY, force_colour, viridis};
use gc2d_record::png::encode_png;
use gc2d_record::{ColourRange, PngOptions, render_png};
use tiny_skia::Pixmap;

/// A 10 cm × 5 cm window around the resting heptagon, 1000 px wide (1 px = 0.1 mm).
fn options(force_network: bool) -> PngOptions {
    PngOptions {
        width: 1000,
        view: Some(Aabb { min: DVec2::new(-0.05, -0.02), max: DVec2::new(0.05, 0.03) }),
        colour_range: ColourRange::Fixed { min: 0.0, max: 1.0 },
        force_network,
        ..PngOptions::default()
    }
}

/// The colour at world point `p` of a picture made with [`options`].
fn colour_at(pixmap: &Pixmap, p: DVec2) -> Rgba {
    let x = ((p.x + 0.05) * 10_000.0) as u32;
    let y = ((0.03 - p.y) * 10_000.0) as u32;
    let c = pixmap.pixel(x, y).unwrap().demultiply();
    Rgba {
        r: c.red() as f64 / 255.0,
        g: c.green() as f64 / 255.0,
        b: c.blue() as f64 / 255.0,
        a: c.alpha() as f64 / 255.0,
    }
}

fn assert_close(actual: Rgba, expected: Rgba, what: &str) {
    let d = (actual.r - expected.r).abs().max((actual.g - expected.g).abs()).max((actual.b - expected.b).abs());
    assert!(d <= 1.5 / 255.0, "{what}: {actual:?} is not {expected:?}");
}

#[test]
fn snapshot_shows_walls_grey_particles_in_the_colour_map_and_the_force_network() {
    let mut world = heptagon_on_the_floor();
    world.run_until(0.5).unwrap();
    let centre = world.bodies().pose[3].position;

    let plain = Pixmap::decode_png(&encode_png(&world, &options(false)).unwrap()).unwrap();
    assert_eq!((plain.width(), plain.height()), (1000, 500), "height from the view's aspect ratio");
    assert_close(colour_at(&plain, DVec2::new(-0.03, 0.02)), Rgba::hex(0xffffff), "background");
    assert_close(colour_at(&plain, DVec2::new(0.0, -0.01)), WALL_GREY, "floor");
    assert_close(colour_at(&plain, centre + DVec2::new(0.0, 0.004)), viridis(0.0), "particle at rest");

    let (point, _) = world.contacts().map(|(_, _, c)| (c.point, c.force_on_a)).next().unwrap();
    let with_forces = Pixmap::decode_png(&encode_png(&world, &options(true)).unwrap()).unwrap();
    let on_the_line = 0.5 * (centre + point);
    assert_close(colour_at(&with_forces, on_the_line), force_colour(1.0), "the only (so largest) force is yellow");
    assert_close(colour_at(&with_forces, centre + DVec2::new(0.006, 0.004)), viridis(0.0), "beside the line");
}

#[test]
fn render_png_writes_a_png_file_and_reports_a_bad_path() {
    let world = heptagon_on_the_floor();
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("png");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("snapshot.png");
    render_png(&world, &path, &PngOptions::default()).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let picture = Pixmap::decode_png(&bytes).unwrap();
    assert_eq!(picture.width(), 1200);
    assert!(render_png(&world, &dir.join("missing/dir/x.png"), &PngOptions::default()).is_err());
    let empty = common::empty_world();
    assert!(encode_png(&empty, &PngOptions::default()).is_err(), "nothing to draw and no view");
    // A view without area is told in numbers, not in Rust's debug form of the vectors.
    let point = gc2d_geometry::DVec2::new(0.5, 0.25);
    let flat = PngOptions { view: Some(gc2d_geometry::Aabb { min: point, max: point }), ..PngOptions::default() };
    let message = encode_png(&world, &flat).unwrap_err().to_string();
    assert_eq!(
        message,
        "PNG snapshot: the region to draw, from (0.5, 0.25) to (0.5, 0.25) m, has no area: give a view with a width and a height"
    );
}
