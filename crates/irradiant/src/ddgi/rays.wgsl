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

// A probe ray's hit whose probe light ddgi/shade leaves to ddgi/between_volumes
// (GpuDdgiDeferredRead: every field documented there).
struct GpuDdgiDeferredRead {
    position: array<f32, 3>,
    viewer_distance: f32,
    normal: u32,
    geometric_normal: u32,
    wo: u32,
    weight_rg: u32,
    weight_b_taken: u32,
}

// One ray's weight in one texel's blend (ddgi/blend_weights). The first entry of each texel
// is its header instead: ray holds the texel's entry count, weight their sum.
struct GpuDdgiBlendWeight {
    ray: u32,
    weight: f32,
}

// Where a thread of a per-ray dispatch over a list of probes falls: the list entry of its
// probe, its ray, and the list entry of the workgroup's first probe with the ray block (the
// workgroup's key). A 64-thread workgroup takes PROBES_PER_GROUP neighbouring listed probes
// (a shader constant from DdgiSettings) and 64 / PROBES_PER_GROUP neighbouring rays of each,
// interleaved so that a warp holds the same rays of all its probes: near-parallel rays from
// nearby origins, or with one probe a cone of rays from one origin.
struct RayPlace {
    listed: u32,
    ray: u32,
    first: u32,
    block: u32,
}

fn ray_place(linear_group: u32, local_index: u32, rays_per_probe: u32) -> RayPlace {
    let rays_per_group = 64u / PROBES_PER_GROUP;
    let blocks = ray_blocks(rays_per_probe);
    var place: RayPlace;
    place.first = (linear_group / blocks) * PROBES_PER_GROUP;
    place.listed = place.first + local_index % PROBES_PER_GROUP;
    place.block = linear_group % blocks;
    place.ray = place.block * rays_per_group + local_index / PROBES_PER_GROUP;
    return place;
}

// Workgroups of 64 / PROBES_PER_GROUP rays that cover one probe's rays.
fn ray_blocks(rays_per_probe: u32) -> u32 {
    let rays_per_group = 64u / PROBES_PER_GROUP;
    return (rays_per_probe + rays_per_group - 1u) / rays_per_group;
}
