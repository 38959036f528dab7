// ddgi/shadow: the shadow rays ddgi/shade queued (DdgiSettings::shadow_queue), one a thread
// with no idle lanes; each adds its light to its probe ray's sample where nothing blocks it.
#import ddgi_volume
#import ddgi_rays
#import ddgi_states
#import lights

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
