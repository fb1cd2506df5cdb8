//! Feed lines where no particle can stay: the drop line of a source (at an absolute height) and the segment of an
//! inlet, where they lie inside the solid of a wall that does not move, or outside the run's domain. A particle placed
//! inside a wall would only overlap it, one outside the domain is removed at its first step, so the source or inlet
//! feeds only on the rest of its line, and nothing where all of it is there: a line wholly inside walls or outside
//! the domain is refused, one partly so is warned about.

use super::walls::PlacedWall;
use crate::checks::number;
use crate::error::SceneError;
use crate::schema::{DropHeight, Scene};
use crate::spans::field_path;
use gc2d_engine::shape_view;
use gc2d_geometry::{Aabb, DVec2};

/// Points sampled along each line, at the middles of equal pieces.
const SAMPLES: usize = 200;

/// How deep a point must lie inside a wall to count as inside, as a fraction of the line's size (its length, or the
/// distance of its points from the origin where that is more): far above round-off, so that a line along a wall's
/// surface (a source on a floor) counts as outside wherever it lies, and far below any particle.
const DEPTH_TOLERANCE: f64 = 1e-9;

/// A source's or inlet's line of which a share lies inside walls or outside the domain.
pub(crate) struct CoveredLine {
    /// The field that places the line: `sources[0].position_m` or `inlets[1].from_m`.
    pub field: String,
    /// What the line is, in words: "drop line" or "segment".
    pub what: &'static str,
    /// The share of the line inside walls or outside the domain, in (0, 1].
    pub share: f64,
    /// Where those parts lie, in words (``inside `walls[0]` ``, ``outside `run.domain` ``), with their shares, the
    /// largest first.
    pub places: Vec<(String, f64)>,
}

impl CoveredLine {
    /// The refusal of a line wholly inside walls.
    pub fn error(&self) -> SceneError {
        SceneError::value(
            &self.field,
            format!("its {} lies entirely {}: it could feed no particle", self.what, self.place_list()),
        )
        .with_label("no particle can stay there")
        .with_help("move it into the open space the walls enclose, inside `run.domain` where the scene has one")
    }

    /// The warning for a line partly inside walls (without the location, which the caller adds).
    pub fn warning(&self) -> String {
        format!(
            "{} % of its {} lies {}: only the rest feeds particles into the run",
            percent(self.share),
            self.what,
            self.place_list()
        )
    }

    /// The places in words: ``inside `walls[0]` ``, or with their shares where there are several.
    fn place_list(&self) -> String {
        match self.places.as_slice() {
            [(place, _)] => place.clone(),
            places => {
                let parts: Vec<String> =
                    places.iter().map(|(place, share)| format!("{place} ({} %)", percent(*share))).collect();
                parts.join(", ")
            }
        }
    }
}

/// A share as a percentage with one decimal.
fn percent(share: f64) -> String {
    number((share * 1000.0).round() / 10.0)
}

/// The sources' drop lines (those at an absolute height) and the inlets' segments of `scene` that lie partly or
/// wholly inside the static walls among `walls` or outside `run.domain`, in scene order.
pub(crate) fn covered_lines(scene: &Scene, walls: &[PlacedWall]) -> Vec<CoveredLine> {
    let solids: Vec<(Vec<DVec2>, &PlacedWall)> = walls
        .iter()
        .filter(|w| w.motion.is_static())
        .map(|w| (w.shape.body_points().iter().map(|v| w.pose.apply(*v)).collect(), w))
        .collect();
    let domain = scene.run.domain.map(|d| d.aabb());
    // Where a point lies that no particle can stay at: inside a wall, or beyond the domain's sides by more than the
    // tolerance (a line along a side counts as inside, as a centre on it does for the engine).
    let place = |point: DVec2, tolerance: f64| {
        let wall = solids.iter().find(|(points, w)| {
            shape_view(w.shape.kind(), points, w.shape.radius() * w.pose.scale).depth_of(point) > tolerance
        });
        match (wall, domain) {
            (Some((_, w)), _) => Some(format!("inside `{}`", w.path)),
            (None, Some(domain)) => (beyond(domain, point) > tolerance).then(|| "outside `run.domain`".to_string()),
            (None, None) => None,
        }
    };
    let cover = |from: DVec2, to: DVec2, field: String, what: &'static str| {
        let tolerance = DEPTH_TOLERANCE * line_size(from, to);
        let mut places: Vec<(String, usize)> = Vec::new();
        for point in samples(from, to) {
            if let Some(place) = place(point, tolerance) {
                match places.iter_mut().find(|(known, _)| *known == place) {
                    Some((_, count)) => *count += 1,
                    None => places.push((place, 1)),
                }
            }
        }
        let covered: usize = places.iter().map(|(_, count)| count).sum();
        places.sort_by_key(|(_, count)| std::cmp::Reverse(*count));
        let places = places.into_iter().map(|(place, count)| (place, count as f64 / SAMPLES as f64)).collect();
        (covered > 0).then(|| CoveredLine { field, what, share: covered as f64 / SAMPLES as f64, places })
    };
    let sources =
        scene.sources.iter().enumerate().filter(|(_, s)| s.height == DropHeight::Absolute).filter_map(|(i, source)| {
            let centre = DVec2::from_array(source.position_m);
            let half = DVec2::new(0.5 * source.width_m, 0.0);
            cover(centre - half, centre + half, field_path(&format!("sources[{i}]"), "position_m"), "drop line")
        });
    let inlets = scene.inlets.iter().enumerate().filter_map(|(i, inlet)| {
        let (from, to) = (DVec2::from_array(inlet.from_m), DVec2::from_array(inlet.to_m));
        cover(from, to, field_path(&format!("inlets[{i}]"), "from_m"), "segment")
    });
    sources.chain(inlets).collect()
}

/// The outlets of `scene` whose segment lies wholly outside `run.domain` (each sampled as the feed lines are): the
/// domain removes every particle before it could cross such an outlet, which then counts nothing. Their fields
/// (`outlets[0].from_m`), in scene order.
pub(crate) fn outlets_outside_domain(scene: &Scene) -> Vec<String> {
    let Some(domain) = scene.run.domain.map(|d| d.aabb()) else { return Vec::new() };
    outlet_fields(scene, |from, to| {
        let tolerance = DEPTH_TOLERANCE * line_size(from, to);
        samples(from, to).all(|point| beyond(domain, point) > tolerance)
    })
}

/// The outlets of `scene` that every inlet lies behind: each inlet's middle is strictly on the outlet's outer side
/// (its right, from `from_m` to `to_m`; the domain is on the left), so the particles fed reach the outlet crossing
/// inward and it removes none: almost always `from_m` and `to_m` swapped. Their fields (`outlets[0].from_m`), in
/// scene order; none in a scene without inlets.
pub(crate) fn reversed_outlets(scene: &Scene) -> Vec<String> {
    if scene.inlets.is_empty() {
        return Vec::new();
    }
    let behind = |from: DVec2, to: DVec2, point: DVec2| (to - from).perp().dot(point - from) < 0.0;
    outlet_fields(scene, |from, to| {
        scene.inlets.iter().all(|inlet| {
            let middle = DVec2::from_array(inlet.from_m).lerp(DVec2::from_array(inlet.to_m), 0.5);
            behind(from, to, middle)
        })
    })
}

/// The fields (`outlets[0].from_m`) of the outlets of `scene` whose segment, from its `from_m` to its `to_m`, is
/// `picked`, in scene order.
fn outlet_fields(scene: &Scene, picked: impl Fn(DVec2, DVec2) -> bool) -> Vec<String> {
    scene
        .outlets
        .iter()
        .enumerate()
        .filter(|(_, outlet)| picked(DVec2::from_array(outlet.from_m), DVec2::from_array(outlet.to_m)))
        .map(|(i, _)| field_path(&format!("outlets[{i}]"), "from_m"))
        .collect()
}

/// A line's size for the depth tolerance: its length, or the distance of its ends from the origin where that is more.
fn line_size(from: DVec2, to: DVec2) -> f64 {
    from.distance(to).max(from.abs().max_element()).max(to.abs().max_element())
}

/// The [`SAMPLES`] points of the line from `from` to `to`, at the middles of equal pieces.
fn samples(from: DVec2, to: DVec2) -> impl Iterator<Item = DVec2> {
    (0..SAMPLES).map(move |k| from.lerp(to, (k as f64 + 0.5) / SAMPLES as f64))
}

/// How far `point` lies beyond the sides of `domain`, m (negative inside).
fn beyond(domain: Aabb, point: DVec2) -> f64 {
    (domain.min - point).max(point - domain.max).max_element()
}
