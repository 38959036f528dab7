// ddgi/reflect_filter: ddgi/reflect's rays into the frame's indirect light. A pixel takes the
// rays traced this frame within a radius that grows with its roughness (1 pixel at a mirror,
// 2 at REFLECT_MAX_ROUGHNESS: with half-resolution tracing its own 2×2 block's ray is always
// among them), from neighbours on its plane whose rays went about as far (a reflection of
// the same thing); then a running mean along the motion vectors where last frame's pixel held
// the same surface, over up to REFLECT_HISTORY frames at REFLECT_MAX_ROUGHNESS and 2 at a
// mirror, whose reflection moves over it with the view. The mean and the geometry it was taken
// on are next frame's history; the mean is added to `indirect` (whose weighted sum becomes a
// plain sum: a = 1).
#import gbuffer
#import history
#import brdf

@group(2) @binding(10) var indirect: texture_storage_2d<rgba32float, read_write>;
@group(2) @binding(41) var reflection_rays_read: texture_2d<f32>;
@group(2) @binding(42) var reflection_history: texture_2d<f32>;
@group(2) @binding(43) var reflection_history_geometry: texture_2d<f32>;
@group(2) @binding(44) var reflection_mean: texture_storage_2d<rgba16float, write>;
@group(2) @binding(45) var reflection_mean_geometry: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let pixel = vec2<i32>(id.xy);
    let here = history_geometry(id.xy);
    textureStore(reflection_mean_geometry, pixel, here);
    if here.w < 0.0 {
        textureStore(reflection_mean, pixel, vec4<f32>(0.0));
        return;
    }
    let s = gbuffer_surface(id.xy);
    if !(has_specular(s) && s.roughness <= REFLECT_MAX_ROUGHNESS) {
        textureStore(reflection_mean, pixel, vec4<f32>(0.0));
        return;
    }
    let glossiness = saturate(s.roughness / max(REFLECT_MAX_ROUGHNESS, 1e-6));
    // This frame's rays around the pixel. The pixel's own ray length is its 2×2 block's ray's
    // with half-resolution tracing (ddgi/reflect's turn), where the pixel did not trace.
    let turn = frame.frame_index % (REFLECT_STEP * REFLECT_STEP);
    let traced = (id.xy / REFLECT_STEP) * REFLECT_STEP + vec2<u32>(turn % REFLECT_STEP, turn / REFLECT_STEP);
    var own = textureLoad(reflection_rays_read, pixel, 0);
    if own.a < 0.0 && in_frame(traced) {
        own = textureLoad(reflection_rays_read, vec2<i32>(traced), 0);
    }
    let radius = 1 + i32(round(glossiness));
    let size = vec2<i32>(frame_size());
    var sum = vec3<f32>(0.0);
    var total = 0.0;
    for (var dy = -radius; dy <= radius; dy++) {
        for (var dx = -radius; dx <= radius; dx++) {
            let q = pixel + vec2<i32>(dx, dy);
            if any(q < vec2<i32>(0)) || any(q >= size) {
                continue;
            }
            let ray = textureLoad(reflection_rays_read, q, 0);
            if ray.a < 0.0 {
                continue;
            }
            let other = history_geometry(vec2<u32>(q));
            // On the pixel's plane: the normals agree and the depths within 5 %.
            if other.w < 0.0 || dot(other.xyz, here.xyz) < 0.9 || abs(other.w - here.w) > 0.05 * here.w {
                continue;
            }
            var w = exp(-0.5 * f32(dx * dx + dy * dy));
            // Rays that went much farther or shorter than this pixel's saw something else.
            if own.a > 0.0 && ray.a > 0.0 {
                let ratio = max(own.a, ray.a) / min(own.a, ray.a);
                w *= 1.0 / (1.0 + (ratio - 1.0) * (ratio - 1.0));
            }
            sum += w * ray.rgb;
            total += w;
        }
    }
    var light = vec3<f32>(0.0);
    var frames = 0.0;
    if total > 0.0 {
        light = sum / total;
        frames = 1.0;
    }
    let most = mix(2.0, REFLECT_HISTORY, glossiness);
    let p = same_surface_texel(id.xy, here.xyz, reflection_history_geometry);
    if p.x >= 0 {
        let old = textureLoad(reflection_history, p, 0);
        if frames > 0.0 {
            frames = min(old.a + 1.0, most);
            light = mix(old.rgb, light, 1.0 / frames);
        } else {
            frames = old.a;
            light = old.rgb;
        }
    }
    textureStore(reflection_mean, pixel, vec4<f32>(light, frames));
    let diffuse = textureLoad(indirect, pixel);
    textureStore(indirect, pixel, vec4<f32>(diffuse.rgb / max(diffuse.a, 1.0) + light, 1.0));
}
