// lightfield/resolve: the frame's indirect light: the diffuse reflection of the Lambertian
// term — prefiltered irradiance with Chebyshev visibility (DDGI's query over the baked tiles)
// for the prefiltered algorithm, the traced and filtered incident light otherwise — plus the
// glossy term.
#import lightfield
#import ddgi_query
#import gbuffer
#import brdf

@group(2) @binding(46) var lambert_light: texture_2d<f32>;
@group(2) @binding(47) var glossy_light: texture_2d<f32>;
@group(2) @binding(48) var indirect: texture_storage_2d<rgba32float, read_write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let pixel = vec2<i32>(id.xy);
    if gbuffer_depth_at(id.xy) < 0.0 {
        textureStore(indirect, pixel, vec4<f32>(0.0));
        return;
    }
    let s = gbuffer_surface(id.xy);
    var lambert: vec3<f32>;
    if lightfield.algorithm == ALGORITHM_PREFILTERED {
        lambert = ddgi_irradiance(s.position, s.normal, view_dir(s.position));
    } else {
        lambert = textureLoad(lambert_light, pixel, 0).rgb;
    }
    let out = diffuse_weight(s) * lambert + textureLoad(glossy_light, pixel, 0).rgb;
    textureStore(indirect, pixel, vec4<f32>(out, 1.0));
}
