// ddgi/blend_distance: per texel, the cosine^exponent-weighted mean of hit distance and of
// its square (the moments that Chebyshev visibility needs), blended with hysteresis.
#import ddgi_volume
#import ddgi_rays

@group(1) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(1) @binding(3) var<storage, read> directions: array<vec4<f32>>;
@group(1) @binding(6) var<storage, read> samples: array<GpuDdgiRaySample>;
@group(1) @binding(8) var<storage, read_write> distance_atlas: array<vec2<f32>>;

// cos^distance_exponent. A whole exponent (DISTANCE_POWER, a shader constant) unrolls into
// squarings and products; pow costs two special-function operations, which are scarce.
fn cosine_power(c: f32) -> f32 {
    if DISTANCE_POWER == 0u {
        return pow(c, volume.distance_exponent);
    }
    var result = 1.0;
    var square = c;
    for (var bit = 0u; bit < 8u; bit++) {
        if (DISTANCE_POWER & (1u << bit)) != 0u {
            result *= square;
        }
        square *= square;
    }
    return result;
}

const CACHE: u32 = BLEND_GROUP * BLEND_GROUP;
var<workgroup> cache_direction: array<vec4<f32>, CACHE>;

@compute @workgroup_size(BLEND_GROUP, BLEND_GROUP, 1)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>, @builtin(local_invocation_id) local: vec3<u32>, @builtin(local_invocation_index) li: u32) {
    let probe = group.x + group.y * groups.x;
    if probe >= volume.probe_count {
        return;
    }
    let texels = volume.distance_texels;
    let texel_dir = texel_direction(local.xy, texels);
    let m = volume.rays_per_probe;
    var sum = vec2<f32>(0.0);
    var weight_sum = 0.0;
    for (var base = 0u; base < m; base += CACHE) {
        if base + li < m {
            let d = min(abs(samples[probe * m + base + li].distance), volume.max_ray_distance);
            cache_direction[li] = vec4<f32>(directions[base + li].xyz, d);
        }
        workgroupBarrier();
        let n = min(CACHE, m - base);
        for (var k = 0u; k < n; k++) {
            let c = cache_direction[k];
            let w = cosine_power(max(0.0, dot(texel_dir, c.xyz)));
            sum += w * vec2<f32>(c.w, c.w * c.w);
            weight_sum += w;
        }
        workgroupBarrier();
    }
    if local.x >= texels || local.y >= texels {
        return;
    }
    let texel = tile_origin(probe, texels + 2u) + 1u + local.xy;
    let index = texel.y * atlas_width(texels + 2u) + texel.x;
    let old = distance_atlas[index];
    // A texel no ray came near this frame keeps its old value.
    if weight_sum <= 0.0 && volume.frame > 0u {
        return;
    }
    let value = select(vec2<f32>(volume.max_ray_distance, volume.max_ray_distance * volume.max_ray_distance), sum / weight_sum, weight_sum > 0.0);
    let hysteresis = startup_hysteresis(volume.distance_hysteresis);
    distance_atlas[index] = mix(value, old, hysteresis);
}
