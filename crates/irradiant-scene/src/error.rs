use std::path::PathBuf;

/// Why a scene could not be loaded. Every message names the file, the problem and the fix.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// A file (manifest, mesh or camera file) is missing or cannot be read.
    #[error(
        "{path}: cannot read the file: {source}. Check the path (relative paths in a manifest are relative to the manifest)."
    )]
    Io {
        /// The file.
        path: PathBuf,
        /// Why it cannot be read.
        source: std::io::Error,
    },
    /// The OBJ file cannot be parsed (a missing or broken MTL file is only a warning).
    #[error(
        "{path}: not a valid Wavefront OBJ file: {message}. Re-export the mesh, or check that the .mtl it names sits beside it."
    )]
    Obj {
        /// The OBJ file.
        path: PathBuf,
        /// The parser's message.
        message: String,
    },
    /// The glTF file, or a buffer or image it refers to, cannot be imported.
    #[error(
        "{path}: not a valid glTF 2.0 file: {message}. Validate it with the Khronos glTF validator."
    )]
    Gltf {
        /// The glTF file.
        path: PathBuf,
        /// The importer's message.
        message: String,
    },
    /// The manifest is not TOML, or not of a manifest's shape (a required key missing, a
    /// value of the wrong type).
    #[error(
        "{path}: invalid scene manifest: {message}. See scenes/README.md for the manifest format."
    )]
    Manifest {
        /// The manifest.
        path: PathBuf,
        /// The TOML parser's message.
        message: String,
    },
    /// What the file describes cannot be used: a non-finite vertex, an index or a value out
    /// of range, a name the scene lacks, a camera file without a usable camera, ….
    #[error("{path}: {problem}. {fix}")]
    Invalid {
        /// The file at fault.
        path: PathBuf,
        /// What is wrong.
        problem: String,
        /// What to do about it, as a sentence.
        fix: String,
    },
    /// The name given is no built-in scene, and no file of a known extension (`.toml`,
    /// `.obj`, `.gltf`, `.glb`).
    #[error(
        "unknown scene '{name}': not a built-in scene ({builtins}) and not a file ending in .toml, .obj, .gltf or .glb. Pass a built-in name or a path."
    )]
    Unknown {
        /// The name given.
        name: String,
        /// The built-in scenes' names, comma-separated, for the message.
        builtins: String,
    },
}

/// A result whose error is a [`SceneError`] unless said otherwise.
pub type Result<T, E = SceneError> = std::result::Result<T, E>;

thread_local! {
    static CONTAINING: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Runs a third-party parser (tobj, gltf) that may panic on malformed input instead of
/// returning an error (the fuzz targets found such inputs), and turns a panic into the
/// parser's message. The process's panic hook stays quiet for panics contained here and
/// reports every other panic as before.
pub(crate) fn contain_parser_panic<T>(parse: impl FnOnce() -> T) -> std::result::Result<T, String> {
    static QUIET_HOOK: std::sync::Once = std::sync::Once::new();
    QUIET_HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !CONTAINING.with(|c| c.get()) {
                previous(info);
            }
        }));
    });
    CONTAINING.with(|c| c.set(true));
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(parse));
    CONTAINING.with(|c| c.set(false));
    result.map_err(|payload| {
        let message = payload
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| payload.downcast_ref::<&str>().copied())
            .unwrap_or("no message");
        format!("the parser failed on malformed input ({message})")
    })
}
