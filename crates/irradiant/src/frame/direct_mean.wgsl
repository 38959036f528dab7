// The frame's direct light (`direct`): a running mean while the view and the scene stay still,
// which frame/direct or, with emitter resampling, frame/direct_reuse keeps.
#import gbuffer

@group(2) @binding(0) var direct: texture_storage_2d<rgba32float, read_write>;

// Stores this frame's direct light at `pixel`, averaged with the frames before it since the
// last restart (`accumulated_frames` 0: it starts over).
fn keep_direct_mean(pixel: vec2<u32>, light: vec3<f32>) {
    let n = f32(frame.accumulated_frames);
    let previous = textureLoad(direct, pixel).rgb;
    textureStore(direct, pixel, vec4<f32>(select(light, mix(previous, light, 1.0 / (n + 1.0)), frame.accumulated_frames > 0u), 1.0));
}
