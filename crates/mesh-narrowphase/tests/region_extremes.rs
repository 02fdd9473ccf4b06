//! `collision_regions::region_extremes` on closed loops whose extent is known in closed form.

use glam::DVec3;
use mesh_narrowphase::triangles::collision_regions::{
    IntersectionSegment, RegionScratch, group_regions, region_centres, region_extremes,
};

/// A closed polygon of `n` segments through `points(i)`, i = 0..n, as one region's loop.
fn loop_segments(n: usize, points: impl Fn(usize) -> DVec3) -> Vec<IntersectionSegment> {
    (0..n)
        .map(|i| IntersectionSegment {
            a_triangle: i as u32,
            b_triangle: 0,
            start: points(i),
            end: points((i + 1) % n),
        })
        .collect()
}

/// Centres and extremes of the regions of `segments`.
fn extremes(segments: &[IntersectionSegment]) -> (Vec<DVec3>, Vec<(f64, [DVec3; 2])>) {
    let mut scratch = RegionScratch::default();
    let mut region_of = Vec::new();
    let regions = group_regions(segments, &mut scratch, &mut region_of);
    let mut centres = Vec::new();
    region_centres(segments, &region_of, regions, &mut scratch, &mut centres);
    let mut out = Vec::new();
    region_extremes(segments, &region_of, &centres, &mut scratch, &mut out);
    (centres, out)
}

#[test]
fn an_ellipse_has_its_major_axis_as_diameter() {
    // Semi-axes 3 (along x) and 1 (along y) about (10, -2, 5), in the plane z = 5; 64 vertices,
    // two of them on the major axis's ends (i = 0 and 32).
    let c = DVec3::new(10.0, -2.0, 5.0);
    let n = 64;
    let segments = loop_segments(n, |i| {
        let t = std::f64::consts::TAU * i as f64 / n as f64;
        c + DVec3::new(3.0 * t.cos(), t.sin(), 0.0)
    });
    let (centres, out) = extremes(&segments);
    assert_eq!(centres.len(), 1);
    assert!(centres[0].distance(c) < 1e-12, "{:?}", centres[0]);
    let (radius, [e1, e2]) = out[0];
    assert!((radius - 3.0).abs() < 1e-12, "{radius}");
    let ends = [c + DVec3::X * 3.0, c - DVec3::X * 3.0];
    for e in [e1, e2] {
        assert!(
            ends.iter().any(|x| x.distance(e) < 1e-12),
            "{e} is not an end of the major axis"
        );
    }
    assert!((e1.distance(e2) - 6.0).abs() < 1e-12);
}

#[test]
fn two_loops_are_measured_apart() {
    // Unit circles about (0, 0, 0) and (5, 0, 0) (16 vertices each): two regions of radius 1.
    let n = 16;
    let circle = |centre: DVec3| {
        loop_segments(n, move |i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            centre + DVec3::new(t.cos(), t.sin(), 0.0)
        })
    };
    let mut segments = circle(DVec3::ZERO);
    segments.extend(circle(DVec3::new(5.0, 0.0, 0.0)));
    let (centres, out) = extremes(&segments);
    assert_eq!(centres.len(), 2);
    for (centre, (radius, [e1, e2])) in centres.iter().zip(&out) {
        assert!((radius - 1.0).abs() < 1e-12, "{radius}");
        assert!((e1.distance(*centre) - 1.0).abs() < 1e-12);
        // Opposite vertices of the 16-gon.
        assert!((e1.distance(*e2) - 2.0).abs() < 1e-12, "{e1} {e2}");
    }
}

#[test]
fn a_single_point_has_radius_zero() {
    let p = DVec3::new(1.0, 2.0, 3.0);
    let segments = [IntersectionSegment {
        a_triangle: 0,
        b_triangle: 0,
        start: p,
        end: p,
    }];
    let (_, out) = extremes(&segments);
    assert_eq!(out, vec![(0.0, [p, p])]);
}
