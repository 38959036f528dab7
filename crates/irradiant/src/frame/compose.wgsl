// frame/compose: emission + direct + the technique's indirect light (+ sky where the camera
// ray left the scene) → linear radiance. `indirect` holds a weighted sum and its weight (a):
// probe volumes blend into it one after another (ddgi/resolve); a weight of 0 means none.
#import gbuffer

@group(2) @binding(0) var direct: texture_2d<f32>;
@group(2) @binding(1) var indirect: texture_2d<f32>;
@group(2) @binding(2) var<uniform> sky: vec4<f32>;
@group(2) @binding(3) var radiance: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    var l = sky.rgb;
    if gbuffer_depth_at(id.xy) >= 0.0 {
        let gi = textureLoad(indirect, id.xy, 0);
        l = textureLoad(gbuffer_emission, id.xy, 0).rgb + textureLoad(direct, id.xy, 0).rgb + gi.rgb / max(gi.a, 1.0);
    }
    textureStore(radiance, vec2<i32>(id.xy), vec4<f32>(l, 1.0));
}
