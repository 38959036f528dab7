// host/indirect: the technique's indirect light as a host composes it: outgoing radiance
// (albedo applied) in rgb, 0 where the pixel sees no surface. The frame's `indirect` holds a
// weighted sum and its weight; this is the sum over the weight, as frame/compose reads it.
#import gbuffer

@group(2) @binding(0) var indirect: texture_2d<f32>;
@group(2) @binding(1) var host_indirect: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    var l = vec3<f32>(0.0);
    if gbuffer_depth_at(id.xy) >= 0.0 {
        let gi = textureLoad(indirect, id.xy, 0);
        l = gi.rgb / max(gi.a, 1.0);
    }
    textureStore(host_indirect, vec2<i32>(id.xy), vec4<f32>(l, 1.0));
}
