//! Wavefront OBJ export of an object's component meshes, for looking at in any viewer.

use geom_param::ObjectModel;
use std::fmt::Write as _;

/// The object's component meshes as one OBJ text, one group per component, coordinates in mm
/// rounded to 1 nm so that the file is stable across machines.
#[must_use]
pub fn to_obj(model: &ObjectModel, header: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "# {header}");
    let _ = writeln!(
        out,
        "# {}: {} components, chordal tolerance {} mm",
        model.name,
        model.components.len(),
        model.mesh_options.chordal_tolerance
    );
    let mut base = 1;
    for (component, mesh) in model.components.iter().zip(&model.meshes) {
        let _ = writeln!(out, "g component_{}_{:?}", component.id.0, component.kind);
        for p in &mesh.positions {
            let _ = writeln!(out, "v {} {} {}", round(p.x), round(p.y), round(p.z));
        }
        for t in &mesh.triangles {
            let _ = writeln!(
                out,
                "f {} {} {}",
                t[0] as usize + base,
                t[1] as usize + base,
                t[2] as usize + base
            );
        }
        base += mesh.positions.len();
    }
    out
}

fn round(x: f64) -> f64 {
    let r = (x * 1e6).round() / 1e6;
    if r == 0.0 { 0.0 } else { r }
}
