// lightfield/reduce: the maps averaged down to the prefilter's resolution, per probe: radiance,
// and the first two moments of distance (mean r and mean r², distances clamped to
// `max_distance` so that rays that leave the scene count as far, not infinite). Averaging
// keeps the moments exact: the prefilters then convolve a few thousand texels a probe instead
// of a million.
#import lightfield

@group(2) @binding(27) var target_small_radiance: texture_storage_2d_array<rgba16float, write>;
@group(2) @binding(28) var target_small_moments: texture_storage_2d_array<rg32float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = lightfield.prefilter_resolution;
    if id.x >= size || id.y >= size || id.z >= lightfield.probe_count {
        return;
    }
    let block = lightfield.resolution / size;
    var radiance = vec3<f32>(0.0);
    var moments = vec2<f32>(0.0);
    for (var y = 0u; y < block; y++) {
        for (var x = 0u; x < block; x++) {
            let texel = id.xy * block + vec2<u32>(x, y);
            radiance += unpack_r11g11b10(textureLoad(lightfield_radiance, texel, id.z, 0).r);
            let r = min(geometry_distance(textureLoad(lightfield_geometry, texel, id.z, 0).r), lightfield.max_distance);
            moments += vec2<f32>(r, r * r);
        }
    }
    let n = f32(block * block);
    textureStore(target_small_radiance, id.xy, id.z, vec4<f32>(radiance / n, 1.0));
    textureStore(target_small_moments, id.xy, id.z, vec4<f32>(moments / n, 0.0, 0.0));
}
