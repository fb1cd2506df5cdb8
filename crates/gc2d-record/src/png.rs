//! PNG snapshots for people without Foxglove: walls grey, a fluid's velocity as arrows (crate::fluid), particles in
//! the recording's colour map, optionally the force network, drawn with tiny-skia (pure Rust). The picture shows the
//! x-y plane with y up.

use crate::RecordError;
use crate::colour::{Rgba, WALL_GREY, force_colour};
use crate::fluid::{drawn_region, fluid_arrows};
use crate::network::{ContactForce, collect_contact_forces, contact_segments, line_width};
use crate::quantities::{ColourBy, ColourRange, ParticleColours, mean_inscribed_radius};
use crate::recorder::DEFAULT_FORCE_WIDTH_RADII;
use gc2d_engine::{BodyId, BodyKind, World};
use gc2d_geometry::{Aabb, DVec2, TracedOutline};
use std::path::{Path, PathBuf};
use tiny_skia::{Color, FillRule, LineCap, Paint, PathBuilder, Pixmap, Stroke, Transform};

/// Largest picture side, pixels: taller pictures are cut to it, and `gc2d-rs snapshot` refuses wider ones.
pub const MAX_PIXELS: u32 = 16384;

/// What a snapshot shows and how large it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PngOptions {
    /// Picture width, pixels; the height follows from the view's aspect ratio.
    pub width: u32,
    /// The region drawn; `None`: the box around every living body (walls included) with a 2 % margin.
    pub view: Option<Aabb>,
    /// What the particle colours show.
    pub colour_by: ColourBy,
    /// The range the colour map spans.
    pub colour_range: ColourRange,
    /// Draw the force network (reference §5.5).
    pub force_network: bool,
    /// Width of the largest force's lines, m; `None`: half the mean inscribed radius, as in recordings.
    pub force_line_max_width: Option<f64>,
    /// Background colour.
    pub background: Rgba,
}

impl Default for PngOptions {
    fn default() -> Self {
        Self {
            width: 1200,
            view: None,
            colour_by: ColourBy::default(),
            colour_range: ColourRange::default(),
            force_network: false,
            force_line_max_width: None,
            background: Rgba::hex(0xffffff),
        }
    }
}

/// Draws `world` and writes it to `path` as a PNG file, whole or not at all: into `<path>.tmp`, then renamed over
/// `path`. A write that fails (a full disk) removes the temporary file and leaves `path` as it was, never a truncated
/// picture.
pub fn render_png(world: &World, path: &Path, options: &PngOptions) -> Result<(), RecordError> {
    let bytes = encode_png(world, options)?;
    let mut temporary = path.as_os_str().to_owned();
    temporary.push(".tmp");
    let temporary = PathBuf::from(temporary);
    std::fs::write(&temporary, bytes).and_then(|()| std::fs::rename(&temporary, path)).map_err(|source| {
        let _ = std::fs::remove_file(&temporary);
        RecordError::Io { path: path.display().to_string(), source }
    })
}

/// Draws `world` and returns the PNG file's bytes.
pub fn encode_png(world: &World, options: &PngOptions) -> Result<Vec<u8>, RecordError> {
    render(world, options)?.encode_png().map_err(|e| RecordError::Png(e.to_string()))
}

/// World-to-pixel mapping: x to the right, y up.
#[derive(Debug, Clone, Copy)]
struct Canvas {
    origin: DVec2,
    top: f64,
    pixels_per_metre: f64,
}

impl Canvas {
    fn pixel(&self, p: DVec2) -> (f32, f32) {
        (((p.x - self.origin.x) * self.pixels_per_metre) as f32, ((self.top - p.y) * self.pixels_per_metre) as f32)
    }
}

/// Draws `world` into a new pixmap.
fn render(world: &World, options: &PngOptions) -> Result<Pixmap, RecordError> {
    let view = options.view.or_else(|| body_bounds(world)).ok_or_else(|| RecordError::Png("nothing to draw".into()))?;
    let size = view.max - view.min;
    if !(size.x > 0.0 && size.y > 0.0 && size.is_finite()) {
        return Err(RecordError::Png(format!(
            "the region to draw, from ({}, {}) to ({}, {}) m, has no area: {}",
            view.min.x,
            view.min.y,
            view.max.x,
            view.max.y,
            if size.is_finite() {
                "give a view with a width and a height"
            } else {
                "a position is not a finite number"
            }
        )));
    }
    let width = options.width.clamp(1, MAX_PIXELS);
    let height = ((width as f64 * size.y / size.x).round() as u32).clamp(1, MAX_PIXELS);
    let mut pixmap =
        Pixmap::new(width, height).ok_or_else(|| RecordError::Png("cannot allocate the picture".into()))?;
    pixmap.fill(skia_colour(options.background));
    let canvas = Canvas { origin: view.min, top: view.max.y, pixels_per_metre: width as f64 / size.x };

    let bodies = world.bodies();
    for i in (0..bodies.len()).filter(|&i| bodies.alive[i] && bodies.kind[i] == BodyKind::Wall) {
        draw_outline(&mut pixmap, &canvas, &bodies.shape_view(BodyId(i as u32)).traced_outline(), WALL_GREY);
    }
    if let Some(arrows) = drawn_region(world).and_then(|region| fluid_arrows(world, region)) {
        for arrow in &arrows {
            for (from, to) in arrow.segments() {
                draw_segment(&mut pixmap, &canvas, from, to, FLUID_ARROW_PIXELS, arrow.colour);
            }
        }
    }
    let mut forces: Vec<ContactForce> = Vec::new();
    let max_force = collect_contact_forces(world, &mut forces);
    let mut colours = ParticleColours::default();
    colours.update(world, options.colour_by, options.colour_range, &forces);
    for id in bodies.particles() {
        draw_outline(&mut pixmap, &canvas, &bodies.shape_view(id).traced_outline(), colours.colours[id.index()]);
    }
    if options.force_network {
        let max_width = options
            .force_line_max_width
            .or_else(|| mean_inscribed_radius(world).map(|r| DEFAULT_FORCE_WIDTH_RADII * r))
            .unwrap_or(0.0);
        draw_force_network(&mut pixmap, &canvas, world, &forces, max_force, max_width);
    }
    Ok(pixmap)
}

/// The region a picture of `world` without a view shows ([`PngOptions::view`]): the box around every living body, 2 %
/// larger on each side; `None` for a World without bodies.
pub fn body_bounds(world: &World) -> Option<Aabb> {
    let bounds = drawn_region(world)?;
    Some(bounds.expanded(0.02 * (bounds.max - bounds.min).max_element()))
}

/// A filled outline (a ring: the band between its circles) with a darker one-pixel edge.
fn draw_outline(pixmap: &mut Pixmap, canvas: &Canvas, outline: &TracedOutline, fill: Rgba) {
    let mut builder = PathBuilder::new();
    let loops: Vec<&[DVec2]> = match outline {
        TracedOutline::Convex(vertices) => vec![vertices.as_ref()],
        TracedOutline::Ring { inner, outer } => vec![inner.as_slice(), outer.as_slice()],
    };
    for vertices in loops {
        for (k, &v) in vertices.iter().enumerate() {
            let (x, y) = canvas.pixel(v);
            if k == 0 { builder.move_to(x, y) } else { builder.line_to(x, y) }
        }
        builder.close();
    }
    let Some(path) = builder.finish() else { return };
    let mut paint = Paint::default();
    paint.set_color(skia_colour(fill));
    pixmap.fill_path(&path, &paint, FillRule::EvenOdd, Transform::identity(), None);
    paint.set_color(skia_colour(fill.darkened(0.55)));
    let stroke = Stroke { width: 1.0, ..Stroke::default() };
    pixmap.stroke_path(&path, &paint, &stroke, Transform::identity(), None);
}

/// gc2d's force network: per contact, lines from each particle centroid to the force point, width ∝ |F|.
fn draw_force_network(
    pixmap: &mut Pixmap,
    canvas: &Canvas,
    world: &World,
    forces: &[ContactForce],
    max_force: f64,
    max_width: f64,
) {
    let mut paint = Paint::default();
    for force in forces {
        let width = line_width(force.magnitude, max_force, max_width) * canvas.pixels_per_metre;
        if width <= 0.0 {
            continue;
        }
        let mut builder = PathBuilder::new();
        for (from, to) in contact_segments(world, force).into_iter().flatten() {
            let ((x0, y0), (x1, y1)) = (canvas.pixel(from), canvas.pixel(to));
            builder.move_to(x0, y0);
            builder.line_to(x1, y1);
        }
        let Some(path) = builder.finish() else { continue };
        paint.set_color(skia_colour(force_colour(force.magnitude / max_force)));
        let stroke = Stroke { width: width.max(0.5) as f32, line_cap: LineCap::Round, ..Stroke::default() };
        pixmap.stroke_path(&path, &paint, &stroke, Transform::identity(), None);
    }
}

/// Width of the fluid's arrows, pixels.
const FLUID_ARROW_PIXELS: f64 = 1.5;

/// A straight line from `from` to `to` (m), `width` pixels wide.
fn draw_segment(pixmap: &mut Pixmap, canvas: &Canvas, from: DVec2, to: DVec2, width: f64, colour: Rgba) {
    let ((x0, y0), (x1, y1)) = (canvas.pixel(from), canvas.pixel(to));
    let mut builder = PathBuilder::new();
    builder.move_to(x0, y0);
    builder.line_to(x1, y1);
    let Some(path) = builder.finish() else { return };
    let mut paint = Paint::default();
    paint.set_color(skia_colour(colour));
    let stroke = Stroke { width: width as f32, line_cap: LineCap::Round, ..Stroke::default() };
    pixmap.stroke_path(&path, &paint, &stroke, Transform::identity(), None);
}

fn skia_colour(c: Rgba) -> Color {
    let unit = |x: f64| if x.is_finite() { x.clamp(0.0, 1.0) as f32 } else { 0.0 };
    Color::from_rgba(unit(c.r), unit(c.g), unit(c.b), unit(c.a)).unwrap_or(Color::BLACK)
}
