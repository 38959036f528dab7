// ddgi/between_volumes: light between volumes (003 §7.4). With several volumes, ddgi/shade
// leaves the probes' light at each probe ray's hit out (GpuDdgiDeferredRead). For each volume
// that updates, this pass then runs once for every volume, finest first, bound to that
// volume's probes (group 2, as ddgi/shade's query is) and to the updating volume's rays
// (owner_*), and adds that volume's share of the hit's light: the share ddgi/resolve would
// give a pixel there (volume_share), so that the shares add up to one. A probe ray that leaves
// its own volume thus reads the volume it lands in, and the light of a lamp in one volume
// reaches the probes of the next.
#import ddgi_hit_light
#import ddgi_rays

@group(3) @binding(10) var<uniform> owner: GpuDdgiVolume;
@group(3) @binding(11) var<storage, read> owner_active_probes: DdgiActiveProbes;
@group(3) @binding(12) var<storage, read_write> owner_samples: array<GpuDdgiRaySample>;
@group(3) @binding(13) var<storage, read_write> owner_deferred_reads: array<GpuDdgiDeferredRead>;

// Dispatched as the owner's ddgi/shade is, over its updating probes (ray_place).
@compute @workgroup_size(64, 1, 1)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    let place = ray_place(folded_index(group), local_index, owner.rays_per_probe);
    if place.listed >= owner_active_probes.lists[LIST_UPDATING].count || place.ray >= owner.rays_per_probe {
        return;
    }
    let index = owner_active_probes.probes[LIST_UPDATING * owner.probe_count + place.listed] * owner.rays_per_probe + place.ray;
    var r = owner_deferred_reads[index];
    let taken = deferred_taken(r);
    let s = deferred_surface(r);
    let share = volume_share(s.position, taken);
    if share <= 0.0 {
        return;
    }
    let wo = deferred_wo(r);
    var read: ProbeRead;
    if r.viewer_distance > 0.0 {
        read = ddgi_irradiance_seen_from(s.position, s.normal, wo, r.viewer_distance);
    } else {
        read = ddgi_irradiance(s.position, s.normal, wo);
    }
    var rng = rng_seed(index, owner.frame, 0x3c6ef372u + volume.volume_index);
    owner_samples[index].radiance += share * hit_probe_light(s, wo, read, BLIND_BOUNCES, &rng);
    r.weight_b_taken = pack2x16float(vec2<f32>(s.albedo.b, taken + share));
    owner_deferred_reads[index] = r;
}
