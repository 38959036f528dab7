//! DDGI's GPU structs (`ddgi/volume.wgsl`, `ddgi/rays.wgsl`): one Rust definition each,
//! checked against the WGSL by `tests/gpu_structs.rs`.

use bytemuck::{Pod, Zeroable};

/// A DDGI probe volume's parameters (`ddgi/volume.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuDdgiVolume {
    /// World position of probe (0, 0, 0), before relocation.
    pub origin: [f32; 3],
    /// Probes in the volume.
    pub probe_count: u32,
    /// World distance between neighbouring probes along each axis.
    pub spacing: [f32; 3],
    /// Rays each probe traces a frame.
    pub rays_per_probe: u32,
    /// Probes along each axis.
    pub counts: [u32; 3],
    /// Probe tiles in each row of the atlases.
    pub probes_per_row: u32,
    /// Row 0 of this frame's random rotation of the ray set (w unused).
    pub ray_rotation0: [f32; 4],
    /// Row 1 of the rotation.
    pub ray_rotation1: [f32; 4],
    /// Row 2 of the rotation.
    pub ray_rotation2: [f32; 4],
    /// Interior texels a side of a probe's irradiance tile (the tile adds a 1-texel border).
    pub irradiance_texels: u32,
    /// Interior texels a side of a probe's distance tile (the tile adds a 1-texel border).
    pub distance_texels: u32,
    /// Share of the old irradiance each blend keeps, lowered for a while after a scene change.
    pub irradiance_hysteresis: f32,
    /// Share of the old distance moments each blend keeps.
    pub distance_hysteresis: f32,
    /// Longest probe ray, in scene units; misses count as this far.
    pub max_ray_distance: f32,
    /// Self-shadow bias in probe cells: world bias = (n·0.2 + ωo·0.8) · 0.75 · spacing · this.
    /// 0 unless every weight is on.
    pub self_shadow_bias: f32,
    /// Cosine power of the distance blend.
    pub distance_exponent: f32,
    /// Perceptual encoding: irradiance is stored as value^(1/gamma).
    pub irradiance_gamma: f32,
    /// `WEIGHT_*` bits of [`super::constants`].
    pub weights: u32,
    /// Frames blended so far; 0 blends with hysteresis 0 (the probes start over).
    pub frame: u32,
    /// The smallest of `spacing`'s three axes.
    pub min_spacing: f32,
    /// 1 when the per-texel convergence thresholds (003 §4.3) are on, else 0.
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
    /// The slot of grid coordinate 0 along x of a tracking window (`ProbeGrid::phase`); 0 for a
    /// volume that stays.
    pub phase_x: u32,
    /// The same along y.
    pub phase_y: u32,
    /// The same along z.
    pub phase_z: u32,
    /// The planes a window step brought in this frame (`EnteringPlanes`): first coordinate
    /// along each axis; w is 1 on the frame of a step, when ddgi/window_enter runs.
    pub entering_start: [u32; 4],
    /// One past the last entering coordinate along each axis; w: the frames a probe that
    /// entered keeps being relocated and classified on its own (PROBE_FRESH_*).
    pub entering_end: [u32; 4],
    /// A volume that follows the camera or an instance: xyz the point its blend weights centre
    /// on (ddgi/resolve, 003 §7.4), w 1; w 0 for a volume that stays.
    pub blend_centre: [f32; 4],
    /// Convergence rounds recorded this frame (`update.convergence_rounds`, ddgi_convergence);
    /// 0 in frames without them.
    pub convergence_rounds: u32,
    /// 1: probe rays leave the probes' light at their hits to ddgi/between_volumes, which
    /// reads it from every volume that covers the hit (`update.light_between_volumes`, with
    /// several volumes); 0: each ray reads its own volume in ddgi/shade.
    pub light_between_volumes: u32,
    /// Pads the struct to a multiple of 16 bytes.
    pub padding1: u32,
    /// Padding.
    pub padding2: u32,
}
const _: () = assert!(size_of::<GpuDdgiVolume>() == 272);

/// A probe ray's closest hit; `t` < 0 for a miss; `bary` is `pack2x16unorm`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuDdgiRayHit {
    /// Distance to the hit; negative for a miss.
    pub t: f32,
    /// GPU triangle slot hit.
    pub triangle: u32,
    /// Instance hit, in instance-buffer order.
    pub instance: u32,
    /// The hit's barycentrics (u, v), `pack2x16unorm`.
    pub bary: u32,
}

/// The radiance a probe ray brought back and the distance it travelled (negative: a backface).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuDdgiRaySample {
    /// Radiance arriving at the probe along the ray.
    pub radiance: [f32; 3],
    /// Distance to what the ray hit (`max_ray_distance` for a miss); negative for a backface.
    pub distance: f32,
}

/// A probe ray's shadow ray, queued by ddgi/shade for ddgi/shadow (`DdgiSettings::shadow_queue`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuDdgiShadowRay {
    /// Start of the shadow ray: the hit point, offset off its surface.
    pub origin: [f32; 3],
    /// Index of the probe ray's [`GpuDdgiRaySample`].
    pub sample: u32,
    /// The light's f · L · cos if nothing blocks it.
    pub contribution: [f32; 3],
    /// Index into the scene's lights.
    pub light: u32,
}
const _: () = assert!(size_of::<GpuDdgiShadowRay>() == 32);

/// A probe ray's hit whose probe light ddgi/shade leaves to ddgi/between_volumes: each volume
/// that covers the point adds its share (003 §7.4's weights, finest first), so that light
/// passes between volumes. Scalars only, 36 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuDdgiDeferredRead {
    /// Where the probes are read: the probe ray's hit, or with the traced bounce the traced
    /// ray's.
    pub position: [f32; 3],
    /// How far the viewer of the point is: 0 for a probe ray's own hit (read as the probe
    /// rays read), the traced ray's length for a traced bounce's hit (read as a ray from a
    /// surface reads, `ddgi_irradiance_seen_from`).
    pub viewer_distance: f32,
    /// Shading normal, octahedral, `pack2x16snorm`.
    pub normal: u32,
    /// Geometric normal, the same: where a ray traced on starts.
    pub geometric_normal: u32,
    /// Towards the viewer, the same.
    pub wo: u32,
    /// What the read irradiance is multiplied by on its way to the probe (r, g), `pack2x16float`.
    pub weight_rg: u32,
    /// The same's b, and the share of the volumes' weight given so far (1: nothing to read).
    pub weight_b_taken: u32,
}
const _: () = assert!(size_of::<GpuDdgiDeferredRead>() == 36);

/// One ray's weight in one texel's blend (ddgi/blend_weights.wgsl); a texel's header entry
/// holds its entry count in `ray` and their weight sum in `weight`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuDdgiBlendWeight {
    /// The ray's index in the probe's ray set; in a header, the texel's entry count.
    pub ray: u32,
    /// The ray's weight in the texel's blend; in a header, the texel's weight sum.
    pub weight: f32,
}
