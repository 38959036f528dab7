// ddgi: the light a ray's hit sends back along the ray, for the probe rays (ddgi/shade) and the
// final gather at the pixels (ddgi/resolve): punctual light with shadow rays, one emitter
// sample, and the probes' irradiance — read at the hit, or one traced bounce further on
// (`traced_light`), and traced on past hits the probes are blind to (`probes_blind_to`).
// Emission is left out: the frame's direct pass samples every emitter already.
#import ddgi_query
#import resampling

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

// One emitter sample, where the scene has emitters, kept by RIS from `candidates`.
fn hit_emitter_light(s: Surface, wo: vec3<f32>, candidates: u32, rng: ptr<function, u32>) -> vec3<f32> {
    if scene_info.emitter_count == 0u {
        return vec3<f32>(0.0);
    }
    return emitter_light_from(s, wo, candidates, rng);
}

// A cosine-distributed direction around n.
fn cosine_direction(n: vec3<f32>, rng: ptr<function, u32>) -> vec3<f32> {
    return normalize(basis(n) * cosine_hemisphere(rand2(rng)));
}

// Whether the probes are too blind to a point to give its light (BLIND_BOUNCES and
// BLIND_THRESHOLD, DdgiUpdateSettings::blind_bounces): the ray that reached it traces on.
fn probes_blind_to(read: ProbeRead, bounces_left: u32) -> bool {
    return bounces_left > 0u && read.seen < BLIND_THRESHOLD;
}

// A probe ray's hit, beyond its punctual lights: one emitter sample and the probes' irradiance
// read at the hit, or, where they are blind to it, one ray traced on.
fn hit_emitter_and_probe_light(s: Surface, wo: vec3<f32>, rng: ptr<function, u32>) -> vec3<f32> {
    let l = hit_emitter_light(s, wo, HIT_EMITTER_CANDIDATES, rng);
    let read = ddgi_irradiance(s.position, s.normal, wo);
    // A `let`, not the constant itself: `BLIND_BOUNCES - 1u` would be a constant expression,
    // and one that overflows where BLIND_BOUNCES is 0.
    let bounces = BLIND_BOUNCES;
    if probes_blind_to(read, bounces) {
        return l + reflected_from_a_traced_ray(s, bounces - 1u, rng);
    }
    return l + diffuse_weight(s) * read.irradiance;
}

// What a Lambertian surface reflects of the light one cosine-distributed ray traced on from it
// brings back (traced_light, with `blind_bounces` of its own).
fn reflected_from_a_traced_ray(s: Surface, blind_bounces: u32, rng: ptr<function, u32>) -> vec3<f32> {
    let origin = offset_ray(s.position, s.geometric_normal);
    return diffuse_weight(s) * traced_light(origin, cosine_direction(s.normal, rng), blind_bounces, HIT_EMITTER_CANDIDATES, rng);
}

// The radiance a ray from `origin` along `dir` brings back: the sky where it leaves the scene,
// else its hit's direct light (its emitter sample kept from `candidates`) and the probes seen
// from the ray's length away; where they are
// blind to the hit, the ray goes on, cosine-distributed, at most `blind_bounces` times. A ray
// that meets a back face is shaded from that side, as the path tracer does.
fn traced_light(origin: vec3<f32>, dir: vec3<f32>, blind_bounces: u32, candidates: u32, rng: ptr<function, u32>) -> vec3<f32> {
    var ray_origin = origin;
    var ray_dir = dir;
    var throughput = vec3<f32>(1.0);
    var light = vec3<f32>(0.0);
    for (var bounce = 0u; bounce <= blind_bounces; bounce++) {
        let hit = trace_ray(ray_origin, ray_dir, RAY_FAR, false);
        if hit.triangle == INVALID {
            return light + throughput * scene_info.sky;
        }
        let h = surface_at(ray_origin, ray_dir, hit.t, hit.triangle, hit.instance, hit.bary);
        let wo = -ray_dir;
        light += throughput * (hit_punctual_light(h, wo, rand(rng)) + hit_emitter_light(h, wo, candidates, rng));
        let read = ddgi_irradiance_seen_from(h.position, h.normal, wo, hit.t);
        if !probes_blind_to(read, blind_bounces - bounce) {
            return light + throughput * diffuse_weight(h) * read.irradiance;
        }
        throughput *= diffuse_weight(h);
        ray_origin = offset_ray(h.position, h.geometric_normal);
        ray_dir = cosine_direction(h.normal, rng);
    }
    return light;
}

// The traced bounce (DdgiUpdateSettings::traced_bounce): one emitter sample and the light one
// cosine-distributed ray from the hit brings back, which reads the probes where it lands. The
// hit's own surroundings, not the probes', decide its light: surfaces by an opening narrower
// than the probe spacing see what lies beyond it.
fn hit_emitter_and_traced_bounce(s: Surface, wo: vec3<f32>, rng: ptr<function, u32>) -> vec3<f32> {
    return hit_emitter_light(s, wo, HIT_EMITTER_CANDIDATES, rng) + reflected_from_a_traced_ray(s, BLIND_BOUNCES, rng);
}
