// pathtrace_params: the uniform of the path tracer's passes (the megakernel pathtrace/trace and
// the wavefront's pathtrace/camera and pathtrace/bounce) and the camera ray they share.
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

// A sample's camera ray through `pixel`, jittered within it: the same for either schedule.
fn pixel_ray_dir(params: GpuPathTraceParams, pixel: vec2<u32>, rng: ptr<function, u32>) -> vec3<f32> {
    let size = vec2<f32>(f32(params.width), f32(params.height));
    return camera_ray_dir(params.camera, vec2<f32>(pixel) + rand2(rng), size);
}
