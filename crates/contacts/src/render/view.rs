//! Choosing where to look from: perpendicular to the first contact normal, raised as little as
//! needed for the marked points to be seen.

use super::camera::WORLD_UP;
use super::world_mesh::WorldTriangle;
use glam::DVec3;

/// Elevations tried (degrees above the horizontal), lowest first: the picture is taken from the
/// lowest one (and the side) from which the most marked points are unoccluded.
const ELEVATIONS_DEG: [f64; 6] = [20.0, 30.0, 40.0, 50.0, 60.0, 70.0];

/// Occluders closer to a marked point than this fraction of the scene's size along the line of
/// sight are ignored: the point lies on (or within the band of) both objects' surfaces, and a
/// line of sight perpendicular to the contact normal grazes them.
const GRAZING_FRACTION: f64 = 0.05;

/// The viewing direction (unit, world frame, from the viewer into the scene).
///
/// The horizontal base direction is perpendicular to `normal` (the first contact's) and, when
/// there are several marked points, to the line from the first to the farthest one, so the
/// contacts appear side by side; without a normal it is world +y. Its sign is fixed by a
/// deterministic rule (positive y, else x, else z). It is then tilted down by each of
/// [`ELEVATIONS_DEG`] on both sides, and the first direction that sees the most `points` past
/// the `triangles` wins. `size` (mm) is the scene's diameter.
pub(crate) fn choose_forward(
    normal: Option<DVec3>,
    points: &[DVec3],
    triangles: &[WorldTriangle],
    size: f64,
) -> DVec3 {
    let base = normal.map_or(DVec3::Y, |n| base_direction(n, points));
    let grazing = GRAZING_FRACTION * size;
    let mut best: Option<(usize, DVec3)> = None;
    for degrees in ELEVATIONS_DEG {
        for side in [base, -base] {
            let forward = elevated(side, degrees);
            let seen = points
                .iter()
                .filter(|&&p| !occluded(p, -forward, triangles, grazing))
                .count();
            if seen == points.len() {
                return forward;
            }
            if best.is_none_or(|(most, _)| seen > most) {
                best = Some((seen, forward));
            }
        }
    }
    best.map_or(base, |(_, forward)| forward)
}

/// A unit direction perpendicular to `normal`, and to the spread of `points` when they spread.
fn base_direction(normal: DVec3, points: &[DVec3]) -> DVec3 {
    let spread = points.first().and_then(|&p0| {
        points
            .iter()
            .map(|&p| p - p0)
            .max_by(|a, b| a.length_squared().total_cmp(&b.length_squared()))
    });
    let direction = spread
        .and_then(|s| normal.cross(s).try_normalize())
        .or_else(|| normal.cross(WORLD_UP).try_normalize())
        .or_else(|| normal.cross(DVec3::X).try_normalize())
        .unwrap_or(DVec3::Y);
    let key = [direction.y, direction.x, direction.z]
        .into_iter()
        .find(|c| c.abs() > 1e-9)
        .unwrap_or(1.0);
    if key < 0.0 { -direction } else { direction }
}

/// `direction`'s horizontal part tilted down by `degrees` (looking down on the scene);
/// a vertical `direction` is returned as is.
fn elevated(direction: DVec3, degrees: f64) -> DVec3 {
    let horizontal = direction - direction.dot(WORLD_UP) * WORLD_UP;
    match horizontal.try_normalize() {
        Some(h) => {
            let (sin, cos) = degrees.to_radians().sin_cos();
            (cos * h - sin * WORLD_UP).normalize()
        }
        None => direction,
    }
}

/// Whether the ray from `p` along unit `towards_viewer` hits a triangle farther than `grazing`.
fn occluded(p: DVec3, towards_viewer: DVec3, triangles: &[WorldTriangle], grazing: f64) -> bool {
    triangles
        .iter()
        .any(|t| ray_hit(p, towards_viewer, &t.corners).is_some_and(|d| d > grazing))
}

/// Möller–Trumbore: the distance along unit `dir` from `origin` to the triangle, if the ray
/// meets it (edge-on triangles are missed).
fn ray_hit(origin: DVec3, dir: DVec3, [a, b, c]: &[DVec3; 3]) -> Option<f64> {
    let (e1, e2) = (*b - *a, *c - *a);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-12 * e1.length_squared().max(e2.length_squared()) {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - *a;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t > 0.0).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_meets_triangle_at_closed_form_distance() {
        let tri = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let origin = DVec3::new(0.25, 0.25, -3.0);
        assert_eq!(ray_hit(origin, DVec3::Z, &tri), Some(3.0));
        assert_eq!(ray_hit(origin, -DVec3::Z, &tri), None);
        assert_eq!(ray_hit(DVec3::new(0.75, 0.75, -3.0), DVec3::Z, &tri), None);
    }

    #[test]
    fn base_direction_is_perpendicular_to_normal_and_spread() {
        let n = DVec3::new(0.876, 0.0, 0.482).normalize();
        let points = [DVec3::new(15.0, 0.0, 44.0), DVec3::new(34.0, 0.0, 10.0)];
        let d = base_direction(n, &points);
        assert!(d.dot(n).abs() < 1e-12);
        assert!(d.dot(points[1] - points[0]).abs() < 1e-12);
        assert!((d - DVec3::Y).length() < 1e-12, "{d}");
    }

    #[test]
    fn elevation_tilts_down_by_the_angle() {
        let f = elevated(DVec3::Y, 30.0);
        assert!((f.dot(-WORLD_UP) - 0.5).abs() < 1e-12);
        assert!((f.length() - 1.0).abs() < 1e-12);
    }
}
