// ssil/upsample: the levels combined, coarsest first (Soler et al. §4): each level's gather
// plus the level above joint-bilaterally upsampled (Kopf et al. 2007) — bilinear weights times
// the agreement of depth and normal between the texel and each coarse texel, so that light
// does not bleed across edges. The coarsest level is its gather alone (no `coarse_level`). At
// level 0 with a start level above 0 the same pass brings the start level up to full
// resolution (no gather of its own: `with_gather` 0).
#import ssil_common

@group(2) @binding(0) var<uniform> ssil: GpuSsilParams;
@group(2) @binding(1) var<uniform> ssil_pass: GpuSsilPass;
@group(2) @binding(2) var pyramid_normal_depth: texture_2d<f32>;
// this level's gather (light, specular), unused at full resolution
@group(2) @binding(3) var source_light: texture_2d<f32>;
@group(2) @binding(4) var source_specular: texture_2d<f32>;
// the combined level above, one mip each
@group(2) @binding(5) var coarse_light: texture_2d<f32>;
@group(2) @binding(6) var coarse_specular: texture_2d<f32>;
@group(2) @binding(7) var target_light: texture_storage_2d<rgba16float, write>;
@group(2) @binding(8) var target_specular: texture_storage_2d<rgba16float, write>;
@group(1) @binding(0) var<uniform> frame: GpuFrameParams;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let level = ssil_pass.level;
    let size = level_size(level);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let texel = vec2<i32>(id.xy);
    var light = vec4<f32>(0.0);
    var specular = vec3<f32>(0.0);
    // the covered directions (covered_directions.wgsl), combined as the light is
    var covered = vec3<f32>(0.0);
    if ssil_pass.with_gather == 1u {
        light = textureLoad(source_light, texel, 0);
        specular = textureLoad(source_specular, texel, 0).rgb;
        covered = source_covered(texel);
    }
    let here = textureLoad(pyramid_normal_depth, id.xy, level);
    if ssil_pass.coarse_level > level && here.w >= 0.0 {
        let coarse_level = ssil_pass.coarse_level;
        let scale = f32(1u << (coarse_level - level));
        let coarse_size = vec2<i32>(level_size(coarse_level));
        let c = (vec2<f32>(id.xy) + 0.5) / scale - 0.5;
        let c0 = vec2<i32>(floor(c));
        let f = c - floor(c);
        var sum = vec4<f32>(0.0);
        var sum_specular = vec3<f32>(0.0);
        var sum_covered = vec3<f32>(0.0);
        var total = 0.0;
        var nearest = vec4<f32>(0.0);
        var nearest_specular = vec3<f32>(0.0);
        var nearest_covered = vec3<f32>(0.0);
        var nearest_distance = 1e30;
        for (var k = 0; k < 4; k++) {
            let o = vec2<i32>(k & 1, k >> 1);
            let q = clamp(c0 + o, vec2<i32>(0), coarse_size - 1);
            let there = textureLoad(pyramid_normal_depth, vec2<u32>(q), coarse_level);
            if there.w < 0.0 {
                continue;
            }
            let bilinear = select(1.0 - f.x, f.x, o.x == 1) * select(1.0 - f.y, f.y, o.y == 1);
            let depth_difference = abs(there.w - here.w) / max(here.w, 1e-6);
            let w = bilinear * exp(-depth_difference * depth_difference / (2.0 * 0.05 * 0.05))
                * pow(max(dot(there.xyz, here.xyz), 0.0), 8.0);
            let value = textureLoad(coarse_light, q, 0);
            let value_specular = textureLoad(coarse_specular, q, 0).rgb;
            let value_covered = coarse_covered(q);
            sum += w * value;
            sum_specular += w * value_specular;
            sum_covered += w * value_covered;
            total += w;
            if depth_difference < nearest_distance {
                nearest_distance = depth_difference;
                nearest = value;
                nearest_specular = value_specular;
                nearest_covered = value_covered;
            }
        }
        // Where no coarse texel agrees (a thin object, a silhouette), the closest in depth.
        if total > 1e-4 {
            light += sum / total;
            specular += sum_specular / total;
            covered += sum_covered / total;
        } else {
            light += nearest;
            specular += nearest_specular;
            covered += nearest_covered;
        }
    }
    textureStore(target_light, texel, vec4<f32>(light.rgb, min(light.a, 1.0)));
    textureStore(target_specular, texel, vec4<f32>(specular, 1.0));
    store_covered(texel, covered_within_lobe(covered, light.a));
}
