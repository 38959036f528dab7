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
