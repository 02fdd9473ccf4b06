//! The shipped real STEP exports (`fixtures/step/`): each reads into validated solids, meshes
//! watertight, and its volume and surface area from the mesh (divergence theorem) agree with a
//! closed form, or with the volume of the exporter's own STL of the same part, within the bound
//! the chordal error allows.

use geom_param::step::{StepSolid, read_step};
use geom_param::{DVec3, FeatureLocation, MeshOptions, ObjectModel};
use std::collections::HashMap;
use std::f64::consts::PI;

fn fixture(name: &str) -> Vec<u8> {
    let path = format!("{}/../../fixtures/step/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn read(name: &str) -> Vec<StepSolid> {
    read_step(&fixture(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Volume, area and chordal error of a model's meshes.
#[derive(Debug, Default)]
struct Measured {
    volume: f64,
    area: f64,
    chordal_error: f64,
}

/// Samples of each triangle per side for the independent chordal error.
const N: usize = 6;

fn measure(model: &ObjectModel) -> Measured {
    let solid = &model.solid;
    let mut m = Measured::default();
    for mesh in &model.meshes {
        m.chordal_error = m.chordal_error.max(mesh.chordal_error);
        for (k, params) in mesh.triangle_params.iter().enumerate() {
            let face = mesh.triangle_faces[k];
            let p = mesh.triangle(k);
            m.area += 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length();
            m.volume += p[0].dot(p[1].cross(p[2])) / 6.0;
            for i in 0..=N {
                for j in 0..=N - i {
                    let b = [
                        i as f64 / N as f64,
                        j as f64 / N as f64,
                        (N - i - j) as f64 / N as f64,
                    ];
                    let u = b[0] * params[0][0] + b[1] * params[1][0] + b[2] * params[2][0];
                    let v = b[0] * params[0][1] + b[1] * params[1][1] + b[2] * params[2][1];
                    let exact = solid.eval_face(face, u, v).point;
                    let linear = p[0] * b[0] + p[1] * b[1] + p[2] * b[2];
                    m.chordal_error = m.chordal_error.max(exact.distance(linear));
                }
            }
        }
    }
    m
}

fn location_key(location: &FeatureLocation) -> (u8, u32, u64, u64) {
    match *location {
        FeatureLocation::Face { id, u, v } => (0, id.0, u.to_bits(), v.to_bits()),
        FeatureLocation::Edge { id, t } => (1, id.0, t.to_bits(), 0),
        FeatureLocation::Vertex { id } => (2, id.0, 0, 0),
    }
}

/// Every mesh edge (vertices merged by exact location across components) is used once in each
/// direction: the union of the component meshes is a closed, consistently oriented surface.
fn assert_watertight(name: &str, model: &ObjectModel) {
    let mut merged: HashMap<(u8, u32, u64, u64), usize> = HashMap::new();
    let mut directed: HashMap<(usize, usize), usize> = HashMap::new();
    for mesh in &model.meshes {
        let ids: Vec<usize> = mesh
            .vertex_locations
            .iter()
            .map(|loc| {
                let n = merged.len();
                *merged.entry(location_key(loc)).or_insert(n)
            })
            .collect();
        for t in &mesh.triangles {
            let v = t.map(|i| ids[i as usize]);
            for e in 0..3 {
                *directed.entry((v[e], v[(e + 1) % 3])).or_default() += 1;
            }
        }
    }
    for (&(a, b), &count) in &directed {
        assert_eq!(
            count, 1,
            "{name}: a mesh edge is used twice in one direction"
        );
        assert_eq!(directed.get(&(b, a)), Some(&1), "{name}: open mesh edge");
    }
}

fn model(s: StepSolid, tolerance: f64) -> ObjectModel {
    let name = s.name.clone();
    ObjectModel::from_solid(
        name.clone(),
        s.solid,
        &MeshOptions {
            chordal_tolerance: tolerance,
        },
    )
    .unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// |ΔV| <= A ε (the mesh lies within ε of the surface), plus rounding.
fn assert_volume(name: &str, m: &Measured, volume: f64) {
    let bound = m.area * m.chordal_error + 1e-9 * volume;
    assert!(
        (m.volume - volume).abs() <= bound,
        "{name}: mesh volume {} vs {volume} (bound {bound})",
        m.volume
    );
}

#[test]
fn cube_and_cylinder_match_their_closed_forms() {
    // A CAD export from CadQuery's test data, lengths in metres: a 10 mm cube and a
    // cylinder of radius 5 mm and height 10 mm, its side written without a seam edge.
    let solids = read("red_cube_blue_cylinder.step");
    let names: Vec<&str> = solids.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["blue_cylinder", "red_cube"]);
    for s in solids {
        // The file's uncertainty is 1e-6 m = 1e-3 mm.
        assert!(
            (s.solid.tolerance - 1e-3).abs() < 1e-12,
            "{}",
            s.solid.tolerance
        );
        let name = s.name.clone();
        let m = model(s, 0.01);
        assert_watertight(&name, &m);
        let measured = measure(&m);
        let (volume, area) = if name == "red_cube" {
            (1000.0, 600.0)
        } else {
            (PI * 25.0 * 10.0, 2.0 * PI * 5.0 * 10.0 + 2.0 * PI * 25.0)
        };
        assert_volume(&name, &measured, volume);
        // A flat solid's mesh is exact; the cylinder's faces lose at most 1 - cos of the
        // normal deviation, bounded through the chordal error ε: cos θ >= 1 - 2ε/r.
        let area_bound = if name == "red_cube" {
            1e-9 * area
        } else {
            area * 2.0 * measured.chordal_error / 5.0
                + 2.0 * 2.0 * PI * 5.0 * measured.chordal_error
        };
        assert!(
            (measured.area - area).abs() <= area_bound,
            "{name}: area {} vs {area} (bound {area_bound})",
            measured.area
        );
    }
}

/// The triangles of a binary STL, scaled by `scale`.
fn stl_triangles(bytes: &[u8], scale: f64) -> Vec<[DVec3; 3]> {
    let count = u32::from_le_bytes(bytes[80..84].try_into().expect("4 bytes")) as usize;
    assert_eq!(bytes.len(), 84 + 50 * count, "a binary STL");
    (0..count)
        .map(|k| {
            let at = 84 + 50 * k + 12;
            let f = |i: usize| {
                let o = at + 4 * i;
                f64::from(f32::from_le_bytes(
                    bytes[o..o + 4].try_into().expect("4 bytes"),
                ))
            };
            [0, 1, 2].map(|v| DVec3::new(f(3 * v), f(3 * v + 1), f(3 * v + 2)) * scale)
        })
        .collect()
}

/// The point of triangle `t` nearest `p` (Ericson, Real-Time Collision Detection, 5.1.5).
fn closest_on_triangle(p: DVec3, [a, b, c]: [DVec3; 3]) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

/// Largest distance from the STL's vertices, edge midpoints and centroids to the model's mesh
/// (a uniform grid of the mesh's triangles, searched ring by ring).
fn stl_deviation(stl: &[[DVec3; 3]], model: &ObjectModel) -> f64 {
    let triangles: Vec<[DVec3; 3]> = model
        .meshes
        .iter()
        .flat_map(|m| (0..m.len()).map(move |k| m.triangle(k)))
        .collect();
    let cell = 2.0;
    let key = |p: DVec3| (p / cell).floor().as_ivec3();
    let mut grid: HashMap<glam::IVec3, Vec<usize>> = HashMap::new();
    for (i, t) in triangles.iter().enumerate() {
        let lo = key(t[0].min(t[1]).min(t[2]));
        let hi = key(t[0].max(t[1]).max(t[2]));
        for x in lo.x..=hi.x {
            for y in lo.y..=hi.y {
                for z in lo.z..=hi.z {
                    grid.entry(glam::IVec3::new(x, y, z)).or_default().push(i);
                }
            }
        }
    }
    let distance = |p: DVec3| -> f64 {
        let k = key(p);
        for ring in 1..8 {
            let mut best = f64::INFINITY;
            for x in -ring..=ring {
                for y in -ring..=ring {
                    for z in -ring..=ring {
                        for &i in grid
                            .get(&(k + glam::IVec3::new(x, y, z)))
                            .into_iter()
                            .flatten()
                        {
                            best = best.min(closest_on_triangle(p, triangles[i]).distance(p));
                        }
                    }
                }
            }
            // Every triangle within ring cells' distance has been seen.
            if best <= f64::from(ring) * cell {
                return best;
            }
        }
        f64::INFINITY
    };
    let mut worst: f64 = 0.0;
    for t in stl {
        let samples = [
            t[0],
            t[1],
            t[2],
            0.5 * (t[0] + t[1]),
            0.5 * (t[1] + t[2]),
            0.5 * (t[2] + t[0]),
            (t[0] + t[1] + t[2]) / 3.0,
        ];
        for p in samples {
            worst = worst.max(distance(p));
        }
    }
    worst
}

#[test]
fn solidworks_featuretype_matches_its_own_stl_export() {
    // SolidWorks 2013 export in inches (trimesh's test models), with the binary STL SolidWorks
    // wrote of the same part (also inches) as the independent value.
    let solids = read("solidworks_featuretype.step");
    assert_eq!(solids.len(), 1);
    let s = solids.into_iter().next().expect("one solid");
    assert_eq!(s.name, "Cut-Extrude6");
    let name = s.name.clone();
    let m = model(s, 0.02);
    assert_watertight(&name, &m);
    let measured = measure(&m);
    let stl = stl_triangles(&fixture("solidworks_featuretype.stl"), 25.4);
    let stl_volume: f64 = stl.iter().map(|p| p[0].dot(p[1].cross(p[2])) / 6.0).sum();
    let stl_area: f64 = stl
        .iter()
        .map(|p| 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length())
        .sum();
    // Both meshes approximate one solid: the STL within its measured deviation from our mesh
    // plus our chordal error, ours within the chordal error. The volumes differ by at most the
    // sum of area x deviation.
    let stl_error = stl_deviation(&stl, &m) + measured.chordal_error;
    let bound = stl_area * stl_error + measured.area * measured.chordal_error;
    println!(
        "{name}: mesh volume {} mm^3, STL {stl_volume} mm^3, bound {bound} (STL deviation {stl_error} mm)",
        measured.volume
    );
    assert!(
        (measured.volume - stl_volume).abs() <= bound,
        "{name}: volume {} vs the STL's {stl_volume} (bound {bound})",
        measured.volume
    );
}

#[test]
fn solidworks_base_interface_reads_and_meshes_watertight() {
    let solids = read("solidworks_base_interface.step");
    assert_eq!(solids.len(), 1);
    let s = solids.into_iter().next().expect("one solid");
    let name = s.name.clone();
    let m = model(s, 0.05);
    assert_watertight(&name, &m);
    let measured = measure(&m);
    println!(
        "{name}: mesh volume {} area {}",
        measured.volume, measured.area
    );
    assert!(measured.volume > 0.0);
}

/// A frustum of a cone written by hand (not an export): bottom radius 10 at z = 0, top radius 5
/// at z = 8; the conical face bounded by its two circles without a seam (the reader adds one),
/// the bottom cap a plane facing +z used with same_sense false.
const FRUSTUM: &str = "ISO-10303-21;
HEADER;
FILE_DESCRIPTION((''),'2;1');
FILE_NAME('frustum','',(''),(''),'','','');
FILE_SCHEMA(('CONFIG_CONTROL_DESIGN'));
ENDSEC;
DATA;
#1 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );
#2 = ( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );
#3 = UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#1,'distance_accuracy_value','');
#4 = ( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#3)) GLOBAL_UNIT_ASSIGNED_CONTEXT((#1,#2)) REPRESENTATION_CONTEXT('','') );
#5 = ADVANCED_BREP_SHAPE_REPRESENTATION('',(#10),#4);
#10 = MANIFOLD_SOLID_BREP('frustum',#11);
#11 = CLOSED_SHELL('',(#20,#30,#40));
#12 = DIRECTION('',(0.,0.,1.));
#13 = DIRECTION('',(1.,0.,0.));
#14 = DIRECTION('',(0.,0.,-1.));
#15 = CARTESIAN_POINT('',(0.,0.,0.));
#16 = CARTESIAN_POINT('',(0.,0.,8.));
#17 = AXIS2_PLACEMENT_3D('',#15,#12,#13);
#18 = AXIS2_PLACEMENT_3D('',#16,#12,#13);
#19 = AXIS2_PLACEMENT_3D('',#16,#14,#13);
#50 = CIRCLE('',#17,10.);
#51 = CIRCLE('',#18,5.);
#52 = CARTESIAN_POINT('',(10.,0.,0.));
#53 = CARTESIAN_POINT('',(5.,0.,8.));
#54 = VERTEX_POINT('',#52);
#55 = VERTEX_POINT('',#53);
#56 = EDGE_CURVE('',#54,#54,#50,.T.);
#57 = EDGE_CURVE('',#55,#55,#51,.T.);
#20 = ADVANCED_FACE('',(#21,#22),#25,.T.);
#21 = FACE_BOUND('',#23,.T.);
#22 = FACE_BOUND('',#24,.T.);
#23 = EDGE_LOOP('',(#26));
#24 = EDGE_LOOP('',(#27));
#26 = ORIENTED_EDGE('',*,*,#56,.T.);
#27 = ORIENTED_EDGE('',*,*,#57,.F.);
#25 = CONICAL_SURFACE('',#19,5.,0.5585993153435624);
#30 = ADVANCED_FACE('',(#31),#33,.F.);
#31 = FACE_OUTER_BOUND('',#32,.T.);
#32 = EDGE_LOOP('',(#34));
#34 = ORIENTED_EDGE('',*,*,#56,.F.);
#33 = PLANE('',#17);
#40 = ADVANCED_FACE('',(#41),#43,.T.);
#41 = FACE_OUTER_BOUND('',#42,.T.);
#42 = EDGE_LOOP('',(#44));
#44 = ORIENTED_EDGE('',*,*,#57,.T.);
#43 = PLANE('',#18);
ENDSEC;
END-ISO-10303-21;
";

#[test]
fn a_cone_frustum_matches_its_closed_form() {
    // tan a = 5 / 8: the semi-angle in the file is atan(5/8).
    assert!((0.5585993153435624_f64.tan() - 0.625).abs() < 1e-15);
    let solids = read_step(FRUSTUM.as_bytes()).expect("reads");
    let s = solids.into_iter().next().expect("one solid");
    assert_eq!(
        (s.solid.faces.len(), s.solid.edges.len()),
        (3, 3),
        "two circles and a seam"
    );
    let m = model(s, 0.01);
    assert_watertight("frustum", &m);
    let measured = measure(&m);
    let (big, small, h) = (10.0, 5.0, 8.0);
    let volume = PI * h * (big * big + big * small + small * small) / 3.0;
    assert_volume("frustum", &measured, volume);
    let slant = f64::hypot(h, big - small);
    let area = PI * (big * big + small * small) + PI * (big + small) * slant;
    // Curved faces lose at most 1 - cos of the normal deviation (cos θ >= 1 - 2ε/ρ with ρ the
    // smallest radius of curvature, 5 / cos a on the cone), plus ε along each curved edge.
    let rho = small / (8.0 / slant);
    let bound = area * 2.0 * measured.chordal_error / rho
        + 2.0 * 2.0 * PI * (big + small) * measured.chordal_error;
    assert!(
        (measured.area - area).abs() <= bound,
        "area {} vs {area} (bound {bound})",
        measured.area
    );
}

#[test]
fn brep_with_voids_flips_its_void_shells() {
    // The cube of the CadQuery export given the cylinder's shell as a void (an
    // ORIENTED_CLOSED_SHELL with orientation false): its faces are turned inside out, so the
    // mesh's signed volume is the cube's less the cylinder's (the divergence theorem adds
    // oriented boundaries whatever they enclose).
    let text = String::from_utf8(fixture("red_cube_blue_cylinder.step")).expect("ASCII");
    let text = text.replacen(
        "#61 = MANIFOLD_SOLID_BREP( 'red_cube', #111 );",
        "#61 = BREP_WITH_VOIDS( 'red_cube', #111, ( #900 ) );\n#900 = ORIENTED_CLOSED_SHELL( '', *, #106, .F. );",
        1,
    );
    let solids = read_step(text.as_bytes()).expect("reads");
    let s = solids
        .into_iter()
        .find(|s| s.name == "red_cube")
        .expect("the cube");
    assert_eq!(s.solid.faces.len(), 9);
    let m = model(s, 0.01);
    let measured = measure(&m);
    assert_volume("cube less cylinder", &measured, 1000.0 - PI * 25.0 * 10.0);
}

/// |A_mesh − A| for a solid whose curved faces are cylinders of radius at least `radius`:
/// each face loses at most 1 − cos of the normal deviation (cos θ >= 1 − 2ε/r), plus ε along
/// each curved edge of total length `curved_edges`.
fn cylinder_area_bound(m: &Measured, area: f64, radius: f64, curved_edges: f64) -> f64 {
    area * 2.0 * m.chordal_error / radius + 2.0 * curved_edges * m.chordal_error + 1e-9 * area
}

#[test]
fn proe_inch_cube_matches_its_closed_form() {
    // Pro/ENGINEER 2001 (CAx-IF c1), lengths in inches (a CONVERSION_BASED_UNIT), the
    // uncertainty a complex LENGTH_MEASURE_WITH_UNIT, the solid also listed by a
    // SHELL_BASED_SURFACE_MODEL (read once): an 80 in = 2032 mm cube.
    let solids = read("proe_cube_inch.stp");
    assert_eq!(
        solids.len(),
        1,
        "the surface model's shell is the solid's own"
    );
    let s = solids.into_iter().next().expect("one solid");
    let extent = s
        .solid
        .vertices
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v.point), hi.max(v.point))
        });
    assert!(
        ((extent.1 - extent.0) - DVec3::splat(2032.0))
            .abs()
            .max_element()
            < 1e-9
    );
    let m = model(s, 0.5);
    assert_watertight("proe cube", &m);
    let measured = measure(&m);
    assert_volume("proe cube", &measured, 2032.0_f64.powi(3));
    let area = 6.0 * 2032.0_f64.powi(2);
    assert!(
        (measured.area - area).abs() <= 1e-9 * area,
        "{}",
        measured.area
    );
}

#[test]
fn ideas_block_with_a_bspline_hole_matches_its_closed_form() {
    // I-DEAS Master Series 9 (CAx-IF gd1), inches: a 3 x 2 x 1 in block with a through hole
    // of radius 0.5 in about the axis x = 1.5, y = 1 in, written as a closed rational
    // B-spline surface (QUASI_UNIFORM knots, weights 1 and 1/2: an exact circle) whose seam
    // edges the reader places on either side of the closed parameter.
    let solids = read("ideas_block_hole.stp");
    let s = solids.into_iter().next().expect("one solid");
    let m = model(s, 0.01);
    assert_watertight("ideas block", &m);
    let measured = measure(&m);
    let inch: f64 = 25.4;
    let volume = (6.0 - PI * 0.25) * inch.powi(3);
    assert_volume("ideas block", &measured, volume);
    let area = (2.0 * (6.0 - PI * 0.25) + 2.0 * (3.0 + 2.0) + 2.0 * PI * 0.5) * inch * inch;
    let bound = cylinder_area_bound(&measured, area, 0.5 * inch, 2.0 * 2.0 * PI * 0.5 * inch);
    assert!(
        (measured.area - area).abs() <= bound,
        "area {} vs {area} (bound {bound})",
        measured.area
    );
}

#[test]
fn onshape_block_with_a_hole_matches_its_closed_form() {
    // Onshape (Parasolid) export in metres: a 2 x 1 x 1 in block with a through hole of
    // radius 1/4 in, 1 in long.
    let solids = read("onshape_cube_hole.step");
    let s = solids.into_iter().next().expect("one solid");
    let m = model(s, 0.01);
    assert_watertight("onshape block", &m);
    let measured = measure(&m);
    let (w, h, r) = (50.8, 25.4, 6.35);
    let volume = w * h * h - PI * r * r * h;
    assert_volume("onshape block", &measured, volume);
    let area = 4.0 * w * h + 2.0 * h * h - 2.0 * PI * r * r + 2.0 * PI * r * h;
    let bound = cylinder_area_bound(&measured, area, r, 2.0 * 2.0 * PI * r);
    assert!(
        (measured.area - area).abs() <= bound,
        "area {} vs {area} (bound {bound})",
        measured.area
    );
}

/// Volume of one solid of a file meshed at `tolerance`, with its bound A ε.
fn volume_with_bound(file: &str, tolerance: f64) -> (f64, f64) {
    let solids = read(file);
    let s = solids.into_iter().next().expect("a solid");
    let name = format!("{file}: {}", s.name);
    let m = model(s, tolerance);
    assert_watertight(&name, &m);
    let measured = measure(&m);
    (
        measured.volume,
        measured.area * measured.chordal_error + 1e-9 * measured.volume,
    )
}

#[test]
fn one_part_exported_by_two_systems_has_one_volume() {
    // The same design written by two CAD systems through different kernels: the CAx-IF
    // AS1 L-bracket from CATIA V5 R13 and from Unigraphics (Theorem's translator, B-spline
    // surfaces throughout), the IO1 flange from Autodesk Inventor 2.0 and AutoCAD 2000. Each
    // mesh is within A ε of its exact volume, so the two agree within the sum of the bounds.
    for (a, b) in [
        ("catia_v5_l_bracket.stp", "unigraphics_l_bracket.stp"),
        ("inventor_io1.stp", "autocad_io1.stp"),
    ] {
        let (va, ba) = volume_with_bound(a, 0.01);
        let (vb, bb) = volume_with_bound(b, 0.01);
        assert!(
            (va - vb).abs() <= ba + bb,
            "{a}: {va} vs {b}: {vb} (bound {})",
            ba + bb
        );
        assert!(va > 0.0 && vb > 0.0);
    }
}

#[test]
fn solidworks_box_sides_reads_its_six_solids_watertight() {
    // SolidWorks 2015, six bodies in inches. Regression: a loop's last p-curve ended one
    // rounding unit from its first one's start, which put the closing point on the first
    // segment (a false self-intersection); line p-curves now pass through their snapped ends
    // bit for bit.
    let solids = read("solidworks_box_sides.step");
    let names: Vec<&str> = solids.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "Cut-Extrude5",
            "Cut-Extrude6",
            "Boss-Extrude2",
            "Cut-Extrude3",
            "Mirror3",
            "Cut-Extrude1"
        ]
    );
    for s in solids {
        let name = s.name.clone();
        let m = model(s, 0.05);
        assert_watertight(&name, &m);
        assert!(measure(&m).volume > 0.0, "{name}");
    }
}

#[test]
fn cascade_pcurves_are_read_where_they_agree_with_the_projection() {
    // Matra Datavision's CASCADE 4.0 (OpenCASCADE's ancestor, CAx-IF io1): every edge a
    // SURFACE_CURVE or SEAM_CURVE with a PCURVE per face, on planes, 11 cylinders and a 45°
    // cone (whose v the model measures along the ruling, STEP along the axis). The lines and
    // circles are taken from the file; the six rational B-spline circles on planes carry
    // another parameter than the edge's angle and are projected.
    let text = String::from_utf8(fixture("cascade_io1.stp")).expect("ASCII");
    let with_file = read_step(text.as_bytes()).expect("reads");
    let [s] = with_file.as_slice() else {
        panic!("one solid");
    };
    assert_eq!(
        (s.pcurves.from_file, s.pcurves.projected),
        (64, 6),
        "{:?}",
        s.pcurves
    );
    // The same file with its PCURVE entities renamed: every p-curve projected.
    let projected = read_step(text.replace("PCURVE(", "XPCURVE(").as_bytes()).expect("reads");
    let [p] = projected.as_slice() else {
        panic!("one solid");
    };
    assert_eq!((p.pcurves.from_file, p.pcurves.projected), (0, 70));
    // Both p-curves of every edge use land on the same surface points (the file's and the
    // fitted ones meet the edge within the fit tolerance, a quarter of the uncertainty).
    let tolerance = 0.5 * s.solid.tolerance;
    for (fi, (fa, fb)) in s.solid.faces.iter().zip(&p.solid.faces).enumerate() {
        let (Some(ta), Some(tb)) = (&fa.trim, &fb.trim) else {
            panic!("trimmed faces");
        };
        let [ru, rv] = fa.surface.domain();
        for (la, lb) in ta.loops.iter().zip(&tb.loops) {
            for (ea, eb) in la.entries.iter().zip(&lb.entries) {
                assert_eq!(ea.edge, eb.edge);
                let d = ea.pcurve.domain();
                for k in 0..=32 {
                    let t = d.min + d.span() * f64::from(k) / 32.0;
                    let on = |c: &dyn geom_param::Curve2| {
                        let q = c.eval(t).point;
                        fa.surface.eval(ru.normalize(q.x), rv.normalize(q.y)).point
                    };
                    let gap = on(ea.pcurve.as_ref()).distance(on(eb.pcurve.as_ref()));
                    assert!(gap <= tolerance, "face {fi}: {gap} mm at t = {t}");
                }
            }
        }
    }
    // And the solid is the same: volumes within the meshes' bounds.
    let volume = |solids: Vec<StepSolid>| {
        let s = solids.into_iter().next().expect("one solid");
        let m = model(s, 0.01);
        assert_watertight("cascade io1", &m);
        let measured = measure(&m);
        (
            measured.volume,
            measured.area * measured.chordal_error + 1e-9 * measured.volume,
        )
    };
    let (va, ba) = volume(with_file);
    let (vb, bb) = volume(projected);
    assert!((va - vb).abs() <= ba + bb, "{va} vs {vb}");
}
