// lightfield/view: the debug view of the paper's Figure 20: every camera ray traced through
// the light field alone (no BVH), showing the radiance the probes hold where it hits, tinted
// by the probe that resolved it. Replaces the frame's radiance when the probe view is on.
#import lightfield
#import gbuffer

@group(2) @binding(49) var radiance: texture_storage_2d<rgba32float, read_write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let dir = camera_ray_dir(frame.camera, vec2<f32>(id.xy) + 0.5, frame_size());
    let hit = lightfield_trace(frame.camera.position, dir, lf_far());
    var l = lightfield_radiance_of(hit, vec3<f32>(0.0));
    if hit.result == LF_HIT {
        let c = grid_coord(hit.probe, lightfield.counts);
        let tint = vec3<f32>(f32(c.x & 1u), f32(c.y & 1u), f32(c.z & 1u)) * 0.25 + 0.75;
        l *= tint;
    }
    textureStore(radiance, vec2<i32>(id.xy), vec4<f32>(l, 1.0));
}
