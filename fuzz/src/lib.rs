//! What the fuzz targets share: a scratch folder of this process into which a target writes
//! the files a loader reads (the loaders take paths, as users give them).

use std::path::{Path, PathBuf};

/// This process's scratch folder, emptied of the files a target writes before each input.
pub fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("irradiant-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `files` (name, contents) into the scratch folder and returns the folder.
pub fn write_files(files: &[(&str, &[u8])]) -> PathBuf {
    let dir = scratch();
    for (name, contents) in files {
        std::fs::write(dir.join(name), contents).unwrap();
    }
    dir
}

/// Splits an input at its first NUL byte: two files in one input (an OBJ and its MTL).
pub fn split(data: &[u8]) -> (&[u8], &[u8]) {
    match data.iter().position(|&b| b == 0) {
        Some(i) => (&data[..i], &data[i + 1..]),
        None => (data, &[]),
    }
}

pub fn path_str(path: &Path) -> &str {
    path.to_str().expect("the scratch folder's path is UTF-8")
}
