// lightfield/resolve: the frame's indirect light: the diffuse reflection of the Lambertian
// term — prefiltered irradiance with Chebyshev visibility (DDGI's query over the baked tiles)
// for the prefiltered algorithm, the traced and filtered incident light otherwise — plus the
// glossy term.
#import lightfield
#import ddgi_query
#import gbuffer
#import brdf

@group(2) @binding(46) var lambert_light: texture_2d<f32>;
@group(2) @binding(47) var glossy_light: texture_2d<f32>;
@group(2) @binding(48) var indirect: texture_storage_2d<rgba32float, read_write>;
// lightfield/irradiance's block queries (irradiance_block > 1).
@group(2) @binding(58) var coarse_irradiance: texture_2d<f32>;
@group(2) @binding(59) var coarse_normal: texture_2d<f32>;

// The block irradiance at this pixel: the four nearest queries, bilinearly weighted
// and each by how well its surface matches this one (view depth within 5 %, normals alike);
// where none matches (silhouettes, thin objects), the one that matches best. No exact query
// here: its registers would slow the whole pass (EXACT_IRRADIANCE, a shader constant, keeps
// it out when the irradiance is upsampled).
fn upsampled_irradiance(pixel: vec2<u32>, s: Surface, depth: f32) -> vec3<f32> {
    let block = lightfield.irradiance_block;
    let last = vec2<i32>((vec2<u32>(frame_size()) + block - 1u) / block) - 1;
    let c = (vec2<f32>(pixel) + 0.5) / f32(block) - 0.5;
    let base = vec2<i32>(floor(c));
    let f = c - floor(c);
    var sum = vec3<f32>(0.0);
    var weight_sum = 0.0;
    var best = vec4<f32>(0.0, 0.0, 0.0, -1.0);
    for (var k = 0u; k < 4u; k++) {
        let offset = vec2<u32>(k & 1u, k >> 1u);
        let t = clamp(base + vec2<i32>(offset), vec2<i32>(0), last);
        let v = textureLoad(coarse_irradiance, t, 0);
        if v.w < 0.0 {
            continue;
        }
        let bilinear = mix(1.0 - f, f, vec2<f32>(offset));
        let depth_agreement = max(1.0 - abs(v.w - depth) / (0.05 * depth), 0.0);
        let normal_agreement = pow(max(dot(textureLoad(coarse_normal, t, 0).xyz, s.normal), 0.0), 8.0);
        let agreement = (depth_agreement + 1e-3) * (normal_agreement + 1e-3);
        if agreement > best.w {
            best = vec4<f32>(v.rgb, agreement);
        }
        let w = bilinear.x * bilinear.y * depth_agreement * normal_agreement;
        sum += w * v.rgb;
        weight_sum += w;
    }
    if weight_sum < 1e-3 {
        return best.rgb;
    }
    return sum / weight_sum;
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let pixel = vec2<i32>(id.xy);
    if gbuffer_depth_at(id.xy) < 0.0 {
        textureStore(indirect, pixel, vec4<f32>(0.0));
        return;
    }
    let s = gbuffer_surface(id.xy);
    var lambert: vec3<f32>;
    if lightfield.algorithm == ALGORITHM_PREFILTERED && EXACT_IRRADIANCE == 0u {
        lambert = upsampled_irradiance(id.xy, s, gbuffer_depth_at(id.xy));
    } else if lightfield.algorithm == ALGORITHM_PREFILTERED {
        lambert = ddgi_irradiance(s.position, s.normal, view_dir(s.position)).irradiance;
    } else {
        lambert = textureLoad(lambert_light, pixel, 0).rgb;
    }
    var out = diffuse_weight(s) * lambert + textureLoad(glossy_light, pixel, 0).rgb;
    // A specular surface too rough for a glossy ray: its wide lobe reflects about the
    // irradiance, F0 of it.
    if has_specular(s) && s.roughness > lightfield.glossy_max_roughness {
        out += f0_of(s) * lambert;
    }
    textureStore(indirect, pixel, vec4<f32>(out, 1.0));
}
