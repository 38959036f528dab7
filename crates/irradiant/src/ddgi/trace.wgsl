// ddgi/trace: m rays from every probe that updates, closest hit, into the hit buffer.
// FETCH_RAYS (0 or 1, DdgiSettings::fetches_rays): a workgroup a listed probe (the blends'
// dispatch) whose lanes walk all its rays and fetch the next as theirs ends (bvh_fetch);
// else a thread a ray (ray_slot).
#import ddgi_probes
#import ddgi_rays
#import ddgi_active
#import bvh_fetch

@group(2) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(2) @binding(3) var<storage, read> directions: array<vec4<f32>>;
@group(2) @binding(4) var<storage, read_write> hits: array<GpuDdgiRayHit>;

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    if FETCH_RAYS == 1u {
        fetching_probe = listed_probe(group);
        let rays = select(volume.rays_per_probe, 0u, fetching_probe == NOT_LISTED);
        fetching_origin = probe_position(min(fetching_probe, volume.probe_count - 1u));
        trace_fetching(rays, TRACE_CLOSEST, local_index);
        return;
    }
    let slot = ray_slot(group, local_index);
    if !slot.valid {
        return;
    }
    let dir = directions[slot.ray].xyz;
    write_hit(slot.index, trace_ray(probe_position(slot.probe), dir, volume.max_ray_distance, false));
}

fn write_hit(index: u32, hit: Hit) {
    var out: GpuDdgiRayHit;
    out.t = select(hit.t, -1.0, hit.triangle == INVALID);
    out.triangle = hit.triangle;
    out.instance = hit.instance;
    out.bary = pack2x16unorm(hit.bary);
    hits[index] = out;
}

// The workgroup's probe and its position, with FETCH_RAYS.
var<private> fetching_probe: u32;
var<private> fetching_origin: vec3<f32>;

fn fetched_ray(k: u32) -> FetchedRay {
    return FetchedRay(fetching_origin, volume.max_ray_distance, directions[k].xyz);
}

fn fetched_hit(k: u32, hit: Hit) {
    write_hit(fetching_probe * volume.rays_per_probe + k, hit);
}
