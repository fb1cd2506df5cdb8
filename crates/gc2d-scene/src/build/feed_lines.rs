//! Feed lines inside walls: the drop line of a source (at an absolute height) and the segment of an inlet, where
//! they lie inside the solid of a wall that does not move. A particle is placed there only to overlap the wall, so
//! the source or inlet feeds only on the rest of its line, and nothing where all of it is inside: a line wholly inside
//! walls is refused, one partly inside is warned about.

use super::walls::PlacedWall;
use crate::checks::number;
use crate::error::SceneError;
use crate::schema::{DropHeight, Scene};
use crate::spans::field_path;
use gc2d_engine::shape_view;
use gc2d_geometry::DVec2;

/// Points sampled along each line, at the middles of equal pieces.
const SAMPLES: usize = 200;

/// How deep a point must lie inside a wall to count as inside, as a fraction of the line's size (its length, or the
/// distance of its points from the origin where that is more): far above round-off, so that a line along a wall's
/// surface (a source on a floor) counts as outside wherever it lies, and far below any particle.
const DEPTH_TOLERANCE: f64 = 1e-9;

/// A source's or inlet's line of which a share lies inside walls.
pub(crate) struct CoveredLine {
    /// The field that places the line: `sources[0].position_m` or `inlets[1].from_m`.
    pub field: String,
    /// What the line is, in words: "drop line" or "segment".
    pub what: &'static str,
    /// The share of the line inside walls, in (0, 1].
    pub share: f64,
    /// The wall entries that hold it, with their shares, the largest first.
    pub walls: Vec<(String, f64)>,
}

impl CoveredLine {
    /// The refusal of a line wholly inside walls.
    pub fn error(&self) -> SceneError {
        SceneError::value(
            &self.field,
            format!("its {} lies entirely inside {}: it could feed no particle", self.what, self.wall_list()),
        )
        .with_label("inside a wall")
        .with_help("move it into the open space the walls enclose")
    }

    /// The warning for a line partly inside walls (without the location, which the caller adds).
    pub fn warning(&self) -> String {
        format!(
            "{} % of its {} lies inside {}: particles are fed only on the rest",
            percent(self.share),
            self.what,
            self.wall_list()
        )
    }

    /// The walls in words: `` `walls[0]` ``, or with their shares where there are several.
    fn wall_list(&self) -> String {
        match self.walls.as_slice() {
            [(wall, _)] => format!("`{wall}`"),
            walls => {
                let parts: Vec<String> =
                    walls.iter().map(|(wall, share)| format!("`{wall}` ({} %)", percent(*share))).collect();
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
/// wholly inside the static walls among `walls`, in scene order.
pub(crate) fn covered_lines(scene: &Scene, walls: &[PlacedWall]) -> Vec<CoveredLine> {
    let solids: Vec<(Vec<DVec2>, &PlacedWall)> = walls
        .iter()
        .filter(|w| w.motion.is_static())
        .map(|w| (w.shape.body_points().iter().map(|v| w.pose.apply(*v)).collect(), w))
        .collect();
    let inside = |point: DVec2, tolerance: f64| {
        solids
            .iter()
            .find(|(points, w)| {
                shape_view(w.shape.kind(), points, w.shape.radius() * w.pose.scale).depth_of(point) > tolerance
            })
            .map(|(_, w)| w.path.as_str())
    };
    let cover = |from: DVec2, to: DVec2, field: String, what: &'static str| {
        let size = from.distance(to).max(from.abs().max_element()).max(to.abs().max_element());
        let mut walls: Vec<(&str, usize)> = Vec::new();
        for k in 0..SAMPLES {
            let point = from.lerp(to, (k as f64 + 0.5) / SAMPLES as f64);
            if let Some(wall) = inside(point, DEPTH_TOLERANCE * size) {
                match walls.iter_mut().find(|(path, _)| *path == wall) {
                    Some((_, count)) => *count += 1,
                    None => walls.push((wall, 1)),
                }
            }
        }
        let covered: usize = walls.iter().map(|(_, count)| count).sum();
        walls.sort_by_key(|(_, count)| std::cmp::Reverse(*count));
        let walls = walls.into_iter().map(|(wall, count)| (wall.to_owned(), count as f64 / SAMPLES as f64)).collect();
        (covered > 0).then(|| CoveredLine { field, what, share: covered as f64 / SAMPLES as f64, walls })
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
