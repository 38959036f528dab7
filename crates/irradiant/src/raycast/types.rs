//! The ray-cast pass's GPU structs (`raycast/trace.wgsl`), checked against the WGSL by
//! `tests/gpu_structs.rs`.

use bytemuck::{Pod, Zeroable};

/// A ray for the ray-cast pass (tests, benchmarks).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuRay {
    pub origin: [f32; 3],
    pub t_max: f32,
    pub dir: [f32; 3],
    pub _pad: u32,
}

/// The closest hit of a [`GpuRay`]: triangle and instance are `u32::MAX` on a miss.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuRayHit {
    pub t: f32,
    pub triangle: u32,
    pub instance: u32,
    pub _pad: u32,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuRayCastParams {
    pub ray_count: u32,
    /// 1: stop at the first hit (shadow rays).
    pub any_hit: u32,
    pub _pad0: u32,
    pub _pad1: u32,
}
