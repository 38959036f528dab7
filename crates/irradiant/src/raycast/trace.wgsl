// raycast/trace: closest-hit (or any-hit) of a buffer of rays. Used to test the GPU traversal
// against a CPU oracle and to measure rays per second; its counting variant (COUNT_WORK 1)
// also returns each ray's node visits and triangle tests, and ends a closest-hit ray's search
// at its `stop` (trace_ray_until), which the timed pass leaves out.
// FETCH_RAYS (0 or 1; 1 where GpuScene::fetches_rays): a workgroup's lanes walk a run of
// fetch_run(ray_count, FETCH_WORKGROUPS) rays and fetch the next as theirs ends (bvh_fetch);
// 0 traces a ray a thread.
#import bvh_fetch

struct GpuRay {
    origin: vec3<f32>,
    t_max: f32,
    dir: vec3<f32>,
    // the counting variant's trace_ray_until distance for closest-hit rays (0: none)
    stop: f32,
}

struct GpuRayHit {
    t: f32,
    triangle: u32,
    instance: u32,
    // COUNT_WORK 1: node visits (bits 0–15) and triangle tests (16–31), each saturating
    work: u32,
}

struct GpuRayCastParams {
    ray_count: u32,
    any_hit: u32,
    _pad0: u32,
    _pad1: u32,
}

@group(1) @binding(0) var<uniform> params: GpuRayCastParams;
@group(1) @binding(1) var<storage, read> rays: array<GpuRay>;
@group(1) @binding(2) var<storage, read_write> hits: array<GpuRayHit>;

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>, @builtin(local_invocation_index) local_index: u32, @builtin(workgroup_id) group: vec3<u32>) {
    bvh_thread(local_index);
    if FETCH_RAYS == 1u {
        let run = fetch_run(params.ray_count, FETCH_WORKGROUPS);
        run_first = (group.x + group.y * groups.x) * run;
        let left = params.ray_count - min(run_first, params.ray_count);
        trace_fetching(min(left, run), select(TRACE_CLOSEST, TRACE_ANY, params.any_hit != 0u), local_index);
        return;
    }
    // 2D dispatch for ray counts above 65535 × 64.
    let index = id.x + id.y * groups.x * 64u;
    if index >= params.ray_count {
        return;
    }
    let ray = rays[index];
    var hit: Hit;
    if COUNT_WORK == 1u && params.any_hit == 0u && ray.stop > 0.0 {
        hit = trace_ray_until(ray.origin, ray.dir, ray.t_max, ray.stop);
    } else {
        hit = trace_ray(ray.origin, ray.dir, ray.t_max, params.any_hit != 0u);
    }
    write_hit(index, hit);
}

fn write_hit(index: u32, hit: Hit) {
    var out: GpuRayHit;
    out.t = select(hit.t, -1.0, hit.triangle == INVALID);
    out.triangle = hit.triangle;
    out.instance = hit.instance;
    if COUNT_WORK == 1u {
        out.work = min(work_nodes, 0xffffu) | (min(work_triangles, 0xffffu) << 16u);
    }
    hits[index] = out;
}

// The workgroup's first ray, with FETCH_RAYS.
var<private> run_first: u32;

fn fetched_ray(k: u32) -> FetchedRay {
    let ray = rays[run_first + k];
    return FetchedRay(ray.origin, ray.t_max, ray.dir);
}

fn fetched_hit(k: u32, hit: Hit) {
    write_hit(run_first + k, hit);
}
