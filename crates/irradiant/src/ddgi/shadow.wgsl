// ddgi/shadow: the shadow rays ddgi/shade queued (DdgiSettings::shadow_queue), densely with no
// idle lanes; each adds its light to its probe ray's sample where nothing blocks it.
// FETCH_RAYS (0 or 1, DdgiSettings::fetches_rays): a workgroup takes a run of fetch_run queued
// rays, and its lanes fetch the next as theirs ends (bvh_fetch).
#import ddgi_volume
#import ddgi_rays
#import ddgi_states
#import lights
#import bvh_fetch

@group(2) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(2) @binding(6) var<storage, read_write> samples: array<GpuDdgiRaySample>;

// ddgi/shade's DdgiShadowQueue, read only.
struct DdgiShadowQueueRead {
    count: u32,
    groups_x: u32,
    groups_y: u32,
    groups_z: u32,
    rays: array<GpuDdgiShadowRay>,
}
@group(2) @binding(19) var<storage, read> shadow_queue: DdgiShadowQueueRead;

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    if FETCH_RAYS == 1u {
        let run = fetch_run(shadow_queue.count, FETCH_WORKGROUPS);
        run_first = folded_index(group) * run;
        let left = shadow_queue.count - min(run_first, shadow_queue.count);
        trace_fetching(min(left, run), TRACE_ANY, local_index);
        return;
    }
    let i = folded_index(group) * 64u + local_index;
    if i >= shadow_queue.count {
        return;
    }
    let ray = shadow_queue.rays[i];
    let light = light_ray(ray.light, ray.origin);
    if !occluded(ray.origin, light.wi, light.distance) {
        samples[ray.sample].radiance += ray.contribution;
    }
}

// The workgroup's first queued ray, with FETCH_RAYS.
var<private> run_first: u32;

fn fetched_ray(k: u32) -> FetchedRay {
    let ray = shadow_queue.rays[run_first + k];
    let light = light_ray(ray.light, ray.origin);
    return FetchedRay(ray.origin, light.distance, light.wi);
}

fn fetched_hit(k: u32, hit: Hit) {
    if hit.triangle == INVALID {
        let ray = shadow_queue.rays[run_first + k];
        samples[ray.sample].radiance += ray.contribution;
    }
}
