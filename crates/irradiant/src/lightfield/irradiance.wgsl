// lightfield/irradiance: the prefiltered irradiance query (DDGI's, over the baked tiles) at
// half resolution, for lightfield/resolve to upsample: irradiance is smooth, so a quarter of
// the queries serve every pixel whose 2×2 block neighbours share its surface. Each texel
// queries one pixel of its block (the first with a surface) and keeps that pixel's view depth
// and normal, the geometry the upsampling compares against.
#import ddgi_query
#import gbuffer

@group(2) @binding(56) var target_half_irradiance: texture_storage_2d<rgba16float, write>;
@group(2) @binding(57) var target_half_normal: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let half_size = (vec2<u32>(frame_size()) + 1u) / 2u;
    if any(id.xy >= half_size) {
        return;
    }
    var pixel = id.xy * 2u;
    var depth = -1.0;
    for (var k = 0u; k < 4u; k++) {
        let p = id.xy * 2u + vec2<u32>(k & 1u, k >> 1u);
        if in_frame(p) && gbuffer_depth_at(p) >= 0.0 {
            pixel = p;
            depth = gbuffer_depth_at(p);
            break;
        }
    }
    if depth < 0.0 {
        textureStore(target_half_irradiance, id.xy, vec4<f32>(0.0, 0.0, 0.0, -1.0));
        return;
    }
    let s = gbuffer_surface(pixel);
    let e = ddgi_irradiance(s.position, s.normal, view_dir(s.position));
    textureStore(target_half_irradiance, id.xy, vec4<f32>(e, depth));
    textureStore(target_half_normal, id.xy, vec4<f32>(s.normal, 0.0));
}
