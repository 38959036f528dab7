// ddgi/ray_directions: the probe ray set (spherical Fibonacci, in trace order: see
// octahedral::probe_ray_set), rotated by this frame's random rotation so that over frames the
// probes see every direction; in a convergence round also turned by the round's angle.
#import ddgi_volume
#import ddgi_convergence

@group(2) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(2) @binding(3) var<storage, read_write> directions: array<vec4<f32>>;
@group(2) @binding(14) var<storage, read> ray_set: array<vec4<f32>>;

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= volume.rays_per_probe {
        return;
    }
    directions[id.x] = vec4<f32>(normalize(rotate_ray(round_turn(ray_set[id.x].xyz))), 0.0);
}
