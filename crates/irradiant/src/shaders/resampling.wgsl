// Emitter samples chosen by resampled importance sampling (RIS, Talbot et al. 2005) and held in
// reservoirs that later frames and neighbouring pixels reuse (ReSTIR DI, Bitterli et al. 2020,
// Algorithms 3-5). Candidates come from the power-proportional pick of every emitter
// (sample_emitter); RIS keeps one in proportion to what it sends to the surface unshadowed
// (Le · brdf · both cosines / d²), so that near, facing emitters win over far ones of the same
// power. One shadow ray then tests the one kept. Shared by frame/direct and every ray hit's
// emitter sample (emitter_light); the path tracer keeps sample_emitter_light, whose pdf its MIS
// weights need.
#import lights

// Candidates a ray hit's one emitter sample is chosen from (emitter_light): enough that the
// nearest of a hall's emitters win most of the time; each costs a pick and a few loads, no ray.
const HIT_EMITTER_CANDIDATES: u32 = 8u;

// How far a reused reservoir's surface may lie from the pixel's, as a share of the view depth,
// and the smallest cosine between their normals (ReSTIR DI's 10 % and 25°).
const REUSE_DEPTH_TOLERANCE: f32 = 0.1;
const REUSE_NORMAL_TOLERANCE: f32 = 0.9;

// cos(max(θ − α − β, 0)) from the cosines of θ, α and β (scene/light_tree.rs).
fn cos_sub_clamped(cos_theta: f32, cos_alpha: f32, cos_beta: f32) -> f32 {
    let sin_alpha = sqrt(max(1.0 - cos_alpha * cos_alpha, 0.0));
    let sin_beta = sqrt(max(1.0 - cos_beta * cos_beta, 0.0));
    let cos_sum = cos_alpha * cos_beta - sin_alpha * sin_beta;
    let sin_sum = sin_alpha * cos_beta + cos_alpha * sin_beta;
    if sin_sum < 0.0 || cos_theta >= cos_sum {
        return 1.0;
    }
    return cos_theta * cos_sum + sqrt(max(1.0 - cos_theta * cos_theta, 0.0)) * sin_sum;
}

// A light-tree node's importance seen from p with normal n: power / d², where the box could
// face p and p the box; 0 only where nothing under it can light p (scene/light_tree.rs,
// `importance`, which the tests hold this to).
fn light_node_importance(node: GpuLightNode, p: vec3<f32>, n: vec3<f32>) -> f32 {
    let centre = 0.5 * (node.bounds_min + node.bounds_max);
    let radius = 0.5 * length(node.bounds_max - node.bounds_min);
    let to_point = p - centre;
    let d2 = dot(to_point, to_point);
    if d2 <= radius * radius * 1.0001 {
        return node.power / max(radius * radius, 1e-8);
    }
    let d = sqrt(d2);
    let dir = to_point / d;
    let sin_u = min(radius / d, 1.0);
    let cos_u = sqrt(max(1.0 - sin_u * sin_u, 0.0));
    let emitter_side = cos_sub_clamped(dot(node.axis, dir), node.cos_spread, cos_u);
    let receiver_side = cos_sub_clamped(dot(n, -dir), 1.0, cos_u);
    if emitter_side <= 0.0 || receiver_side <= 0.0 {
        return 0.0;
    }
    return node.power * emitter_side * receiver_side / max(d2, radius * radius);
}

// An emitter picked from p with normal n down the light tree, each child in proportion to its
// importance (to power where neither can light p), and the probability of that pick.
struct LightPick {
    emitter: u32,
    probability: f32,
}

fn pick_emitter_near(p: vec3<f32>, n: vec3<f32>, rng: ptr<function, u32>) -> LightPick {
    var at = 0u;
    var probability = 1.0;
    for (var depth = 0u; depth < LIGHT_TREE_MAX_DEPTH; depth++) {
        let node = light_tree[at];
        if (node.child_or_emitter & LIGHT_LEAF) != 0u {
            break;
        }
        let first = node.child_or_emitter;
        let left = light_tree[first];
        let right = light_tree[first + 1u];
        let a = light_node_importance(left, p, n);
        let b = light_node_importance(right, p, n);
        var take_left = a / max(a + b, 1e-30);
        if a + b <= 0.0 {
            take_left = left.power / max(left.power + right.power, 1e-30);
        }
        if rand(rng) < take_left {
            at = first;
            probability *= take_left;
        } else {
            at = first + 1u;
            probability *= 1.0 - take_left;
        }
    }
    return LightPick(light_tree[at].child_or_emitter & ~LIGHT_LEAF, probability);
}

// A reservoir: the sample it holds (an emitter and barycentrics on its triangle), its target
// value p̂ at the pixel that holds it, the sum of the candidates' resampling weights, M (how
// many candidates it stands for), and W, the unbiased contribution weight that makes
// f(y) · W an estimate of the light from every emitter.
struct Reservoir {
    emitter: u32,
    bary: vec2<f32>,
    target_value: f32,
    weight_sum: f32,
    m: f32,
    w: f32,
}

fn empty_reservoir() -> Reservoir {
    return Reservoir(INVALID, vec2<f32>(0.0), 0.0, 0.0, 0.0, 0.0);
}

// What an emitter point sends to a surface, shadows aside, in the area measure
// (brdf · Le · cos at the surface · cos at the emitter / d²), and the shadow ray that decides
// whether it arrives.
struct EmitterReach {
    light: vec3<f32>,
    wi: vec3<f32>,
    distance: f32,
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
    out.light = brdf_eval(s, wo, out.wi) * e.radiance * (cos_surface * cos_light / d2);
    return out;
}

// The target function p̂ the reservoirs resample towards at a surface: the emitter point's
// luminance × both cosines / d², what it sends unshadowed to a white Lambertian surface. The
// BRDF is left out (a candidate costs no BRDF evaluation); p̂ is positive wherever the light
// f(y) is, so the estimate stays unbiased, with a little more noise on glossy surfaces.
fn target_value(s: Surface, origin: vec3<f32>, e: EmitterSample) -> f32 {
    let to_light = e.position - origin;
    let d2 = dot(to_light, to_light);
    let cos_light = -dot(e.normal, to_light);
    let cos_surface = dot(s.normal, to_light);
    if cos_light <= 0.0 || cos_surface <= 0.0 || dot(s.geometric_normal, to_light) <= 0.0 || d2 <= 0.0 {
        return 0.0;
    }
    // The cosines of unnormalised vectors: d² twice over.
    return luminance(e.radiance) * cos_surface * cos_light / (d2 * d2);
}

// Streams one candidate of resampling weight `weight` into r (Algorithm 2's update); `m` is
// how many candidates it stands for.
fn reservoir_add(r: ptr<function, Reservoir>, emitter: u32, bary: vec2<f32>, target_value: f32, weight: f32, m: f32, u: f32) {
    (*r).m += m;
    if weight <= 0.0 {
        return;
    }
    (*r).weight_sum += weight;
    if u * (*r).weight_sum < weight {
        (*r).emitter = emitter;
        (*r).bary = bary;
        (*r).target_value = target_value;
    }
}

// Sets W = (Σ weights) / (M · p̂(y)) once every candidate is in.
fn reservoir_finish(r: ptr<function, Reservoir>) {
    let denominator = (*r).m * (*r).target_value;
    (*r).w = select(0.0, (*r).weight_sum / denominator, denominator > 0.0);
}

// Merges the reservoir `other` (held at another pixel or frame) into r: its sample at the
// target value it has here, weighted by p̂ · W · M (Algorithm 4).
fn reservoir_merge(r: ptr<function, Reservoir>, s: Surface, origin: vec3<f32>, other: Reservoir, u: f32) {
    if other.emitter >= scene_info.emitter_count || other.w <= 0.0 {
        (*r).m += other.m;
        return;
    }
    let here = target_value(s, origin, emitter_point(other.emitter, other.bary));
    reservoir_add(r, other.emitter, other.bary, here, here * other.w * other.m, other.m, u);
}

// RIS over `candidates` emitter points picked down the light tree: the reservoir that keeps
// one, its W set (no shadow ray yet).
fn resample_emitters(s: Surface, origin: vec3<f32>, candidates: u32, rng: ptr<function, u32>) -> Reservoir {
    var r = empty_reservoir();
    for (var i = 0u; i < candidates; i++) {
        let pick = pick_emitter_near(origin, s.normal, rng);
        let bary = uniform_triangle(rand2(rng));
        let e = emitter_point(pick.emitter, bary);
        let value = target_value(s, origin, e);
        // The candidate's pdf over area: the pick's probability spread over the triangle.
        let pdf = pick.probability / emitter_area(pick.emitter);
        reservoir_add(&r, pick.emitter, bary, value, value / max(pdf, 1e-30), 1.0, rand(rng));
    }
    reservoir_finish(&r);
    return r;
}

// The light r's sample brings, f(y) · W, where it reaches the surface unblocked (one shadow
// ray); zero otherwise.
fn reservoir_light(s: Surface, wo: vec3<f32>, origin: vec3<f32>, r: Reservoir) -> vec3<f32> {
    if r.emitter >= scene_info.emitter_count || r.w <= 0.0 {
        return vec3<f32>(0.0);
    }
    let e = emitter_point(r.emitter, r.bary);
    let reach = emitter_reach(s, wo, origin, e);
    if all(reach.light == vec3<f32>(0.0)) || !emitter_visible(origin, reach.wi, reach.distance, e) {
        return vec3<f32>(0.0);
    }
    return reach.light * r.w;
}

// Whether r's sample reaches the surface unblocked (visibility reuse: a reservoir whose sample
// is shadowed keeps its M and loses its weight, so its neighbours stop taking it).
fn reservoir_visible(origin: vec3<f32>, r: Reservoir) -> bool {
    if r.emitter >= scene_info.emitter_count || r.w <= 0.0 {
        return false;
    }
    return point_visible(origin, emitter_point(r.emitter, r.bary));
}

// Whether the emitter point e is the first thing a ray from `origin` towards it meets.
fn point_visible(origin: vec3<f32>, e: EmitterSample) -> bool {
    let to_light = e.position - origin;
    let distance = length(to_light);
    return emitter_visible(origin, to_light / max(distance, 1e-20), distance, e);
}

// Reservoirs in an rgba32uint texel: the emitter, the barycentrics as two 16-bit unorms, W and M.
fn pack_reservoir(r: Reservoir) -> vec4<u32> {
    return vec4<u32>(r.emitter, pack2x16unorm(r.bary), bitcast<u32>(r.w), bitcast<u32>(r.m));
}

fn unpack_reservoir(texel: vec4<u32>) -> Reservoir {
    var r = empty_reservoir();
    r.emitter = texel.x;
    r.bary = unpack2x16unorm(texel.y);
    r.w = bitcast<f32>(texel.z);
    r.m = bitcast<f32>(texel.w);
    return r;
}

// An unbiased estimate of the direct light from every emitter at a ray's hit: RIS over
// HIT_EMITTER_CANDIDATES candidates and one shadow ray.
fn emitter_light(s: Surface, wo: vec3<f32>, rng: ptr<function, u32>) -> vec3<f32> {
    if SCENE_HAS_EMITTERS == 0u {
        return vec3<f32>(0.0);
    }
    let origin = offset_ray(s.position, s.geometric_normal);
    return reservoir_light(s, wo, origin, resample_emitters(s, origin, HIT_EMITTER_CANDIDATES, rng));
}
