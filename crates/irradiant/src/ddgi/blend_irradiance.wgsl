// ddgi/blend_irradiance: one workgroup a probe, one thread an interior texel. Each texel
// takes the cosine-weighted mean of the radiance its probe's rays brought back this frame,
// perceptually encoded (value^(1/gamma)), and blends it into the old value with hysteresis —
// lowered per texel where the light changed a lot (003, §4.3).
#import ddgi_volume
#import ddgi_rays

@group(1) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(1) @binding(3) var<storage, read> directions: array<vec4<f32>>;
@group(1) @binding(6) var<storage, read> samples: array<GpuDdgiRaySample>;
@group(1) @binding(7) var<storage, read_write> irradiance_atlas: array<vec2<u32>>;

const CACHE: u32 = BLEND_GROUP * BLEND_GROUP;
var<workgroup> cache_direction: array<vec4<f32>, CACHE>;
var<workgroup> cache_radiance: array<vec4<f32>, CACHE>;

@compute @workgroup_size(BLEND_GROUP, BLEND_GROUP, 1)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>, @builtin(local_invocation_id) local: vec3<u32>, @builtin(local_invocation_index) li: u32) {
    let probe = group.x + group.y * groups.x;
    if probe >= volume.probe_count {
        return;
    }
    let texels = volume.irradiance_texels;
    let texel_dir = texel_direction(local.xy, texels);
    let m = volume.rays_per_probe;
    var sum = vec3<f32>(0.0);
    var weight_sum = 0.0;
    for (var base = 0u; base < m; base += CACHE) {
        if base + li < m {
            cache_direction[li] = directions[base + li];
            let s = samples[probe * m + base + li];
            cache_radiance[li] = vec4<f32>(s.radiance, 0.0);
        }
        workgroupBarrier();
        let n = min(CACHE, m - base);
        for (var k = 0u; k < n; k++) {
            let w = max(0.0, dot(texel_dir, cache_direction[k].xyz));
            sum += w * cache_radiance[k].rgb;
            weight_sum += w;
        }
        workgroupBarrier();
    }
    if local.x >= texels || local.y >= texels {
        return;
    }
    let value = select(vec3<f32>(0.0), sum / weight_sum, weight_sum > 0.0);
    let encoded = pow(max(value, vec3<f32>(0.0)), vec3<f32>(1.0 / volume.irradiance_gamma));
    let texel = tile_origin(probe, texels + 2u) + 1u + local.xy;
    let index = texel.y * atlas_width(texels + 2u) + texel.x;
    let packed_old = irradiance_atlas[index];
    let old = vec3<f32>(unpack2x16float(packed_old.x), unpack2x16float(packed_old.y).x);
    var hysteresis = startup_hysteresis(volume.irradiance_hysteresis);
    if volume.convergence_heuristics != 0u && hysteresis > 0.0 {
        let delta = abs(encoded - old);
        let change = max(delta.x, max(delta.y, delta.z)) / max(max(max(encoded.x, encoded.y), max(encoded.z, max(old.x, max(old.y, old.z)))), 1e-4);
        if change > 0.8 {
            // The distribution the probe samples has changed completely.
            hysteresis = 0.0;
        } else if change > 0.25 {
            hysteresis = max(0.0, hysteresis - 0.15);
        }
    }
    let blended = mix(encoded, old, hysteresis);
    irradiance_atlas[index] = vec2<u32>(pack2x16float(blended.xy), pack2x16float(vec2<f32>(blended.z, 0.0)));
}
