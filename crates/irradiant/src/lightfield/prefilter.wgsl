// lightfield/prefilter: each probe's irradiance and distance-moment tiles, in DDGI's atlas
// layout (octahedral tiles with a mirrored 1-texel border, irradiance stored as
// value^(1/gamma)), so that DDGI's query reads them unchanged (the paper's §5.2: prefiltered
// irradiance with Chebyshev visibility). A texel's irradiance is the cosine-weighted mean of
// the reduced radiance map around its direction (E/π, as DDGI stores); its moments the
// cosine^distance_exponent-weighted means of r and r². Each reduced texel counts with its
// solid angle, dΩ ∝ 1/|v|³ for the octahedral map's unnormalised direction v.
#import lightfield
#import ddgi_volume

@group(2) @binding(29) var small_radiance: texture_2d_array<f32>;
@group(2) @binding(30) var small_moments: texture_2d_array<f32>;
@group(2) @binding(31) var target_irradiance: texture_storage_2d<rgba16float, write>;
@group(2) @binding(32) var target_distance: texture_storage_2d<rg32float, write>;
@group(2) @binding(0) var<uniform> volume: GpuDdgiVolume;

// The reduced map texel (x, y)'s direction and solid-angle weight.
fn reduced_texel(x: u32, y: u32, size: u32) -> vec4<f32> {
    let p = (vec2<f32>(f32(x), f32(y)) + 0.5) / f32(size) * 2.0 - 1.0;
    var v = vec3<f32>(p, 1.0 - abs(p.x) - abs(p.y));
    if v.z < 0.0 {
        v = vec3<f32>((1.0 - abs(v.yx)) * sign_not_zero2(v.xy), v.z);
    }
    let length_v = length(v);
    return vec4<f32>(v / length_v, 1.0 / (length_v * length_v * length_v));
}

// Thread per tile texel (border included) of the larger of the two tiles; x, y in the tile.
@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let probe = id.z;
    if probe >= lightfield.probe_count {
        return;
    }
    let size = lightfield.prefilter_resolution;
    for (var which = 0u; which < 2u; which++) {
        let texels = select(volume.distance_texels, volume.irradiance_texels, which == 0u);
        let tile = texels + 2u;
        if id.x >= tile || id.y >= tile {
            continue;
        }
        // A border texel repeats the interior texel across the octahedral fold.
        let interior = all(id.xy >= vec2<u32>(1u)) && all(id.xy <= vec2<u32>(texels));
        let source = select(border_source(id.x, id.y, texels), id.xy, interior);
        let n = texel_direction(source - 1u, texels);
        var sum = vec3<f32>(0.0);
        var weight_sum = 0.0;
        for (var y = 0u; y < size; y++) {
            for (var x = 0u; x < size; x++) {
                let t = reduced_texel(x, y, size);
                let c = max(dot(n, t.xyz), 0.0);
                if c <= 0.0 {
                    continue;
                }
                if which == 0u {
                    let w = c * t.w;
                    sum += w * textureLoad(small_radiance, vec2<u32>(x, y), probe, 0).rgb;
                    weight_sum += w;
                } else {
                    let w = pow(c, volume.distance_exponent) * t.w;
                    sum += vec3<f32>(w * textureLoad(small_moments, vec2<u32>(x, y), probe, 0).rg, 0.0);
                    weight_sum += w;
                }
            }
        }
        let mean = sum / max(weight_sum, 1e-12);
        let texel = tile_origin(probe, tile) + id.xy;
        if which == 0u {
            let encoded = pow(max(mean, vec3<f32>(0.0)), vec3<f32>(1.0 / volume.irradiance_gamma));
            textureStore(target_irradiance, texel, vec4<f32>(encoded, 1.0));
        } else {
            textureStore(target_distance, texel, vec4<f32>(mean.xy, 0.0, 0.0));
        }
    }
}
