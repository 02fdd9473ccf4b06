//! [`ContainmentGrid`]: a grid over a trim's parameter box whose cells lie clear of every
//! polyline, each remembering its side of the trim and how far it is clear, so that
//! [`crate::Trim::contains`] answers a point in such a cell with one lookup.
//!
//! Why: a Newton run on a trimmed face asks whether its point is still on the face at every
//! step, and the full test (a nearest polyline point within the boundary band, then the
//! winding number of every loop) was a quarter of a STEP pair's query (base-interface,
//! cascade) and of a loft on a tube.

use glam::DVec2;

/// About how many cells a grid has (their sides are chosen square, so the count varies with
/// the box's aspect).
const TARGET_CELLS: f64 = 1024.0;

/// A grid of cells over the box of a trim's polylines. A cell's clearance is a lower bound on
/// the distance (parameter units) from every point of the cell to every polyline segment,
/// closing segments included; no segment crosses such a cell, so the winding number is the
/// same all over it.
#[derive(Debug)]
pub(crate) struct ContainmentGrid {
    /// The lower corner of cell (0, 0).
    origin: DVec2,
    /// The sides of a cell (u, v).
    cell: DVec2,
    columns: usize,
    rows: usize,
    /// Per cell, row by row: its clearance, positive where the winding number is non-zero
    /// (inside the trim), negated where it is zero; 0 where a polyline comes within the
    /// cell's half diagonal of its centre. Rounded down to `f32`, so still a lower bound.
    clearance: Vec<f32>,
}

impl ContainmentGrid {
    /// A grid over the box `(lo, hi)`, from the distance of a point to the polylines (every
    /// segment, closing segments included) and whether the winding number there is non-zero.
    /// `None` for a box without area (nothing to classify).
    pub(crate) fn new(
        (lo, hi): (DVec2, DVec2),
        distance: impl Fn(DVec2) -> f64,
        inside: impl Fn(DVec2) -> bool,
    ) -> Option<Self> {
        let size = hi - lo;
        if !(size.x > 0.0 && size.y > 0.0 && size.is_finite()) {
            return None;
        }
        let side = (size.x * size.y / TARGET_CELLS).sqrt();
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let count = |extent: f64| ((extent / side).ceil() as usize).clamp(1, 4 * 1024);
        let (columns, rows) = (count(size.x), count(size.y));
        #[allow(clippy::cast_precision_loss)]
        let cell = size / DVec2::new(columns as f64, rows as f64);
        let half_diagonal = 0.5 * cell.length();
        // Far more than the rounding of a computed distance (a few ε of the coordinates) and
        // of a point's cell index.
        let slack = 1e-9 * (size.max_element() + lo.abs().max(hi.abs()).max_element());
        let mut clearance = Vec::with_capacity(columns * rows);
        for row in 0..rows {
            for column in 0..columns {
                #[allow(clippy::cast_precision_loss)]
                let centre = lo + cell * DVec2::new(column as f64 + 0.5, row as f64 + 0.5);
                let clear = distance(centre) - half_diagonal - slack;
                let value = if clear > 0.0 && clear.is_finite() {
                    // `as` rounds to nearest (and overflows to ∞); scaled down and capped
                    // first, the result stays below.
                    #[allow(clippy::cast_possible_truncation)]
                    let down = (clear * (1.0 - 1e-6)).min(f64::from(f32::MAX)) as f32;
                    if inside(centre) { down } else { -down }
                } else {
                    0.0
                };
                clearance.push(value);
            }
        }
        Some(Self {
            origin: lo,
            cell,
            columns,
            rows,
            clearance,
        })
    }

    /// Whether `uv` lies inside the trim (the winding number non-zero) when its cell is clear
    /// of every polyline by more than `limit`; `None` when it is not (or `uv` lies outside the
    /// grid or is not finite).
    pub(crate) fn side(&self, uv: DVec2, limit: f64) -> Option<bool> {
        let index = (uv - self.origin) / self.cell;
        if !(index.x >= 0.0 && index.y >= 0.0) {
            return None;
        }
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let (column, row) = (index.x as usize, index.y as usize);
        if column >= self.columns || row >= self.rows {
            return None;
        }
        let clearance = self.clearance[row * self.columns + column];
        (f64::from(clearance.abs()) > limit).then_some(clearance > 0.0)
    }
}
