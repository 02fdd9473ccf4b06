//! Tests of the Stage 1 bounding volumes (OBBs and bevelled boxes): containment of the
//! inflated input, tightness against the OBB (Monte Carlo), exactness of the overlap tests
//! against a brute-force GJK written here, and degenerate inputs. Lengths in mm.

use bvh_hybrid::bevelled_volume::{BevelledVolume, SLAB_DIRECTIONS};
use bvh_hybrid::obb::Obb;
use glam::{DMat3, DQuat, DVec3};

/// SplitMix64: a small seeded generator, so every test is reproducible.
struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.uniform()
    }

    fn unit_vector(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let l2 = v.length_squared();
            if l2 > 1e-4 && l2 <= 1.0 {
                return v / l2.sqrt();
            }
        }
    }

    fn rotation(&mut self) -> DQuat {
        loop {
            let q = DQuat::from_xyzw(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let l2 = q.length_squared();
            if l2 > 1e-4 && l2 <= 1.0 {
                return q.normalize();
            }
        }
    }

    /// Uniform point of the box (body frame).
    fn point_in_obb(&mut self, obb: &Obb) -> DVec3 {
        let h = obb.half_extents;
        let q = DVec3::new(
            self.range(-h.x, h.x),
            self.range(-h.y, h.y),
            self.range(-h.z, h.z),
        );
        obb.center + obb.axes * q
    }
}

fn sphere_points(rng: &mut Rng, radius: f64, n: usize) -> Vec<DVec3> {
    (0..n).map(|_| rng.unit_vector() * radius).collect()
}

/// Points on the side and the two caps of a closed cylinder along z.
fn cylinder_points(rng: &mut Rng, radius: f64, height: f64, n: usize) -> Vec<DVec3> {
    (0..n)
        .map(|i| {
            let phi = rng.range(0.0, std::f64::consts::TAU);
            let (s, c) = phi.sin_cos();
            match i % 4 {
                0 => DVec3::new(radius * c, radius * s, height),
                1 => DVec3::new(radius * c, radius * s, 0.0),
                _ => DVec3::new(radius * c, radius * s, rng.range(0.0, height)),
            }
        })
        .collect()
}

/// A random surface-like point cloud (ellipsoid patch, cylinder patch, box cloud or torus
/// patch), moved by a random rigid motion up to 500 mm from the origin.
fn random_cloud(rng: &mut Rng) -> Vec<DVec3> {
    let n = 4 + (rng.next_u64() % 60) as usize;
    let kind = rng.next_u64() % 4;
    let (a, b, c) = (
        rng.range(0.2, 6.0),
        rng.range(0.2, 6.0),
        rng.range(0.2, 6.0),
    );
    let (theta_max, phi_max) = (
        rng.range(0.2, std::f64::consts::PI),
        rng.range(0.2, std::f64::consts::TAU),
    );
    let local: Vec<DVec3> = (0..n)
        .map(|_| {
            let theta = rng.range(0.0, theta_max);
            let phi = rng.range(0.0, phi_max);
            match kind {
                0 => DVec3::new(
                    a * theta.sin() * phi.cos(),
                    b * theta.sin() * phi.sin(),
                    c * theta.cos(),
                ),
                1 => DVec3::new(a * phi.cos(), a * phi.sin(), rng.range(0.0, c)),
                2 => DVec3::new(rng.range(0.0, a), rng.range(0.0, b), rng.range(0.0, c)),
                _ => {
                    let r = a + 0.5 * b * theta.cos();
                    DVec3::new(r * phi.cos(), r * phi.sin(), 0.5 * b * theta.sin())
                }
            }
        })
        .collect();
    let rot = rng.rotation();
    let trans = rng.unit_vector() * rng.range(0.0, 500.0);
    local.into_iter().map(|p| rot * p + trans).collect()
}

fn random_inflate(rng: &mut Rng) -> f64 {
    [0.0, 1e-3, 0.05, 0.5][(rng.next_u64() % 4) as usize]
}

fn assert_rotation(axes: DMat3) {
    let err = (axes.transpose() * axes - DMat3::IDENTITY)
        .abs()
        .to_cols_array();
    assert!(
        err.iter().all(|e| *e < 1e-12),
        "axes not orthonormal: {axes:?}"
    );
    assert!(
        (axes.determinant() - 1.0).abs() < 1e-12,
        "axes not right-handed"
    );
}

/// Vertices (body frame) of a bevelled volume, enumerated independently of the library from
/// its slabs: every feasible intersection of three planes (not deduplicated), solved by
/// matrix inversion.
fn brute_vertices(v: &BevelledVolume) -> Vec<DVec3> {
    let (min, max) = (v.slab_min(), v.slab_max());
    let scale = min.iter().chain(max).fold(0.0f64, |m, o| m.max(o.abs()));
    let tol = 1e-9 * scale + 1e-12;
    let planes: Vec<(DVec3, f64)> = (0..18)
        .map(|i| {
            let k = i / 2;
            (SLAB_DIRECTIONS[k], if i % 2 == 0 { min[k] } else { max[k] })
        })
        .collect();
    let mut out = Vec::new();
    for i in 0..18 {
        for j in (i + 1)..18 {
            for l in (j + 1)..18 {
                let rows = DMat3::from_cols(planes[i].0, planes[j].0, planes[l].0).transpose();
                if rows.determinant().abs() < 1e-3 {
                    continue;
                }
                let q = rows.inverse() * DVec3::new(planes[i].1, planes[j].1, planes[l].1);
                let ok = (0..9).all(|k| {
                    let s = SLAB_DIRECTIONS[k].dot(q);
                    s >= min[k] - tol && s <= max[k] + tol
                });
                if ok {
                    out.push(v.center() + v.axes() * q);
                }
            }
        }
    }
    out
}

fn support(points: &[DVec3], d: DVec3) -> DVec3 {
    points
        .iter()
        .copied()
        .max_by(|a, b| a.dot(d).total_cmp(&b.dot(d)))
        .unwrap_or(DVec3::ZERO)
}

/// Closest point to the origin of the hull of a simplex (1 to 4 points), by trying every
/// face: returns the point and the face's vertices, or `None` when the origin lies inside a
/// full (non-flat) tetrahedron. Nearly degenerate faces are skipped: their boundary faces
/// give the answer.
fn closest_on_simplex(simplex: &[DVec3]) -> Option<(DVec3, Vec<DVec3>)> {
    let n = simplex.len();
    if n == 4 {
        let [p0, p1, p2, p3] = [simplex[0], simplex[1], simplex[2], simplex[3]];
        let vol = |a: DVec3, b: DVec3, c: DVec3, d: DVec3| (b - a).dot((c - a).cross(d - a));
        let full = vol(p0, p1, p2, p3);
        let edge = simplex
            .iter()
            .flat_map(|a| simplex.iter().map(move |b| a.distance(*b)))
            .fold(0.0, f64::max);
        if full.abs() > 1e-9 * edge.powi(3) {
            let o = DVec3::ZERO;
            let parts = [
                vol(o, p1, p2, p3),
                vol(p0, o, p2, p3),
                vol(p0, p1, o, p3),
                vol(p0, p1, p2, o),
            ];
            if parts.iter().all(|v| v / full >= 0.0) {
                return None;
            }
        }
    }
    let mut best: Option<(DVec3, Vec<DVec3>)> = None;
    for mask in 1u32..(1 << n) {
        if mask.count_ones() == 4 {
            continue;
        }
        let pts: Vec<DVec3> = (0..n)
            .filter(|i| mask & (1 << i) != 0)
            .map(|i| simplex[i])
            .collect();
        let p0 = pts[0];
        let e: Vec<DVec3> = pts[1..].iter().map(|p| *p - p0).collect();
        let k = e.len();
        // Solve the normal equations G mu = -E^T p0 (k <= 2) through a padded 3x3 system.
        let mut g = DMat3::IDENTITY;
        let mut rhs = DVec3::ZERO;
        for r in 0..k {
            for c in 0..k {
                g.col_mut(c)[r] = e[r].dot(e[c]);
            }
            rhs[r] = -e[r].dot(p0);
        }
        let norms: f64 = e.iter().map(|v| v.length_squared()).product();
        if k > 0 && g.determinant() <= 1e-18 * norms {
            continue;
        }
        let mu = g.inverse() * rhs;
        let lambda0 = 1.0 - (0..k).map(|r| mu[r]).sum::<f64>();
        if !(lambda0 > 0.0 && (0..k).all(|r| mu[r] > 0.0)) {
            continue;
        }
        let x = p0 + (0..k).fold(DVec3::ZERO, |acc, r| acc + e[r] * mu[r]);
        if best.as_ref().is_none_or(|(b, _)| x.length() < b.length()) {
            best = Some((x, pts));
        }
    }
    best
}

/// GJK distance between the convex hulls of `a` and `b`: a certified lower bound and an
/// upper bound (both 0 when the hulls intersect).
fn gjk_distance(a: &[DVec3], b: &[DVec3]) -> (f64, f64) {
    let mut v = a[0] - b[0];
    let mut simplex: Vec<DVec3> = Vec::new();
    let mut lower = 0.0f64;
    for _ in 0..100 {
        let vn = v.length();
        if vn == 0.0 {
            return (0.0, 0.0);
        }
        let w = support(a, -v) - support(b, v);
        lower = lower.max(v.dot(w) / vn);
        if vn - lower <= 1e-13 * (1.0 + vn) || simplex.contains(&w) {
            return (lower, vn);
        }
        simplex.push(w);
        match closest_on_simplex(&simplex) {
            None => return (0.0, 0.0),
            Some((x, kept)) => {
                v = x;
                simplex = kept;
            }
        }
    }
    (lower, v.length())
}

fn centroid(points: &[DVec3]) -> DVec3 {
    points.iter().copied().sum::<DVec3>() / points.len() as f64
}

/// Largest distance from `c` to the points.
fn radius(points: &[DVec3], c: DVec3) -> f64 {
    points.iter().map(|p| p.distance(c)).fold(0.0, f64::max)
}

/// Offset `s` along `dir` at which hull(b) moved by `base + s dir` stops touching hull(a),
/// by bisection on the GJK distance (hull(b) at `base` overlaps hull(a)).
fn touching_offset(a: &[DVec3], b: &[DVec3], base: DVec3, dir: DVec3) -> f64 {
    let (mut lo, mut hi) = (0.0, radius(a, centroid(a)) + radius(b, centroid(b)) + 1.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        let moved: Vec<DVec3> = b.iter().map(|p| *p + base + dir * mid).collect();
        if gjk_distance(a, &moved).1 > 1e-13 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn containment() {
    let mut rng = Rng(1);
    for _ in 0..300 {
        let points = random_cloud(&mut rng);
        let inflate = random_inflate(&mut rng);
        let obb = Obb::fit(&points, inflate).expect("finite input");
        let bevelled = BevelledVolume::fit(&points, inflate).expect("finite input");
        let bounding = bevelled.bounding_obb();
        assert_rotation(obb.axes);
        assert_rotation(bevelled.axes());
        let rot = rng.rotation();
        let trans = rng.unit_vector() * 100.0;
        let (obb_moved, bevelled_moved) = (
            obb.transformed(rot, trans),
            bevelled.transformed(rot, trans),
        );
        for &p in &points {
            // The point, 6 random points at distance `inflate`, and the extreme ones along
            // every box axis and slab normal (where rounding bites first).
            let mut probes = vec![p];
            probes.extend((0..6).map(|_| p + rng.unit_vector() * inflate));
            for d in (0..3)
                .map(|k| obb.axes.col(k))
                .chain(SLAB_DIRECTIONS.iter().map(|d| bevelled.axes() * *d))
            {
                probes.extend([p + d * inflate, p - d * inflate]);
            }
            for q in probes {
                assert!(obb.contains_point(q), "OBB misses {q:?}");
                assert!(bevelled.contains_point(q), "bevelled misses {q:?}");
                assert!(bounding.contains_point(q), "bounding OBB misses {q:?}");
                let moved = rot * q + trans;
                // Moving adds rounding of order 1e-13 mm, which exact tests may see.
                let inward = moved + (obb_moved.center - moved).normalize_or_zero() * 1e-9;
                assert!(obb_moved.contains_point(inward));
                let inward = moved + (bevelled_moved.center() - moved).normalize_or_zero() * 1e-9;
                assert!(bevelled_moved.contains_point(inward));
            }
        }
        let parent = Obb::enclosing([&obb, &bounding]).expect("finite boxes");
        for c in obb.corners().into_iter().chain(bounding.corners()) {
            assert!(
                parent.contains_point(c),
                "enclosing box misses a child corner"
            );
        }
        // Random points of the bevelled volume lie in its bounding box and its vertices'
        // hull spans every slab.
        for (k, d) in SLAB_DIRECTIONS.iter().enumerate() {
            let (lo, hi) = bevelled
                .vertices()
                .iter()
                .map(|v| d.dot(*v))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| {
                    (a.min(s), b.max(s))
                });
            let tol = 2.0 * bevelled.tolerance();
            assert!(
                (lo - bevelled.slab_min()[k]).abs() <= tol,
                "slab {k} min not spanned"
            );
            assert!(
                (hi - bevelled.slab_max()[k]).abs() <= tol,
                "slab {k} max not spanned"
            );
        }
    }
}

/// Monte Carlo estimate of vol(bevelled) / vol(its bounding OBB), by sampling the box.
fn volume_ratio(rng: &mut Rng, bevelled: &BevelledVolume, samples: usize) -> f64 {
    let bounding = bevelled.bounding_obb();
    let inside = (0..samples)
        .filter(|_| bevelled.contains_point(rng.point_in_obb(&bounding)))
        .count();
    inside as f64 / samples as f64
}

#[test]
fn bevelled_is_tighter_than_obb() {
    let mut rng = Rng(2);
    let samples = 400_000;
    // Sphere of radius 10: the solid fills pi/6 = 0.524 of its cube.
    let sphere = sphere_points(&mut rng, 10.0, 4000);
    let obb = Obb::fit(&sphere, 0.0).expect("finite");
    let bevelled = BevelledVolume::fit(&sphere, 0.0).expect("finite");
    let bounding = bevelled.bounding_obb();
    let relative = (bounding.half_extents - obb.half_extents)
        .abs()
        .max_element();
    assert!(relative < 1e-9, "bounding OBB differs from fitted OBB");
    let ratio = volume_ratio(&mut rng, &bevelled, samples);
    println!("sphere r=10: bevelled/OBB volume = {ratio:.4}");
    assert!(ratio < 0.75, "sphere ratio {ratio}");
    assert!(
        ratio > std::f64::consts::PI / 6.0 - 0.01,
        "sphere ratio {ratio}"
    );

    // Closed cylinder r=5, h=30: an octagonal prism fills 2(sqrt(2)-1)*2 = 0.828 of its box.
    let cylinder = cylinder_points(&mut rng, 5.0, 30.0, 4000);
    let obb = Obb::fit(&cylinder, 0.0).expect("finite");
    let obb_volume = 8.0 * obb.half_extents.x * obb.half_extents.y * obb.half_extents.z;
    assert!(
        (obb_volume / 3000.0 - 1.0).abs() < 0.01,
        "cylinder OBB volume {obb_volume}"
    );
    let bevelled = BevelledVolume::fit(&cylinder, 0.0).expect("finite");
    let ratio = volume_ratio(&mut rng, &bevelled, samples);
    println!("cylinder r=5 h=30: bevelled/OBB volume = {ratio:.4}");
    assert!(ratio < 0.86, "cylinder ratio {ratio}");
    assert!(
        ratio > std::f64::consts::PI / 4.0 - 0.01,
        "cylinder ratio {ratio}"
    );

    // Same, inflated by 0.1 mm and moved far from the origin.
    let rot = rng.rotation();
    let moved: Vec<DVec3> = cylinder
        .iter()
        .map(|p| rot * *p + DVec3::new(400.0, -300.0, 250.0))
        .collect();
    let bevelled = BevelledVolume::fit(&moved, 0.1).expect("finite");
    let ratio = volume_ratio(&mut rng, &bevelled, samples);
    println!("cylinder r=5 h=30, inflate 0.1, moved: bevelled/OBB volume = {ratio:.4}");
    assert!(ratio < 0.86, "moved cylinder ratio {ratio}");

    // Random surface patches: the bevelled volume is never larger than its OBB; print the
    // mean ratio.
    let mut sum = 0.0;
    let count = 50;
    for _ in 0..count {
        let points = random_cloud(&mut rng);
        let bevelled = BevelledVolume::fit(&points, 0.05).expect("finite");
        sum += volume_ratio(&mut rng, &bevelled, 20_000);
    }
    println!(
        "random patches: mean bevelled/OBB volume = {:.4}",
        sum / count as f64
    );
    assert!(sum / count as f64 <= 1.0);
}

/// Outcome counts of one overlap comparison series: GJK-certified intersecting, certified
/// more than 1e-6 mm apart, in between (either answer allowed), and sampled common points.
#[derive(Default, Debug)]
struct Tally {
    overlapping: usize,
    separated: usize,
    in_between: usize,
    in_between_reported_separated: usize,
    sampled_common_points: usize,
}

/// Checks one overlap answer against GJK on the vertex sets (body frame of A): a certified
/// intersection (or a sampled common point) must be reported overlapping, a certified
/// distance above 1e-6 mm separated, and a reported separation needs a GJK distance > 1e-12.
fn check(
    answer: bool,
    a: &[DVec3],
    b: &[DVec3],
    common_point: bool,
    tally: &mut Tally,
    what: &str,
) {
    let (lower, upper) = gjk_distance(a, b);
    if common_point {
        tally.sampled_common_points += 1;
        assert!(answer, "{what}: common point found but reported separated");
    }
    if upper == 0.0 {
        tally.overlapping += 1;
        assert!(answer, "{what}: intersecting (GJK) but reported separated");
    } else if lower > 1e-6 {
        tally.separated += 1;
        assert!(!answer, "{what}: {lower} mm apart but reported overlapping");
    } else {
        tally.in_between += 1;
        tally.in_between_reported_separated += usize::from(!answer);
    }
    if !answer {
        assert!(
            upper > 1e-12,
            "{what}: reported separated at GJK distance {upper}"
        );
    }
}

#[test]
fn overlap_matches_brute_force() {
    let mut rng = Rng(3);
    let offsets = [
        -0.5, -1e-2, -1e-4, -1e-6, -1e-8, 0.0, 1e-8, 1e-6, 3e-6, 1e-5, 1e-4, 1e-2, 0.5,
    ];
    let mut bevelled_tally = Tally::default();
    let mut obb_tally = Tally::default();
    let mut mixed_tally = Tally::default();
    let mut max_vertices = 0;
    for _ in 0..150 {
        let (cloud_a, cloud_b) = (random_cloud(&mut rng), random_cloud(&mut rng));
        let (inflate_a, inflate_b) = (random_inflate(&mut rng), random_inflate(&mut rng));
        let a = BevelledVolume::fit(&cloud_a, inflate_a).expect("finite");
        let b = BevelledVolume::fit(&cloud_b, inflate_b).expect("finite");
        let obb_a = Obb::fit(&cloud_a, inflate_a).expect("finite");
        let obb_b = Obb::fit(&cloud_b, inflate_b).expect("finite");
        let (verts_a, verts_b) = (brute_vertices(&a), brute_vertices(&b));
        max_vertices = max_vertices.max(a.vertices().len());

        // The library's vertices match the independent enumeration.
        for (lib, brute) in [(&a, &verts_a), (&b, &verts_b)] {
            let world: Vec<DVec3> = lib.world_vertices().collect();
            for v in &world {
                assert!(brute.iter().any(|w| w.distance(*v) < 1e-8), "extra vertex");
            }
            for w in brute {
                assert!(
                    world.iter().any(|v| v.distance(*w) < 1e-8),
                    "missing vertex"
                );
            }
        }

        let rot = rng.rotation();
        let dir = rng.unit_vector();
        for (which, verts_a, verts_b) in [
            (0, verts_a.clone(), verts_b.clone()),
            (1, obb_a.corners().to_vec(), obb_b.corners().to_vec()),
            (2, verts_a.clone(), obb_b.corners().to_vec()),
        ] {
            let rotated_b: Vec<DVec3> = verts_b.iter().map(|p| rot * *p).collect();
            let base = centroid(&verts_a) - centroid(&rotated_b);
            let touch = touching_offset(&verts_a, &rotated_b, base, dir);
            for delta in offsets {
                let trans = base + dir * (touch + delta);
                let moved_b: Vec<DVec3> = rotated_b.iter().map(|p| *p + trans).collect();
                let (answer, tally, what, common) = match which {
                    0 => {
                        let common = (0..200).any(|_| {
                            let p = rng.point_in_obb(&a.bounding_obb());
                            a.contains_point(p) && b.contains_point(rot.inverse() * (p - trans))
                        });
                        (
                            a.overlaps(&b, rot, trans),
                            &mut bevelled_tally,
                            "bevelled",
                            common,
                        )
                    }
                    1 => {
                        let moved = obb_b.transformed(rot, trans);
                        let common =
                            (0..200).any(|_| moved.contains_point(rng.point_in_obb(&obb_a)));
                        (obb_a.overlaps(&moved), &mut obb_tally, "OBB", common)
                    }
                    _ => {
                        let common = (0..200).any(|_| {
                            let p = rng.point_in_obb(&a.bounding_obb());
                            a.contains_point(p) && obb_b.contains_point(rot.inverse() * (p - trans))
                        });
                        (
                            a.overlaps_obb(&obb_b, rot, trans),
                            &mut mixed_tally,
                            "bevelled-OBB",
                            common,
                        )
                    }
                };
                check(answer, &verts_a, &moved_b, common, tally, what);
            }
        }
    }
    println!("bevelled pairs: {bevelled_tally:?}");
    println!("OBB pairs: {obb_tally:?}");
    println!("bevelled-OBB pairs: {mixed_tally:?}");
    println!("max bevelled vertex count: {max_vertices}");
    for tally in [&bevelled_tally, &obb_tally, &mixed_tally] {
        assert!(
            tally.overlapping > 300 && tally.separated > 700,
            "{tally:?}"
        );
    }
}

#[test]
fn degenerate_inputs() {
    let p = DVec3::new(1.0, -2.0, 3.0);
    // Non-finite or empty input.
    for bad in [
        vec![],
        vec![p, DVec3::new(f64::NAN, 0.0, 0.0)],
        vec![DVec3::new(0.0, f64::INFINITY, 0.0)],
    ] {
        assert!(Obb::fit(&bad, 0.1).is_none());
        assert!(BevelledVolume::fit(&bad, 0.1).is_none());
    }
    for bad_inflate in [f64::NAN, -1.0, f64::INFINITY] {
        assert!(Obb::fit(&[p], bad_inflate).is_none());
        assert!(BevelledVolume::fit(&[p], bad_inflate).is_none());
    }
    assert!(Obb::enclosing(&[]).is_none());

    // One point.
    let obb = Obb::fit(&[p], 0.0).expect("finite");
    assert!(obb.contains_point(p) && obb.half_extents.max_element() < 1e-9);
    let single = BevelledVolume::fit(&[p], 0.0).expect("finite");
    assert!(single.contains_point(p));
    assert_eq!(single.vertices().len(), 1);
    let ball = BevelledVolume::fit(&[p], 0.5).expect("finite");
    assert!(
        (Obb::fit(&[p], 0.5).expect("finite").half_extents - DVec3::splat(0.5))
            .abs()
            .max_element()
            < 1e-9
    );
    // The 18-DOP of a ball of radius 0.5 reaches (a, a, a) for a = 0.5 / sqrt(2) = 0.354.
    assert!(ball.contains_point(p + DVec3::new(0.35, 0.35, 0.35)));
    assert!(!ball.contains_point(p + DVec3::new(0.36, 0.36, 0.36)));

    // Collinear points: the first axis follows the line, the box is thin across it.
    let dir = DVec3::new(1.0, 2.0, -0.5).normalize();
    let line: Vec<DVec3> = (0..20).map(|i| p + dir * (i as f64 * 0.7)).collect();
    for inflate in [0.0, 0.2] {
        let obb = Obb::fit(&line, inflate).expect("finite");
        assert_rotation(obb.axes);
        assert!(obb.axes.col(0).cross(dir).length() < 1e-9);
        assert!((obb.half_extents.x - (0.5 * 19.0 * 0.7 + inflate)).abs() < 1e-9);
        assert!((obb.half_extents.y - inflate).abs() < 1e-9);
        assert!((obb.half_extents.z - inflate).abs() < 1e-9);
        let bevelled = BevelledVolume::fit(&line, inflate).expect("finite");
        assert!(line.iter().all(|q| bevelled.contains_point(*q)));
        if inflate == 0.0 {
            assert_eq!(bevelled.vertices().len(), 2);
        }
    }

    // Coplanar points: a flat disk (and its rim circle), tilted. The normal is the third
    // axis, the box and the bevelled volume are flat, and the bevelled one is an octagon.
    let normal = DVec3::new(0.3, -0.2, 1.0).normalize();
    let (u, v) = normal.any_orthonormal_pair();
    let mut rng = Rng(4);
    let circle: Vec<DVec3> = (0..64)
        .map(|i| {
            let phi = i as f64 * std::f64::consts::TAU / 64.0;
            p + (u * phi.cos() + v * phi.sin()) * 3.0
        })
        .collect();
    let mut disk = circle.clone();
    disk.extend((0..200).map(|_| {
        let r = 3.0 * rng.uniform().sqrt();
        let phi = rng.range(0.0, std::f64::consts::TAU);
        p + (u * phi.cos() + v * phi.sin()) * r
    }));
    for points in [&circle, &disk] {
        let obb = Obb::fit(points, 0.0).expect("finite");
        assert_rotation(obb.axes);
        assert!(obb.axes.col(2).cross(normal).length() < 1e-9);
        assert!(obb.half_extents.z < 1e-9);
        let flat = BevelledVolume::fit(points, 0.0).expect("finite");
        assert!(points.iter().all(|q| flat.contains_point(*q)));
        assert_eq!(flat.vertices().len(), 8, "octagon expected");
        assert!(
            flat.world_vertices()
                .all(|w| (w - p).dot(normal).abs() < 1e-9)
        );
        // Overlaps of a flat disk with a point: on the disk, above it, beside it.
        let dot_at = |q: DVec3| BevelledVolume::fit(&[q], 0.0).expect("finite");
        let inside = p + u * 1.0;
        assert!(flat.overlaps(&dot_at(inside), DQuat::IDENTITY, DVec3::ZERO));
        assert!(!flat.overlaps(
            &dot_at(inside + normal * 1e-3),
            DQuat::IDENTITY,
            DVec3::ZERO
        ));
        assert!(!flat.overlaps(&dot_at(p + u * 3.2), DQuat::IDENTITY, DVec3::ZERO));
        let dot_box = Obb::fit(&[inside], 0.0).expect("finite");
        assert!(obb.overlaps(&dot_box));
        assert!(flat.overlaps_obb(&dot_box, DQuat::IDENTITY, DVec3::ZERO));
        let above = Obb::fit(&[inside + normal * 1e-3], 0.0).expect("finite");
        assert!(!obb.overlaps(&above));
        assert!(!flat.overlaps_obb(&above, DQuat::IDENTITY, DVec3::ZERO));
    }

    // Two crossing segments touch; lifted along their common normal by 1e-3 they do not.
    // Only the edge-edge cross-product axis separates them.
    let seg_a = [DVec3::new(-1.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0)];
    let seg_b = [DVec3::new(0.0, -1.0, 0.0), DVec3::new(0.0, 1.0, 0.0)];
    let (a, b) = (
        BevelledVolume::fit(&seg_a, 0.0).expect("finite"),
        BevelledVolume::fit(&seg_b, 0.0).expect("finite"),
    );
    let (box_a, box_b) = (
        Obb::fit(&seg_a, 0.0).expect("finite"),
        Obb::fit(&seg_b, 0.0).expect("finite"),
    );
    let rot = DQuat::from_axis_angle(DVec3::new(1.0, 1.0, 0.0).normalize(), 0.0);
    assert!(a.overlaps(&b, rot, DVec3::ZERO));
    assert!(!a.overlaps(&b, rot, DVec3::Z * 1e-3));
    assert!(box_a.overlaps(&box_b));
    assert!(!box_a.overlaps(&box_b.transformed(DQuat::IDENTITY, DVec3::Z * 1e-3)));
    assert!(!a.overlaps_obb(&box_b, DQuat::IDENTITY, DVec3::Z * 1e-3));
    // Skew crossing: rotate b about x so the segments are not perpendicular in 3D.
    let tilt = DQuat::from_rotation_x(0.4);
    assert!(a.overlaps(&b, tilt, DVec3::ZERO));
    assert!(!a.overlaps(&b, tilt, DVec3::Z * 1e-3));
}
