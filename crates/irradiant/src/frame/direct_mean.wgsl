// The frame's direct light (`direct`) and its diffuse part (`direct_diffuse`, what
// frame/pyramid hands screen-space gathers): running means while the view and the scene stay
// still, which frame/direct or, with emitter resampling, frame/direct_reuse keeps.
#import gbuffer
#import lights
#import random

@group(2) @binding(0) var direct: texture_storage_2d<rgba32float, read_write>;
@group(2) @binding(4) var direct_diffuse: texture_storage_2d<rgba32float, read_write>;

// Stores this frame's direct light at `pixel`, averaged with the frames before it since the
// last restart (`accumulated_frames` 0: it starts over).
fn keep_direct_mean(pixel: vec2<u32>, light: DirectLight) {
    let n = f32(frame.accumulated_frames);
    let restart = frame.accumulated_frames == 0u;
    let total = select(mix(textureLoad(direct, pixel).rgb, light.total, 1.0 / (n + 1.0)), light.total, restart);
    let diffuse = select(mix(textureLoad(direct_diffuse, pixel).rgb, light.diffuse, 1.0 / (n + 1.0)), light.diffuse, restart);
    textureStore(direct, pixel, vec4<f32>(total, 1.0));
    textureStore(direct_diffuse, pixel, vec4<f32>(diffuse, 1.0));
}

// The random stream a pixel's own candidates are drawn from, which frame/direct and
// frame/direct_reuse seed alike, so that a frame whose frame/direct_reuse draws them
// (`direct_in_reuse`) shows what frame/direct would have drawn.
fn candidate_stream(pixel_index: u32) -> u32 {
    return rng_seed(pixel_index, frame.frame_index, frame.seed ^ 0x2545f491u);
}

// The punctual lights' direct light at `pixel` (none where the camera ray left the scene).
fn punctual_light_at(pixel: vec2<u32>) -> DirectLight {
    if gbuffer_depth_at(pixel) < 0.0 {
        return DirectLight(vec3<f32>(0.0), vec3<f32>(0.0));
    }
    let s = gbuffer_surface(pixel);
    return direct_punctual_split(s, view_dir(s.position));
}
