// frame/direct: direct light at each G-buffer pixel — punctual lights with shadow rays, and
// `area_light_samples` samples of the emissive triangles — kept as a running mean while the
// view and the scene stay still (restarted by the frame's one reset mechanism).
#import frame_types
#import gbuffer_surface
#import lights
#import random

@group(1) @binding(0) var<uniform> params: GpuFrameParams;
@group(1) @binding(1) var<storage, read> gbuffer: array<GpuGBufferTexel>;
@group(1) @binding(2) var<storage, read_write> direct: array<vec4<f32>>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let index = id.y * params.width + id.x;
    let g = gbuffer[index];
    var light = vec3<f32>(0.0);
    if g.depth >= 0.0 {
        let s = surface_from_gbuffer(g);
        let wo = normalize(params.camera.position - s.position);
        light = direct_punctual(s, wo);
        if scene_info.emitter_count > 0u && params.area_light_samples > 0u {
            var rng = rng_seed(index, params.frame_index, params.seed ^ 0x5bd1e995u);
            var sum = vec3<f32>(0.0);
            for (var i = 0u; i < params.area_light_samples; i++) {
                sum += emitter_light(s, wo, &rng);
            }
            light += sum / f32(params.area_light_samples);
        }
    }
    let n = f32(params.accumulated_frames);
    let previous = direct[index].rgb;
    direct[index] = vec4<f32>(select(light, mix(previous, light, 1.0 / (n + 1.0)), params.accumulated_frames > 0u), 1.0);
}
