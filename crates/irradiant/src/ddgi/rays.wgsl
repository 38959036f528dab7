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

// Rays of a dispatch are laid out probe-major: ray r of probe p is p × rays_per_probe + r.
fn ray_index(id: vec3<u32>, groups: vec3<u32>) -> u32 {
    return id.x + id.y * groups.x * 64u;
}
