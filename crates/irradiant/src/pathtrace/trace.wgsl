// pathtrace/trace: the reference path tracer. One thread a pixel traces `samples` paths (the
// path module) and adds them to the accumulation texture.
#import path
#import camera
#import random

struct GpuPathTraceParams {
    camera: GpuCamera,
    width: u32,
    height: u32,
    // index of the first sample of this dispatch (decorrelates dispatches)
    sample_offset: u32,
    samples: u32,
    max_bounces: u32,
    seed: u32,
    light_sampling: u32,
    _pad1: u32,
}

@group(1) @binding(0) var<uniform> params: GpuPathTraceParams;
// rgb: sum of radiance samples; a: their count
@group(1) @binding(1) var accumulation: texture_storage_2d<rgba32float, read_write>;

fn trace_path(pixel: vec2<u32>, rng: ptr<function, u32>) -> vec3<f32> {
    let size = vec2<f32>(f32(params.width), f32(params.height));
    let dir = camera_ray_dir(params.camera, vec2<f32>(pixel) + rand2(rng), size);
    return path_radiance(params.camera.position, dir, params.max_bounces, true, params.light_sampling, rng);
}

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
        sum += finite_or_zero(trace_path(id.xy, &rng));
    }
    textureStore(accumulation, id.xy, textureLoad(accumulation, id.xy) + vec4<f32>(sum, f32(params.samples)));
}
