// ddgi: the per-ray buffers between trace, shade and blend.
struct GpuDdgiRayHit {
    // distance to the hit; negative for a miss
    t: f32,
    triangle: u32,
    instance: u32,
    // barycentrics, pack2x16unorm
    bary: u32,
}

struct GpuDdgiRaySample {
    // radiance arriving at the probe along the ray
    radiance: vec3<f32>,
    // distance to what the ray hit (max_ray_distance for a miss); negative for a backface
    distance: f32,
}

// A probe ray's shadow ray, queued by ddgi/shade for ddgi/shadow (DdgiSettings::shadow_queue).
struct GpuDdgiShadowRay {
    // shadow_origin of the hit surface
    origin: vec3<f32>,
    // index of the probe ray's GpuDdgiRaySample
    sample: u32,
    // the light's f · L · cos if nothing blocks it
    contribution: vec3<f32>,
    // index into the scene's lights
    light: u32,
}

// One ray's weight in one texel's blend (ddgi/blend_weights). The first entry of each texel
// is its header instead: ray holds the texel's entry count, weight their sum.
struct GpuDdgiBlendWeight {
    ray: u32,
    weight: f32,
}

// Rays are stored probe-major: ray r of probe p is p × rays_per_probe + r.
struct RaySlot {
    probe: u32,
    ray: u32,
    index: u32,
    valid: bool,
}

// Which ray a thread of ddgi/trace or ddgi/shade takes. A 64-thread workgroup takes
// PROBES_PER_GROUP neighbouring probes (a shader constant from DdgiSettings) and
// 64 / PROBES_PER_GROUP neighbouring rays of each, interleaved so that a warp holds the
// same rays of all its probes: near-parallel rays from nearby origins, or with one probe a
// cone of rays from one origin.
fn ray_slot(group: vec3<u32>, groups: vec3<u32>, local_index: u32) -> RaySlot {
    let rays_per_group = 64u / PROBES_PER_GROUP;
    let ray_blocks = (volume.rays_per_probe + rays_per_group - 1u) / rays_per_group;
    let linear = group.x + group.y * groups.x;
    var slot: RaySlot;
    slot.probe = (linear / ray_blocks) * PROBES_PER_GROUP + local_index % PROBES_PER_GROUP;
    slot.ray = (linear % ray_blocks) * rays_per_group + local_index / PROBES_PER_GROUP;
    slot.index = slot.probe * volume.rays_per_probe + slot.ray;
    slot.valid = slot.probe < volume.probe_count && slot.ray < volume.rays_per_probe;
    return slot;
}
