//! OBJ + MTL: an input is the OBJ, a NUL byte, and the MTL it may name as `m.mtl`. Loading
//! (tobj, our conversion, validation) must return a scene or an error, never panic or hang.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let (obj, mtl) = irradiant_fuzz::split(data);
    let dir = irradiant_fuzz::write_files(&[("f.obj", obj), ("m.mtl", mtl)]);
    let _ = irradiant_scene::load(irradiant_fuzz::path_str(&dir.join("f.obj")));
});
