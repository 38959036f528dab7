use std::path::PathBuf;

/// Why a scene could not be loaded. Every message names the file, the problem and the fix.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error(
        "{path}: cannot read the file: {source}. Check the path (relative paths in a manifest are relative to the manifest)."
    )]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error(
        "{path}: not a valid Wavefront OBJ file: {message}. Re-export the mesh, or check that the .mtl it names sits beside it."
    )]
    Obj { path: PathBuf, message: String },
    #[error(
        "{path}: not a valid glTF 2.0 file: {message}. Validate it with the Khronos glTF validator."
    )]
    Gltf { path: PathBuf, message: String },
    #[error(
        "{path}: invalid scene manifest: {message}. See scenes/README.md for the manifest format."
    )]
    Manifest { path: PathBuf, message: String },
    #[error("{path}: {problem}. {fix}")]
    Invalid {
        path: PathBuf,
        problem: String,
        fix: String,
    },
    #[error(
        "unknown scene '{name}': not a built-in scene ({builtins}) and not a file ending in .toml, .obj, .gltf or .glb. Pass a built-in name or a path."
    )]
    Unknown { name: String, builtins: String },
}

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
