//! The path tracer's GPU struct (`pathtrace/trace.wgsl`), checked against the WGSL by
//! `tests/gpu_structs.rs`.

use bytemuck::{Pod, Zeroable};

use crate::scene::types::GpuCamera;

/// One dispatch of `pathtrace/trace`, or one sample of the wavefront's passes (their uniform,
/// `pathtrace_params` in WGSL).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuPathTraceParams {
    /// The view traced.
    pub camera: GpuCamera,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Index of this dispatch's first sample (decorrelates dispatches).
    pub sample_offset: u32,
    /// Paths each pixel traces in this dispatch.
    pub samples: u32,
    /// Longest path, in bounces after the camera ray.
    pub max_bounces: u32,
    /// Random seed.
    pub seed: u32,
    /// `LightSampling::gpu`
    pub light_sampling: u32,
    /// Padding to a 16-byte multiple; 0.
    pub _pad1: u32,
}
const _: () = assert!(size_of::<GpuPathTraceParams>() == 96);

/// One point the path tracer gathers light or distance at (`pathtrace/gather.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuGatherQuery {
    /// World-space point the samples start from.
    pub origin: [f32; 3],
    /// Distance queries: the distance misses and longer hits count as.
    pub far: f32,
    /// Unit axis of the lobe.
    pub axis: [f32; 3],
    /// The lobe is cos^exponent about `axis` (1: cosine-weighted).
    pub exponent: f32,
    /// 0: radiance, 1: distance ([`crate::pathtrace::GatherKind`]).
    pub kind: u32,
    /// 1 when the origin lies on a surface whose normal is `axis` (rays start just off it),
    /// else 0.
    pub on_surface: u32,
    /// Padding to a 16-byte multiple; 0.
    pub _pad0: u32,
    /// Padding to a 16-byte multiple; 0.
    pub _pad1: u32,
}
const _: () = assert!(size_of::<GpuGatherQuery>() == 48);

/// One dispatch of `pathtrace/gather` (its uniform).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuGatherParams {
    /// Queries in the buffer; threads past it do nothing.
    pub count: u32,
    /// Index of this dispatch's first sample (decorrelates dispatches).
    pub sample_offset: u32,
    /// Samples each query takes in this dispatch.
    pub samples: u32,
    /// Longest path, in bounces after the query's ray.
    pub max_bounces: u32,
    /// Random seed.
    pub seed: u32,
    /// `LightSampling::gpu`
    pub light_sampling: u32,
    /// Padding to a 16-byte multiple; 0.
    pub _pad1: u32,
    /// Padding to a 16-byte multiple; 0.
    pub _pad2: u32,
}
const _: () = assert!(size_of::<GpuGatherParams>() == 32);
