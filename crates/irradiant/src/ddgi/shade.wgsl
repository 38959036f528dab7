// ddgi/shade: the radiance each probe ray brings back (ddgi_hit_light): direct light and
// indirect light from last frame's probes (read at the hit, or with TRACED_BOUNCE one traced
// ray further on), so that bounces accumulate over frames. Misses take the sky. The probes
// hold indirect light only.
#import ddgi_hit_light
#import ddgi_rays
#import ddgi_active

@group(2) @binding(3) var<storage, read> directions: array<vec4<f32>>;
@group(2) @binding(4) var<storage, read> hits: array<GpuDdgiRayHit>;
@group(2) @binding(6) var<storage, read_write> samples: array<GpuDdgiRaySample>;
// With several volumes and `update.light_between_volumes`: each ray's hit, whose probe light
// ddgi/between_volumes adds from every volume that covers it (defers_probe_light).
@group(2) @binding(25) var<storage, read_write> deferred_reads: array<GpuDdgiDeferredRead>;

// TRACED_BOUNCE (0 or 1, DdgiUpdateSettings::traced_bounce): each hit's indirect light from one
// cosine-distributed ray traced on from it (traced_light), instead of the probes read at the
// hit. Either way, hits the probes are blind to trace on (BLIND_BOUNCES, ddgi_hit_light).
// SHADOW_QUEUE (0 or 1, DdgiSettings::shadow_queue): instead of tracing the punctual light's
// shadow ray here, where only the lanes whose hit faces the light trace while the rest of the
// warp waits, append it to this queue; ddgi/shadow traces the queue densely and adds the
// light to the sample where nothing blocks it. The header doubles as ddgi/shadow's indirect
// dispatch: (count, workgroups x, y, z), cleared before this pass.
struct DdgiShadowQueue {
    count: atomic<u32>,
    groups_x: atomic<u32>,
    groups_y: atomic<u32>,
    groups_z: atomic<u32>,
    rays: array<GpuDdgiShadowRay>,
}
@group(2) @binding(19) var<storage, read_write> shadow_queue: DdgiShadowQueue;

var<workgroup> queued_in_group: atomic<u32>;
var<workgroup> group_base: u32;

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    let slot = ray_slot(group, local_index);
    var shadow: GpuDdgiShadowRay;
    var queued = false;
    if slot.valid {
        // LIGHT_PER_WARP: one random light for each 32 neighbouring threads (a warp) instead
        // of each ray, so that a warp's shadow rays walk to one light together rather than
        // taking turns for each light; every ray still sees each light with equal probability.
        var light_rng = ray_rng(slot.index);
        if LIGHT_PER_WARP == 1u {
            light_rng = rng_seed(slot.group_key * 2u + local_index / 32u, ray_frame(), 0x2c1b3c6du);
        }
        queued = shade_ray(slot, rand(&light_rng), &shadow);
    }
    if SHADOW_QUEUE == 1u {
        enqueue_shadow(queued, shadow, local_index);
    }
}

// Probe ray `index`'s random numbers this frame (its light choice takes the first unless
// LIGHT_PER_WARP; emitter_light starts over from the seed).
fn ray_rng(index: u32) -> u32 {
    return rng_seed(index, ray_frame(), 0x68bc21ebu);
}

// Whether the probes' light at this pass's hits is left to ddgi/between_volumes: with several
// volumes, in the normal update. A convergence round runs before the passes that would read
// the other volumes, and reads its own.
fn defers_probe_light() -> bool {
    return volume.light_between_volumes != 0u && convergence.round == 0u;
}

// Shades one probe ray into samples[slot.index]; with SHADOW_QUEUE, leaves out the chosen
// light and returns true with its shadow ray in `shadow` where that light can reach the hit.
fn shade_ray(slot: RaySlot, light_u: f32, shadow: ptr<function, GpuDdgiShadowRay>) -> bool {
    let index = slot.index;
    let probe = slot.probe;
    let dir = directions[slot.ray].xyz;
    // FUSED_TRACE: this pass traces the ray itself (ddgi/trace_shade) instead of reading
    // ddgi/trace's hit: no hit buffer round trip and one dispatch fewer.
    var hit: GpuDdgiRayHit;
    if FUSED_TRACE == 1u {
        let found = trace_ray(probe_position(probe), dir, volume.max_ray_distance, false);
        hit.t = select(found.t, -1.0, found.triangle == INVALID);
        hit.triangle = found.triangle;
        hit.instance = found.instance;
        hit.bary = pack2x16unorm(found.bary);
    } else {
        hit = hits[index];
    }
    var out: GpuDdgiRaySample;
    if hit.t < 0.0 {
        out.radiance = scene_info.sky;
        out.distance = volume.max_ray_distance;
        samples[index] = out;
        if defers_probe_light() {
            deferred_reads[index] = nothing_to_read();
        }
        return false;
    }
    let origin = probe_position(probe);
    let tri = triangle_at(hit.triangle);
    let face = to_world_normal(instances[hit.instance], cross(tri.e1, tri.e2));
    let backface = dot(face, dir) > 0.0;
    if backface && (volume.weights & WEIGHT_BACKFACE_HITS) != 0u {
        // Inside geometry, or looking at the back of a one-sided wall: no light, and a
        // shortened depth so that the probe reads this direction as shadowed.
        out.radiance = vec3<f32>(0.0);
        out.distance = -BACKFACE_DEPTH_SCALE * hit.t;
        samples[index] = out;
        if defers_probe_light() {
            deferred_reads[index] = nothing_to_read();
        }
        return false;
    }
    let s = surface_at(origin, dir, hit.t, hit.triangle, hit.instance, unpack2x16unorm(hit.bary));
    let wo = -dir;
    var rng = ray_rng(index);
    var l = vec3<f32>(0.0);
    var queued = false;
    if SHADOW_QUEUE == 1u && volume.all_lights == 0u && scene_info.light_count > 0u {
        let light = pick_light(light_u);
        let shadow_from = shadow_origin(s);
        let contribution = unshadowed_light(s, wo, light_ray(light, shadow_from)) * f32(scene_info.light_count);
        if any(contribution != vec3<f32>(0.0)) {
            (*shadow).origin = shadow_from;
            (*shadow).sample = index;
            (*shadow).contribution = contribution;
            (*shadow).light = light;
            queued = true;
        }
    } else {
        l = hit_punctual_light(s, wo, light_u);
    }
    if defers_probe_light() {
        var deferred: GpuDdgiDeferredRead;
        if TRACED_BOUNCE == 1u {
            l += hit_emitter_and_traced_bounce_deferred(s, wo, &rng, &deferred);
        } else {
            l += hit_emitter_light(s, wo, HIT_EMITTER_CANDIDATES, &rng);
            deferred = deferred_read(s, wo, 0.0, diffuse_weight(s));
        }
        deferred_reads[index] = deferred;
    } else if TRACED_BOUNCE == 1u {
        l += hit_emitter_and_traced_bounce(s, wo, &rng);
    } else {
        l += hit_emitter_and_probe_light(s, wo, &rng);
    }
    out.radiance = l;
    // The sign marks backfaces for relocation, whatever the weights.
    out.distance = select(hit.t, -hit.t, backface);
    samples[index] = out;
    return queued;
}

// Appends the workgroup's queued shadow rays to the queue with one global atomic a workgroup,
// and raises ddgi/shadow's indirect dispatch to cover them.
fn enqueue_shadow(queued: bool, ray: GpuDdgiShadowRay, local_index: u32) {
    if local_index == 0u {
        atomicStore(&queued_in_group, 0u);
    }
    workgroupBarrier();
    var place = 0u;
    if queued {
        place = atomicAdd(&queued_in_group, 1u);
    }
    workgroupBarrier();
    if local_index == 0u {
        let count = atomicLoad(&queued_in_group);
        var base = 0u;
        if count > 0u {
            base = atomicAdd(&shadow_queue.count, count);
            // A thread a ray, or with FETCH_RAYS runs of fetch_run rays (bvh_fetch); the last
            // workgroup to append counts every queued ray, and the maximum covers it.
            let in_queue = base + count;
            var groups = folded_groups((in_queue + 63u) / 64u);
            if FETCH_RAYS == 1u {
                groups = fetch_groups(in_queue, FETCH_WORKGROUPS);
            }
            atomicMax(&shadow_queue.groups_x, groups.x);
            atomicMax(&shadow_queue.groups_y, groups.y);
            atomicMax(&shadow_queue.groups_z, 1u);
        }
        group_base = base;
    }
    workgroupBarrier();
    if queued {
        shadow_queue.rays[group_base + place] = ray;
    }
}
