// lightfield/trace: each pixel's indirect light from rays traced through the light field
// (§5): `lambert_rays` cosine-distributed rays, whose mean radiance estimates the cosine-
// weighted incident radiance E/π (stored as incident light, so that filters do not blur the
// albedo), and `glossy_rays` rays drawn from the specular lobe's visible normals, each worth
// its radiance × F·G2/G1 (the specular lobe's f·cos/pdf). The naive renderer takes many of
// both and stops here; the filtered ones take one and filter.
#import lightfield
#import gbuffer
#import brdf
#import random

// Rougher surfaces take F0 × the irradiance instead (lightfield/resolve).
fn traces_glossy(s: Surface) -> bool {
    return has_specular(s) && s.roughness <= lightfield.glossy_max_roughness;
}

@group(2) @binding(33) var target_lambert: texture_storage_2d<rgba16float, write>;
@group(2) @binding(34) var target_glossy: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let pixel = vec2<i32>(id.xy);
    if gbuffer_depth_at(id.xy) < 0.0 {
        textureStore(target_lambert, pixel, vec4<f32>(0.0));
        textureStore(target_glossy, pixel, vec4<f32>(0.0));
        return;
    }
    let s = gbuffer_surface(id.xy);
    let wo = view_dir(s.position);
    // Off the surface by more than its thickness in the probes, so that rays do not meet the
    // surface they leave.
    let origin = s.position + s.geometric_normal * (2.0 * lightfield.min_thickness);
    var rng = rng_seed(id.y * frame.width + id.x, frame.frame_index, 0x3c6ef372u);
    let frame_basis = basis(s.normal);
    var lambert = vec3<f32>(0.0);
    for (var i = 0u; i < lightfield.lambert_rays; i++) {
        let dir = frame_basis * cosine_hemisphere(rand2(&rng));
        let hit = lightfield_trace(origin, dir, lf_far());
        lambert += lightfield_radiance_of(hit, scene_info.sky);
    }
    lambert /= f32(max(lightfield.lambert_rays, 1u));
    var glossy = vec3<f32>(0.0);
    if traces_glossy(s) && lightfield.glossy_rays > 0u {
        let alpha = s.roughness * s.roughness;
        let n_dot_v = max(dot(s.normal, wo), 1e-4);
        let v_local = transpose(frame_basis) * wo;
        for (var i = 0u; i < lightfield.glossy_rays; i++) {
            let h = frame_basis * sample_ggx_vndf(v_local, alpha, rand2(&rng));
            let wi = reflect(-wo, h);
            let n_dot_l = dot(s.normal, wi);
            if n_dot_l <= 0.0 {
                continue;
            }
            let g1 = 1.0 / (1.0 + smith_lambda(n_dot_v, alpha));
            let g2 = 1.0 / (1.0 + smith_lambda(n_dot_v, alpha) + smith_lambda(n_dot_l, alpha));
            let weight = fresnel_schlick(f0_of(s), dot(wo, h)) * g2 / g1;
            let hit = lightfield_trace(origin, wi, lf_far());
            glossy += weight * lightfield_radiance_of(hit, scene_info.sky);
        }
        glossy /= f32(lightfield.glossy_rays);
    }
    textureStore(target_lambert, pixel, vec4<f32>(lambert, 1.0));
    textureStore(target_glossy, pixel, vec4<f32>(glossy, 1.0));
}
