use glam::DVec3;
use mesh_narrowphase::triangle_intersection::*;
type Tri = [DVec3; 3];
fn closest_on_segment(p: DVec3, a: DVec3, b: DVec3) -> DVec3 {
    let ab = b - a;
    let l2 = ab.length_squared();
    if l2 == 0.0 {
        return a;
    }
    a + ab * ((p - a).dot(ab) / l2).clamp(0.0, 1.0)
}

/// Closest point of a triangle (Ericson, Real-Time Collision Detection §5.1.5); degenerate
/// triangles are handled as the union of their edges.
fn closest_on_triangle(p: DVec3, t: &Tri) -> DVec3 {
    let [a, b, c] = *t;
    let (ab, ac) = (b - a, c - a);
    if ab.cross(ac).length_squared() <= 1e-30 * ab.length_squared() * ac.length_squared() {
        let cands = [
            closest_on_segment(p, a, b),
            closest_on_segment(p, b, c),
            closest_on_segment(p, c, a),
        ];
        return cands
            .into_iter()
            .min_by(|x, y| (*x - p).length().total_cmp(&(*y - p).length()))
            .unwrap_or(a);
    }
    let ap = p - a;
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

fn dist(p: DVec3, t: &Tri) -> f64 {
    (closest_on_triangle(p, t) - p).length()
}


fn main() {
    let f = |a: [[f64;3];3]| a.map(|p| DVec3::from_array(p));
    let t1 = f([[2.,1.,-3.],[-2.,2.,1.],[-3.,2.,2.]]);
    let t2 = f([[-12.,4.,11.],[2.,1.,-3.],[7.,0.,-8.]]);
    if let TriangleContact::Coplanar{points} = intersect_triangles(&t1, &t2) {
        for p in points.iter() { println!("{p} {:e} {:e} {} {}", dist(*p,&t1), dist(*p,&t2), closest_on_triangle(*p,&t1), closest_on_triangle(*p,&t2)); }
    }
}
