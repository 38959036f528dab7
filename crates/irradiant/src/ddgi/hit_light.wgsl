// ddgi: the light a ray's hit sends back along the ray, for the probe rays (ddgi/shade) and the
// final gather at the pixels (ddgi/resolve): punctual light with shadow rays, one emitter
// sample, and the probes' irradiance. Emission is left out: the frame's direct pass samples
// every emitter already.
#import ddgi_query
#import lights

// The punctual lights' share: every light with `all_lights`, else the one `u` picks, weighted
// by the light count.
fn hit_punctual_light(s: Surface, wo: vec3<f32>, u: f32) -> vec3<f32> {
    if volume.all_lights != 0u {
        return direct_punctual(s, wo);
    }
    if scene_info.light_count == 0u {
        return vec3<f32>(0.0);
    }
    return direct_from_light(s, wo, pick_light(u)) * f32(scene_info.light_count);
}

// The rest: one emitter sample and the probes' irradiance, seen from `viewer_distance` away
// (ddgi_irradiance_seen_from; NO_VIEWER_LIMIT: the plain query).
fn hit_emitter_and_probe_light(s: Surface, wo: vec3<f32>, viewer_distance: f32, rng: ptr<function, u32>) -> vec3<f32> {
    var l = vec3<f32>(0.0);
    if scene_info.emitter_count > 0u {
        l = emitter_light(s, wo, rng);
    }
    var probes: vec3<f32>;
    if viewer_distance == NO_VIEWER_LIMIT {
        probes = ddgi_irradiance(s.position, s.normal, wo);
    } else {
        probes = ddgi_irradiance_seen_from(s.position, s.normal, wo, viewer_distance);
    }
    return l + diffuse_weight(s) * probes;
}
