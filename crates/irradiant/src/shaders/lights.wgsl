// Direct light from the punctual lights (point, spot, directional) with shadow rays.
#import bvh
#import brdf

// Σ over lights of f · L · cos, for a surface seen from wo.
fn direct_punctual(s: Surface, wo: vec3<f32>) -> vec3<f32> {
    var total = vec3<f32>(0.0);
    let origin = offset_ray(s.position, s.geometric_normal);
    for (var i = 0u; i < scene_info.light_count; i++) {
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
            continue;
        }
        if !occluded(origin, wi, distance) {
            total += brdf_eval(s, wo, wi) * radiance * cos_l;
        }
    }
    return total;
}
