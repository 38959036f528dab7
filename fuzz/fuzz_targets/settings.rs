//! Settings files: the [frame] and [technique] tables over every preset, and every registered
//! technique's reading of its own table.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let mut warnings = Vec::new();
    let Ok(file) = irradiant::SettingsFile::parse(text, "fuzz.toml", &mut warnings) else { return };
    for preset in irradiant::Preset::ALL {
        let _ = file.frame_settings(preset, &mut warnings);
    }
    if let Some(spec) = &file.technique
        && let Ok(kind) = spec.kind()
    {
        let _ = kind.check(spec);
        let _ = kind.plan(spec, &irradiant_scene::builtin("cornell").unwrap(), (64, 64));
    }
    // What parses must round-trip.
    let again = irradiant::SettingsFile::parse(&file.to_toml(), "again", &mut warnings).unwrap();
    assert_eq!(file, again);
});
