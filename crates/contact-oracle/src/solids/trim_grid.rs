//! A grid over a trim's (u, v) box that answers containment away from the trim's boundary
//! without a nearest-point search: each cell that no polyline segment of the trim comes near
//! lies wholly on one side of the boundary, the side of its centre; only the cells along the
//! boundary classify the point itself ([`contains_near_boundary`]).

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
    /// (parameter units, at most [`GROW`] of the extent): by the cell away from the boundary,
    /// by [`contains_near_boundary`] in cells along it and for points outside the box.
    pub fn contains(&self, trim: &Trim, uv: DVec2, tolerance: f64) -> bool {
        match self.cell(uv) {
            Some(Region::Inside) => true,
            Some(Region::Outside) => false,
            _ => contains_near_boundary(trim, uv, tolerance),
        }
    }
}

/// Whether `uv` lies in the trimmed region, the boundary included within `tolerance`: as
/// [`Trim::contains`] (the side of the exact p-curve at the nearest boundary point, or the
/// polylines' winding number away from the boundary), except where the nearest boundary point
/// is a corner of a loop (the end of an entry). There the side of one entry's tangent does not
/// decide: a point just beyond an acute corner lies on the inner side of one entry's line and
/// outside the face. The corner's sector decides instead: with the tangents a_in arriving at
/// the corner and a_out leaving it, the point is inside when left of both lines at a left turn
/// (convex corner), left of either at a right turn (reflex corner).
pub(crate) fn contains_near_boundary(trim: &Trim, uv: DVec2, tolerance: f64) -> bool {
    let p = trim.unwrap(uv);
    let Some(near) = trim.nearest(p) else {
        return false;
    };
    if near.distance <= tolerance {
        return true;
    }
    let entries = &trim.loops[near.loop_index].entries;
    let entry = &entries[near.index];
    let range = entry.pcurve.domain();
    // Rounding of the nearest point's parameter at an end.
    let end = 1e-9 * range.span();
    let (at_min, at_max) = (near.t <= range.min + end, near.t >= range.max - end);
    if !(at_min || at_max) {
        return trim.contains(p, tolerance);
    }
    // The travel direction of an entry at parameter t (the loop's direction).
    let travel = |e: &geom_param::TrimEntry, t: f64| {
        let d1 = e.pcurve.eval(t).d1;
        if e.reversed { -d1 } else { d1 }
    };
    let n = entries.len();
    // The loop leaves this entry at t_max (t_min when reversed).
    let leaving = at_max != entry.reversed;
    let (a_in, a_out) = if leaving {
        let next = &entries[(near.index + 1) % n];
        let start = if next.reversed {
            next.pcurve.domain().max
        } else {
            next.pcurve.domain().min
        };
        (travel(entry, near.t), travel(next, start))
    } else {
        let previous = &entries[(near.index + n - 1) % n];
        let stop = if previous.reversed {
            previous.pcurve.domain().min
        } else {
            previous.pcurve.domain().max
        };
        (travel(previous, stop), travel(entry, near.t))
    };
    let v = p - near.point;
    let (left_in, left_out) = (a_in.perp_dot(v) > 0.0, a_out.perp_dot(v) > 0.0);
    let turn = a_in.perp_dot(a_out);
    if turn > 0.0 {
        left_in && left_out
    } else if turn < 0.0 {
        left_in || left_out
    } else {
        left_out
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
    } else if contains_near_boundary(trim, 0.5 * (lo + hi), 0.0) {
        Region::Inside
    } else {
        Region::Outside
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::closed_form::brep::{holed_plate, tetrahedron};
    use geom_param::DVec3;

    /// Around every corner of a tetrahedron's (trimmed) faces, points within 1e-4 of the
    /// face's extent are classified as the closed form says (barycentric coordinates of the
    /// surface point, all positive inside), acute corners included, where the side of one
    /// entry's tangent alone would call the points just beyond the corner inside.
    #[test]
    fn points_around_corners_are_classified_by_the_corner_sector() {
        let p = [
            DVec3::new(-8.0, -6.0, -4.0),
            DVec3::new(12.0, -3.0, -4.0),
            DVec3::new(-2.0, 11.0, -3.0),
            DVec3::new(1.0, 1.0, 10.0),
        ];
        let solid = tetrahedron(p).expect("builds");
        let mut acute_misread_by_tangent = 0;
        for face in &solid.faces {
            let trim = face.trim.as_ref().expect("trimmed");
            let grid = TrimGrid::new(trim);
            let corners: Vec<DVec2> = trim.loops[0].entries.iter().map(|e| e.start()).collect();
            let at = |uv: DVec2| face.surface.eval(uv.x, uv.y).point;
            let (a, b, c) = (at(corners[0]), at(corners[1]), at(corners[2]));
            let n = (b - a).cross(c - a);
            let inside = |q: DVec3| {
                [(a, b), (b, c), (c, a)]
                    .iter()
                    .all(|&(x, y)| (y - x).cross(q - x).dot(n) > 0.0)
            };
            for &corner in &corners {
                for k in 0..64 {
                    let angle = std::f64::consts::TAU * f64::from(k) / 64.0 + 0.01;
                    let uv = corner + 1e-4 * grid.extent * DVec2::from_angle(angle);
                    let truth = inside(at(uv));
                    assert_eq!(grid.contains(trim, uv, 0.0), truth, "{uv}");
                    if trim.contains(uv, 0.0) != truth {
                        acute_misread_by_tangent += 1;
                    }
                }
            }
        }
        // geom-param's `Trim::contains` decides corners by their sector too (it misread 70 of
        // these 768 points when it used one entry's tangent); the oracle keeps its own grid.
        assert_eq!(acute_misread_by_tangent, 0);
    }

    /// The grid agrees with the closed form of the plate's top face (outside the hole's
    /// circle, inside the square) and with the trim's own classifier at points on a fine
    /// lattice, boundary cells included.
    #[test]
    fn grid_containment_matches_the_closed_form() {
        let solid = holed_plate(40.0, 8.0, 6.0).expect("builds");
        // The top cap: the trimmed face above z = 0; its (u, v) is (x, y).
        let trim = solid
            .faces
            .iter()
            .filter_map(|f| f.trim.as_ref().map(|t| (f, t)))
            .find(|(f, t)| {
                let (lo, hi) = t.bounds();
                let mid = 0.5 * (lo + hi);
                f.surface.eval(mid.x, mid.y).point.z > 0.0
            })
            .map(|(_, t)| t)
            .expect("a top cap");
        let grid = TrimGrid::new(trim);
        let mut boundary_cells = 0;
        for cell in &grid.cells {
            boundary_cells += usize::from(*cell == Region::Boundary);
        }
        assert!(boundary_cells > 0 && boundary_cells < CELLS * CELLS / 2);
        for i in 0..=200 {
            for j in 0..=200 {
                let uv = DVec2::new(-21.0 + 0.21 * f64::from(i), -21.0 + 0.21 * f64::from(j));
                let (x, y) = (uv.x, uv.y);
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
