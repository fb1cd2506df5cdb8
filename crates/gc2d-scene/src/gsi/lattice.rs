//! Where a GENERATE_BLOCK puts its particles (reference §9.7, Abb. B.6): the lattice sites inside X_RANGE × Y_RANGE.
//!
//! Rows start at the lower edge of the range and are Δy apart; sites in a row start at the left edge and are Δx apart.
//! FCC shifts every other row (the 2nd, 4th, …) right by Δx/2. A site on the upper or right edge (to 1e-9 of a
//! spacing, against round-off in the range) is included. The *_GAUSS and *_EQUAL grids scatter the centroids about
//! these sites when the particles are made; the sites themselves are the same.

use gc2d_geometry::DVec2;

use super::scene::GsiBlock;

/// Largest number of sites a block may have. Ten million particles is far beyond any gc2d scene; the limit stops a
/// mistyped spacing from allocating gigabytes.
pub const MAX_GRID_SITES: f64 = 1e7;

/// Round-off allowance when counting sites up to the edge of the range, in units of the spacing.
const EDGE_TOLERANCE: f64 = 1e-9;

impl GsiBlock {
    /// Number of rows of sites.
    pub fn row_count(&self) -> usize {
        let range = self.y_range.value;
        count_along(range.max - range.min, self.grid_distance.value.y)
    }

    /// Number of sites in row `row` (0-based).
    pub fn column_count(&self, row: usize) -> usize {
        let range = self.x_range.value;
        count_along(range.max - range.min - self.row_shift(row), self.grid_distance.value.x)
    }

    /// Total number of sites.
    pub fn site_count(&self) -> usize {
        let rows = self.row_count();
        let (even, odd) = (self.column_count(0), self.column_count(1));
        rows.div_ceil(2).saturating_mul(even).saturating_add((rows / 2).saturating_mul(odd))
    }

    /// The sites, row by row from the bottom, left to right.
    pub fn grid_sites(&self) -> Vec<DVec2> {
        let (x_min, y_min) = (self.x_range.value.min, self.y_range.value.min);
        let spacing = self.grid_distance.value;
        let mut sites = Vec::with_capacity(self.site_count().min(MAX_GRID_SITES as usize));
        for row in 0..self.row_count() {
            let y = y_min + row as f64 * spacing.y;
            let x0 = x_min + self.row_shift(row);
            sites.extend((0..self.column_count(row)).map(|column| DVec2::new(x0 + column as f64 * spacing.x, y)));
        }
        sites
    }

    /// Distance between the nearest two sites, or `None` for fewer than two sites.
    pub fn nearest_site_distance(&self) -> Option<f64> {
        let spacing = self.grid_distance.value;
        let rows = self.row_count();
        let mut candidates = Vec::with_capacity(3);
        if self.column_count(0) >= 2 || (rows >= 2 && self.column_count(1) >= 2) {
            candidates.push(spacing.x);
        }
        if self.grid_type.value.is_fcc() {
            if rows >= 2 && self.column_count(1) >= 1 {
                candidates.push(spacing.x.hypot(2.0 * spacing.y) / 2.0);
            }
            if rows >= 3 {
                candidates.push(2.0 * spacing.y);
            }
        } else if rows >= 2 {
            candidates.push(spacing.y);
        }
        candidates.into_iter().reduce(f64::min)
    }

    /// Checks that the lattice can be laid out: finite positive spacings and at most [`MAX_GRID_SITES`] sites.
    /// Returns the line to blame and the reason otherwise. (The reader admits only finite numbers.)
    pub(super) fn check_grid(&self) -> Result<(), (usize, String)> {
        let spacing = self.grid_distance.value;
        if !(spacing.x.is_finite() && spacing.y.is_finite() && spacing.x > 0.0 && spacing.y > 0.0) {
            let reason =
                format!("GRID_DISTANCE must be two finite positive spacings, found {} {}", spacing.x, spacing.y);
            return Err((self.grid_distance.line(), reason));
        }
        let x_span = (self.x_range.value.max - self.x_range.value.min).max(0.0);
        let y_span = (self.y_range.value.max - self.y_range.value.min).max(0.0);
        let estimate = (x_span / spacing.x + 1.0) * (y_span / spacing.y + 1.0);
        if estimate > MAX_GRID_SITES {
            let reason = format!("the grid would hold about {estimate:.3e} sites, more than {MAX_GRID_SITES:.0e}");
            return Err((self.grid_distance.line(), reason));
        }
        Ok(())
    }

    fn row_shift(&self, row: usize) -> f64 {
        if self.grid_type.value.is_fcc() && row % 2 == 1 { 0.5 * self.grid_distance.value.x } else { 0.0 }
    }
}

/// Sites at 0, s, 2s, … up to `span` (inclusive, to round-off); 0 for a negative span or a spacing that is not
/// finite and positive.
fn count_along(span: f64, spacing: f64) -> usize {
    if !(span >= 0.0 && spacing > 0.0 && span.is_finite() && spacing.is_finite()) {
        return 0;
    }
    let steps = (span / spacing + EDGE_TOLERANCE).floor();
    if steps < MAX_GRID_SITES { steps as usize + 1 } else { MAX_GRID_SITES as usize }
}
