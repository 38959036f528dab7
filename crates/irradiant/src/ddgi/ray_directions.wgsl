// ddgi/ray_directions: the spherical Fibonacci ray set, rotated by this frame's random
// rotation so that over frames the probes see every direction.
#import ddgi_volume

@group(1) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(1) @binding(3) var<storage, read_write> directions: array<vec4<f32>>;

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= volume.rays_per_probe {
        return;
    }
    let d = spherical_fibonacci(f32(id.x), f32(volume.rays_per_probe));
    directions[id.x] = vec4<f32>(normalize(rotate_ray(d)), 0.0);
}
