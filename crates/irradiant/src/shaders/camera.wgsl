#import types

// The primary ray through a point of the image: `pixel` in pixels, y down.
fn camera_ray_dir(cam: GpuCamera, pixel: vec2<f32>, size: vec2<f32>) -> vec3<f32> {
    let ndc = vec2<f32>(pixel.x / size.x * 2.0 - 1.0, 1.0 - pixel.y / size.y * 2.0);
    let d = cam.forward + cam.right * (ndc.x * cam.tan_half_fov_y * cam.aspect) + cam.up * (ndc.y * cam.tan_half_fov_y);
    return normalize(d);
}
