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

// Workgroups of 64 / PROBES_PER_GROUP rays that cover one probe's rays.
fn ray_blocks(rays_per_probe: u32) -> u32 {
    let rays_per_group = 64u / PROBES_PER_GROUP;
    return (rays_per_probe + rays_per_group - 1u) / rays_per_group;
}
