//! The comparison lab's reference cache: an entry is an OpenEXR file that a crashed or
//! concurrent run may have left in any state; reading it must fail cleanly.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let dir = irradiant_fuzz::write_files(&[("reference.exr", data)]);
    // As the comparison lab reads its entries: at the size it expects.
    let path = dir.join("reference.exr");
    if let Ok(image) = irradiant::frame::Image::read_exr(&path, Some((64, 64))) {
        assert_eq!(image.pixels.len(), image.width as usize * image.height as usize);
    }
});
