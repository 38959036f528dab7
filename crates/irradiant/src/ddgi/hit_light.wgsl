// ddgi: the light a ray's hit sends back along the ray, for the probe rays (ddgi/shade) and the
// final gather at the pixels (ddgi/resolve): punctual light with shadow rays, one emitter
// sample, and the probes' irradiance — read at the hit, or one traced bounce further on
// (`traced_light`). Emission is left out: the frame's direct pass samples every emitter
// already.
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

// One emitter sample, where the scene has emitters.
fn hit_emitter_light(s: Surface, wo: vec3<f32>, rng: ptr<function, u32>) -> vec3<f32> {
    if scene_info.emitter_count == 0u {
        return vec3<f32>(0.0);
    }
    return emitter_light(s, wo, rng);
}

// The rest: one emitter sample and the probes' irradiance, seen from `viewer_distance` away
// (ddgi_irradiance_seen_from; NO_VIEWER_LIMIT: the plain query).
fn hit_emitter_and_probe_light(s: Surface, wo: vec3<f32>, viewer_distance: f32, rng: ptr<function, u32>) -> vec3<f32> {
    let l = hit_emitter_light(s, wo, rng);
    var probes: vec3<f32>;
    if viewer_distance == NO_VIEWER_LIMIT {
        probes = ddgi_irradiance(s.position, s.normal, wo);
    } else {
        probes = ddgi_irradiance_seen_from(s.position, s.normal, wo, viewer_distance);
    }
    return l + diffuse_weight(s) * probes;
}

// The radiance a ray from `origin` along `dir` brings back: the sky where it leaves the scene,
// else its hit's light with the probes seen from the ray's length away. A ray that meets a
// back face is shaded from that side, as the path tracer does.
fn traced_light(origin: vec3<f32>, dir: vec3<f32>, rng: ptr<function, u32>) -> vec3<f32> {
    let hit = trace_ray(origin, dir, RAY_FAR, false);
    if hit.triangle == INVALID {
        return scene_info.sky;
    }
    let h = surface_at(origin, dir, hit.t, hit.triangle, hit.instance, hit.bary);
    let wo = -dir;
    return hit_punctual_light(h, wo, rand(rng)) + hit_emitter_and_probe_light(h, wo, hit.t, rng);
}

// The traced bounce (DdgiUpdateSettings::traced_bounce): one emitter sample and the light one
// cosine-distributed ray from the hit brings back, which reads the probes where it lands. The
// hit's own surroundings, not the probes', decide its light: surfaces by an opening narrower
// than the probe spacing see what lies beyond it.
fn hit_emitter_and_traced_bounce(s: Surface, wo: vec3<f32>, rng: ptr<function, u32>) -> vec3<f32> {
    let l = hit_emitter_light(s, wo, rng);
    let dir = normalize(basis(s.normal) * cosine_hemisphere(rand2(rng)));
    return l + diffuse_weight(s) * traced_light(offset_ray(s.position, s.geometric_normal), dir, rng);
}
