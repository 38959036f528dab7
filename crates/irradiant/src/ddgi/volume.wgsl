// ddgi: the probe volume's parameters and addressing, shared by every DDGI pass (the
// constants WEIGHT_*, BACKFACE_DEPTH_SCALE and the probe states come from ddgi::constants).
#import ddgi_constants
#import probe_grid
#import probe_atlas

struct GpuDdgiVolume {
    // position of probe (0, 0, 0)
    origin: vec3<f32>,
    probe_count: u32,
    spacing: vec3<f32>,
    rays_per_probe: u32,
    counts: vec3<u32>,
    // probes per row of the atlases
    probes_per_row: u32,
    // rows of this frame's random rotation of the ray set
    ray_rotation0: vec4<f32>,
    ray_rotation1: vec4<f32>,
    ray_rotation2: vec4<f32>,
    // interior texels per side of a probe's octahedral tile (the tile adds a 1-texel border)
    irradiance_texels: u32,
    distance_texels: u32,
    irradiance_hysteresis: f32,
    distance_hysteresis: f32,
    max_ray_distance: f32,
    // world-space bias = (n·0.2 + ωo·0.8) · 0.75 · spacing · self_shadow_bias, per axis
    self_shadow_bias: f32,
    // cosine power of the distance blend
    distance_exponent: f32,
    // perceptual encoding: irradiance is stored as value^(1/gamma)
    irradiance_gamma: f32,
    // WEIGHT_* bits
    weights: u32,
    // frames since the volume was created; 0 blends with hysteresis 0
    frame: u32,
    min_spacing: f32,
    // 1 when the per-texel convergence thresholds (003, §4.3) are on
    convergence_heuristics: u32,
    // 1 while probes are being relocated (003, §5)
    relocating: u32,
    // 1: probe rays shade every punctual light; 0: one, chosen at random
    all_lights: u32,
    // STATES_* (ddgi/states.wgsl)
    state_phase: u32,
    // boxes in the wake-box buffer
    wake_box_count: u32,
    // this volume's place among the technique's volumes, finest first (ddgi/resolve blends
    // them in that order)
    volume_index: u32,
    // 1 for the coarsest volume, which fills whatever weight the finer ones left
    volume_is_last: u32,
    // hysteresis of the bounce copy of irradiance that probe rays read (ddgi/blend_irradiance)
    bounce_hysteresis: f32,
    // cells past the outermost probes that the query extrapolates (DdgiUpdateSettings)
    extrapolation: f32,
    // query weight of a probe that left geometry by a tied exit (DdgiUpdateSettings)
    tied_probe_weight: f32,
    // 1 with `speed.probe_states` off: every probe traces and blends, while the states still
    // decide which probes the query reads, so that the image is the same
    every_probe_updates: u32,
    // 1: probes left inside geometry stay on and shade (DdgiUpdateSettings)
    shade_probes_in_geometry: u32,
    // frames the final gather's running mean spans at most (DdgiGatherSettings)
    gather_history_frames: u32,
    // frames between a pixel's gathers (DdgiGatherSettings::pixel_interval)
    gather_interval: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// Whether the pixels of image tile `tile` (IMAGE_TILE pixels a side: one workgroup, so that
// no warp waits on a few tracing lanes) gather in frame `frame_index`: one tile in every
// `gather_interval`, in turn, neighbours on different frames.
fn gather_tile_traces(tile: vec2<u32>, frame_index: u32) -> bool {
    return (tile.x + 3u * tile.y + frame_index) % max(volume.gather_interval, 1u) == 0u;
}

fn probe_index(coord: vec3<u32>) -> u32 {
    return grid_index(coord, volume.counts);
}

// Where a probe sits on the regular grid, before relocation.
fn grid_position(probe: u32) -> vec3<f32> {
    return grid_position_at(grid_coord(probe, volume.counts));
}

// The same from the probe's grid coordinates.
fn grid_position_at(coord: vec3<u32>) -> vec3<f32> {
    return volume.origin + vec3<f32>(coord) * volume.spacing;
}

// Top-left texel of a probe's tile (side `tile` texels, border included) in an atlas.
fn tile_origin(probe: u32, tile: u32) -> vec2<u32> {
    return atlas_tile_origin(probe, tile, volume.probes_per_row);
}

fn atlas_width(tile: u32) -> u32 {
    return volume.probes_per_row * tile;
}

fn rotate_ray(d: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(volume.ray_rotation0.xyz, d), dot(volume.ray_rotation1.xyz, d), dot(volume.ray_rotation2.xyz, d));
}

// A probe that starts updating (a new volume, or a probe just woken) is a running mean
// (after f blends it keeps f/(f+1) of the old value) until that reaches the set hysteresis:
// it converges in tens of frames from nothing instead of creeping up at 1 − hysteresis a
// frame, and its first blend (hysteresis 0) discards whatever it held.
fn startup_hysteresis(hysteresis: f32, blends: u32) -> f32 {
    let f = f32(blends);
    return min(hysteresis, f / (f + 1.0));
}
