// host/import: a host's G-buffer (the embedding API, host/gbuffer.rs) into Irradiant's layout
// (gbuffer_layout), so that every technique reads it as it reads the frame's own. Each channel
// is read as the host's convention says; the position is not stored (the ray through the pixel
// centre at the stored distance), which is why the host's projection must be the camera's.
#import host_constants
#import gbuffer_write
#import camera

struct GpuHostImport {
    // DEPTH_* of host::gbuffer: how host_depth measures depth
    depth_convention: u32,
    // NORMAL_*: how host_normal holds the shading normal
    normal_encoding: u32,
    // MOTION_*; MOTION_NONE: no motion texture
    motion_convention: u32,
    // material channels: roughness, metallic, specular (CHANNEL_NONE: none); 0 without a texture
    has_material: u32,
    roughness_channel: u32,
    metallic_channel: u32,
    specular_channel: u32,
    has_emission: u32,
    // the hardware depth's projection
    near: f32,
    far: f32,
    pad0: u32,
    pad1: u32,
}

@group(0) @binding(0) var<uniform> import_params: GpuHostImport;
@group(0) @binding(1) var host_depth: texture_2d<f32>;
@group(0) @binding(2) var host_normal: texture_2d<f32>;
@group(0) @binding(3) var host_base_colour: texture_2d<f32>;
@group(0) @binding(4) var host_material: texture_2d<f32>;
@group(0) @binding(5) var host_emission: texture_2d<f32>;
@group(0) @binding(6) var host_motion: texture_2d<f32>;

// The distance along the ray `dir` of the host's depth texel d; negative where the pixel sees no
// surface (the far plane, or 0 in a reversed buffer).
fn ray_distance(d: f32, dir: vec3<f32>) -> f32 {
    let p = import_params;
    var view_z: f32;
    switch p.depth_convention {
        case DEPTH_RAY_DISTANCE: { return select(d, -1.0, d < 0.0); }
        case DEPTH_VIEW_Z: {
            if d <= 0.0 { return -1.0; }
            view_z = d;
        }
        case DEPTH_HARDWARE: {
            if d >= 1.0 { return -1.0; }
            view_z = p.near * p.far / (p.far - d * (p.far - p.near));
        }
        case DEPTH_HARDWARE_REVERSED: {
            if d <= 0.0 { return -1.0; }
            view_z = p.near * p.far / (p.near + d * (p.far - p.near));
        }
        default: {
            // DEPTH_HARDWARE_REVERSED_INFINITE
            if d <= 0.0 { return -1.0; }
            view_z = p.near / d;
        }
    }
    return view_z / max(dot(dir, frame.camera.forward), 1e-6);
}

fn world_normal(t: vec4<f32>) -> vec3<f32> {
    let c = frame.camera;
    switch import_params.normal_encoding {
        case NORMAL_WORLD_SIGNED: { return normalize(t.xyz); }
        case NORMAL_WORLD_UNORM: { return normalize(t.xyz * 2.0 - 1.0); }
        case NORMAL_VIEW_SIGNED, NORMAL_VIEW_UNORM: {
            // View space: x right, y up, z towards the viewer.
            let v = select(t.xyz, t.xyz * 2.0 - 1.0, import_params.normal_encoding == NORMAL_VIEW_UNORM);
            return normalize(c.right * v.x + c.up * v.y - c.forward * v.z);
        }
        default: { return oct_decode(t.xy); }
    }
}

fn channel(t: vec4<f32>, i: u32, otherwise: f32) -> f32 {
    if i >= 4u {
        return otherwise;
    }
    return t[i];
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    let pixel = vec2<i32>(id.xy);
    let size = vec2<f32>(f32(frame.width), f32(frame.height));
    let dir = camera_ray_dir(frame.camera, vec2<f32>(id.xy) + 0.5, size);
    let depth = ray_distance(textureLoad(host_depth, pixel, 0).r, dir);
    var t: GBufferTexels;
    if depth < 0.0 {
        t.depth = -1.0;
        t.normal = vec4<f32>(oct_encode(-dir), oct_encode(-dir));
    } else {
        var n = world_normal(textureLoad(host_normal, pixel, 0));
        // Turned towards the eye, as the traced G-buffer's are (surfaces are two-sided).
        n = select(n, -n, dot(n, dir) > 0.0);
        var s: Surface;
        s.position = frame.camera.position + dir * depth;
        s.normal = n;
        s.geometric_normal = n;
        s.albedo = max(textureLoad(host_base_colour, pixel, 0).rgb, vec3<f32>(0.0));
        s.roughness = 1.0;
        s.metallic = 0.0;
        s.specular = 1.0;
        if import_params.has_material != 0u {
            let m = textureLoad(host_material, pixel, 0);
            s.roughness = clamp(channel(m, import_params.roughness_channel, 1.0), 0.0, 1.0);
            s.metallic = clamp(channel(m, import_params.metallic_channel, 0.0), 0.0, 1.0);
            s.specular = max(channel(m, import_params.specular_channel, 1.0), 0.0);
        }
        s.emission = vec3<f32>(0.0);
        if import_params.has_emission != 0u {
            s.emission = max(textureLoad(host_emission, pixel, 0).rgb, vec3<f32>(0.0));
        }
        var motion = vec2<f32>(0.0);
        let m = textureLoad(host_motion, pixel, 0).xy;
        switch import_params.motion_convention {
            case MOTION_PIXELS_TO_PREVIOUS: { motion = m; }
            case MOTION_UV_TO_PREVIOUS: { motion = m * size; }
            case MOTION_UV_FROM_PREVIOUS: { motion = -m * size; }
            default: {
                // No motion texture: the camera's own motion, for a static surface.
                motion = project(frame.previous_camera, s.position, size) - project(frame.camera, s.position, size);
            }
        }
        t = gbuffer_pack(s, depth, motion);
    }
    gbuffer_store(pixel, t);
}
