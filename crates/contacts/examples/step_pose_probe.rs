use contact_oracle::{OracleOptions, find_contacts};
use geom_param::step::read_step;
use geom_param::{DPose3, DQuat, DVec3};
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let file = &args[1];
    let bytes = std::fs::read(file).unwrap();
    let solids = read_step(&bytes).unwrap();
    let s = &solids[0].solid;
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for v in &s.vertices {
        lo = lo.min(v.point);
        hi = hi.max(v.point);
    }
    println!("bbox {lo} {hi}");
    if args.len() < 9 {
        return;
    }
    let p: Vec<f64> = args[2..9].iter().map(|a| a.parse().unwrap()).collect();
    let rot = DQuat::from_euler(glam::EulerRot::XYZ, p[3], p[4], p[5]);
    let dir = DVec3::new(p[0], p[1], p[2]).normalize();
    let gap = p[6];
    let b = &read_step(&bytes).unwrap()[0].solid;
    // Bisection on the translation along dir so that the oracle's minimum is `gap`.
    if args.len() > 9 {
        // Single: translation along dir by args[9] exactly; one oracle run.
        let t: f64 = args[9].parse().unwrap();
        let pose = DPose3 {
            rotation: rot,
            translation: dir * t,
        };
        let opts = OracleOptions::for_solids(s, b, 3.0);
        let r = find_contacts(s, &DPose3::IDENTITY, b, &pose, &opts).unwrap();
        println!(
            "translation {:?} rotation {:?} min {}",
            pose.translation.to_array(),
            pose.rotation.to_array(),
            r.min_distance
        );
        for c in &r.contacts {
            println!(
                "  d {} a {} b {} n {}",
                c.distance, c.point_a, c.point_b, c.normal
            );
        }
        return;
    }
    let (mut t0, mut t1) = (0.0, 2.0 * (hi - lo).length());
    let mut pose = DPose3::IDENTITY;
    for _ in 0..40 {
        let t = 0.5 * (t0 + t1);
        pose = DPose3 {
            rotation: rot,
            translation: dir * t,
        };
        let opts = OracleOptions::for_solids(s, b, 5.0);
        let r = find_contacts(s, &DPose3::IDENTITY, b, &pose, &opts).unwrap();
        let d = if r.contacts.is_empty() {
            f64::INFINITY
        } else {
            r.min_distance
        };
        if d < gap {
            t0 = t
        } else {
            t1 = t
        }
        if (t1 - t0) < 1e-9 {
            break;
        }
    }
    let opts = OracleOptions::for_solids(s, b, 0.2);
    let r = find_contacts(s, &DPose3::IDENTITY, b, &pose, &opts).unwrap();
    println!(
        "translation {:?} rotation {:?}",
        pose.translation.to_array(),
        pose.rotation.to_array()
    );
    for c in &r.contacts {
        println!("  d {} a {} b {}", c.distance, c.point_a, c.point_b);
    }
}
