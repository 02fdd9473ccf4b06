use geom_param::step::read_step;
#[test]
fn probe() {
    for f in [
        "onshape_red_cube_blue_cylinder.step",
        "solidworks_featuretype.step",
        "solidworks_base_interface.step",
        "/tmp/stepdata/m6.step",
    ] {
        let path = if f.starts_with('/') {
            f.to_string()
        } else {
            format!("{}/../../fixtures/step/{f}", env!("CARGO_MANIFEST_DIR"))
        };
        let bytes = std::fs::read(&path).unwrap();
        let t = std::time::Instant::now();
        match read_step(&bytes) {
            Ok(solids) => {
                for s in &solids {
                    println!(
                        "{f}: {} faces {} edges tol {:e} in {:?}",
                        s.solid.faces.len(),
                        s.solid.edges.len(),
                        s.solid.tolerance,
                        t.elapsed()
                    );
                }
            }
            Err(e) => println!("{f}: ERROR {e}"),
        }
    }
}
#[test]
fn dump() {
    let f = std::env::var("STEP_FILE").unwrap_or_default();
    let face: usize = std::env::var("STEP_FACE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    if f.is_empty() {
        return;
    }
    let bytes = std::fs::read(&f).unwrap();
    let solids = geom_param::step::debug_read(&bytes);
    let s = &solids[0];
    let fc = &s.faces[face];
    println!("surface {:?}", fc.surface.domain());
    for (li, l) in fc.trim.as_ref().unwrap().loops.iter().enumerate() {
        for e in &l.entries {
            let d = e.pcurve.domain();
            let a = e.pcurve.eval(d.min).point;
            let b = e.pcurve.eval(d.max).point;
            let m = e.pcurve.eval(0.5 * (d.min + d.max)).point;
            println!(
                "loop {li} edge {} rev {} {:?} -> {:?} mid {:?}  3d {:?} -> {:?}",
                e.edge.0,
                e.reversed,
                a,
                b,
                m,
                s.edges[e.edge.0 as usize].curve.eval(d.min).point,
                s.edges[e.edge.0 as usize].curve.eval(d.max).point
            );
        }
    }
}
