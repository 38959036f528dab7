// pathtrace/trace: the reference path tracer. One thread a pixel traces `samples` paths and
// adds them to the accumulation texture: Lambert + GGX, next-event estimation of punctual
// lights and of one emissive triangle (power-proportional choice) with multiple importance
// sampling against BRDF sampling, Russian roulette after three bounces.
#import bvh
#import brdf
#import lights
#import camera
#import random

struct GpuPathTraceParams {
    camera: GpuCamera,
    width: u32,
    height: u32,
    // index of the first sample of this dispatch (decorrelates dispatches)
    sample_offset: u32,
    samples: u32,
    max_bounces: u32,
    seed: u32,
    _pad0: u32,
    _pad1: u32,
}

@group(1) @binding(0) var<uniform> params: GpuPathTraceParams;
// rgb: sum of radiance samples; a: their count
@group(1) @binding(1) var accumulation: texture_storage_2d<rgba32float, read_write>;

fn trace_path(pixel: vec2<u32>, rng: ptr<function, u32>) -> vec3<f32> {
    let size = vec2<f32>(f32(params.width), f32(params.height));
    var origin = params.camera.position;
    var dir = camera_ray_dir(params.camera, vec2<f32>(pixel) + rand2(rng), size);
    var throughput = vec3<f32>(1.0);
    var radiance = vec3<f32>(0.0);
    // pdf of the BRDF sample that produced `dir`; 0 for the camera ray (no MIS on it)
    var brdf_pdf_prev = 0.0;
    for (var bounce = 0u; bounce <= params.max_bounces; bounce++) {
        let hit = trace_ray(origin, dir, RAY_FAR, false);
        if hit.triangle == INVALID {
            radiance += throughput * scene_info.sky;
            break;
        }
        let s = surface_at(origin, dir, hit.t, hit.triangle, hit.instance, hit.bary);
        if max(s.emission.x, max(s.emission.y, s.emission.z)) > 0.0 {
            var w = 1.0;
            if brdf_pdf_prev > 0.0 && scene_info.emitter_count > 0u {
                let cos_light = abs(dot(s.geometric_normal, dir));
                let light_pdf = emitter_pdf_area(s.emission) * hit.t * hit.t / max(cos_light, 1e-8);
                w = power_heuristic(brdf_pdf_prev, light_pdf);
            }
            radiance += throughput * s.emission * w;
        }
        if bounce == params.max_bounces {
            break;
        }
        let wo = -dir;
        radiance += throughput * direct_punctual(s, wo);

        let origin_next = offset_ray(s.position, s.geometric_normal);
        if scene_info.emitter_count > 0u {
            let u_select = rand(rng);
            let e = sample_emitter(u_select, rand2(rng));
            let to_light = e.position - origin_next;
            let d2 = dot(to_light, to_light);
            let distance = sqrt(d2);
            let wi = to_light / distance;
            let cos_light = -dot(e.normal, wi);
            let cos_surface = dot(s.normal, wi);
            if cos_light > 0.0 && cos_surface > 0.0 && dot(s.geometric_normal, wi) > 0.0 {
                let light_pdf = e.pdf_area * d2 / cos_light;
                // Stop short of the emitter so that it does not occlude itself.
                if !occluded(origin_next, wi, distance * (1.0 - 1e-4)) {
                    let w = power_heuristic(light_pdf, brdf_pdf(s, wo, wi));
                    radiance += throughput * brdf_eval(s, wo, wi) * e.radiance * cos_surface * w / light_pdf;
                }
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

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let index = id.y * params.width + id.x;
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < params.samples; i++) {
        var rng = rng_seed(index, params.sample_offset + i, params.seed);
        let l = trace_path(id.xy, &rng);
        // A NaN or infinite sample would ruin the whole accumulation: drop it.
        if all(l == l) && all(abs(l) < vec3<f32>(1e30)) {
            sum += l;
        }
    }
    textureStore(accumulation, id.xy, textureLoad(accumulation, id.xy) + vec4<f32>(sum, f32(params.samples)));
}
