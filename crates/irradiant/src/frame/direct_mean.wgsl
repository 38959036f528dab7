// The frame's direct light (`direct`) and its diffuse part (`direct_diffuse`, what
// frame/pyramid hands screen-space gathers): running means while the view and the scene stay
// still, which frame/direct or, with emitter resampling, frame/direct_reuse keeps.
#import gbuffer
#import lights
#import random
#import resampling

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

// Where a pixel's own candidates take their picks. In a frame where no pixel takes another's
// reservoir or last frame's (a still view's frames after its first, unless `unbiased`; the host
// decides, `pick_sequence`), each frame only adds to the pixel's own mean, and the picks walk one
// golden-ratio sequence through those frames (PickSequence): frame f's candidates are its points
// f·c to f·c + c − 1. Each pixel's turn of it follows interleaved gradient noise (Jimenez 2014),
// turned as a whole by the seed, so that neighbouring pixels pick differently and their noise
// averages out where the eye blurs them. Where reservoirs are shared the picks stay independent: a
// neighbour whose sequence runs alongside would hand over the candidates the pixel drew itself.
fn candidate_sequence(pixel_index: u32) -> PickSequence {
    let pixel = vec2<f32>(f32(pixel_index % frame.width), f32(pixel_index / frame.width));
    let seed_turn = f32(pcg_hash(frame.seed ^ 0x9e3779b9u) >> 8u) * (1.0 / 16777216.0);
    let shift = fract(52.9829189 * fract(dot(pixel, vec2<f32>(0.06711056, 0.00583715))) + seed_turn);
    return PickSequence(frame.pick_sequence != 0u, shift, frame.frame_index * frame.cut_candidates);
}

// The punctual lights' direct light at `pixel` (none where the camera ray left the scene).
fn punctual_light_at(pixel: vec2<u32>) -> DirectLight {
    if gbuffer_depth_at(pixel) < 0.0 {
        return DirectLight(vec3<f32>(0.0), vec3<f32>(0.0));
    }
    let s = gbuffer_surface(pixel);
    return direct_punctual_split(s, view_dir(s.position));
}
