//! Light-field probes' GPU structs (`lightfield/lightfield.wgsl`, `filter.wgsl`, `trace_rays.wgsl`): one Rust definition
//! each, checked against the WGSL by `tests/gpu_structs.rs`.

use bytemuck::{Pod, Zeroable};

/// The probe grid and the maps' sizes, and how the frame shades with them.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuLightfieldParams {
    /// Position of probe (0, 0, 0).
    pub origin: [f32; 3],
    /// Probes in the grid.
    pub probe_count: u32,
    /// World distance between neighbouring probes along each axis.
    pub spacing: [f32; 3],
    /// Texels a side of the radiance, normal and distance maps.
    pub resolution: u32,
    /// Probes along each axis.
    pub counts: [u32; 3],
    /// Texels a side of the min-mip.
    pub low_resolution: u32,
    /// Surface thickness for a hit, in scene units, head-on and grazing.
    pub min_thickness: f32,
    /// Surface thickness for a hit at grazing views, in scene units.
    pub max_thickness: f32,
    /// Distance over which the thickness grows to its full value.
    pub thickness_distance: f32,
    /// Probes a ray may try before it takes the last point seen as its hit.
    pub max_probe_visits: u32,
    /// Longest distance the distance moments count (misses and far hits are clamped to it).
    pub max_distance: f32,
    /// Texels a side of the reduced maps the prefilters read.
    pub prefilter_resolution: u32,
    /// Emitter samples a probe texel takes in the bake's radiance pass.
    pub emitter_samples: u32,
    /// The bake's bounce (0: direct light only, no probe irradiance read).
    pub bounce: u32,
    /// ALGORITHM_* of lightfield::constants.
    pub algorithm: u32,
    /// Lambertian and glossy rays a pixel this frame.
    pub lambert_rays: u32,
    /// Glossy rays a pixel this frame (0: no glossy term).
    pub glossy_rays: u32,
    /// Frames rendered since the history last restarted.
    pub frame: u32,
    /// The filters' shares of history; 0 on a frame with no valid history.
    pub lambert_hysteresis: f32,
    /// The glossy filter's share of history; 0 on a frame with no valid history.
    pub glossy_hysteresis: f32,
    /// 1 when last frame's buffers hold a history to reproject, else 0.
    pub history_valid: u32,
    /// Pixels a side of the fast path's irradiance blocks (1: every pixel queried).
    pub irradiance_block: u32,
    /// Rougher surfaces trace no glossy ray (their specular light comes from the irradiance).
    pub glossy_max_roughness: f32,
    /// Padding to a 16-byte multiple; 0.
    pub _pad0: u32,
    /// Padding to a 16-byte multiple; 0.
    pub _pad1: u32,
    /// Padding to a 16-byte multiple; 0.
    pub _pad2: u32,
}
const _: () = assert!(size_of::<GpuLightfieldParams>() == 128);

/// One pass of the separable cross-bilateral filter.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct GpuLightfieldFilterPass {
    /// (1, 0) or (0, 1).
    pub direction: [i32; 2],
    /// Farthest tap, in pixels (0: the pass copies its input).
    pub radius: u32,
    /// Pixels between taps.
    pub stride: u32,
}

/// What the light field made of a test ray (`Lightfield::trace_rays`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuLightfieldHit {
    /// LF_HIT or LF_MISS (a ray every probe failed on is a hit at the last point seen).
    pub result: u32,
    /// Distance along the ray to the hit.
    pub t: f32,
    /// The probe that resolved it.
    pub probe: u32,
    /// Probes tried.
    pub visits: u32,
}
