//! The frame's GPU structs (`frame/frame_types.wgsl`): one Rust definition each, checked against
//! the WGSL by `tests/gpu_structs.rs`.

use bytemuck::{Pod, Zeroable};

use crate::scene::types::GpuCamera;

/// The real-time frame's parameters, written once a frame.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuFrameParams {
    /// The view this frame renders.
    pub camera: GpuCamera,
    /// Last frame's view (this frame's on the first), for motion vectors and reprojection.
    pub previous_camera: GpuCamera,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Frames recorded since the frame was made: seeds per-frame random numbers.
    pub frame_index: u32,
    /// Emitter samples per pixel per frame for direct light from emissive surfaces.
    pub area_light_samples: u32,
    /// Random seed of the frame's sampling.
    pub seed: u32,
    /// Frames already in the direct-light running mean; 0 restarts it.
    pub accumulated_frames: u32,
    /// Sub-pixel offset of this frame's primary rays, in pixels (zero without TAA).
    pub jitter: [f32; 2],
    /// The share of the current frame in the TAA blend once the history is warm; 1: no TAA.
    pub taa_blend: f32,
    /// Frames in the TAA history; 0 when it holds nothing usable.
    pub history_frames: u32,
    /// Neighbourhood clip box half-width, in standard deviations.
    pub taa_clip_sigma: f32,
    /// frame/tonemap's multiplier before the curve.
    pub exposure: f32,
    /// [`super::constants::TONE_FILMIC`] or [`super::constants::TONE_CLAMP`].
    pub tone_curve: u32,
    /// The G-buffer pyramid's voting filter: Gaussian widths of the pixel distance, of
    /// 1 − n·n' and of the relative depth difference.
    pub pyramid_pixel_sigma: f32,
    /// Gaussian width of 1 − n·n' in the pyramid's voting filter.
    pub pyramid_normal_sigma: f32,
    /// Gaussian width of the relative depth difference in the pyramid's voting filter.
    pub pyramid_depth_sigma: f32,
    /// Emitter candidates a pixel draws (0: resampling off).
    pub emitter_candidates: u32,
    /// The most candidates last frame's reservoir may count for (0: no temporal reuse, or
    /// nothing to reuse).
    pub reservoir_history: u32,
    /// Neighbours a pixel takes reservoirs from.
    pub reuse_neighbours: u32,
    /// How far those neighbours lie, in pixels.
    pub reuse_radius: f32,
    /// 1: a shadow ray from each neighbour tells whether it could have drawn the winner
    /// (unbiased); 0: its unshadowed target value is enough.
    pub reuse_visibility: u32,
    /// Emitter candidates a pixel with no history draws (`emitter_candidates` where a still
    /// view joins its mean).
    pub cut_candidates: u32,
    /// Neighbours a pixel with no history takes reservoirs from.
    pub cut_neighbours: u32,
    /// 1: no pixel takes another's reservoir or last frame's this frame (a still view after
    /// its first frame), so frame/direct does not run and frame/direct_reuse draws each
    /// pixel's candidates itself.
    pub direct_in_reuse: u32,
    /// 1: no pixel takes another's reservoir or last frame's this frame, and the candidates
    /// pick along each pixel's sequence (`ResamplingSettings::pick_sequence`).
    pub pick_sequence: u32,
    /// Padding to WGSL's size of the struct (a multiple of 16 bytes); 0.
    pub _pad: [u32; 3],
}
const _: () = assert!(size_of::<GpuFrameParams>() == 240);
