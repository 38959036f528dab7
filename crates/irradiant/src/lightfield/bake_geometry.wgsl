// lightfield/bake_geometry: every probe texel's nearest surface in the texel's direction,
// traced with our BVH (the paper rasterizes cube maps; tracing needs no rasterizer and no
// resampling): its normal (as stored, not turned to face the probe, so that the trace can
// tell front from back faces) and its radial distance (LF_NO_SURFACE where the ray leaves).
#import lightfield
#import bvh
#import scene

@group(2) @binding(24) var target_geometry: texture_storage_2d_array<r32uint, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    let size = lightfield.resolution;
    if id.x >= size || id.y >= size || id.z >= lightfield.probe_count {
        return;
    }
    let probe = id.z;
    let dir = lf_direction((vec2<f32>(id.xy) + 0.5) / f32(size));
    let hit = trace_ray(lf_probe_position(probe), dir, RAY_FAR, false);
    var packed = pack_geometry(vec3<f32>(0.0, 0.0, 1.0), LF_NO_SURFACE);
    if hit.triangle != INVALID {
        let tri = triangle_at(hit.triangle);
        let face = normalize(to_world_normal(instances[hit.instance], cross(tri.e1, tri.e2)));
        packed = pack_geometry(face, hit.t);
    }
    textureStore(target_geometry, id.xy, probe, vec4<u32>(packed, 0u, 0u, 0u));
}
