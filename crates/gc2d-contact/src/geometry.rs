//! The geometric description of one contact, as the narrowphase produces it (reference §2.4, Abb. 2.4).

use gc2d_geometry::DVec2;

/// Geometry of the overlap of bodies i and j at one instant.
///
/// The force acts at the contact point s, the midpoint of the contact line c1c2; the arms locate s relative to each
/// centre of mass. `normal` is the unit vector perpendicular to c1c2 pointing from j towards i, so the repulsive force
/// on i is along `+normal`; the tangent is `normal` turned counter-clockwise by 90° (decision D2 in `docs/model.md`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactGeometry {
    /// Overlap area A in m²; zero (or negative) when the bodies do not overlap.
    pub area: f64,
    /// Unit normal of the contact line, pointing from j to i.
    pub normal: DVec2,
    /// Length |c1c2| of the contact line in m.
    pub chord_length: f64,
    /// r_i = s − x_i: from i's centre of mass to the contact point, m.
    pub arm_i: DVec2,
    /// r_j = s − x_j: from j's centre of mass (for a wall: its reference point) to the contact point, m.
    pub arm_j: DVec2,
    /// Where the overlap's centroid projects on the contact line, measured from s along the tangent, m; 0 where it is
    /// not computed. Read only by the [`Winkler`](crate::AreaFormulation::Winkler) formulation.
    pub centroid_offset: f64,
    /// True where both outlines can present a straight edge at the contact, so that one can tilt against the other;
    /// false where one body is a disk, whose surface at the contact turns with the normal, not with its spin (a disk
    /// rolling on a face does not rock it). Read only by the [`Winkler`](crate::AreaFormulation::Winkler)
    /// formulation, whose couples act only on tilting contacts.
    pub rocking: bool,
}

impl ContactGeometry {
    /// A pair that does not overlap. Evaluating it ends a contact that was active.
    pub const SEPARATED: Self = Self {
        area: 0.0,
        normal: DVec2::Y,
        chord_length: 0.0,
        arm_i: DVec2::ZERO,
        arm_j: DVec2::ZERO,
        centroid_offset: 0.0,
        rocking: false,
    };

    /// Unit tangent n∥: the normal turned counter-clockwise by 90°, (−n_y, n_x).
    #[inline]
    pub fn tangent(&self) -> DVec2 {
        self.normal.perp()
    }

    /// True when the bodies overlap with a usable (finite) geometry. NaN or infinite input counts as no overlap,
    /// so bad geometry produces no force rather than a NaN. The finiteness tests are combined without early exits
    /// (`&`), which the processor need not foresee branch by branch.
    #[inline]
    pub fn is_overlapping(&self) -> bool {
        self.area > 0.0
            && (self.area.is_finite()
                & self.chord_length.is_finite()
                & self.normal.is_finite()
                & self.arm_i.is_finite()
                & self.arm_j.is_finite()
                & self.centroid_offset.is_finite())
    }
}
