// lightfield/irradiance: the prefiltered irradiance query (DDGI's, over the baked tiles) once
// per block of irradiance_block² pixels, for lightfield/resolve to upsample: irradiance is
// smooth, so a query serves every pixel whose neighbours share its surface. Each texel queries
// one pixel of its block (the first with a surface, scanning from the block's centre) and keeps
// that pixel's view depth and normal, the geometry the upsampling compares against.
#import lightfield
#import ddgi_query
#import gbuffer

@group(2) @binding(56) var target_coarse_irradiance: texture_storage_2d<rgba16float, write>;
@group(2) @binding(57) var target_coarse_normal: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let block = lightfield.irradiance_block;
    let coarse_size = (vec2<u32>(frame_size()) + block - 1u) / block;
    if any(id.xy >= coarse_size) {
        return;
    }
    var pixel = id.xy * block;
    var depth = -1.0;
    for (var k = 0u; k < block * block; k++) {
        // From the block's centre outwards, so that the query sits mid-block where it can.
        let i = (k + (block * block) / 2u + block / 2u) % (block * block);
        let p = id.xy * block + vec2<u32>(i % block, i / block);
        if in_frame(p) && gbuffer_depth_at(p) >= 0.0 {
            pixel = p;
            depth = gbuffer_depth_at(p);
            break;
        }
    }
    if depth < 0.0 {
        textureStore(target_coarse_irradiance, id.xy, vec4<f32>(0.0, 0.0, 0.0, -1.0));
        return;
    }
    let s = gbuffer_surface(pixel);
    let e = ddgi_irradiance(s.position, s.normal, view_dir(s.position)).irradiance;
    textureStore(target_coarse_irradiance, id.xy, vec4<f32>(e, depth));
    textureStore(target_coarse_normal, id.xy, vec4<f32>(s.normal, 0.0));
}
