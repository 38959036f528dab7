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
    // a tracking window's circular buffer (ProbeGrid::phase): the slot of grid coordinate 0
    phase_x: u32,
    phase_y: u32,
    phase_z: u32,
    // the planes a window step brought in this frame (EnteringPlanes): xyz the first grid
    // coordinate along each axis, w 1 on the frame of a step
    entering_start: vec4<u32>,
    // xyz one past the last entering coordinate, w the frames an entered probe is relocated and
    // classified on its own (PROBE_FRESH_*)
    entering_end: vec4<u32>,
    // a volume that follows the camera or an instance: xyz the point its blend weights centre
    // on (ddgi/resolve, 003 §7.4), w 1; w 0 for a volume that stays
    blend_centre: vec4<f32>,
    // convergence rounds recorded this frame (ddgi_convergence); 0 in frames without them
    convergence_rounds: u32,
    // 1: probe rays leave their hits' probe light to ddgi/between_volumes (GpuDdgiDeferredRead)
    light_between_volumes: u32,
    padding1: u32,
    padding2: u32,
}

// 1 inside the volume's probe box by more than a cell, falling to 0 at its outermost probes
// (003 §7.4). For a volume that follows the camera or an instance, the same box tightened by a
// cell and centred on the target (blend_centre): a plane that leapfrogs ahead of the camera
// then lights nothing at once, and points pass from a coarser volume to this one gradually
// as the target comes near them, not when the window steps. The window keeps its centre
// within ¾ of a cell of the target (ProbeGrid::cells_to_centre), so the tightened box stays
// inside the probes.
fn volume_weight(p: vec3<f32>) -> f32 {
    var inside: vec3<f32>;
    if volume.blend_centre.w != 0.0 {
        let half = vec3<f32>(volume.counts - 1u) * volume.spacing * 0.5;
        inside = (half - volume.spacing - abs(p - volume.blend_centre.xyz)) / volume.spacing;
    } else {
        let last = volume.origin + vec3<f32>(volume.counts - 1u) * volume.spacing;
        inside = min(p - volume.origin, last - p) / volume.spacing;
    }
    // Axes with one probe have no extent to fade over.
    let fade = select(saturate(inside), vec3<f32>(1.0), volume.counts == vec3<u32>(1u));
    return fade.x * fade.y * fade.z;
}

// The share of a point's light this volume gives, when the finer volumes gave `taken`: the
// weight they left where the point lies inside it (volume_weight), and all that is left for
// the coarsest, so that the shares add up to 1 (003 §7.4: densest first, until the weights
// reach 1).
fn volume_share(p: vec3<f32>, taken: f32) -> f32 {
    var share = max(1.0 - taken, 0.0);
    if volume.volume_is_last == 0u {
        share *= volume_weight(p);
    }
    return share;
}

// Whether the pixels of image tile `tile` (IMAGE_TILE pixels a side: one workgroup, so that
// no warp waits on a few tracing lanes) gather in frame `frame_index`: one tile in every
// `gather_interval`, in turn, neighbours on different frames.
fn gather_tile_traces(tile: vec2<u32>, frame_index: u32) -> bool {
    return (tile.x + 3u * tile.y + frame_index) % max(volume.gather_interval, 1u) == 0u;
}

fn window_phase() -> vec3<u32> {
    return vec3<u32>(volume.phase_x, volume.phase_y, volume.phase_z);
}

// The slot (the index into every per-probe buffer and atlas tile) of the probe at grid
// coordinates `coord`: a tracking window stores its grid as a circular buffer (ProbeGrid::slot).
fn probe_index(coord: vec3<u32>) -> u32 {
    return grid_index((coord + window_phase()) % volume.counts, volume.counts);
}

// The grid coordinates of the probe in slot `probe` (ProbeGrid::coord).
fn probe_grid_coord(probe: u32) -> vec3<u32> {
    return (grid_coord(probe, volume.counts) + volume.counts - window_phase()) % volume.counts;
}

// Where a probe sits on the regular grid, before relocation.
fn grid_position(probe: u32) -> vec3<f32> {
    return grid_position_at(probe_grid_coord(probe));
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
