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
            let pdf_area = emitter_area_pdf(emitter_cell(origin), hit_emitter(hit.instance, hit.triangle));
            let light_pdf = pdf_area * hit.t * hit.t / max(cos_light, 1e-8);
            w = select(power_heuristic(brdf_pdf_prev, light_pdf), 0.0, light_sampling == LIGHT_SAMPLING_EMITTERS);
        }
        radiance += s.emission * w;
    }
    if bounce == max_bounces {
        (*path).radiance += throughput * radiance;
        return false;
    }
    let wo = -dir;
    radiance += direct_punctual(s, wo);

    let origin_next = offset_ray(s.position, s.geometric_normal);
    if scene_info.emitter_count > 0u && light_sampling != LIGHT_SAMPLING_BRDF {
        radiance += emitter_sample_light(s, wo, origin_next, light_sampling, &rng);
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

// The emitters' light at s by next-event estimation: RIS over HIT_EMITTER_CANDIDATES points the
// emitter grid picks, one shadow ray, weighted against BRDF sampling. The resampled pdf has no
// closed form, so the MIS weights take the grid's pdf for the light strategy, here and at a
// BRDF ray's emitter hit alike: weights that sum to one for every direction keep the estimator
// unbiased whatever pdf they are built on, and the sample's own weight is the reservoir's W.
// What it costs where the weights fit badly, and why p̂ over an estimate of its integral was
// no better: docs/notes/light-quality.md, 2026-11-27.
fn emitter_sample_light(s: Surface, wo: vec3<f32>, origin: vec3<f32>, light_sampling: u32, rng: ptr<function, u32>) -> vec3<f32> {
    if SCENE_HAS_EMITTERS == 0u {
        return vec3<f32>(0.0);
    }
    let r = resample_emitters(s, origin, HIT_EMITTER_CANDIDATES, rng);
    if r.emitter >= scene_info.emitter_count || r.w <= 0.0 {
        return vec3<f32>(0.0);
    }
    let e = emitter_point(r.emitter, r.bary);
    let reach = emitter_reach(s, wo, origin, e);
    // A blocked sample brings nothing: no MIS weight to work out.
    if all(reach.light == vec3<f32>(0.0)) || !emitter_visible(origin, reach.wi, reach.distance, e) {
        return vec3<f32>(0.0);
    }
    var w = 1.0;
    if light_sampling != LIGHT_SAMPLING_EMITTERS {
        let light_pdf = emitter_area_pdf(emitter_cell(origin), r.emitter) * reach.distance * reach.distance / reach.cos_light;
        w = power_heuristic(light_pdf, brdf_pdf(s, wo, reach.wi));
    }
    return reach.light * r.w * w;
}

// A NaN or infinite sample would ruin a whole accumulation: such a sample counts as none.
fn finite_or_zero(l: vec3<f32>) -> vec3<f32> {
    return select(vec3<f32>(0.0), l, all(l == l) && all(abs(l) < vec3<f32>(1e30)));
}
