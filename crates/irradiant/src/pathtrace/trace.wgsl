// pathtrace/trace: the reference path tracer as one kernel (PathSchedule::Megakernel). One
// thread a pixel traces `samples` paths (the path module) and adds them to the accumulation
// texture.
#import path
#import pathtrace_params
#import random

@group(1) @binding(0) var<uniform> params: GpuPathTraceParams;
// rgb: sum of radiance samples; a: their count
@group(1) @binding(1) var accumulation: texture_storage_2d<rgba32float, read_write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let index = id.y * params.width + id.x;
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < params.samples; i++) {
        var rng = rng_seed(index, params.sample_offset + i, params.seed);
        let dir = pixel_ray_dir(params, id.xy, &rng);
        sum += finite_or_zero(path_radiance(params.camera.position, dir, params.max_bounces, true, params.light_sampling, &rng));
    }
    textureStore(accumulation, id.xy, textureLoad(accumulation, id.xy) + vec4<f32>(sum, f32(params.samples)));
}
