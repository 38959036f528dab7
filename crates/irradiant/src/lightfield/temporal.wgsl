// lightfield/temporal: the filtered Lambertian and glossy buffers blended with last frame's,
// warped along the motion vectors where last frame's pixel held the same surface (an
// exponentially weighted moving average, §5.1: 98 % and 75 % of history by default). The
// result, with the geometry it was filtered on, is next frame's history (two sets, ping-
// ponged). The prefiltered algorithm has no Lambertian buffer and skips its half.
#import lightfield
#import gbuffer
#import history

@group(2) @binding(38) var lambert_now: texture_2d<f32>;
@group(2) @binding(39) var glossy_now: texture_2d<f32>;
@group(2) @binding(40) var lambert_history: texture_2d<f32>;
@group(2) @binding(41) var glossy_history: texture_2d<f32>;
@group(2) @binding(42) var geometry_history: texture_2d<f32>;
@group(2) @binding(43) var lambert_filtered: texture_storage_2d<rgba16float, write>;
@group(2) @binding(44) var glossy_filtered: texture_storage_2d<rgba16float, write>;
@group(2) @binding(45) var geometry_filtered: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let pixel = vec2<i32>(id.xy);
    let here = history_geometry(id.xy);
    textureStore(geometry_filtered, pixel, here);
    let with_lambert = lightfield.algorithm == ALGORITHM_FILTERED;
    var lambert = vec4<f32>(0.0);
    if with_lambert {
        lambert = textureLoad(lambert_now, pixel, 0);
    }
    var glossy = textureLoad(glossy_now, pixel, 0);
    if here.w >= 0.0 && lightfield.history_valid == 1u {
        let previous = history_position(id.xy);
        if all(previous >= vec2<f32>(0.0)) && all(previous < frame_size()) {
            let p = vec2<i32>(previous);
            let x = gbuffer_position(id.xy, gbuffer_depth_at(id.xy));
            if same_surface(textureLoad(geometry_history, p, 0), x, here.xyz, HISTORY_DEPTH_TOLERANCE, HISTORY_NORMAL_TOLERANCE) {
                if with_lambert {
                    lambert = mix(lambert, textureLoad(lambert_history, p, 0), lightfield.lambert_hysteresis);
                }
                glossy = mix(glossy, textureLoad(glossy_history, p, 0), lightfield.glossy_hysteresis);
            }
        }
    }
    textureStore(lambert_filtered, pixel, lambert);
    textureStore(glossy_filtered, pixel, glossy);
}
