// frame/gbuffer: one primary ray through each pixel centre; what it hits, as a G-buffer.
#import frame_types
#import gbuffer_surface
#import bvh
#import camera

@group(1) @binding(0) var<uniform> params: GpuFrameParams;
@group(1) @binding(1) var<storage, read_write> gbuffer: array<GpuGBufferTexel>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let size = vec2<f32>(f32(params.width), f32(params.height));
    let pixel = vec2<f32>(id.xy) + 0.5;
    let origin = params.camera.position;
    let dir = camera_ray_dir(params.camera, pixel, size);
    let hit = trace_ray(origin, dir, RAY_FAR, false);
    var g: GpuGBufferTexel;
    if hit.triangle == INVALID {
        g.depth = -1.0;
        g.position = origin + dir * RAY_FAR;
        g.normal = -dir;
        g.geometric_normal = -dir;
        g.motion = vec2<f32>(0.0);
    } else {
        let s = surface_at(origin, dir, hit.t, hit.triangle, hit.instance, hit.bary);
        g = gbuffer_from_surface(s, hit.t);
        // Where this surface point was last frame: back through the instance's previous
        // transform, then the previous camera.
        let inst = instances[hit.instance];
        let object_point = to_object_point(inst, s.position);
        let q = vec4<f32>(object_point, 1.0);
        let previous = vec3<f32>(dot(inst.previous_object_to_world0, q), dot(inst.previous_object_to_world1, q), dot(inst.previous_object_to_world2, q));
        g.motion = project(params.previous_camera, previous, size) - pixel;
    }
    gbuffer[id.y * params.width + id.x] = g;
}
