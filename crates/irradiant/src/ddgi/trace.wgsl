// ddgi/trace: m rays from every probe, closest hit, into the hit buffer.
#import ddgi_probes
#import ddgi_rays
#import bvh

@group(1) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(1) @binding(3) var<storage, read> directions: array<vec4<f32>>;
@group(1) @binding(4) var<storage, read_write> hits: array<GpuDdgiRayHit>;

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    let index = ray_index(id, groups);
    if index >= volume.probe_count * volume.rays_per_probe {
        return;
    }
    let probe = index / volume.rays_per_probe;
    let dir = directions[index % volume.rays_per_probe].xyz;
    let hit = trace_ray(probe_position(probe), dir, volume.max_ray_distance, false);
    var out: GpuDdgiRayHit;
    out.t = select(hit.t, -1.0, hit.triangle == INVALID);
    out.triangle = hit.triangle;
    out.instance = hit.instance;
    out.bary = pack2x16unorm(hit.bary);
    hits[index] = out;
}
