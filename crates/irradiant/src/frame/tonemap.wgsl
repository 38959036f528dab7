// frame/tonemap: the frame's final linear radiance → exposure → filmic curve (ACES fit,
// Narkowicz 2015) or clamp → sRGB → the RGBA8 output texture a window presents and images
// are written from (CPU twin: Image::to_srgb8).
#import gbuffer

@group(2) @binding(0) var resolved: texture_2d<f32>;
@group(2) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;

fn aces_fit(x: vec3<f32>) -> vec3<f32> {
    return saturate((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14));
}

fn linear_to_srgb(c: vec3<f32>) -> vec3<f32> {
    let lo = c * 12.92;
    let hi = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(hi, lo, c <= vec3<f32>(0.0031308));
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    var c = max(textureLoad(resolved, id.xy, 0).rgb, vec3<f32>(0.0)) * frame.exposure;
    if frame.tone_curve == TONE_FILMIC {
        c = aces_fit(c);
    }
    textureStore(output, vec2<i32>(id.xy), vec4<f32>(linear_to_srgb(saturate(c)), 1.0));
}
