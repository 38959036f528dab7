// path: the reference path tracer's estimator of the radiance arriving along one ray, shared by
// the camera (pathtrace/trace) and the oracles that measure probes and queries against the truth
// (pathtrace/gather): Lambert + GGX, next-event estimation of punctual lights and of one
// emissive triangle (power-proportional choice) with multiple importance sampling against BRDF
// sampling, Russian roulette after three bounces.
#import bvh
#import brdf
#import lights
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
                let light_pdf = emitter_pdf_area(s.emission) * hit.t * hit.t / max(cos_light, 1e-8);
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
            let light = sample_emitter_light(s, wo, rng);
            // A blocked sample brings nothing: no MIS weight to work out.
            if any(light.radiance != vec3<f32>(0.0)) {
                let w = select(power_heuristic(light.pdf, brdf_pdf(s, wo, light.wi)), 1.0, light_sampling == LIGHT_SAMPLING_EMITTERS);
                radiance += throughput * light.radiance * w;
            }
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

// A NaN or infinite sample would ruin a whole accumulation: such a sample counts as none.
fn finite_or_zero(l: vec3<f32>) -> vec3<f32> {
    return select(vec3<f32>(0.0), l, all(l == l) && all(abs(l) < vec3<f32>(1e30)));
}
