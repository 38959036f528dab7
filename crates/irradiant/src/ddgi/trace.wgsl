// ddgi/trace: m rays from every probe that updates, closest hit, into the hit buffer.
#import ddgi_probes
#import ddgi_rays
#import ddgi_active
#import bvh

@group(2) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(2) @binding(3) var<storage, read> directions: array<vec4<f32>>;
@group(2) @binding(4) var<storage, read_write> hits: array<GpuDdgiRayHit>;

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    let slot = ray_slot(group, local_index);
    if !slot.valid {
        return;
    }
    let dir = directions[slot.ray].xyz;
    let hit = trace_ray(probe_position(slot.probe), dir, volume.max_ray_distance, false);
    var out: GpuDdgiRayHit;
    out.t = select(hit.t, -1.0, hit.triangle == INVALID);
    out.triangle = hit.triangle;
    out.instance = hit.instance;
    out.bary = pack2x16unorm(hit.bary);
    hits[slot.index] = out;
}
