// ddgi: the probe volume's parameters and addressing, shared by every DDGI pass.
#import octahedral

const WEIGHT_BACKFACE: u32 = 1u;
const WEIGHT_CHEBYSHEV: u32 = 2u;
// Production rule (003, §4.1): rays that hit backfaces record no light and 80 % shorter depth.
const WEIGHT_BACKFACE_HITS: u32 = 4u;
const BACKFACE_DEPTH_SCALE: f32 = 0.2;

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
    // world-space bias = (n·0.2 + ωo·0.8) · 0.75 · min_spacing · self_shadow_bias
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
}

fn probe_grid_coord(probe: u32) -> vec3<u32> {
    let c = volume.counts;
    return vec3<u32>(probe % c.x, (probe / c.x) % c.y, probe / (c.x * c.y));
}

fn probe_index(coord: vec3<u32>) -> u32 {
    let c = volume.counts;
    return coord.x + c.x * (coord.y + c.y * coord.z);
}

// Where a probe sits on the regular grid, before relocation.
fn grid_position(probe: u32) -> vec3<f32> {
    return volume.origin + vec3<f32>(probe_grid_coord(probe)) * volume.spacing;
}

// Top-left texel of a probe's tile (side `tile` texels, border included) in an atlas.
fn tile_origin(probe: u32, tile: u32) -> vec2<u32> {
    return vec2<u32>(probe % volume.probes_per_row, probe / volume.probes_per_row) * tile;
}

fn atlas_width(tile: u32) -> u32 {
    return volume.probes_per_row * tile;
}

// The world direction that an interior texel (i, j) of a tile of `texels` interior texels stands for.
fn texel_direction(texel: vec2<u32>, texels: u32) -> vec3<f32> {
    let uv = (vec2<f32>(texel) + 0.5) / f32(texels) * 2.0 - 1.0;
    return oct_decode(uv);
}

// The tile texel (border included, so interior texels are 1…texels) whose value border
// texel (x, y) repeats, mirrored as the octahedral map folds, so that bilinear filtering is
// seamless across the map's edges (CPU twin: ddgi::octahedral::border_source).
fn border_source(x: u32, y: u32, texels: u32) -> vec2<u32> {
    let last = texels + 1u;
    let corner_x = select(1u, texels, x == 0u);
    let corner_y = select(1u, texels, y == 0u);
    if (x == 0u || x == last) && (y == 0u || y == last) {
        return vec2<u32>(corner_x, corner_y);
    }
    if y == 0u || y == last {
        return vec2<u32>(last - x, select(texels, 1u, y == 0u));
    }
    return vec2<u32>(select(texels, 1u, x == 0u), last - y);
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
