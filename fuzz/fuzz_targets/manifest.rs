//! Scene manifests (TOML): parsing, placing a built-in mesh, lights, camera, volumes, regions,
//! animation, the renderer's tables, and validation.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let dir = irradiant_fuzz::write_files(&[("scene.toml", data)]);
    if let Ok(loaded) = irradiant_scene::load(irradiant_fuzz::path_str(&dir.join("scene.toml"))) {
        // A scene that loads must be safe to pose at any time its animation covers.
        for t in [0.0, 0.5, 1.0, 1e6] {
            let _ = loaded.scene.pose_at(t);
        }
    }
});
