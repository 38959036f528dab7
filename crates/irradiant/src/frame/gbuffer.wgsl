// frame/gbuffer: one primary ray through each pixel's sample point (its centre, plus this
// frame's sub-pixel jitter when TAA is on); what it hits, as the G-buffer (gbuffer_layout).
#import gbuffer_write
#import bvh
#import camera

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    let size = vec2<f32>(f32(frame.width), f32(frame.height));
    let sample_point = vec2<f32>(id.xy) + 0.5 + frame.jitter;
    let origin = frame.camera.position;
    let dir = camera_ray_dir(frame.camera, sample_point, size);
    let hit = trace_ray(origin, dir, RAY_FAR, false);
    var t: GBufferTexels;
    if hit.triangle == INVALID {
        t.depth = -1.0;
        t.normal = vec4<f32>(oct_encode(-dir), oct_encode(-dir));
    } else {
        let s = surface_at(origin, dir, hit.t, hit.triangle, hit.instance, hit.bary);
        // Where this surface point was last frame: back through the instance's previous
        // transform, then the previous camera; both projections unjittered.
        let inst = instances[hit.instance];
        let q = vec4<f32>(to_object_point(inst, s.position), 1.0);
        let previous = vec3<f32>(dot(inst.previous_object_to_world0, q), dot(inst.previous_object_to_world1, q), dot(inst.previous_object_to_world2, q));
        let motion = project(frame.previous_camera, previous, size) - project(frame.camera, s.position, size);
        t = gbuffer_pack(s, hit.t, motion);
    }
    gbuffer_store(vec2<i32>(id.xy), t);
}
