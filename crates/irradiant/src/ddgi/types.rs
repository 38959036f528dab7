//! DDGI's GPU structs (`ddgi/volume.wgsl`, `ddgi/rays.wgsl`): one Rust definition each,
//! checked against the WGSL by `tests/gpu_structs.rs`.

use bytemuck::{Pod, Zeroable};

/// A DDGI probe volume's parameters (`ddgi/volume.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuDdgiVolume {
    pub origin: [f32; 3],
    pub probe_count: u32,
    pub spacing: [f32; 3],
    pub rays_per_probe: u32,
    pub counts: [u32; 3],
    pub probes_per_row: u32,
    pub ray_rotation0: [f32; 4],
    pub ray_rotation1: [f32; 4],
    pub ray_rotation2: [f32; 4],
    pub irradiance_texels: u32,
    pub distance_texels: u32,
    pub irradiance_hysteresis: f32,
    pub distance_hysteresis: f32,
    pub max_ray_distance: f32,
    pub self_shadow_bias: f32,
    pub distance_exponent: f32,
    pub irradiance_gamma: f32,
    /// `WEIGHT_*` bits of [`super::constants`].
    pub weights: u32,
    pub frame: u32,
    pub min_spacing: f32,
    pub convergence_heuristics: u32,
    /// 1 while probes are being relocated (the volume's first frames).
    pub relocating: u32,
    /// 1: probe rays shade every punctual light; 0: one chosen at random.
    pub all_lights: u32,
    /// `STATES_*` of [`super::constants`]: off, classifying, classifying for the last time, or
    /// classified (probes sleep and wake).
    pub state_phase: u32,
    /// Boxes in the wake-box buffer (around animated instances).
    pub wake_box_count: u32,
    /// This volume's place among the technique's volumes, finest first.
    pub volume_index: u32,
    /// 1 for the coarsest volume, which fills whatever weight the finer ones left.
    pub volume_is_last: u32,
    /// Hysteresis of the bounce copy of irradiance that probe rays read.
    pub bounce_hysteresis: f32,
    /// Cells past the outermost probes that the query extrapolates.
    pub extrapolation: f32,
    /// Query weight of a probe that left geometry by a tied exit (ddgi/relocate).
    pub tied_probe_weight: f32,
    /// 1 with `speed.probe_states` off: every probe traces and blends; the states still
    /// decide which probes the query reads, so that the image is the same.
    pub every_probe_updates: u32,
    /// 1: probes left inside geometry stay on and shade (classic probes' baseline).
    pub shade_probes_in_geometry: u32,
    /// Frames the final gather's running mean spans at most (ddgi/temporal).
    pub gather_history_frames: u32,
    /// Frames between a pixel's gathers (`DdgiGatherSettings::pixel_interval`).
    pub gather_interval: u32,
    pub _pad0: u32,
    pub _pad1: u32,
    pub _pad2: u32,
}
const _: () = assert!(size_of::<GpuDdgiVolume>() == 208);

/// A probe ray's closest hit; `t` < 0 for a miss; `bary` is `pack2x16unorm`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuDdgiRayHit {
    pub t: f32,
    pub triangle: u32,
    pub instance: u32,
    pub bary: u32,
}

/// The radiance a probe ray brought back and the distance it travelled (negative: a backface).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuDdgiRaySample {
    pub radiance: [f32; 3],
    pub distance: f32,
}

/// A probe ray's shadow ray, queued by ddgi/shade for ddgi/shadow (`DdgiSettings::shadow_queue`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuDdgiShadowRay {
    pub origin: [f32; 3],
    /// Index of the probe ray's [`GpuDdgiRaySample`].
    pub sample: u32,
    /// The light's f · L · cos if nothing blocks it.
    pub contribution: [f32; 3],
    /// Index into the scene's lights.
    pub light: u32,
}
const _: () = assert!(size_of::<GpuDdgiShadowRay>() == 32);

/// One ray's weight in one texel's blend (ddgi/blend_weights.wgsl); a texel's header entry
/// holds its entry count in `ray` and their weight sum in `weight`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuDdgiBlendWeight {
    pub ray: u32,
    pub weight: f32,
}
