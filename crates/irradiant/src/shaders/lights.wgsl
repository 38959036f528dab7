// Direct light with shadow rays: the punctual lights (point, spot, directional), and one
// sample of the emissive triangles.
#import bvh
#import brdf
#import random

// Direct light leaving a surface: towards the viewer (every lobe of the BRDF), and its diffuse
// part alone, the view-independent share a screen-space gather may take as leaving the surface
// every way (a highlight the camera sees lights nothing else).
struct DirectLight {
    total: vec3<f32>,
    diffuse: vec3<f32>,
}

// `arriving` (L · cos at the surface, from wi) reflected towards wo.
fn reflected(s: Surface, wo: vec3<f32>, wi: vec3<f32>, arriving: vec3<f32>) -> DirectLight {
    return with_diffuse(s, brdf_eval(s, wo, wi) * arriving, arriving);
}

// Light `total` reflected from `arriving`, with the diffuse lobe's share (none where the BRDF
// reflected nothing: the light or the viewer below the surface).
fn with_diffuse(s: Surface, total: vec3<f32>, arriving: vec3<f32>) -> DirectLight {
    let diffuse = select(vec3<f32>(0.0), diffuse_weight(s) / PI * arriving, any(total != vec3<f32>(0.0)));
    return DirectLight(total, diffuse);
}

fn add_direct(a: DirectLight, b: DirectLight) -> DirectLight {
    return DirectLight(a.total + b.total, a.diffuse + b.diffuse);
}

// Σ over lights of f · L · cos, for a surface seen from wo.
fn direct_punctual(s: Surface, wo: vec3<f32>) -> vec3<f32> {
    return direct_punctual_split(s, wo).total;
}

// direct_punctual with its diffuse part.
fn direct_punctual_split(s: Surface, wo: vec3<f32>) -> DirectLight {
    var sum = DirectLight(vec3<f32>(0.0), vec3<f32>(0.0));
    for (var i = 0u; i < scene_info.light_count; i++) {
        sum = add_direct(sum, direct_from_light_split(s, wo, i));
    }
    return sum;
}

// An unbiased one-shadow-ray estimate of direct_punctual: one light chosen uniformly by `u`,
// weighted by the light count. Its cost does not grow with the number of lights.
fn direct_punctual_one(s: Surface, wo: vec3<f32>, u: f32) -> vec3<f32> {
    let n = scene_info.light_count;
    if n == 0u {
        return vec3<f32>(0.0);
    }
    return direct_from_light(s, wo, pick_light(u)) * f32(n);
}

// The light direct_punctual_one takes for a uniform random u (the scene must have lights).
fn pick_light(u: f32) -> u32 {
    let n = scene_info.light_count;
    return min(u32(u * f32(n)), n - 1u);
}

// Light i as seen from a shadow ray's origin: the direction to it, how far the shadow ray
// goes, and the radiance (irradiance for a punctual light) that arrives when nothing blocks it.
struct LightRay {
    wi: vec3<f32>,
    distance: f32,
    radiance: vec3<f32>,
}

fn light_ray(i: u32, origin: vec3<f32>) -> LightRay {
    let light = lights[i];
    var ray: LightRay;
    if light.kind == LIGHT_DIRECTIONAL {
        ray.wi = -light.direction;
        ray.distance = RAY_FAR;
        ray.radiance = light.power;
    } else {
        let to_light = light.position - origin;
        ray.distance = length(to_light);
        ray.wi = to_light / ray.distance;
        ray.radiance = light.power / max(ray.distance * ray.distance, 1e-8);
        if light.kind == LIGHT_SPOT {
            ray.radiance *= smoothstep(light.cos_outer, light.cos_inner, dot(-ray.wi, light.direction));
        }
    }
    return ray;
}

// The origin of a surface's shadow rays: off the surface along its geometric normal.
fn shadow_origin(s: Surface) -> vec3<f32> {
    return offset_ray(s.position, s.geometric_normal);
}

// L · cos from a light along `ray` if nothing blocks it; zero where the light cannot reach
// the surface's side, so that no shadow ray is needed.
fn arriving_light(s: Surface, ray: LightRay) -> vec3<f32> {
    let cos_l = dot(s.normal, ray.wi);
    if cos_l <= 0.0 || dot(s.geometric_normal, ray.wi) <= 0.0 || max(ray.radiance.x, max(ray.radiance.y, ray.radiance.z)) <= 0.0 {
        return vec3<f32>(0.0);
    }
    return ray.radiance * cos_l;
}

// f · L · cos from a light along `ray` if nothing blocks it.
fn unshadowed_light(s: Surface, wo: vec3<f32>, ray: LightRay) -> vec3<f32> {
    return brdf_eval(s, wo, ray.wi) * arriving_light(s, ray);
}

// f · L · cos from light i, with its shadow ray.
fn direct_from_light(s: Surface, wo: vec3<f32>, i: u32) -> vec3<f32> {
    return direct_from_light_split(s, wo, i).total;
}

// direct_from_light with its diffuse part.
fn direct_from_light_split(s: Surface, wo: vec3<f32>, i: u32) -> DirectLight {
    let origin = shadow_origin(s);
    let ray = light_ray(i, origin);
    let light = reflected(s, wo, ray.wi, arriving_light(s, ray));
    if any(light.total != vec3<f32>(0.0)) && occluded(origin, ray.wi, ray.distance) {
        return DirectLight(vec3<f32>(0.0), vec3<f32>(0.0));
    }
    return light;
}

// What an emitter point sends to a surface, shadows aside, in the area measure
// (brdf · Le · cos at the surface · cos at the emitter / d²), and the shadow ray that decides
// whether it arrives.
struct EmitterReach {
    light: vec3<f32>,
    // Le · cos at the surface · cos at the emitter / d², before the BRDF
    arriving: vec3<f32>,
    wi: vec3<f32>,
    distance: f32,
    // the cosine at the emitter; 0 where the point cannot reach the surface's side
    cos_light: f32,
}

fn emitter_reach(s: Surface, wo: vec3<f32>, origin: vec3<f32>, e: EmitterSample) -> EmitterReach {
    var out: EmitterReach;
    let to_light = e.position - origin;
    let d2 = dot(to_light, to_light);
    out.distance = sqrt(d2);
    out.wi = to_light / max(out.distance, 1e-20);
    let cos_light = -dot(e.normal, out.wi);
    let cos_surface = dot(s.normal, out.wi);
    if cos_light <= 0.0 || cos_surface <= 0.0 || dot(s.geometric_normal, out.wi) <= 0.0 || d2 <= 0.0 {
        return out;
    }
    out.cos_light = cos_light;
    out.arriving = e.radiance * (cos_surface * cos_light / d2);
    out.light = brdf_eval(s, wo, out.wi) * out.arriving;
    return out;
}

// How far around an emitter point, as a share of its distance, emitter_visible takes a hit to
// be the point's own depth.
const EMITTER_POINT_MARGIN: f32 = 1e-3;

// Whether the emitter point `e`, `distance` along `wi`, is the first thing a ray from `origin`
// hits: visible exactly when a BRDF-sampled ray would see it, so that the two ways of finding
// emitted light agree. A shadow ray stopped short of the point (to keep the emitter from
// blocking itself) missed surfaces closer in front of it than that margin, and an any-hit ray
// past every triangle but the emitter's still saw it through a coincident face that wins the
// closest hit (two-sided walls made of two faces): a glowing Sponza read 16 and 11 % too
// bright against BRDF sampling, this test 1 % dark (docs/ddgi.md).
fn emitter_visible(origin: vec3<f32>, wi: vec3<f32>, distance: f32, e: EmitterSample) -> bool {
    // The search reaches past the point by the margin, so that a coincident face is found; a
    // surface nearer than the point by more than the margin is nearer than the emitter
    // whatever else the search would find, so the search ends at the first such hit.
    let margin = distance * EMITTER_POINT_MARGIN;
    let hit = trace_ray_until(origin, wi, distance + margin, distance - margin);
    return hit.triangle == e.triangle && hit.instance == e.instance;
}
