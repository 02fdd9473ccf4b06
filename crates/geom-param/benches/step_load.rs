//! Load time of the shipped STEP exports (`fixtures/step/`): `read_step` (parse, map, project
//! p-curves, validate) alone, and with the model's preparation (`ObjectModel::from_solid`:
//! convexity, meshing at 0.05 mm, components and hulls) for each solid.

use criterion::{Criterion, black_box};
use geom_param::step::read_step;
use geom_param::{MeshOptions, ObjectModel};
use std::time::Duration;

const FILES: [&str; 12] = [
    "red_cube_blue_cylinder.step",
    "solidworks_base_interface.step",
    "solidworks_featuretype.step",
    "solidworks_box_sides.step",
    "catia_v5_l_bracket.stp",
    "unigraphics_l_bracket.stp",
    "ideas_block_hole.stp",
    "proe_cube_inch.stp",
    "inventor_io1.stp",
    "autocad_io1.stp",
    "onshape_cube_hole.step",
    "cascade_io1.stp",
];

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("step_load");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(3));
    for name in FILES {
        let path = format!("{}/../../fixtures/step/{name}", env!("CARGO_MANIFEST_DIR"));
        let bytes = std::fs::read(&path).expect("fixture");
        group.bench_function(format!("read_step/{name}"), |b| {
            b.iter(|| read_step(black_box(&bytes)).expect("reads"));
        });
        group.bench_function(format!("read_and_prepare/{name}"), |b| {
            b.iter(|| {
                for s in read_step(black_box(&bytes)).expect("reads") {
                    let options = MeshOptions {
                        chordal_tolerance: 0.05,
                    };
                    black_box(
                        ObjectModel::from_solid(s.name, s.solid, &options).expect("prepares"),
                    );
                }
            });
        });
    }
    group.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench(&mut c);
    c.final_summary();
}
