//! Debug probe (not committed): per-seed Stage 3 results for one pose.
use bvh_hybrid::HybridBvh;
use contact_pipeline::{ContactOptions, ContactPipeline, QueryScratch};
use exact_refine::{NewtonRefiner, RefinedContact, Refiner};
use geom_param::{DPose3, DQuat, DVec3, Seed, Solid};
use mesh_narrowphase::MeshNarrowphase;

struct Logging(NewtonRefiner);
impl Refiner for Logging {
    type Scratch = ();
    fn refine(&self, a: &Solid, b: &Solid, p: &DPose3, s: &Seed, sc: &mut ()) -> RefinedContact {
        let r = self.0.refine(a, b, p, s, sc);
        eprintln!(
            "SEED a {:?} {:?}\n     b {:?} {:?}",
            s.a.location, s.a.local_point, s.b.location, s.b.local_point
        );
        eprintln!(
            "  -> d {:e} {:?} {:?} status {:?} it {} lm {} err {:e} cond {:e} pa {:?}",
            r.distance,
            r.location_a,
            r.location_b,
            r.diagnostics.status,
            r.diagnostics.iterations,
            r.diagnostics.is_local_minimum,
            r.diagnostics.error_estimate,
            r.diagnostics.condition,
            r.point_a
        );
        r
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let v = |s: &str| {
        s.split(',')
            .map(|x| x.parse::<f64>().unwrap())
            .collect::<Vec<_>>()
    };
    let t = v(&args[3]);
    let q = v(&args[4]);
    let pose = DPose3 {
        translation: DVec3::new(t[0], t[1], t[2]),
        rotation: DQuat::from_xyzw(q[0], q[1], q[2], q[3]),
    };
    let pipeline = ContactPipeline::with_stages(
        HybridBvh::default(),
        MeshNarrowphase::default(),
        Logging(NewtonRefiner::default()),
        ContactOptions::default(),
    )
    .unwrap();
    let objs: std::collections::BTreeMap<_, _> = xtask::paper_objects::paper_objects()
        .iter()
        .map(|d| (d.name.clone(), pipeline.prepare_description(d).unwrap()))
        .collect();
    let mut scratch = QueryScratch::default();
    let r = pipeline
        .query(
            &objs[&args[1]],
            &DPose3::IDENTITY,
            &objs[&args[2]],
            &pose,
            &mut scratch,
        )
        .unwrap();
    println!("{:?} stats {:?}", r.state, r.stats);
    for c in &r.contacts {
        println!(
            "C d {:e} {:?} {:?} {:?}",
            c.distance, c.location_a, c.location_b, c.point_a
        );
    }
    println!("W {:?}", r.penetration_witnesses);
}
