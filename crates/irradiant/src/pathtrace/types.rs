//! The path tracer's GPU struct (`pathtrace/trace.wgsl`), checked against the WGSL by
//! `tests/gpu_structs.rs`.

use bytemuck::{Pod, Zeroable};

use crate::scene::types::GpuCamera;

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuPathTraceParams {
    pub camera: GpuCamera,
    pub width: u32,
    pub height: u32,
    pub sample_offset: u32,
    pub samples: u32,
    pub max_bounces: u32,
    pub seed: u32,
    /// `LightSampling::gpu`
    pub light_sampling: u32,
    pub _pad1: u32,
}
const _: () = assert!(size_of::<GpuPathTraceParams>() == 96);

/// One point the path tracer gathers light or distance at (`pathtrace/gather.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuGatherQuery {
    pub origin: [f32; 3],
    pub far: f32,
    pub axis: [f32; 3],
    pub exponent: f32,
    pub kind: u32,
    pub on_surface: u32,
    pub _pad0: u32,
    pub _pad1: u32,
}
const _: () = assert!(size_of::<GpuGatherQuery>() == 48);

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuGatherParams {
    pub count: u32,
    pub sample_offset: u32,
    pub samples: u32,
    pub max_bounces: u32,
    pub seed: u32,
    /// `LightSampling::gpu`
    pub light_sampling: u32,
    pub _pad1: u32,
    pub _pad2: u32,
}
const _: () = assert!(size_of::<GpuGatherParams>() == 32);
