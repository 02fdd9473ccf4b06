//! Fuzzes the object loader: any bytes that are UTF-8 go through `ObjectDescription::from_json`
//! and, when they parse, `build` at a coarse tolerance. Any panic is a bug; a built model must
//! hold no NaN in its meshes.
#![no_main]

use geom_param::{MeshOptions, ObjectDescription};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(description) = ObjectDescription::from_json(text) else {
        return;
    };
    let options = MeshOptions {
        chordal_tolerance: 0.5,
    };
    if let Ok(model) = description.build(&options) {
        for mesh in &model.meshes {
            assert!(mesh.chordal_error.is_finite());
            assert!(mesh.positions.iter().all(|p| p.is_finite()));
            assert!(mesh.normals.iter().all(|n| n.is_finite()));
        }
    }
});
