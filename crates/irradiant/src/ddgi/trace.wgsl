// ddgi/trace: m rays from every probe that updates, closest hit, into the hit buffer.
// FETCH_RAYS (0 or 1, DdgiSettings::fetches_rays): a workgroup takes a run of the listed
// probes' rays, fetch_run of them in listed-probe-major order, and its lanes fetch the next as
// theirs ends (bvh_fetch); else a thread a ray (ray_slot).
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
        let probe_rays = listed_count() * volume.rays_per_probe;
        let run = fetch_run(probe_rays, FETCH_WORKGROUPS);
        run_first = folded_index(group) * run;
        let left = probe_rays - min(run_first, probe_rays);
        trace_fetching(min(left, run), TRACE_CLOSEST, local_index);
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

// With FETCH_RAYS: the workgroup's first ray (in listed-probe-major order), and the hit slot of
// the lane's ray, kept from fetched_ray for fetched_hit.
var<private> run_first: u32;
var<private> fetched_slot: u32;

fn fetched_ray(k: u32) -> FetchedRay {
    let listed_ray = run_first + k;
    let ray = listed_ray % volume.rays_per_probe;
    let probe = listed_at(listed_ray / volume.rays_per_probe);
    fetched_slot = probe * volume.rays_per_probe + ray;
    return FetchedRay(probe_position(probe), volume.max_ray_distance, directions[ray].xyz);
}

fn fetched_hit(k: u32, hit: Hit) {
    write_hit(fetched_slot, hit);
}
