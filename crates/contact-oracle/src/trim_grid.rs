//! A grid over a trim's (u, v) box that answers containment away from the trim's boundary
//! without a nearest-point search: each cell that no polyline segment of the trim comes near
//! lies wholly on one side of the boundary, the side of its centre; only the cells along the
//! boundary ask the trim itself ([`Trim::contains`]).

use geom_param::Trim;
use glam::DVec2;

/// Cells per side of the grid.
const CELLS: usize = 32;
/// A cell counts as near the boundary when a polyline segment's box meets the cell grown by
/// this fraction of the trim's extent: far more than the polylines' deviation from the exact
/// p-curves (1e-4 of a loop's extent), so a far cell holds no point of the exact boundary.
const GROW: f64 = 1e-3;

/// Where a cell (or a patch of (u, v)) lies with respect to a trim.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Region {
    /// Every point inside.
    Inside,
    /// Every point outside.
    Outside,
    /// Near the boundary: each point must be classified.
    Boundary,
}

/// The classified grid of one trim.
#[derive(Clone, Debug)]
pub(crate) struct TrimGrid {
    lo: DVec2,
    hi: DVec2,
    periods: [f64; 2],
    /// Largest side of the box (parameter units).
    pub extent: f64,
    cells: Vec<Region>,
}

impl TrimGrid {
    /// Classifies the cells of `trim`'s box.
    pub fn new(trim: &Trim) -> Self {
        let (lo, hi) = trim.bounds();
        let extent = (hi - lo).max_element();
        let mut grid = Self {
            lo,
            hi,
            periods: trim.periods,
            extent,
            cells: Vec::with_capacity(CELLS * CELLS),
        };
        let size = (hi - lo) / CELLS as f64;
        for j in 0..CELLS {
            for i in 0..CELLS {
                let a = lo + size * DVec2::new(i as f64, j as f64);
                grid.cells.push(classify(trim, extent, a, a + size));
            }
        }
        grid
    }

    /// The cell holding `uv` (unwrapped by whole periods next to the box), `None` outside
    /// the box.
    fn cell(&self, uv: DVec2) -> Option<Region> {
        let mid = 0.5 * (self.lo + self.hi);
        let mut p = uv;
        for k in 0..2 {
            let period = self.periods[k];
            if period > 0.0 {
                p[k] = uv[k] - period * ((uv[k] - mid[k]) / period).round();
            }
        }
        let f = (p - self.lo) / (self.hi - self.lo) * CELLS as f64;
        if !(f.x >= 0.0 && f.y >= 0.0 && f.x < CELLS as f64 && f.y < CELLS as f64) {
            return None;
        }
        Some(self.cells[f.y as usize * CELLS + f.x as usize])
    }

    /// Whether `uv` lies in the trimmed region, the boundary included within `tolerance`
    /// (parameter units, at most [`GROW`] of the extent): as [`Trim::contains`], asked only
    /// in cells along the boundary and for points outside the box.
    pub fn contains(&self, trim: &Trim, uv: DVec2, tolerance: f64) -> bool {
        match self.cell(uv) {
            Some(Region::Inside) => true,
            Some(Region::Outside) => false,
            _ => trim.contains(uv, tolerance),
        }
    }
}

/// Where the (u, v) rectangle [lo, hi] lies with respect to `trim` (see the module docs).
pub(crate) fn classify(trim: &Trim, extent: f64, lo: DVec2, hi: DVec2) -> Region {
    let grow = GROW * extent;
    let (glo, ghi) = (lo - grow, hi + grow);
    let near = trim.loops.iter().any(|l| {
        l.segments().any(|(p, q)| {
            let (smin, smax) = (p.min(q), p.max(q));
            smin.x <= ghi.x && smax.x >= glo.x && smin.y <= ghi.y && smax.y >= glo.y
        })
    });
    if near {
        Region::Boundary
    } else if trim.contains(0.5 * (lo + hi), 0.0) {
        Region::Inside
    } else {
        Region::Outside
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::closed_form::brep::holed_plate;

    /// The grid agrees with the closed form of the plate's top face (outside the hole's
    /// circle, inside the square) and with the trim's own classifier at points on a fine
    /// lattice, boundary cells included.
    #[test]
    fn grid_containment_matches_the_closed_form() {
        let solid = holed_plate(40.0, 8.0, 6.0);
        let trim = solid.faces[1].trim.as_ref().expect("trimmed");
        let grid = TrimGrid::new(trim);
        let mut boundary_cells = 0;
        for cell in &grid.cells {
            boundary_cells += usize::from(*cell == Region::Boundary);
        }
        assert!(boundary_cells > 0 && boundary_cells < CELLS * CELLS / 2);
        // The top face's (u, v) is (x + 20, y + 20).
        for i in 0..=200 {
            for j in 0..=200 {
                let uv = DVec2::new(-1.0 + 0.21 * f64::from(i), -1.0 + 0.21 * f64::from(j));
                let (x, y) = (uv.x - 20.0, uv.y - 20.0);
                let rho = x.hypot(y);
                let truth = rho > 6.0 && x.abs() < 20.0 && y.abs() < 20.0;
                let clear = (rho - 6.0).abs() > 1e-9
                    && (x.abs() - 20.0).abs() > 1e-9
                    && (y.abs() - 20.0).abs() > 1e-9;
                if clear {
                    assert_eq!(grid.contains(trim, uv, 0.0), truth, "{uv}");
                }
                assert_eq!(grid.contains(trim, uv, 0.0), trim.contains(uv, 0.0), "{uv}");
            }
        }
    }
}
