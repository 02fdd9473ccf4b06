//! The meridians of face sides collapsed into vertices ([`Solid::pole_meridians`]) against
//! closed forms: a sphere's poles (a tangent plane) and a cone's apex (a circular cone of
//! directions).

use geom_param::{
    DVec3, MeshOptions, ObjectModel, POLE_MERIDIANS, ParamSide, Profile, SegmentSpec, Solid,
    VertexId,
};

fn revolved(specs: &[SegmentSpec]) -> Solid {
    let profile = Profile::new(specs).expect("valid profile");
    let chordal = 0.05 * profile.scale();
    ObjectModel::from_profile(
        "test",
        profile,
        &MeshOptions {
            chordal_tolerance: chordal,
        },
    )
    .expect("model")
    .solid
}

/// The vertex at `point` (to rounding).
fn vertex_at(solid: &Solid, point: [f64; 3]) -> VertexId {
    let k = solid
        .vertices
        .iter()
        .position(|v| v.point.distance(point.into()) < 1e-12)
        .expect("a vertex there");
    VertexId(k as u32)
}

#[test]
fn a_sphere_pole_is_left_along_its_tangent_plane_in_every_direction() {
    let r = 7.0;
    let sphere = revolved(&[SegmentSpec::Arc {
        center: [0.0, 0.0],
        from: [0.0, -r],
        to: [0.0, r],
        ccw: true,
    }]);
    for (z, side) in [(-r, ParamSide::VMin), (r, ParamSide::VMax)] {
        let pole = vertex_at(&sphere, [0.0, 0.0, z]);
        let all: Vec<_> = sphere.pole_meridians(pole).collect();
        assert_eq!(all.len(), 1, "one face collapses into each pole");
        let m = all[0];
        assert_eq!((m.vertex, m.side), (pole, side));
        for k in 0..POLE_MERIDIANS {
            let longitude = std::f64::consts::TAU * k as f64 / POLE_MERIDIANS as f64;
            assert!((m.at[k] - longitude).abs() < 1e-15, "{k}: {}", m.at[k]);
            let t = m.tangents[k].normalize();
            // Into the face: along the longitude's meridian, horizontal at the pole.
            let expected = [longitude.cos(), longitude.sin(), 0.0].into();
            assert!(t.distance(expected) < 1e-12, "{k}: {t} against {expected}");
            let o = m.opposite[k].normalize();
            assert!((t + o).length() < 1e-12, "{k}: a smooth pole, {t} and {o}");
        }
    }
}

#[test]
fn a_cone_apex_is_left_down_its_generators() {
    let (radius, height) = (3.0, 4.0);
    let cone = revolved(&[
        SegmentSpec::Line {
            from: [0.0, 0.0],
            to: [radius, 0.0],
        },
        SegmentSpec::Line {
            from: [radius, 0.0],
            to: [0.0, height],
        },
    ]);
    let apex = vertex_at(&cone, [0.0, 0.0, height]);
    let all: Vec<_> = cone.pole_meridians(apex).collect();
    assert_eq!(all.len(), 1, "the mantle collapses into the apex");
    let m = all[0];
    for k in 0..POLE_MERIDIANS {
        let longitude = m.at[k];
        let t = m.tangents[k].normalize();
        // From the apex to the base circle's point at that longitude: (r cos, r sin, -h) / 5.
        let expected =
            DVec3::new(radius * longitude.cos(), radius * longitude.sin(), -height) / 5.0;
        assert!(t.distance(expected) < 1e-12, "{k}: {t} against {expected}");
        let o = m.opposite[k].normalize();
        assert!(
            (t + o).length() > 1.0,
            "{k}: an apex is no tangent plane: {t} and {o}"
        );
    }
    // The base disk collapses into its centre, and is left within its plane.
    let centre = vertex_at(&cone, [0.0, 0.0, 0.0]);
    for m in cone.pole_meridians(centre) {
        for t in m.tangents {
            assert!(
                t.z.abs() < 1e-12,
                "the base disk is left within its plane: {t}"
            );
        }
    }
}
