use glam::DVec3;
use mesh_narrowphase::triangle_intersection::*;
fn main() {
    // t2 vertex v on t1 edge a->b (interior), t2 otherwise crossing to the other side of plane1 outside t1?
    // Find (a,b,k,n) with computed lerp != v.
    for bx in 1..20 { for by in 1..20 { for k in 1..bx { 
        let a = DVec3::new(0.0, 0.0, 0.0);
        let b = DVec3::new(bx as f64, by as f64, 0.0);
        // v = a + (b-a) * k / bx must be representable: choose coords with integer x = k; y = by*k/bx
        if (by * k) % bx != 0 { continue; }
        let vv = DVec3::new(k as f64, (by * k / bx) as f64, 0.0);
        let c = DVec3::new(-3.0, 7.0, 0.0);
        let t1 = [a, b, c];
        // t2 through v, plane not containing t1 edge; other vertices on both sides in z, outside t1
        let dir = DVec3::new(by as f64, -(bx as f64), 0.0); // outward-ish perpendicular in plane
        let t2 = [vv, vv + dir + DVec3::new(0.0, 0.0, 1.0), vv + dir * 2.0 + DVec3::new(0.3, 0.0, -1.0)];
        let r = intersect_triangles(&t1, &t2);
        if let TriangleContact::Segment{a: p, b: q} = r {
            if p != vv || q != vv { println!("b={b} v={vv} got {p} {q}"); }
        } else { println!("b={b} v={vv} {r:?}"); }
    }}}
}
