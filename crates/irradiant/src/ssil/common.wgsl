// ssil: what every screen-space indirect illumination pass shares — its parameters, the
// G-buffer pyramid's positions, and the voxel grid's depth slices (Soler et al. 2009).
#import frame_types
#import ssil_constants
#import sampling
#import camera

struct GpuSsilParams {
    // pyramid level of the first gather (0 full, 1 half, 2 quarter resolution)
    start_level: u32,
    levels: u32,
    samples: u32,
    // 1: march the voxel grid for visibility
    visibility: u32,
    // r, in pixels of every level
    radius: f32,
    // the voxel grid's 128 slices span these view depths
    near: f32,
    far: f32,
    visibility_steps: u32,
    visibility_bias: f32,
    importance_alpha: f32,
    hysteresis: f32,
    motion_pixels: f32,
    depth_tolerance: f32,
    normal_tolerance: f32,
    // Frames the screen's history holds: 0 on the first frame after a reset
    history_frames: u32,
    // 1: probe light fills what the screen does not cover (ssil+ddgi)
    hybrid: u32,
    // the farthest a sender may lie from its receiver (ssil+ddgi's near field); < 0: no limit
    reach: f32,
    // the last bounce gathers glossy reflection at surfaces rougher than this (> 1: none)
    glossy_above: f32,
    _pad1: u32,
    _pad2: u32,
}

// The level a dispatch works on.
struct GpuSsilPass {
    // pyramid level
    level: u32,
    // 1 at the start level: the gather samples the whole disc instead of the ring r/2…r
    first: u32,
    // 1 for the last bounce: the glossy gather
    last_bounce: u32,
    // mip of `source_radiance` that holds this level's light
    radiance_level: u32,
    // ssil/upsample: the pyramid level of the combined light above (0: none, the coarsest)
    coarse_level: u32,
    // ssil/upsample: 1 to add this level's own gather (0 for the pass to full resolution)
    with_gather: u32,
    _pad0: u32,
    _pad1: u32,
}

// Full-resolution pixel coordinates of the centre of texel p of pyramid level `level`.
fn level_to_image(p: vec2<f32>, level: u32) -> vec2<f32> {
    return p * f32(1u << level);
}

fn level_size(level: u32) -> vec2<u32> {
    return max(vec2<u32>(frame.width, frame.height) >> vec2<u32>(level), vec2<u32>(1u));
}

// The world position of texel p of a level whose view depth (along the camera's forward axis)
// is `depth`: on the unjittered ray through the texel's centre.
fn level_position(p: vec2<u32>, level: u32, depth: f32) -> vec3<f32> {
    let size = vec2<f32>(f32(frame.width), f32(frame.height));
    let dir = camera_ray_dir(frame.camera, level_to_image(vec2<f32>(p) + 0.5, level), size);
    return frame.camera.position + dir * (depth / max(dot(dir, frame.camera.forward), 1e-6));
}

fn view_depth(p: vec3<f32>) -> f32 {
    return dot(p - frame.camera.position, frame.camera.forward);
}

// The voxel slice of a view depth (may lie outside 0…127).
fn slice_of(depth: f32) -> i32 {
    return i32(floor((depth - ssil.near) / max(ssil.far - ssil.near, 1e-6) * f32(SLICES)));
}

fn voxel_bit(mask: vec4<u32>, slice: i32) -> bool {
    if slice < 0 || slice >= i32(SLICES) {
        return false;
    }
    let s = u32(slice);
    return ((mask[s / 32u] >> (s % 32u)) & 1u) != 0u;
}
