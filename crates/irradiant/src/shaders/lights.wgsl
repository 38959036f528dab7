// Direct light with shadow rays: the punctual lights (point, spot, directional), and one
// sample of the emissive triangles.
#import bvh
#import brdf
#import random

// Σ over lights of f · L · cos, for a surface seen from wo.
fn direct_punctual(s: Surface, wo: vec3<f32>) -> vec3<f32> {
    var total = vec3<f32>(0.0);
    for (var i = 0u; i < scene_info.light_count; i++) {
        total += direct_from_light(s, wo, i);
    }
    return total;
}

// An unbiased one-shadow-ray estimate of direct_punctual: one light chosen uniformly by `u`,
// weighted by the light count. Its cost does not grow with the number of lights.
fn direct_punctual_one(s: Surface, wo: vec3<f32>, u: f32) -> vec3<f32> {
    let n = scene_info.light_count;
    if n == 0u {
        return vec3<f32>(0.0);
    }
    return direct_from_light(s, wo, min(u32(u * f32(n)), n - 1u)) * f32(n);
}

// f · L · cos from light i, with its shadow ray.
fn direct_from_light(s: Surface, wo: vec3<f32>, i: u32) -> vec3<f32> {
    let origin = offset_ray(s.position, s.geometric_normal);
    let light = lights[i];
    var wi: vec3<f32>;
    var distance: f32;
    var radiance: vec3<f32>;
    if light.kind == LIGHT_DIRECTIONAL {
        wi = -light.direction;
        distance = RAY_FAR;
        radiance = light.power;
    } else {
        let to_light = light.position - origin;
        distance = length(to_light);
        wi = to_light / distance;
        radiance = light.power / max(distance * distance, 1e-8);
        if light.kind == LIGHT_SPOT {
            radiance *= smoothstep(light.cos_outer, light.cos_inner, dot(-wi, light.direction));
        }
    }
    let cos_l = dot(s.normal, wi);
    if cos_l <= 0.0 || dot(s.geometric_normal, wi) <= 0.0 || max(radiance.x, max(radiance.y, radiance.z)) <= 0.0 {
        return vec3<f32>(0.0);
    }
    if occluded(origin, wi, distance) {
        return vec3<f32>(0.0);
    }
    return brdf_eval(s, wo, wi) * radiance * cos_l;
}

// f · Le · cos / pdf for one point on an emissive triangle (chosen ∝ power), with its shadow
// ray: an unbiased estimate of the direct light from every emitter.
fn emitter_light(s: Surface, wo: vec3<f32>, rng: ptr<function, u32>) -> vec3<f32> {
    let origin = offset_ray(s.position, s.geometric_normal);
    let e = sample_emitter(rand(rng), rand2(rng));
    let to_light = e.position - origin;
    let d2 = dot(to_light, to_light);
    let distance = sqrt(d2);
    let wi = to_light / distance;
    let cos_light = -dot(e.normal, wi);
    let cos_surface = dot(s.normal, wi);
    if cos_light <= 0.0 || cos_surface <= 0.0 || dot(s.geometric_normal, wi) <= 0.0 {
        return vec3<f32>(0.0);
    }
    if occluded(origin, wi, distance * (1.0 - 1e-4)) {
        return vec3<f32>(0.0);
    }
    return brdf_eval(s, wo, wi) * e.radiance * cos_surface * cos_light / (e.pdf_area * d2);
}
