//! Merging refined seeds that reached the same local minimum, or the same continuous contact.

use crate::report::Contact;
use geom_param::{DVec3, FaceId, FeatureId, Solid};

/// Largest angle (rad) between the normals of two representatives of one continuous contact:
/// its normal is exact (a flat face's, the common normal of parallel cylinders), so this only
/// absorbs rounding.
const CONTINUOUS_NORMAL_ANGLE: f64 = 1e-9;
/// Relative rounding of coordinates (16 ε).
const ROUNDING: f64 = 16.0 * f64::EPSILON;

/// Adds `candidate` to `contacts` unless one already there is the same minimum: both closest
/// points within `tolerance` (mm) of the candidate's and the same distance ([`same_distance`]);
/// or, when either is a continuous contact
/// ([`Contact::is_continuous`]), the same continuous region of the two solids `(a, b)`
/// ([`same_continuous_region`]). Of two duplicates the one with the smaller final gradient is
/// kept. Returns true when the candidate was merged away.
pub(crate) fn insert_or_merge(
    contacts: &mut Vec<Contact>,
    candidate: Contact,
    tolerance: f64,
    solids: (&Solid, &Solid),
) -> bool {
    let same = |c: &Contact| {
        if c.is_continuous() || candidate.is_continuous() {
            same_continuous_region(c, &candidate, solids)
        } else {
            c.point_a.distance(candidate.point_a) <= tolerance
                && c.point_b.distance(candidate.point_b) <= tolerance
                && same_distance(c, &candidate)
        }
    };
    match contacts.iter_mut().find(|c| same(c)) {
        Some(existing) => {
            if candidate.diagnostics.gradient_norm < existing.diagnostics.gradient_norm {
                *existing = candidate;
            }
            true
        }
        None => {
            contacts.push(candidate);
            false
        }
    }
}

/// Whether two contacts are at the same distance within the sum of their error estimates and
/// the rounding of their coordinates (mm).
///
/// Why: the point tolerance follows the point error estimate, which near a conformal touch is
/// large (0.13 mm for a goblet's wall touching a bowl's inside at 3.7e-10 mm, condition
/// 8e11), and it swallowed a separate minimum 12.6 mm away at 0.0225 mm, whose error estimate
/// is 3e-13 mm: one minimum's two refinements agree in distance even where their points
/// may not.
fn same_distance(x: &Contact, y: &Contact) -> bool {
    distances_agree(
        (x.distance, x.diagnostics.error_estimate),
        (y.distance, y.diagnostics.error_estimate),
        [x.point_a, x.point_b, y.point_a, y.point_b],
    )
}

/// Whether two distances (mm) with their error estimates (mm), `(distance, estimate)`, can be
/// one minimum's: apart by at most the sum of the estimates and the rounding of the largest of
/// `points`' coordinates (at least 1 mm).
pub(crate) fn distances_agree(
    (dx, ex): (f64, f64),
    (dy, ey): (f64, f64),
    points: [DVec3; 4],
) -> bool {
    (dx - dy).abs() <= agreement(ex + ey, points)
}

/// The sum of two error estimates (`estimates`, mm) and the rounding of the largest of
/// `points`' coordinates (at least 1 mm) (mm).
fn agreement(estimates: f64, points: [DVec3; 4]) -> f64 {
    let coordinates = points.iter().fold(1.0_f64, |m, p| m.max(p.length()));
    estimates + ROUNDING * coordinates
}

/// Whether two contacts, one of them continuous, are representatives of one continuous region
/// of the solids `(a, b)`: on each side on one face or its boundary (the same face, or its
/// edges and vertices: [`on_one_face`]), at the same distance (within the sum of their error
/// estimates and rounding), with the same normal (within [`CONTINUOUS_NORMAL_ANGLE`]), and
/// flat between them to first order (each side's two points at the same height along that
/// normal, within the same distance tolerance). A connected region of constant gap lies on
/// one face of each solid and its boundary (where a flat face meets a flat face, the overlap
/// reaches their rims and poles) with one normal. Two separate regions on the same pair of
/// faces at the same distance (a face touching another in two places, possible only where a
/// face is not convex) are merged too: the test does not look at the surfaces between them.
fn same_continuous_region(x: &Contact, y: &Contact, (a, b): (&Solid, &Solid)) -> bool {
    if !on_one_face(a, x.location_a.feature(), y.location_a.feature())
        || !on_one_face(b, x.location_b.feature(), y.location_b.feature())
    {
        return false;
    }
    let tolerance = agreement(
        x.diagnostics.error_estimate + y.diagnostics.error_estimate,
        [x.point_a, x.point_b, y.point_a, y.point_b],
    );
    (x.distance - y.distance).abs() <= tolerance
        && x.normal.angle_between(y.normal) <= CONTINUOUS_NORMAL_ANGLE
        && (y.point_a - x.point_a).dot(x.normal).abs() <= tolerance
        && (y.point_b - x.point_b).dot(x.normal).abs() <= tolerance
}

/// Whether features `x` and `y` of `solid` lie on one face's closure: equal, or some face
/// holds both (itself, an edge with a use on it, a vertex of it).
fn on_one_face(solid: &Solid, x: FeatureId, y: FeatureId) -> bool {
    if x == y {
        return true;
    }
    let holds = |face: FaceId, f: FeatureId| match f {
        FeatureId::Face(id) => id == face,
        FeatureId::Edge(id) => solid.face_edges(face).contains(&id),
        FeatureId::Vertex(id) => solid.face_vertices(face).contains(&id),
    };
    (0..solid.faces.len())
        .filter_map(|k| u32::try_from(k).ok().map(FaceId))
        .any(|face| holds(face, x) && holds(face, y))
}

#[cfg(test)]
mod tests {
    use super::*;
    use exact_refine::{RefineDiagnostics, RefineStatus};
    use geom_param::{EdgeId, FeatureLocation, rounded_box};
    use glam::DVec3;

    /// A rounded box (26 faces, each flat face bounded by edges it shares with its fillets),
    /// for both solids; `face` is a face, `rim` an edge on it, `far` a face sharing nothing
    /// with it.
    struct Boxes {
        solid: Solid,
        face: FaceId,
        rim: EdgeId,
        far: FaceId,
    }

    fn boxes() -> Boxes {
        let solid = rounded_box(DVec3::splat(10.0), 1.0).expect("box builds");
        let face = FaceId(0);
        let rim = solid.face_edges(face)[0];
        let far = (0..solid.faces.len())
            .filter_map(|k| u32::try_from(k).ok().map(FaceId))
            .find(|&f| {
                !solid
                    .face_vertices(f)
                    .iter()
                    .any(|v| solid.face_vertices(face).contains(v))
                    && !solid
                        .face_edges(f)
                        .iter()
                        .any(|e| solid.face_edges(face).contains(e))
            })
            .expect("a face away from face 0");
        Boxes {
            solid,
            face,
            rim,
            far,
        }
    }

    fn on_face(id: FaceId) -> FeatureLocation {
        FeatureLocation::Face { id, u: 0.5, v: 0.5 }
    }

    /// A contact of A's `location_a` and B's `location_b` at `point_a`, `distance` along
    /// `normal`.
    fn contact(
        point_a: DVec3,
        distance: f64,
        normal: DVec3,
        (location_a, location_b): (FeatureLocation, FeatureLocation),
        status: RefineStatus,
    ) -> Contact {
        let continuous = status == RefineStatus::ContinuousContact;
        Contact {
            point_a,
            point_b: point_a + normal * distance,
            distance,
            normal,
            location_a,
            location_b,
            diagnostics: RefineDiagnostics {
                iterations: 3,
                gradient_norm: 1e-15,
                condition: if continuous { f64::INFINITY } else { 10.0 },
                converged: true,
                is_local_minimum: true,
                error_estimate: 1e-13,
                point_error_estimate: if continuous { f64::INFINITY } else { 1e-12 },
                gap_curvature: if continuous { 0.0 } else { 0.1 },
                status,
            },
        }
    }

    const FLAT: RefineStatus = RefineStatus::ContinuousContact;

    /// Two seeds refined to two points of one flat-on-flat contact (gap 0.25 along z, 7 mm
    /// apart in the plane), one on B's face and one on its rim, and an isolated pair on the
    /// same faces at the same gap (a pole or a vertex of the flat face): one contact.
    #[test]
    fn points_of_one_flat_contact_are_one_contact() {
        let x = boxes();
        let solids = (&x.solid, &x.solid);
        let faces = (on_face(x.face), on_face(x.face));
        let mut contacts = vec![contact(
            DVec3::new(1.0, 0.5, 20.0),
            0.25,
            DVec3::Z,
            faces,
            FLAT,
        )];
        let on_rim = (on_face(x.face), FeatureLocation::Edge { id: x.rim, t: 0.3 });
        let candidates = [
            contact(DVec3::new(-4.0, 5.5, 20.0), 0.25, DVec3::Z, faces, FLAT),
            contact(DVec3::new(-4.0, 8.5, 20.0), 0.25, DVec3::Z, on_rim, FLAT),
            contact(
                DVec3::new(2.0, 2.0, 20.0),
                0.25,
                DVec3::Z,
                faces,
                RefineStatus::Converged,
            ),
        ];
        for candidate in candidates {
            assert!(insert_or_merge(&mut contacts, candidate, 1e-4, solids));
        }
        assert_eq!(contacts.len(), 1);
    }

    /// A flat contact and an isolated minimum elsewhere (other faces, another distance) stay
    /// two contacts, in either order (the continuous one's infinite point error used to merge
    /// anything into it).
    #[test]
    fn a_flat_contact_does_not_swallow_another_minimum() {
        let x = boxes();
        let solids = (&x.solid, &x.solid);
        let flat = contact(
            DVec3::new(1.0, 0.5, 20.0),
            0.25,
            DVec3::Z,
            (on_face(x.face), on_face(x.face)),
            FLAT,
        );
        let other = contact(
            DVec3::new(30.0, 0.0, 5.0),
            0.04,
            DVec3::X,
            (on_face(x.far), on_face(x.far)),
            RefineStatus::Converged,
        );
        for (first, second) in [(flat, other), (other, flat)] {
            let mut contacts = vec![first];
            assert!(!insert_or_merge(
                &mut contacts,
                second,
                f64::INFINITY,
                solids
            ));
            assert_eq!(contacts.len(), 2);
        }
    }

    /// Two flat contacts at the same distance and normal on faces of B that share nothing
    /// (two feet on one table) are two regions; on the same faces but at heights 1e-6 mm
    /// apart, or with normals 1e-6 rad apart, they are no single flat region either.
    #[test]
    fn separate_flat_regions_stay_apart() {
        let x = boxes();
        let solids = (&x.solid, &x.solid);
        let faces = (on_face(x.face), on_face(x.face));
        let base = contact(DVec3::new(1.0, 0.5, 20.0), 0.25, DVec3::Z, faces, FLAT);
        let other_foot = contact(
            DVec3::new(-9.0, 0.5, 20.0),
            0.25,
            DVec3::Z,
            (on_face(x.face), on_face(x.far)),
            FLAT,
        );
        let higher = contact(
            DVec3::new(-9.0, 0.5, 20.0 + 1e-6),
            0.25,
            DVec3::Z,
            faces,
            FLAT,
        );
        let tilted_normal = (DVec3::Z + DVec3::X * 1e-6).normalize();
        let tilted = contact(
            DVec3::new(-9.0, 0.5, 20.0),
            0.25,
            tilted_normal,
            faces,
            FLAT,
        );
        for candidate in [other_foot, higher, tilted] {
            let mut contacts = vec![base];
            assert!(!insert_or_merge(
                &mut contacts,
                candidate,
                f64::INFINITY,
                solids
            ));
            assert_eq!(contacts.len(), 2);
        }
    }

    /// Isolated minima merge by their points, as before.
    #[test]
    fn isolated_minima_merge_by_points() {
        let x = boxes();
        let solids = (&x.solid, &x.solid);
        let faces = (on_face(x.face), on_face(x.face));
        let c = contact(DVec3::ZERO, 0.05, DVec3::Z, faces, RefineStatus::Converged);
        let mut near = c;
        near.point_a += DVec3::X * 1e-5;
        near.point_b += DVec3::X * 1e-5;
        let mut contacts = vec![c];
        assert!(insert_or_merge(&mut contacts, near, 1e-4, solids));
        let mut far = c;
        far.point_a += DVec3::X * 1e-3;
        far.point_b += DVec3::X * 1e-3;
        assert!(!insert_or_merge(&mut contacts, far, 1e-4, solids));
        assert_eq!(contacts.len(), 2);
    }

    /// Points within a (large) merge tolerance but distances apart by more than the two error
    /// estimates are two minima, in either order; within the estimates, one.
    #[test]
    fn isolated_minima_at_other_distances_stay_apart() {
        let x = boxes();
        let solids = (&x.solid, &x.solid);
        let faces = (on_face(x.face), on_face(x.face));
        let mut touch = contact(DVec3::ZERO, 0.0, DVec3::Z, faces, RefineStatus::Converged);
        touch.diagnostics.error_estimate = 5e-5;
        let other = contact(
            DVec3::new(12.0, 0.0, 0.0),
            0.02,
            DVec3::Z,
            faces,
            RefineStatus::Converged,
        );
        for (first, second) in [(touch, other), (other, touch)] {
            let mut contacts = vec![first];
            assert!(!insert_or_merge(&mut contacts, second, 13.0, solids));
            assert_eq!(contacts.len(), 2);
        }
        let mut within = touch;
        within.distance = 4e-5;
        within.point_a += DVec3::X * 10.0;
        let mut contacts = vec![touch];
        assert!(insert_or_merge(&mut contacts, within, 13.0, solids));
        assert_eq!(contacts.len(), 1);
    }
}
