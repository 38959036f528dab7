//! Screen-space indirect illumination's GPU structs (`ssil/common.wgsl`), checked against the
//! WGSL by `tests/gpu_structs.rs`.

use bytemuck::{Pod, Zeroable};

/// The technique's parameters, written once a frame.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuSsilParams {
    /// Pyramid level of the first gather (0 full, 1 half, 2 quarter resolution).
    pub start_level: u32,
    /// Pyramid levels gathered from the start level on.
    pub levels: u32,
    /// Samples a level gathers per pixel.
    pub samples: u32,
    /// 1: march the voxel grid for visibility.
    pub visibility: u32,
    /// r, in pixels of every level.
    pub radius: f32,
    /// The voxel grid's 128 slices span these view depths.
    pub near: f32,
    /// Far end of the voxel slices' view depths (`near` is the near end).
    pub far: f32,
    /// Steps of each visibility march.
    pub visibility_steps: u32,
    /// Share of each march skipped at its start and at its end.
    pub visibility_bias: f32,
    /// α of the glossy importance function f(θ) = α + exp(−s(θr − θ)²/2π); 1e9 (uniform
    /// samples) with the glossy gather off.
    pub importance_alpha: f32,
    /// Share of last frame's filtered light a still diffuse pixel keeps.
    pub hysteresis: f32,
    /// Motion, in pixels a frame, at which the hysteresis has fallen to a third.
    pub motion_pixels: f32,
    /// Relative depth difference past which last frame's pixel is another surface.
    pub depth_tolerance: f32,
    /// Smallest cosine between this and last frame's normal for the history to count.
    pub normal_tolerance: f32,
    /// Frames the screen's history holds: 0 on the first frame after a reset.
    pub history_frames: u32,
    /// 1: probe light fills what the screen does not cover.
    pub hybrid: u32,
    /// The farthest a sender may lie from its receiver (ssil+ddgi's near field, scene units);
    /// below 0: no limit.
    pub reach: f32,
    /// The last bounce gathers glossy reflection at surfaces rougher than this (GGX roughness):
    /// below 0 at every glossy surface, above 1 at none (`SsilSettings::glossy` off); in
    /// ssil+ddgi with DDGI's reflections their `max_roughness`, the roughest surface they trace.
    pub glossy_above: f32,
    /// Padding to a 16-byte multiple; 0.
    pub _pad1: u32,
    /// Padding to a 16-byte multiple; 0.
    pub _pad2: u32,
}
const _: () = assert!(size_of::<GpuSsilParams>() == 80);

/// What one dispatch works on.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable, PartialEq)]
pub struct GpuSsilPass {
    /// Pyramid level.
    pub level: u32,
    /// 1 at the start level: the whole disc instead of the ring.
    pub first: u32,
    /// 1 for the last bounce: the glossy gather.
    pub last_bounce: u32,
    /// Mip of the gather's light source that holds this level.
    pub radiance_level: u32,
    /// ssil/upsample: the pyramid level of the combined light above (none: 0).
    pub coarse_level: u32,
    /// ssil/upsample: 1 to add this level's own gather.
    pub with_gather: u32,
    /// Padding to a 16-byte multiple; 0.
    pub _pad0: u32,
    /// Padding to a 16-byte multiple; 0.
    pub _pad1: u32,
}
const _: () = assert!(size_of::<GpuSsilPass>() == 32);
