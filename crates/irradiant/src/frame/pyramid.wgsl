// frame/pyramid: level 0 of the G-buffer pyramid (FrameNeeds::pyramid_levels), from the
// G-buffer and the direct light: normal and view depth, the direct light each surface
// reflects diffusely, and albedo. Not its highlights: they depend on the view, and a highlight
// the camera sees is not light the surface sends every way. Not emission: frame/direct already
// samples every emitter, so an emitter's light gathered again from the screen would be
// counted twice. The radiance's alpha is the share of what the surface reflects that it sends
// every way (`diffuse_share`): ssil+ddgi's screen covers a direction only by that share, and
// leaves the rest (a glossy sender's light toward the receiver, which the screen does not know)
// to the probes. frame/pyramid_down makes the levels above.
#import gbuffer
#import brdf

@group(2) @binding(0) var direct_diffuse: texture_2d<f32>;
@group(2) @binding(1) var pyramid_normal_depth_level0: texture_storage_2d<rgba32float, write>;
@group(2) @binding(2) var pyramid_radiance_level0: texture_storage_2d<rgba16float, write>;
@group(2) @binding(3) var pyramid_albedo_level0: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let pixel = vec2<i32>(id.xy);
    let depth = gbuffer_depth_at(id.xy);
    if depth < 0.0 {
        textureStore(pyramid_normal_depth_level0, pixel, vec4<f32>(0.0, 0.0, 0.0, -1.0));
        textureStore(pyramid_radiance_level0, pixel, vec4<f32>(0.0));
        textureStore(pyramid_albedo_level0, pixel, vec4<f32>(0.0));
        return;
    }
    let s = gbuffer_surface(id.xy);
    let view_depth = dot(s.position - frame.camera.position, frame.camera.forward);
    textureStore(pyramid_normal_depth_level0, pixel, vec4<f32>(s.normal, view_depth));
    let radiance = textureLoad(direct_diffuse, id.xy, 0).rgb;
    textureStore(pyramid_radiance_level0, pixel, vec4<f32>(radiance, diffuse_share(s)));
    textureStore(pyramid_albedo_level0, pixel, vec4<f32>(s.albedo * (1.0 - s.metallic), 1.0));
}
