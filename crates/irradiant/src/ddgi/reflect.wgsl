// ddgi/reflect: GI in glossy reflections (003 §4.4, DdgiReflectionSettings). At each pixel
// whose surface is glossy (has_specular, roughness up to REFLECT_MAX_ROUGHNESS), one direction
// from the GGX lobe's visible normals (Heitz 2018) is traced, and its hit is lit as the final
// gather's rays are: punctual light with a shadow ray, one emitter sample, and the probes'
// irradiance as the second and later bounces. Emission at the hit is left out, as for every
// traced ray of the technique: frame/direct already takes each emitter's highlight through the
// BRDF. With REFLECT_STEP 2 one pixel of each 2×2 traces a frame, in turn; the others are
// marked as not traced (a < 0) for ddgi/reflect_filter.
#import ddgi_hit_light
#import gbuffer
#import brdf

// rgb: the reflected light (f · cos / pdf × what the ray brings back); a: the ray's length,
// 0 where the sample fell below the surface (a sample of no light), NO_RAY where the pixel did
// not trace this frame, sees no surface or is not glossy (no sample at all).
@group(2) @binding(40) var reflection_rays: texture_storage_2d<rgba16float, write>;

// Rays that leave the scene: far enough to read as distant to the filter.
const SKY_DISTANCE: f32 = 1.0e4;
// A pixel without a sample this frame (ddgi/reflect_filter skips it).
const NO_RAY: vec4<f32> = vec4<f32>(0.0, 0.0, 0.0, -1.0);

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    let block = id.xy * REFLECT_STEP;
    if !in_frame(block) {
        return;
    }
    let turn = frame.frame_index % (REFLECT_STEP * REFLECT_STEP);
    let chosen = block + vec2<u32>(turn % REFLECT_STEP, turn / REFLECT_STEP);
    for (var y = 0u; y < REFLECT_STEP; y++) {
        for (var x = 0u; x < REFLECT_STEP; x++) {
            let pixel = block + vec2<u32>(x, y);
            if in_frame(pixel) && any(pixel != chosen) {
                textureStore(reflection_rays, pixel, NO_RAY);
            }
        }
    }
    if in_frame(chosen) {
        textureStore(reflection_rays, chosen, reflected_light(chosen));
    }
}

// Whether a surface traces reflections.
fn is_glossy(s: Surface) -> bool {
    return has_specular(s) && s.roughness <= REFLECT_MAX_ROUGHNESS;
}

fn reflected_light(pixel: vec2<u32>) -> vec4<f32> {
    if gbuffer_depth_at(pixel) < 0.0 {
        return NO_RAY;
    }
    let s = gbuffer_surface(pixel);
    let wo = view_dir(s.position);
    let n_dot_v = dot(s.normal, wo);
    // A matte neighbour is no sample of a glossy pixel's reflection.
    if !is_glossy(s) || n_dot_v <= 0.0 {
        return NO_RAY;
    }
    var rng = rng_seed(pixel.y * frame.width + pixel.x, frame.frame_index, frame.seed ^ 0x85ebca6bu);
    // A mirror's alpha of 0 leaves the lobe a delta, which the visible normals still sample.
    let alpha = max(s.roughness * s.roughness, 1e-4);
    let around = basis(s.normal);
    let h = around * sample_ggx_vndf(transpose(around) * wo, alpha, rand2(&rng));
    let wi = reflect(-wo, h);
    let n_dot_l = dot(s.normal, wi);
    if n_dot_l <= 0.0 || dot(wi, s.geometric_normal) <= 0.0 {
        return vec4<f32>(0.0);
    }
    // f · cos / pdf of a visible-normal sample: F · G2 / G1.
    let g1 = 1.0 / (1.0 + smith_lambda(n_dot_v, alpha));
    let g2 = 1.0 / (1.0 + smith_lambda(n_dot_v, alpha) + smith_lambda(n_dot_l, alpha));
    let weight = fresnel_schlick(f0_of(s), dot(wo, h)) * g2 / g1;
    let origin = offset_ray(s.position, s.geometric_normal);
    let hit = trace_ray(origin, wi, RAY_FAR, false);
    if hit.triangle == INVALID {
        return vec4<f32>(weight * scene_info.sky, SKY_DISTANCE);
    }
    let at = surface_at(origin, wi, hit.t, hit.triangle, hit.instance, hit.bary);
    let back = -wi;
    let direct = hit_punctual_light(at, back, rand(&rng)) + hit_emitter_light(at, back, GATHER_EMITTER_CANDIDATES, &rng);
    let probes = ddgi_irradiance_seen_from(at.position, at.normal, back, hit.t);
    let light = direct + hit_probe_light(at, back, probes, 0u, &rng);
    return vec4<f32>(weight * light, hit.t);
}
