// path: the reference path tracer's estimator of the radiance arriving along one ray, shared by
// the camera (pathtrace/trace) and the oracles that measure probes and queries against the truth
// (pathtrace/gather): Lambert + GGX, next-event estimation of punctual lights and of the
// emitters (one point resampled from candidates the emitter grid picks for the vertex's cell)
// with multiple importance sampling against BRDF sampling, Russian roulette after three bounces.
#import bvh
#import brdf
#import lights
#import resampling
#import random
#import pathtrace_constants

// A path between two vertices: where its next ray starts and goes, what it has gathered and
// what light there still counts for. The megakernel keeps it in a loop; the wavefront stores it
// between its bounce passes (pathtrace/wavefront, GpuPathState's 64 bytes).
struct PathState {
    origin: vec3<f32>,
    // pdf of the BRDF sample that produced `dir`; 0 for the first ray (no MIS on it)
    brdf_pdf_prev: f32,
    dir: vec3<f32>,
    rng: u32,
    throughput: vec3<f32>,
    // the wavefront's pixel, x | y << 16; unused by the megakernel
    pixel: u32,
    radiance: vec3<f32>,
    _pad0: u32,
}

// A shadow ray a vertex leaves to a pass of its own (the wavefront's pathtrace/shadows) with the
// light it brings if it arrives, throughput included: the closest hit short of `stop` or before
// `t_max` must be `emitter_triangle` (an emitter's point), or none (INVALID: a punctual light,
// stop = t_max, so that any hit blocks it). emitter_visible and occluded's tests, deferred.
struct DeferredShadow {
    origin: vec3<f32>,
    t_max: f32,
    dir: vec3<f32>,
    stop: f32,
    light: vec3<f32>,
    emitter_triangle: u32,
}

// Set by a kernel before path_step_at to defer the vertex's shadow rays into `deferred`
// rather than trace them, where they are at most `defer_up_to` (≤ DEFERRED_SHADOWS_MAX); the
// megakernel never sets it.
var<private> defer_up_to: u32;
var<private> deferred: array<DeferredShadow, DEFERRED_SHADOWS_MAX>;
var<private> deferred_count: u32;

fn defer_shadow(ray: DeferredShadow) {
    deferred[deferred_count] = ray;
    deferred_count++;
}

fn path_start(origin: vec3<f32>, dir: vec3<f32>, rng: u32, pixel: u32) -> PathState {
    return PathState(origin, 0.0, dir, rng, vec3<f32>(1.0), pixel, vec3<f32>(0.0), 0u);
}

// Radiance arriving at `origin` from direction -dir, over at most `max_bounces` bounces. With
// `first_emission` false the emission of the first surface hit is left out: what a probe
// stores, since the frame's direct pass samples every emitter itself.
fn path_radiance(start: vec3<f32>, start_dir: vec3<f32>, max_bounces: u32, first_emission: bool, light_sampling: u32, rng: ptr<function, u32>) -> vec3<f32> {
    var path = path_start(start, start_dir, *rng, 0u);
    for (var bounce = 0u; bounce <= max_bounces; bounce++) {
        if !path_step(&path, bounce, max_bounces, first_emission, light_sampling) {
            break;
        }
    }
    *rng = path.rng;
    return path.radiance;
}

// One vertex of a path: traces its ray, adds the light found there and picks the next ray.
// False when the path ends (a miss, the last bounce, a failed sample, Russian roulette).
fn path_step(path: ptr<function, PathState>, bounce: u32, max_bounces: u32, first_emission: bool, light_sampling: u32) -> bool {
    let hit = trace_ray((*path).origin, (*path).dir, RAY_FAR, false);
    return path_step_at(path, hit, bounce, max_bounces, first_emission, light_sampling);
}

// path_step with its ray's closest hit already found (the wavefront's pathtrace/hits traces
// the rays of a bounce apart from their shading).
fn path_step_at(path: ptr<function, PathState>, hit: Hit, bounce: u32, max_bounces: u32, first_emission: bool, light_sampling: u32) -> bool {
    let origin = (*path).origin;
    let dir = (*path).dir;
    let throughput = (*path).throughput;
    var rng = (*path).rng;
    if hit.triangle == INVALID {
        (*path).radiance += throughput * scene_info.sky;
        return false;
    }
    let s = surface_at(origin, dir, hit.t, hit.triangle, hit.instance, hit.bary);
    var radiance = vec3<f32>(0.0);
    if max(s.emission.x, max(s.emission.y, s.emission.z)) > 0.0 && (bounce > 0u || first_emission) {
        var w = 1.0;
        // The first hit is never an emitter sample's: its emission counts whole.
        let brdf_pdf_prev = (*path).brdf_pdf_prev;
        if brdf_pdf_prev > 0.0 && scene_info.emitter_count > 0u && light_sampling != LIGHT_SAMPLING_BRDF {
            let cos_light = abs(dot(s.geometric_normal, dir));
            let light_pdf = emitter_solid_angle_pdf(origin, hit_emitter(hit.instance, hit.triangle), hit.t, cos_light);
            w = select(power_heuristic(brdf_pdf_prev, light_pdf), 0.0, light_sampling == LIGHT_SAMPLING_EMITTERS);
        }
        radiance += s.emission * w;
    }
    if bounce == max_bounces {
        (*path).radiance += throughput * radiance;
        return false;
    }
    let wo = -dir;
    let origin_next = offset_ray(s.position, s.geometric_normal);
    let samples_emitters = scene_info.emitter_count > 0u && light_sampling != LIGHT_SAMPLING_BRDF;
    deferred_count = 0u;
    let defers = scene_info.light_count + u32(samples_emitters) <= defer_up_to;
    if defers {
        defer_punctual(s, wo, origin_next, throughput);
    } else {
        radiance += direct_punctual(s, wo);
    }
    if samples_emitters {
        let e = emitter_sample_unshadowed(s, wo, origin_next, HIT_EMITTER_CANDIDATES, light_sampling != LIGHT_SAMPLING_EMITTERS, &rng);
        if any(e.light.light != vec3<f32>(0.0)) {
            if defers {
                let margin = e.light.distance * EMITTER_POINT_MARGIN;
                defer_shadow(DeferredShadow(origin_next, e.light.distance + margin, e.light.wi, e.light.distance - margin, throughput * e.light.light, e.point.triangle));
            } else if emitter_visible(origin_next, e.light.wi, e.light.distance, e.point) {
                radiance += e.light.light;
            }
        }
    }
    (*path).radiance += throughput * radiance;

    let b = brdf_sample(s, wo, rand(&rng), rand2(&rng));
    (*path).rng = rng;
    if b.pdf <= 0.0 || dot(b.dir, s.geometric_normal) <= 0.0 {
        return false;
    }
    var next = throughput * b.weight;
    if bounce >= 3u {
        let survive = min(max(next.x, max(next.y, next.z)), 0.95);
        if rand(&rng) >= survive {
            (*path).rng = rng;
            return false;
        }
        next /= survive;
    }
    (*path).throughput = next;
    (*path).brdf_pdf_prev = b.pdf;
    (*path).origin = origin_next;
    (*path).dir = b.dir;
    (*path).rng = rng;
    return true;
}

// direct_punctual's lights, each with its shadow ray deferred (defer_shadow), weighted by the
// path's throughput.
fn defer_punctual(s: Surface, wo: vec3<f32>, origin: vec3<f32>, throughput: vec3<f32>) {
    for (var i = 0u; i < scene_info.light_count; i++) {
        let ray = light_ray(i, origin);
        let light = reflected(s, wo, ray.wi, arriving_light(s, ray)).total;
        if any(light != vec3<f32>(0.0)) {
            defer_shadow(DeferredShadow(origin, ray.distance, ray.wi, ray.distance, throughput * light, INVALID));
        }
    }
}

// A NaN or infinite sample would ruin a whole accumulation: such a sample counts as none.
fn finite_or_zero(l: vec3<f32>) -> vec3<f32> {
    return select(vec3<f32>(0.0), l, all(l == l) && all(abs(l) < vec3<f32>(1e30)));
}
