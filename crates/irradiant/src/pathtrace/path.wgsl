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

// Radiance arriving at `origin` from direction -dir, over at most `max_bounces` bounces. With
// `first_emission` false the emission of the first surface hit is left out: what a probe
// stores, since the frame's direct pass samples every emitter itself.
fn path_radiance(start: vec3<f32>, start_dir: vec3<f32>, max_bounces: u32, first_emission: bool, light_sampling: u32, rng: ptr<function, u32>) -> vec3<f32> {
    var origin = start;
    var dir = start_dir;
    var throughput = vec3<f32>(1.0);
    var radiance = vec3<f32>(0.0);
    // pdf of the BRDF sample that produced `dir`; 0 for the first ray (no MIS on it)
    var brdf_pdf_prev = 0.0;
    for (var bounce = 0u; bounce <= max_bounces; bounce++) {
        let hit = trace_ray(origin, dir, RAY_FAR, false);
        if hit.triangle == INVALID {
            radiance += throughput * scene_info.sky;
            break;
        }
        let s = surface_at(origin, dir, hit.t, hit.triangle, hit.instance, hit.bary);
        if max(s.emission.x, max(s.emission.y, s.emission.z)) > 0.0 && (bounce > 0u || first_emission) {
            var w = 1.0;
            // The first hit is never an emitter sample's: its emission counts whole.
            if brdf_pdf_prev > 0.0 && scene_info.emitter_count > 0u && light_sampling != LIGHT_SAMPLING_BRDF {
                let cos_light = abs(dot(s.geometric_normal, dir));
                let pdf_area = emitter_area_pdf(emitter_cell(origin), hit_emitter(hit.instance, hit.triangle));
                let light_pdf = pdf_area * hit.t * hit.t / max(cos_light, 1e-8);
                w = select(power_heuristic(brdf_pdf_prev, light_pdf), 0.0, light_sampling == LIGHT_SAMPLING_EMITTERS);
            }
            radiance += throughput * s.emission * w;
        }
        if bounce == max_bounces {
            break;
        }
        let wo = -dir;
        radiance += throughput * direct_punctual(s, wo);

        let origin_next = offset_ray(s.position, s.geometric_normal);
        if scene_info.emitter_count > 0u && light_sampling != LIGHT_SAMPLING_BRDF {
            radiance += throughput * emitter_sample_light(s, wo, origin_next, light_sampling, rng);
        }

        let b = brdf_sample(s, wo, rand(rng), rand2(rng));
        if b.pdf <= 0.0 || dot(b.dir, s.geometric_normal) <= 0.0 {
            break;
        }
        throughput *= b.weight;
        brdf_pdf_prev = b.pdf;
        origin = origin_next;
        dir = b.dir;
        if bounce >= 3u {
            let survive = min(max(throughput.x, max(throughput.y, throughput.z)), 0.95);
            if rand(rng) >= survive {
                break;
            }
            throughput /= survive;
        }
    }
    return radiance;
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
