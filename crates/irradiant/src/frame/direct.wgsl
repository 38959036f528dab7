// frame/direct: direct light at each G-buffer pixel — punctual lights with shadow rays, and
// `area_light_samples` samples of the emissive triangles — kept as a running mean while the
// view and the scene stay still (restarted by the frame's one reset mechanism). With TAA's
// jitter the mean also averages over the pixel's footprint.
#import gbuffer
#import lights
#import random

@group(2) @binding(0) var direct: texture_storage_2d<rgba32float, read_write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    if !in_frame(id.xy) {
        return;
    }
    let index = id.y * frame.width + id.x;
    var light = vec3<f32>(0.0);
    if gbuffer_depth_at(id.xy) >= 0.0 {
        let s = gbuffer_surface(id.xy);
        let wo = view_dir(s.position);
        light = direct_punctual(s, wo);
        if scene_info.emitter_count > 0u && frame.area_light_samples > 0u {
            var rng = rng_seed(index, frame.frame_index, frame.seed ^ 0x5bd1e995u);
            var sum = vec3<f32>(0.0);
            for (var i = 0u; i < frame.area_light_samples; i++) {
                sum += emitter_light(s, wo, &rng);
            }
            light += sum / f32(frame.area_light_samples);
        }
    }
    let n = f32(frame.accumulated_frames);
    let previous = textureLoad(direct, id.xy).rgb;
    textureStore(direct, id.xy, vec4<f32>(select(light, mix(previous, light, 1.0 / (n + 1.0)), frame.accumulated_frames > 0u), 1.0));
}
