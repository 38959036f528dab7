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

// How much a neighbour's surface counts as the pixel's own, for the filters that borrow their
// neighbours' light (frame/taa's reconstruction, ddgi/gather_filter): 1 where it lies on the
// pixel's plane (position x, normal n) and faces its way, falling as it leaves the plane
// (e^(−PLANE_SHARPNESS × the sine of the angle between the plane and the step to it)) or turns
// away (cos^64, SVGF's σ_n: Schied et al. 2017).
fn surface_agreement(x: vec3<f32>, n: vec3<f32>, q: vec2<u32>, q_depth: f32) -> f32 {
    let step = gbuffer_position(q, q_depth) - x;
    let off_plane = abs(dot(n, step)) / max(length(step), 1e-9);
    var facing = max(dot(n, gbuffer_normal_at(q)), 0.0);
    for (var i = 0; i < 6; i++) {
        facing *= facing;
    }
    return exp(-PLANE_SHARPNESS * off_plane) * facing;
}
const PLANE_SHARPNESS: f32 = 8.0;

// The view direction (towards the camera) at a surface point.
fn view_dir(p: vec3<f32>) -> vec3<f32> {
    return normalize(frame.camera.position - p);
}
