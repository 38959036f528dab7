//! Texture decoding: any bytes a material names as its texture.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(texture) = irradiant_scene::decode_texture(data, "fuzz") {
        assert_eq!(texture.rgba8.len(), 4 * texture.width as usize * texture.height as usize);
    }
});
