// frame/pyramid_down: one level of the G-buffer pyramid from the level below: each texel the
// mean of the 2×2 texels under it that see a surface (normals renormalised); a texel whose
// four all see the sky sees the sky. A technique that needs another filter for depth and
// normals (ssil's voting filter) rewrites those levels itself.

@group(0) @binding(0) var source_normal_depth: texture_2d<f32>;
@group(0) @binding(1) var source_radiance: texture_2d<f32>;
@group(0) @binding(2) var source_albedo: texture_2d<f32>;
@group(0) @binding(3) var target_normal_depth: texture_storage_2d<rgba32float, write>;
@group(0) @binding(4) var target_radiance: texture_storage_2d<rgba16float, write>;
@group(0) @binding(5) var target_albedo: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(target_normal_depth);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let source_size = vec2<i32>(textureDimensions(source_normal_depth));
    var normal = vec3<f32>(0.0);
    var depth = 0.0;
    var radiance = vec3<f32>(0.0);
    var albedo = vec3<f32>(0.0);
    var count = 0.0;
    for (var k = 0; k < 4; k++) {
        let p = min(vec2<i32>(id.xy) * 2 + vec2<i32>(k & 1, k >> 1), source_size - 1);
        let nd = textureLoad(source_normal_depth, p, 0);
        if nd.w >= 0.0 {
            normal += nd.xyz;
            depth += nd.w;
            radiance += textureLoad(source_radiance, p, 0).rgb;
            albedo += textureLoad(source_albedo, p, 0).rgb;
            count += 1.0;
        }
    }
    let pixel = vec2<i32>(id.xy);
    if count == 0.0 {
        textureStore(target_normal_depth, pixel, vec4<f32>(0.0, 0.0, 0.0, -1.0));
        textureStore(target_radiance, pixel, vec4<f32>(0.0));
        textureStore(target_albedo, pixel, vec4<f32>(0.0));
        return;
    }
    let n = select(vec3<f32>(0.0, 0.0, 1.0), normalize(normal), dot(normal, normal) > 1e-12);
    textureStore(target_normal_depth, pixel, vec4<f32>(n, depth / count));
    textureStore(target_radiance, pixel, vec4<f32>(radiance / count, 1.0));
    textureStore(target_albedo, pixel, vec4<f32>(albedo / count, 1.0));
}
