//! Why rendering failed. Every message says what to do.

use std::path::PathBuf;

use irradiant_gpu::{GpuError, PassError, ShaderError};

use crate::settings::SettingsError;

#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(transparent)]
    Gpu(#[from] GpuError),
    #[error(transparent)]
    Shader(#[from] ShaderError),
    #[error(transparent)]
    Pass(#[from] PassError),
    #[error("the scene cannot be put on the GPU: {0}")]
    Scene(String),
    #[error("{0}: cannot write the image: {1}. Check that the folder exists and is writable.")]
    Output(PathBuf, String),
    #[error(
        "{0}: cannot read the image: {1}. Delete it to have it made again, or name an OpenEXR file."
    )]
    Input(PathBuf, String),
    #[error("{0}")]
    Settings(String),
    #[error(transparent)]
    Setting(#[from] SettingsError),
}
