//! The light-field bake cache: an entry is a file that a crashed or concurrent run may have left
//! in any state; parsing it must refuse anything but an exact entry for the key and layout.
#![no_main]

use irradiant::lightfield::{EntryLayout, parse_entry};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // A 2-probe bake of 16² maps: radiance, geometry, min-mip, the two atlases, then the
    // probe states and offsets.
    let layout = EntryLayout {
        maps: vec![[16, 16, 2, 4], [16, 16, 2, 4], [1, 1, 2, 4], [20, 10, 1, 8], [36, 18, 1, 8]],
        buffers: vec![16, 32],
    };
    if let Some(chunks) = parse_entry(data, 7, &layout) {
        assert_eq!(chunks.len(), layout.maps.len() + layout.buffers.len());
        assert_eq!(data.len() as u64, layout.entry_bytes());
    }
});
