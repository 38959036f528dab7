// The frame as its readers see it (the module `gbuffer`): the frame's parameters and the
// G-buffer's textures in group 1, and a surface for any pixel. Every pass that reads the
// G-buffer imports this module; the resources are bound by these names.
#import frame_types
#import gbuffer_layout
#import camera

@group(1) @binding(0) var<uniform> frame: GpuFrameParams;
@group(1) @binding(1) var gbuffer_depth: texture_2d<f32>;
@group(1) @binding(2) var gbuffer_normal: texture_2d<f32>;
@group(1) @binding(3) var gbuffer_albedo: texture_2d<f32>;
@group(1) @binding(4) var gbuffer_emission: texture_2d<f32>;
@group(1) @binding(5) var gbuffer_motion: texture_2d<f32>;

fn frame_size() -> vec2<f32> {
    return vec2<f32>(f32(frame.width), f32(frame.height));
}

fn in_frame(pixel: vec2<u32>) -> bool {
    return pixel.x < frame.width && pixel.y < frame.height;
}

// The primary ray's direction through the pixel's sample point (its centre plus this frame's
// jitter), as frame/gbuffer traced it.
fn pixel_ray_dir(pixel: vec2<u32>) -> vec3<f32> {
    return camera_ray_dir(frame.camera, vec2<f32>(pixel) + 0.5 + frame.jitter, frame_size());
}

// Distance along the primary ray, negative where the ray left the scene.
fn gbuffer_depth_at(pixel: vec2<u32>) -> f32 {
    return textureLoad(gbuffer_depth, pixel, 0).r;
}

fn gbuffer_position(pixel: vec2<u32>, depth: f32) -> vec3<f32> {
    return frame.camera.position + pixel_ray_dir(pixel) * depth;
}

// The surface a pixel sees (only meaningful where gbuffer_depth_at(pixel) >= 0).
fn gbuffer_surface(pixel: vec2<u32>) -> Surface {
    var t: GBufferTexels;
    t.depth = gbuffer_depth_at(pixel);
    t.normal = textureLoad(gbuffer_normal, pixel, 0);
    t.albedo = textureLoad(gbuffer_albedo, pixel, 0);
    t.emission = textureLoad(gbuffer_emission, pixel, 0);
    t.motion = textureLoad(gbuffer_motion, pixel, 0);
    return gbuffer_unpack(t, gbuffer_position(pixel, t.depth));
}

// The shading normal alone (filters compare it without decoding the whole surface).
fn gbuffer_normal_at(pixel: vec2<u32>) -> vec3<f32> {
    return oct_decode(textureLoad(gbuffer_normal, pixel, 0).xy);
}

fn gbuffer_motion_at(pixel: vec2<u32>) -> vec2<f32> {
    return textureLoad(gbuffer_motion, pixel, 0).xy;
}

// The view direction (towards the camera) at a surface point.
fn view_dir(p: vec3<f32>) -> vec3<f32> {
    return normalize(frame.camera.position - p);
}
