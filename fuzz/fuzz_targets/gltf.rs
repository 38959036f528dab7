//! glTF 2.0: an input is a .glb, or (first byte '{') a .gltf whose buffers are embedded.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let name = if data.first() == Some(&b'{') { "f.gltf" } else { "f.glb" };
    let dir = irradiant_fuzz::write_files(&[(name, data)]);
    let _ = irradiant_scene::load(irradiant_fuzz::path_str(&dir.join(name)));
});
