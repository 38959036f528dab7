// ssil/bounce: the light of bounce n, for bounce n + 1 to gather: what leaves each surface of
// the start level — its emission and direct light plus the diffuse reflection of the light
// bounce n gathered there (albedo / π × E), with the surface's diffuse share in alpha as
// frame/pyramid writes it. Written at the start level; ssil/bounce_down averages it up the
// levels.
#import ssil_common

@group(2) @binding(0) var<uniform> ssil: GpuSsilParams;
@group(2) @binding(1) var pyramid_radiance: texture_2d<f32>;
@group(2) @binding(2) var pyramid_albedo: texture_2d<f32>;
@group(2) @binding(3) var combined_light: texture_2d<f32>;
@group(2) @binding(4) var target_radiance: texture_storage_2d<rgba16float, write>;
@group(1) @binding(0) var<uniform> frame: GpuFrameParams;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = level_size(ssil.start_level);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let own = textureLoad(pyramid_radiance, id.xy, ssil.start_level);
    let albedo = textureLoad(pyramid_albedo, id.xy, ssil.start_level).rgb;
    let gathered = textureLoad(combined_light, id.xy, 0).rgb;
    let sent = own.rgb + albedo / PI * gathered;
    textureStore(target_radiance, vec2<i32>(id.xy), vec4<f32>(sent, own.a));
}
