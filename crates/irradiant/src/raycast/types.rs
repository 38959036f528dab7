//! The ray-cast pass's GPU structs (`raycast/trace.wgsl`), checked against the WGSL by
//! `tests/gpu_structs.rs`.

use bytemuck::{Pod, Zeroable};

/// A ray for the ray-cast pass (tests, benchmarks).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuRay {
    /// World-space origin.
    pub origin: [f32; 3],
    /// Farthest ray parameter a hit may have.
    pub t_max: f32,
    /// World-space direction (unit length makes `t` a distance).
    pub dir: [f32; 3],
    /// In the counting variant ([`crate::raycast::RayCaster::counting`]), a closest-hit ray's
    /// search ends at the first hit nearer than this, as an emitter's shadow ray's does
    /// (`trace_ray_until` in shaders/bvh.wgsl); 0: the closest hit. The timed pass ignores it.
    pub stop: f32,
}

/// The closest hit of a [`GpuRay`]: triangle and instance are `u32::MAX` on a miss.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuRayHit {
    /// Ray parameter of the hit; -1 on a miss.
    pub t: f32,
    /// GPU triangle slot hit (see [`crate::GpuScene::triangle_sources`]).
    pub triangle: u32,
    /// Instance hit, in instance-buffer order (see [`crate::GpuScene::instance_order`]).
    pub instance: u32,
    /// The counting variant's node visits (bits 0–15) and triangle tests (bits 16–31), each
    /// saturating at 65 535; 0 from the timed pass.
    pub work: u32,
}

impl GpuRayHit {
    /// Node visits of the counting variant's trace (wide nodes where the bottom level is wide).
    pub fn node_visits(&self) -> u32 {
        self.work & 0xffff
    }
    /// Triangle tests of the counting variant's trace.
    pub fn triangle_tests(&self) -> u32 {
        self.work >> 16
    }
}

/// The ray-cast pass's parameters (its uniform).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuRayCastParams {
    /// Rays in the batch; threads past it do nothing.
    pub ray_count: u32,
    /// 1: stop at the first hit (shadow rays).
    pub any_hit: u32,
    /// Padding to a 16-byte multiple; 0.
    pub _pad0: u32,
    /// Padding to a 16-byte multiple; 0.
    pub _pad1: u32,
}
