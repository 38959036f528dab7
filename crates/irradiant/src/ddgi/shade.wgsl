// ddgi/shade: the radiance each probe ray brings back: direct light (punctual lights with
// shadow rays, one emitter sample) and indirect light from last frame's probes, so that
// bounces accumulate over frames. Misses take the sky. Emission is left out: the frame's
// direct pass samples every emitter already, so the probes hold indirect light only.
#import ddgi_query
#import ddgi_rays
#import lights
#import random

@group(1) @binding(3) var<storage, read> directions: array<vec4<f32>>;
@group(1) @binding(4) var<storage, read> hits: array<GpuDdgiRayHit>;
@group(1) @binding(6) var<storage, read_write> samples: array<GpuDdgiRaySample>;

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    let slot = ray_slot(group, groups, local_index);
    if !slot.valid || !probe_shades(slot.probe) {
        return;
    }
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
        return;
    }
    let origin = probe_position(probe);
    let tri = triangles[hit.triangle];
    let face = to_world_normal(instances[hit.instance], cross(tri.e1, tri.e2));
    let backface = dot(face, dir) > 0.0;
    if backface && (volume.weights & WEIGHT_BACKFACE_HITS) != 0u {
        // Inside geometry, or looking at the back of a one-sided wall: no light, and a
        // shortened depth so that the probe reads this direction as shadowed.
        out.radiance = vec3<f32>(0.0);
        out.distance = -BACKFACE_DEPTH_SCALE * hit.t;
        samples[index] = out;
        return;
    }
    let s = surface_at(origin, dir, hit.t, hit.triangle, hit.instance, unpack2x16unorm(hit.bary));
    let wo = -dir;
    var rng = rng_seed(index, volume.frame, 0x68bc21ebu);
    var l: vec3<f32>;
    if volume.all_lights != 0u {
        l = direct_punctual(s, wo);
    } else {
        // LIGHT_PER_WARP: one random light for each 32 neighbouring threads (a warp) instead
        // of each ray, so that a warp's shadow rays walk to one light together rather than
        // taking turns for each light; every ray still sees each light with equal probability.
        var light_rng = rng;
        if LIGHT_PER_WARP == 1u {
            light_rng = rng_seed((group.x + group.y * groups.x) * 2u + local_index / 32u, volume.frame, 0x2c1b3c6du);
        }
        l = direct_punctual_one(s, wo, rand(&light_rng));
    }
    if scene_info.emitter_count > 0u {
        l += emitter_light(s, wo, &rng);
    }
    l += diffuse_weight(s) * ddgi_irradiance(s.position, s.normal, wo);
    out.radiance = l;
    // The sign marks backfaces for relocation, whatever the weights.
    out.distance = select(hit.t, -hit.t, backface);
    samples[index] = out;
}
