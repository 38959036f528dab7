//! Light-field probes' GPU structs (`lightfield/lightfield.wgsl`, `filter.wgsl`, `trace_rays.wgsl`): one Rust definition
//! each, checked against the WGSL by `tests/gpu_structs.rs`.

use bytemuck::{Pod, Zeroable};

/// The probe grid and the maps' sizes, and how the frame shades with them.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuLightfieldParams {
    /// Position of probe (0, 0, 0).
    pub origin: [f32; 3],
    pub probe_count: u32,
    pub spacing: [f32; 3],
    /// Texels a side of the radiance, normal and distance maps.
    pub resolution: u32,
    pub counts: [u32; 3],
    /// Texels a side of the min-mip.
    pub low_resolution: u32,
    /// Surface thickness for a hit, in scene units, head-on and grazing.
    pub min_thickness: f32,
    pub max_thickness: f32,
    /// Distance over which the thickness grows to its full value.
    pub thickness_distance: f32,
    pub max_probe_visits: u32,
    /// Longest distance the distance moments count (misses and far hits are clamped to it).
    pub max_distance: f32,
    /// Texels a side of the reduced maps the prefilters read.
    pub prefilter_resolution: u32,
    pub emitter_samples: u32,
    /// The bake's bounce (0: direct light only, no probe irradiance read).
    pub bounce: u32,
    /// ALGORITHM_* of lightfield::constants.
    pub algorithm: u32,
    /// Lambertian and glossy rays a pixel this frame.
    pub lambert_rays: u32,
    pub glossy_rays: u32,
    pub frame: u32,
    /// The filters' shares of history; 0 on a frame with no valid history.
    pub lambert_hysteresis: f32,
    pub glossy_hysteresis: f32,
    pub history_valid: u32,
    /// Pixels a side of the fast path's irradiance blocks (1: every pixel queried).
    pub irradiance_block: u32,
    /// Rougher surfaces trace no glossy ray (their specular light comes from the irradiance).
    pub glossy_max_roughness: f32,
    pub _pad0: u32,
    pub _pad1: u32,
    pub _pad2: u32,
}
const _: () = assert!(size_of::<GpuLightfieldParams>() == 128);

/// One pass of the separable cross-bilateral filter.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct GpuLightfieldFilterPass {
    /// (1, 0) or (0, 1).
    pub direction: [i32; 2],
    pub radius: u32,
    pub stride: u32,
}

/// What the light field made of a test ray (`Lightfield::trace_rays`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuLightfieldHit {
    /// LF_HIT or LF_MISS (a ray every probe failed on is a hit at the last point seen).
    pub result: u32,
    pub t: f32,
    /// The probe that resolved it.
    pub probe: u32,
    /// Probes tried.
    pub visits: u32,
}
