//! OpenEXR files as the comparison lab's reference cache reads them: what was written reads
//! back; damaged entries (the inputs the reference_cache fuzzer broke, docs/reliability.md) and
//! entries of another size are refused with the file named, before anything large is decoded.

use std::path::Path;

use irradiant::frame::Image;

#[test]
fn a_written_image_reads_back_and_another_size_is_refused() {
    let dir = std::env::temp_dir().join(format!("irradiant-image-io-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("entry.exr");
    let image = Image {
        width: 3,
        height: 2,
        pixels: (0..6).map(|i| [i as f32, 0.5, 2.0]).collect(),
    };
    image.write_exr(&path).unwrap();
    let back = Image::read_exr(&path, Some((3, 2))).unwrap();
    assert_eq!(back.pixels, image.pixels);
    let message = Image::read_exr(&path, Some((64, 64)))
        .err()
        .unwrap()
        .to_string();
    assert!(
        message.contains("entry.exr") && message.contains("3×2, not the 64×64"),
        "{message}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn damaged_cache_entries_are_refused_naming_the_file() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz-regressions");
    for name in [
        "reference-slow-unit.exr",
        "reference-timeout.exr",
        "reference-huge-offset-table.exr",
    ] {
        let message = Image::read_exr(&dir.join(name), Some((64, 64)))
            .err()
            .unwrap_or_else(|| panic!("{name} is damaged"))
            .to_string();
        assert!(
            message.contains(name) && message.contains("cannot read the image"),
            "{message}"
        );
    }
}

/// Two tests of one process that render the same reference store it at once: every write
/// succeeds and the entry reads back whole. (Their temporary files once shared a name, the
/// process's id: one writer's rename moved the other's half-written file into place and the
/// other's rename failed.)
#[test]
fn writers_of_one_entry_at_once_each_succeed_and_leave_it_whole() {
    let dir = std::env::temp_dir().join(format!("irradiant-image-race-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("entry.exr");
    let image = Image {
        width: 64,
        height: 64,
        pixels: (0..64 * 64).map(|i| [i as f32, 0.25, -1.0]).collect(),
    };
    std::thread::scope(|threads| {
        for _ in 0..4 {
            threads.spawn(|| {
                for _ in 0..25 {
                    image.write_exr(&path).unwrap();
                    let back = Image::read_exr(&path, Some((64, 64))).unwrap();
                    assert_eq!(back.pixels, image.pixels);
                }
            });
        }
    });
    let _ = std::fs::remove_dir_all(&dir);
}
