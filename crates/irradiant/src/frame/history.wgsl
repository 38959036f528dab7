// history: whether a pixel's surface is the one last frame held where the motion vectors lead
// (the module `history`), for the temporal filters of screen-space passes (ssil/temporal,
// lightfield/temporal). A filter stores, beside its light, the normal and view depth the light
// was filtered on; this frame's surface matches when that depth agrees with the surface's
// depth seen from last frame's camera and the normals agree.
#import gbuffer

// How far a stored depth may differ, as a share of the expected one, and the smallest cosine
// between the normals, for a pixel to hold the same surface as last frame (the filters that
// keep no settings of their own).
const HISTORY_DEPTH_TOLERANCE: f32 = 0.05;
const HISTORY_NORMAL_TOLERANCE: f32 = 0.8;

// The geometry a filter stores with its light: the shading normal and the view depth (along
// the camera's forward axis); w < 0 where the pixel saw no surface.
fn history_geometry(pixel: vec2<u32>) -> vec4<f32> {
    let depth = gbuffer_depth_at(pixel);
    if depth < 0.0 {
        return vec4<f32>(0.0, 0.0, 0.0, -1.0);
    }
    let p = gbuffer_position(pixel, depth);
    return vec4<f32>(gbuffer_normal_at(pixel), dot(p - frame.camera.position, frame.camera.forward));
}

// Where last frame held this pixel's surface (continuous pixel coordinates), from the motion
// vectors.
fn history_position(pixel: vec2<u32>) -> vec2<f32> {
    return vec2<f32>(pixel) + 0.5 + gbuffer_motion_at(pixel);
}

// Whether `old` (the geometry stored last frame at history_position) is this surface: world
// position x, normal n.
fn same_surface(old: vec4<f32>, x: vec3<f32>, n: vec3<f32>, depth_tolerance: f32, normal_tolerance: f32) -> bool {
    let expected = dot(x - frame.previous_camera.position, frame.previous_camera.forward);
    return old.w >= 0.0
        && abs(old.w - expected) <= depth_tolerance * max(expected, 1e-6)
        && dot(old.xyz, n) >= normal_tolerance;
}

// The texel of last frame's history that held this pixel's surface (normal n), where the
// history's geometry (history_geometry's layout, in `geometry`) says it is the same surface;
// (-1, -1) where it is another, the motion leads out of the frame or the frame's history
// restarted.
fn same_surface_texel(pixel: vec2<u32>, n: vec3<f32>, geometry: texture_2d<f32>) -> vec2<i32> {
    return same_surface_texel_scaled(pixel, n, geometry, 1u);
}

// same_surface_texel for a history kept at 1/scale of the image per axis, each texel holding
// the geometry of its block's top-left pixel (scaled_pixel).
fn same_surface_texel_scaled(pixel: vec2<u32>, n: vec3<f32>, geometry: texture_2d<f32>, scale: u32) -> vec2<i32> {
    let previous = history_position(pixel);
    if frame.history_frames == 0u || any(previous < vec2<f32>(0.0)) || any(previous >= frame_size()) {
        return vec2<i32>(-1);
    }
    // The texel whose pixel (its block's top-left, scaled_pixel) lies nearest.
    let last = vec2<i32>(scaled_size(scale)) - 1;
    let p = clamp(vec2<i32>(floor((previous - 0.5) / f32(scale) + 0.5)), vec2<i32>(0), last);
    let x = gbuffer_position(pixel, gbuffer_depth_at(pixel));
    if !same_surface(textureLoad(geometry, p, 0), x, n, HISTORY_DEPTH_TOLERANCE, HISTORY_NORMAL_TOLERANCE) {
        return vec2<i32>(-1);
    }
    return p;
}

// A history kept at 1/scale of the image per axis: the G-buffer pixel that texel `texel`
// stands for (the top-left of its block), and the texels per axis.
fn scaled_pixel(texel: vec2<u32>, scale: u32) -> vec2<u32> {
    return texel * scale;
}

fn scaled_size(scale: u32) -> vec2<u32> {
    return (vec2<u32>(frame.width, frame.height) + scale - 1u) / scale;
}
