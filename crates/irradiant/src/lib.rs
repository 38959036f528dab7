//! Irradiant: real-time global illumination on any GPU, in compute shaders.
//!
//! - [`Session`]: the one frame loop — scene, frame, technique, camera and clock.
//! - [`technique`]: the [`Technique`] trait and the registry of
//!   real-time techniques ([`none`], [`ddgi`]).
//! - [`frame`]: the real-time frame (G-buffer, direct light, compose, TAA, tonemap).
//! - [`scene`]: the scene on the GPU (two-level BVH, materials, lights, textures).
//! - [`probes`]: probe grids, octahedral maps, ray sets and atlases, shared by the probe
//!   techniques.
//! - [`pathtrace`]: the reference path tracer. [`raycast`]: rays in, hits out.

#![warn(missing_docs)]

pub mod ddgi;
mod error;
pub mod frame;
pub mod gpu_types;
pub mod host;
pub mod inspect;
pub mod lightfield;
pub mod none;
pub mod pathtrace;
pub mod probes;
pub mod raycast;
pub mod registry;
pub mod scene;
mod session;
pub mod settings;
pub mod shaders;
pub mod ssil;
pub mod technique;

pub use error::RenderError;
pub use irradiant_bvh::BuildQuality;
pub use irradiant_gpu::{AdapterChoice, GpuContext, GpuError};
pub use scene::{BlasLayout, GpuScene, GpuSceneSettings};
pub use session::{Session, SessionSettings};
pub use settings::{Preset, SettingsError, SettingsFile, TechniqueSpec};
pub use technique::Technique;
