//! Fuzzes the scene loader: any bytes that are UTF-8 go through `Scene::from_json`. Any panic
//! is a bug; a loaded scene must hold finite, unit-rotation poses and valid options.
//!
//! Object references are resolved against a folder that does not exist, so that only absolute
//! paths reach the file system (see docs/ROBUSTNESS.md: a reference to a device file such as
//! `/dev/zero` is read to its end).
#![no_main]

use contacts::scene::Scene;
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    // Keep the fuzzer away from device files (an unbounded read is not what is being tested).
    if text.contains("/dev") || text.contains("/proc") || text.contains("/sys") {
        return;
    }
    let base = Path::new("/nonexistent-fuzz-base");
    if let Ok(scene) = Scene::from_json(text, Path::new("fuzz.json"), base) {
        assert!(scene.objects.len() >= 2);
        for object in &scene.objects {
            assert!(object.pose.translation.is_finite());
            assert!((object.pose.rotation.length() - 1.0).abs() < 1e-12);
        }
        assert!(scene.options.validate().is_ok());
    }
});
