//! Why rendering failed. Every message says what to do.

use std::path::PathBuf;

use irradiant_gpu::{GpuError, PassError, ShaderError};

use crate::settings::SettingsError;

/// Why rendering failed: the error of every fallible call in this crate.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The GPU failed: no suitable adapter, a validation error, device lost, out of memory.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// A WGSL shader imports an unknown module or does not compile.
    #[error(transparent)]
    Shader(#[from] ShaderError),
    /// A compute pass could not be built: its bindings do not match its WGSL declarations.
    #[error(transparent)]
    Pass(#[from] PassError),
    /// The scene does not fit this adapter (too many textures) or has a malformed texture.
    #[error("the scene cannot be put on the GPU: {0}")]
    Scene(String),
    /// An image could not be written to this path, with the reason.
    #[error("{0}: cannot write the image: {1}. Check that the folder exists and is writable.")]
    Output(PathBuf, String),
    /// An image (an OpenEXR cache entry) at this path could not be read, with the reason.
    #[error(
        "{0}: cannot read the image: {1}. Delete it to have it made again, or name an OpenEXR file."
    )]
    Input(PathBuf, String),
    /// The settings ask for what cannot be done: an unknown technique, too many probes, a tool
    /// given the wrong technique.
    #[error("{0}")]
    Settings(String),
    /// Settings failed to parse or validate.
    #[error(transparent)]
    Setting(#[from] SettingsError),
    /// A saved probe file could not be written, read or used: the file, the problem and the fix.
    #[error("{path}: {problem}")]
    Probes {
        /// The file.
        path: PathBuf,
        /// What is wrong, and the fix.
        problem: String,
    },
}
