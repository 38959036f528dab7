// frame/pyramid_down: one level of the G-buffer pyramid from the level below (Soler et al.
// 2009, §4). Normal and depth are not averaged — averages make surfaces that are not there —
// but voted (eq. 5): of the 2×2 texels under the target, the one whose neighbourhood (itself
// and its 4 neighbours) agrees most with it, by a Gaussian of the pixel distance, of 1 − n·n'
// and of the relative depth difference (frame.pyramid_*_sigma), lends its normal and depth, so
// large surfaces win over small inconsistent ones. Radiance and albedo are the mean of the
// texels under the target that see a surface; a texel whose four all see the sky sees the sky.
#import frame_types

@group(0) @binding(0) var source_normal_depth: texture_2d<f32>;
@group(0) @binding(1) var source_radiance: texture_2d<f32>;
@group(0) @binding(2) var source_albedo: texture_2d<f32>;
@group(0) @binding(3) var target_normal_depth: texture_storage_2d<rgba32float, write>;
@group(0) @binding(4) var target_radiance: texture_storage_2d<rgba16float, write>;
@group(0) @binding(5) var target_albedo: texture_storage_2d<rgba16float, write>;
@group(1) @binding(0) var<uniform> frame: GpuFrameParams;

fn gaussian(x: f32, sigma: f32) -> f32 {
    return exp(-x * x / (2.0 * sigma * sigma));
}

// Eq. 5's score of source texel p: how much its neighbourhood agrees with it.
fn vote(p: vec2<i32>, size: vec2<i32>) -> f32 {
    let own = textureLoad(source_normal_depth, p, 0);
    let offsets = array<vec2<i32>, 5>(vec2<i32>(0, 0), vec2<i32>(1, 0), vec2<i32>(-1, 0), vec2<i32>(0, 1), vec2<i32>(0, -1));
    var score = 0.0;
    for (var k = 0; k < 5; k++) {
        let q = p + offsets[k];
        if any(q < vec2<i32>(0)) || any(q >= size) {
            continue;
        }
        let other = textureLoad(source_normal_depth, q, 0);
        if other.w < 0.0 {
            continue;
        }
        let distance = f32(abs(offsets[k].x) + abs(offsets[k].y));
        score += gaussian(distance, frame.pyramid_pixel_sigma)
            * gaussian(1.0 - dot(other.xyz, own.xyz), frame.pyramid_normal_sigma)
            * gaussian((other.w - own.w) / max(own.w, 1e-6), frame.pyramid_depth_sigma);
    }
    return score;
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(target_normal_depth);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let source_size = vec2<i32>(textureDimensions(source_normal_depth));
    var radiance = vec4<f32>(0.0);
    var albedo = vec3<f32>(0.0);
    var count = 0.0;
    var best = vec4<f32>(0.0, 0.0, 0.0, -1.0);
    var best_score = -1.0;
    for (var k = 0; k < 4; k++) {
        let p = min(vec2<i32>(id.xy) * 2 + vec2<i32>(k & 1, k >> 1), source_size - 1);
        let nd = textureLoad(source_normal_depth, p, 0);
        if nd.w >= 0.0 {
            radiance += textureLoad(source_radiance, p, 0);
            albedo += textureLoad(source_albedo, p, 0).rgb;
            count += 1.0;
            let score = vote(p, source_size);
            if score > best_score {
                best_score = score;
                best = nd;
            }
        }
    }
    let pixel = vec2<i32>(id.xy);
    if count == 0.0 {
        textureStore(target_normal_depth, pixel, vec4<f32>(0.0, 0.0, 0.0, -1.0));
        textureStore(target_radiance, pixel, vec4<f32>(0.0));
        textureStore(target_albedo, pixel, vec4<f32>(0.0));
        return;
    }
    textureStore(target_normal_depth, pixel, best);
    textureStore(target_radiance, pixel, radiance / count);
    textureStore(target_albedo, pixel, vec4<f32>(albedo / count, 1.0));
}
