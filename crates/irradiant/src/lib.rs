//! Irradiant: real-time global illumination on any GPU, in compute shaders.
//!
//! - [`GpuScene`]: the scene on the GPU (two-level BVH, materials, lights, textures).
//! - [`pathtrace`]: the reference path tracer.
//! - [`raycast`]: rays in, hits out (tests, benchmarks).
//! - [`frame`]: tonemapping and images.

pub mod ddgi;
pub mod frame;
pub mod gpu_scene;
pub mod gpu_types;
pub mod pathtrace;
mod pipeline;
pub mod raycast;
pub mod shaders;

pub use gpu_scene::{BlasLayout, GpuScene, GpuSceneSettings};
pub use irradiant_bvh::BuildQuality;
pub use irradiant_gpu::{AdapterChoice, GpuContext, GpuError};

use std::path::PathBuf;

/// Why rendering failed. Messages say what to do.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error(transparent)]
    Gpu(#[from] GpuError),
    #[error(transparent)]
    Shader(#[from] irradiant_gpu::ShaderError),
    #[error("the scene cannot be put on the GPU: {0}")]
    Scene(String),
    #[error("{0}: cannot write the image: {1}. Check that the folder exists and is writable.")]
    Output(PathBuf, String),
    #[error("{0}")]
    Settings(String),
}
