//! Concave pairs: the seeds both triangle paths give (normal-cone patch pairs; connected
//! collision regions between a proxy mesh and the other mesh), against closed forms.

mod common;

use common::*;
use geom_param::{ComponentKind, DQuat, DVec3, ObjectModel, Seed};
use mesh_narrowphase::{ContactBand, MeshScratch, MeshVerdict};

const TOL: f64 = 0.02;

fn band() -> ContactBand {
    ContactBand {
        margin: 0.5,
        delta1: -0.05,
        delta2: 0.3,
    }
}

/// The seed's points are where its locations say: the exact point at the location is within the
/// mesh's chordal error of the mesh point (checks the parameter interpolation, seams included).
fn check_locations(seed: &Seed, a: &ObjectModel, b: &ObjectModel) {
    for (side, object) in [(&seed.a, a), (&seed.b, b)] {
        let exact = object.solid.point_at(&side.location);
        let err = object.mesh(side.component).chordal_error;
        assert!(
            exact.distance(side.local_point) <= err + 1e-9,
            "location {:?} is at {exact}, {} from the seed point {} (chordal error {err})",
            side.location,
            exact.distance(side.local_point),
            side.local_point
        );
    }
}

/// A seed point against the closed-form contact point `exact` with contact normal `normal`.
/// Along the normal it must be within the chordal tolerance. Along the surface a mesh cannot
/// place a contact better than the band where the exact gap is within the two meshes' errors
/// (2 TOL) of its minimum: for a relative radius of curvature `rho` (mm) that is
/// sqrt(2 rho 2 TOL).
fn check_contact_point(got: DVec3, exact: DVec3, normal: DVec3, rho: f64, what: &str) {
    let e = got - exact;
    let along = e.dot(normal).abs();
    let across = (e - normal * e.dot(normal)).length();
    println!("{what}: normal error {along:.2e}, tangential error {across:.2e}");
    assert!(
        along <= TOL,
        "{what}: {got} is {along} from {exact} along the normal"
    );
    let bound = (4.0 * rho * TOL).sqrt();
    assert!(
        across <= bound,
        "{what}: {got} is {across} > {bound} from {exact} across the normal"
    );
}

#[test]
fn sphere_resting_in_spherical_bowl_gives_one_region() {
    // Bowl: inner sphere R = 30 about (0, 0, 40), its bottom at z = 10. Ball r = 10 with its
    // centre on the axis at z = 20 + gap: closest points (0, 0, 10) and the ball's bottom, gap
    // apart.
    let bowl = Prepared::new(socket(30.0, 35.0, 40.0, TOL));
    let ball = Prepared::new(sphere(10.0, TOL));
    let inner = components_of(&bowl.object, ComponentKind::Concave);
    let outer = components_of(&bowl.object, ComponentKind::Convex);
    assert_eq!((inner.len(), outer.len()), (1, 1));
    let ball_c = ball.object.components[0].id;
    let mut scratch = MeshScratch::default();
    for (path, gap) in PATHS.into_iter().flat_map(|p| [(p, 0.05), (p, 0.2)]) {
        let pose = pose(DQuat::IDENTITY, DVec3::new(0.0, 0.0, 20.0 + gap));
        let (verdict, out) = query_path(
            path,
            (&bowl, inner[0]),
            (&ball, ball_c),
            &pose,
            &band(),
            &mut scratch,
        );
        assert_eq!(verdict, MeshVerdict::Seeds, "{path:?} gap {gap}");
        assert_eq!(out.stats.regions, 1);
        assert_eq!(out.seeds.len(), 1);
        let seed = out.seeds[0];
        // Relative radius of curvature of ball (10) in bowl (30): 1 / (1/10 - 1/30) = 15.
        let rho = 15.0;
        check_contact_point(
            seed.a.local_point,
            DVec3::new(0.0, 0.0, 10.0),
            DVec3::Z,
            rho,
            "bowl",
        );
        check_contact_point(
            seed.b.local_point,
            DVec3::new(0.0, 0.0, -10.0),
            DVec3::Z,
            rho,
            "ball",
        );
        check_locations(&seed, &bowl.object, &ball.object);

        // The outer (convex) component's hull contains the cavity and the ball, but its surface
        // is at least 5 mm away: GJK sees overlapping hulls, the triangle path says separated.
        let (verdict, out) = query_path(
            path,
            (&bowl, outer[0]),
            (&ball, ball_c),
            &pose,
            &band(),
            &mut scratch,
        );
        assert_eq!(verdict, MeshVerdict::Separated);
        assert!(out.stats.convex_fallback);
    }
}

#[test]
fn cylinder_lying_across_torus_gives_two_regions() {
    // Torus rc = 20, a = 5 (one concave component). Cylinder r = 4, length 80, turned to lie
    // along x, its lowest line at z = a + gap over the ring: contacts at (±20, 0, 5) on the torus
    // and (±20, 0, 5 + gap) on the cylinder.
    let ring = Prepared::new(torus(20.0, 5.0, TOL));
    let rod = Prepared::new(cylinder(4.0, 80.0, TOL));
    assert_eq!(ring.object.components.len(), 1);
    assert_eq!(ring.object.components[0].kind, ComponentKind::Concave);
    let (cr, cc) = (ring.object.components[0].id, rod.object.components[0].id);
    let gap = 0.1;
    let rotation = DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2);
    let pose = pose(rotation, DVec3::new(-40.0, 0.0, 5.0 + gap + 4.0));
    let mut scratch = MeshScratch::default();
    for path in PATHS {
        let (verdict, out) =
            query_path(path, (&ring, cr), (&rod, cc), &pose, &band(), &mut scratch);
        assert_eq!(verdict, MeshVerdict::Seeds);
        assert_eq!(out.stats.regions, 2);
        assert_eq!(out.seeds.len(), 2);
        let inverse = pose.inverse();
        for x in [20.0, -20.0] {
            let on_ring = DVec3::new(x, 0.0, 5.0);
            let on_rod = inverse * DVec3::new(x, 0.0, 5.0 + gap);
            let seed = out
                .seeds
                .iter()
                .find(|s| s.a.local_point.x * x > 0.0)
                .unwrap_or_else(|| panic!("no seed near x = {x}: {:?}", out.seeds));
            // Relative radii of curvature: 5 along the rod (the tube's radius), 4 across it (the
            // rod's radius; the ring's top is flat that way).
            check_contact_point(seed.a.local_point, on_ring, DVec3::Z, 5.0, "ring");
            let normal_b = inverse.rotation * DVec3::Z;
            check_contact_point(seed.b.local_point, on_rod, normal_b, 5.0, "rod");
            check_locations(seed, &ring.object, &rod.object);
        }
    }
}
