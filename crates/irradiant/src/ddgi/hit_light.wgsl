// ddgi: the light a ray's hit sends back along the ray, for the probe rays (ddgi/shade), the
// final gather at the pixels (ddgi/gather) and the reflections' rays (ddgi/reflect): punctual
// light with shadow rays, the emitters' (one sample, and at a traced ray's glossy hit a
// BRDF-sampled ray too: traced_hit_emitter_light), and the probes' irradiance — read at the
// hit, or one traced bounce further on (`traced_light`), and traced on past hits the probes are
// blind to (`probes_blind_to`).
// Emission is left out: the frame's direct pass samples every emitter already.
#import ddgi_query
#import ddgi_rays
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

// A probe ray's hit, beyond its punctual lights: one emitter sample and the probes' light.
fn hit_emitter_and_probe_light(s: Surface, wo: vec3<f32>, rng: ptr<function, u32>) -> vec3<f32> {
    let l = hit_emitter_light(s, wo, HIT_EMITTER_CANDIDATES, rng);
    return l + hit_probe_light(s, wo, ddgi_irradiance(s.position, s.normal, wo), BLIND_BOUNCES, rng);
}

// The probes' light a surface reflects, `read` there: their irradiance, or where they are too
// blind to it and `bounces` are left, what one ray traced on brings back. `bounces` is a
// parameter, not the constant: `BLIND_BOUNCES - 1u` would be a constant expression, and one
// that overflows where BLIND_BOUNCES is 0.
fn hit_probe_light(s: Surface, wo: vec3<f32>, read: ProbeRead, bounces: u32, rng: ptr<function, u32>) -> vec3<f32> {
    if probes_blind_to(read, bounces) {
        return reflected_from_a_traced_ray(s, bounces - 1u, rng);
    }
    return probes_reflected(s, wo, read);
}

// What a surface sends back along wo of the probes' light, `read` about its normal: its
// diffuse layer's share and its specular layer's (probes_mirrored).
fn probes_reflected(s: Surface, wo: vec3<f32>, read: ProbeRead) -> vec3<f32> {
    return diffuse_weight(s) * read.irradiance + probes_mirrored(s, wo);
}

// Where a surface's specular layer reflects more than its diffuse one (diffuse_share under a
// half: metals, dark glossy dielectrics), that layer's share of the probes' light about the
// mirror direction, as a rough reflector sees the room; elsewhere none (a mostly diffuse
// surface's small specular share is left out, and a query). A metal floor a ray meets then
// reflects the lit walls instead of reading black (the glossy-floor Cornell box's gather read
// its walls too dark: `quality` 0.127 against `balanced`'s 0.103, H200,
// docs/notes/light-quality.md). The traced bounce's ray stands for its hit's diffuse layer
// only, so that hit adds this too. A hit the probes are blind to does not: it would read the
// probes that cannot see it (the blind bounces trace its diffuse layer on, and its specular
// layer's share of the room is left out). With several volumes a traced bounce's hit is read
// later, as a Lambertian stand-in, and keeps no such share.
fn probes_mirrored(s: Surface, wo: vec3<f32>) -> vec3<f32> {
    if diffuse_share(s) >= 0.5 {
        return vec3<f32>(0.0);
    }
    let mirror = reflect(-wo, s.normal);
    // About the mirror direction, the probes weighed about the surface's normal, so that none
    // behind the surface counts.
    return f0_of(s) * ddgi_irradiance_along(s.position, s.normal, mirror, wo).irradiance;
}

// What a Lambertian surface reflects of the light one cosine-distributed ray traced on from it
// brings back (traced_light, with `blind_bounces` of its own).
fn reflected_from_a_traced_ray(s: Surface, blind_bounces: u32, rng: ptr<function, u32>) -> vec3<f32> {
    let origin = offset_ray(s.position, s.geometric_normal);
    return diffuse_weight(s) * traced_light(origin, cosine_direction(s.normal, rng), blind_bounces, HIT_EMITTER_CANDIDATES, rng);
}

// A traced ray's hit's emitter light: one emitter sample, and where the hit's specular layer
// reflects more than its diffuse one (diffuse_share under a half) a BRDF-sampled ray as well,
// the two weighed by MIS (emitter_light_both_ways). A gather ray from a wall that meets a
// polished floor sees the lamp's reflection there through the floor's sharp lobe, which the
// emitter sample seldom finds: the rare sample that does was a firefly in the pixel's mean for
// `history_frames`, and the gather's clamp cut it (the glossy-floor Cornell box's `quality` read
// darker than `balanced`, docs/notes/light-quality.md). A probe ray's own hit keeps the one
// sample, as each probe averages hundreds of rays over its hysteresis; the rays the traced and
// blind bounces trace on from it are traced rays, and pay the BRDF ray at their glossy hits.
fn traced_hit_emitter_light(s: Surface, wo: vec3<f32>, candidates: u32, rng: ptr<function, u32>) -> vec3<f32> {
    if scene_info.emitter_count == 0u || diffuse_share(s) >= 0.5 {
        return hit_emitter_light(s, wo, candidates, rng);
    }
    return emitter_light_both_ways(s, wo, candidates, rng);
}

// The radiance a ray from `origin` along `dir` brings back: the sky where it leaves the scene,
// else its hit's direct light (its emitters' from `candidates`: traced_hit_emitter_light) and
// the probes seen from the ray's length away; where they are blind to the hit, the ray goes on,
// cosine-distributed, at most `blind_bounces` times. A ray that meets a back face is shaded
// from that side, as the path tracer does.
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
        light += throughput * (hit_punctual_light(h, wo, rand(rng)) + traced_hit_emitter_light(h, wo, candidates, rng));
        let read = ddgi_irradiance_seen_from(h.position, h.normal, wo, hit.t);
        if !probes_blind_to(read, blind_bounces - bounce) {
            return light + throughput * probes_reflected(h, wo, read);
        }
        throughput *= diffuse_weight(h);
        ray_origin = offset_ray(h.position, h.geometric_normal);
        ray_dir = cosine_direction(h.normal, rng);
    }
    return light;
}

// The traced bounce (DdgiUpdateSettings::traced_bounce): one emitter sample and the light one
// cosine-distributed ray from the hit brings back, which reads the probes where it lands, and
// the hit's specular layer's share of the probes' light (probes_mirrored). The hit's own
// surroundings, not the probes', decide its diffuse light: surfaces by an opening narrower
// than the probe spacing see what lies beyond it.
fn hit_emitter_and_traced_bounce(s: Surface, wo: vec3<f32>, rng: ptr<function, u32>) -> vec3<f32> {
    return hit_emitter_light(s, wo, HIT_EMITTER_CANDIDATES, rng) + reflected_from_a_traced_ray(s, BLIND_BOUNCES, rng) + probes_mirrored(s, wo);
}

// The traced bounce with the probes' light at the traced ray's hit left to ddgi/between_volumes
// (light between volumes): one emitter sample at s, and the direct light of the traced ray's
// hit as s reflects it. `deferred` gets the hit, weighted by what both surfaces reflect and
// seen from the ray's length; where the ray leaves the scene it adds the sky instead and
// leaves nothing to read.
fn hit_emitter_and_traced_bounce_deferred(s: Surface, wo: vec3<f32>, rng: ptr<function, u32>, deferred: ptr<function, GpuDdgiDeferredRead>) -> vec3<f32> {
    let l = hit_emitter_light(s, wo, HIT_EMITTER_CANDIDATES, rng);
    let origin = offset_ray(s.position, s.geometric_normal);
    let dir = cosine_direction(s.normal, rng);
    let hit = trace_ray(origin, dir, RAY_FAR, false);
    if hit.triangle == INVALID {
        *deferred = nothing_to_read();
        return l + diffuse_weight(s) * scene_info.sky;
    }
    let h = surface_at(origin, dir, hit.t, hit.triangle, hit.instance, hit.bary);
    let h_wo = -dir;
    let direct = hit_punctual_light(h, h_wo, rand(rng)) + hit_emitter_light(h, h_wo, HIT_EMITTER_CANDIDATES, rng);
    *deferred = deferred_read(h, h_wo, hit.t, diffuse_weight(s) * diffuse_weight(h));
    return l + diffuse_weight(s) * direct;
}

// A point whose probe light is read later (GpuDdgiDeferredRead), none of it given yet.
fn deferred_read(s: Surface, wo: vec3<f32>, viewer_distance: f32, weight: vec3<f32>) -> GpuDdgiDeferredRead {
    var r: GpuDdgiDeferredRead;
    r.position = array<f32, 3>(s.position.x, s.position.y, s.position.z);
    r.viewer_distance = viewer_distance;
    r.normal = pack2x16snorm(oct_encode(s.normal));
    r.geometric_normal = pack2x16snorm(oct_encode(s.geometric_normal));
    r.wo = pack2x16snorm(oct_encode(wo));
    r.weight_rg = pack2x16float(weight.rg);
    r.weight_b_taken = pack2x16float(vec2<f32>(weight.b, 0.0));
    return r;
}

// A ray with no probe light to read: a miss, a backface, or the traced bounce's miss.
fn nothing_to_read() -> GpuDdgiDeferredRead {
    var r: GpuDdgiDeferredRead;
    r.weight_b_taken = pack2x16float(vec2<f32>(0.0, 1.0));
    return r;
}

// The share of the volumes' weight a deferred read has been given so far.
fn deferred_taken(r: GpuDdgiDeferredRead) -> f32 {
    return unpack2x16float(r.weight_b_taken).y;
}

// The Lambertian surface a deferred read stands for: its weight as the albedo, so that
// diffuse_weight gives it back and a ray traced on carries it.
fn deferred_surface(r: GpuDdgiDeferredRead) -> Surface {
    var s: Surface;
    s.position = vec3<f32>(r.position[0], r.position[1], r.position[2]);
    s.normal = oct_decode(unpack2x16snorm(r.normal));
    s.geometric_normal = oct_decode(unpack2x16snorm(r.geometric_normal));
    s.albedo = vec3<f32>(unpack2x16float(r.weight_rg), unpack2x16float(r.weight_b_taken).x);
    return s;
}

// The direction towards a deferred read's viewer.
fn deferred_wo(r: GpuDdgiDeferredRead) -> vec3<f32> {
    return oct_decode(unpack2x16snorm(r.wo));
}
