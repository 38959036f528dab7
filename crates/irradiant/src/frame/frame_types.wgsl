// The real-time frame's parameters (Rust: frame::types::GpuFrameParams).
#import types
#import frame_constants

struct GpuFrameParams {
    camera: GpuCamera,
    previous_camera: GpuCamera,
    width: u32,
    height: u32,
    frame_index: u32,
    // emitter samples per pixel per frame for direct light from emissive surfaces
    area_light_samples: u32,
    seed: u32,
    // frames already in the direct-light running mean; 0 restarts it
    accumulated_frames: u32,
    // sub-pixel offset of this frame's primary rays, in pixels (zero without TAA)
    jitter: vec2<f32>,
    // the share of the current frame in the TAA blend once the history is warm; 1: no TAA
    taa_blend: f32,
    // frames in the TAA history; 0 when it holds nothing usable (first frame, reset)
    history_frames: u32,
    // neighbourhood clip box half-width, in standard deviations
    taa_clip_sigma: f32,
    // frame/tonemap: multiplier before the curve, and TONE_FILMIC or TONE_CLAMP
    exposure: f32,
    tone_curve: u32,
    // the G-buffer pyramid's voting filter (frame/pyramid_down): Gaussian widths of the pixel
    // distance, of 1 − n·n' and of the relative depth difference
    pyramid_pixel_sigma: f32,
    pyramid_normal_sigma: f32,
    pyramid_depth_sigma: f32,
    // emitter candidates a pixel draws (0: resampling off), the most candidates last frame's
    // reservoir counts for (0: no temporal reuse), neighbours and their radius in pixels
    emitter_candidates: u32,
    reservoir_history: u32,
    reuse_neighbours: u32,
    reuse_radius: f32,
    // 1: a shadow ray from each neighbour tells whether it could have drawn the winner
    // (unbiased); 0: its unshadowed target value is enough
    reuse_visibility: u32,
    // what a pixel with no history takes instead of emitter_candidates and reuse_neighbours:
    // the first frame after a cut, pixels a moving view uncovers
    cut_candidates: u32,
    cut_neighbours: u32,
    // 1: no pixel takes another's reservoir or last frame's, so frame/direct does not run and
    // frame/direct_reuse draws each pixel's candidates itself
    direct_in_reuse: u32,
    // 1: no pixel takes another's reservoir or last frame's, and the candidates pick along
    // each pixel's sequence
    pick_sequence: u32,
}

// Pixel coordinates (y down, continuous: pixel centres at .5) of a world point seen by a camera.
fn project(cam: GpuCamera, p: vec3<f32>, size: vec2<f32>) -> vec2<f32> {
    let d = p - cam.position;
    let z = max(dot(d, cam.forward), 1e-6);
    let ndc = vec2<f32>(dot(d, cam.right) / (z * cam.tan_half_fov_y * cam.aspect), dot(d, cam.up) / (z * cam.tan_half_fov_y));
    return vec2<f32>((ndc.x + 1.0) * 0.5 * size.x, (1.0 - ndc.y) * 0.5 * size.y);
}
