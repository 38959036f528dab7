// The real-time frame's shared declarations: its parameters and the G-buffer texel, which a
// host engine can fill instead of Irradiant's primary rays.
#import types

struct GpuFrameParams {
    camera: GpuCamera,
    previous_camera: GpuCamera,
    width: u32,
    height: u32,
    frame_index: u32,
    // emitter samples per pixel per frame for direct light from emissive surfaces
    area_light_samples: u32,
    seed: u32,
    // frames already in the direct-light running mean; 0 restarts it
    accumulated_frames: u32,
    _pad0: u32,
    _pad1: u32,
}

struct GpuGBufferTexel {
    position: vec3<f32>,
    // distance along the primary ray; negative where the ray left the scene
    depth: f32,
    normal: vec3<f32>,
    roughness: f32,
    geometric_normal: vec3<f32>,
    metallic: f32,
    albedo: vec3<f32>,
    specular: f32,
    emission: vec3<f32>,
    _pad0: f32,
    // where this pixel was last frame, minus where it is now, in pixels
    motion: vec2<f32>,
    _pad1: vec2<f32>,
}

// Pixel coordinates (y down) of a world point seen by a camera.
fn project(cam: GpuCamera, p: vec3<f32>, size: vec2<f32>) -> vec2<f32> {
    let d = p - cam.position;
    let z = max(dot(d, cam.forward), 1e-6);
    let ndc = vec2<f32>(dot(d, cam.right) / (z * cam.tan_half_fov_y * cam.aspect), dot(d, cam.up) / (z * cam.tan_half_fov_y));
    return vec2<f32>((ndc.x + 1.0) * 0.5 * size.x, (1.0 - ndc.y) * 0.5 * size.y);
}
