// Emitter samples chosen by resampled importance sampling (RIS, Talbot et al. 2005) and held in
// reservoirs that later frames and neighbouring pixels reuse (ReSTIR DI, Bitterli et al. 2020,
// Algorithms 3-5). Candidates come from the emitter grid's pick for the surface's cell
// (pick_emitter: by power, facing and distance to the cell); RIS keeps one in proportion to
// what it sends to the surface unshadowed (Le × both cosines / d², target_value), so that near,
// facing emitters win over far ones of the same power. One shadow ray then tests the one kept.
// Shared by frame/direct, every ray hit's emitter sample (emitter_light) and the path
// tracer's next-event estimation.
#import lights

// Candidates a ray hit's one emitter sample is chosen from (emitter_light): enough that the
// nearest of a hall's emitters win most of the time; each costs a pick and a few loads, no ray.
const HIT_EMITTER_CANDIDATES: u32 = 8u;
// The same for DDGI's final gather, whose hits are a pixel's light for up to `history_frames`
// frames: a hit beside a small emitter that few candidates find is a firefly there.
const GATHER_EMITTER_CANDIDATES: u32 = 32u;

// How far a reused reservoir's surface may lie from the pixel's, as a share of the view depth,
// and the smallest cosine between their normals (ReSTIR DI's 10 % and 25°).
const REUSE_DEPTH_TOLERANCE: f32 = 0.1;
const REUSE_NORMAL_TOLERANCE: f32 = 0.9;

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
    // Drawn this frame where no history was found (frame/direct, or frame/direct_reuse when it
    // draws the candidates itself), so that frame/direct_reuse takes `cut_neighbours` for it.
    fresh: bool,
}

fn empty_reservoir() -> Reservoir {
    return Reservoir(INVALID, vec2<f32>(0.0), 0.0, 0.0, 0.0, 0.0, false);
}

// The target function p̂ the reservoirs resample towards at a surface: the emitter point's
// luminance × both cosines / d², what it sends unshadowed to a white Lambertian surface. The
// BRDF is left out (a candidate costs no BRDF evaluation); p̂ is positive wherever the light
// f(y) is, so the estimate stays unbiased, with a little more noise on glossy surfaces.
fn target_value(s: Surface, origin: vec3<f32>, e: EmitterSample) -> f32 {
    return target_value_seen(TargetView(origin, s.normal, s.geometric_normal), e.position, e.normal, luminance(e.radiance));
}

// What target_value reads of a surface: where its shadow rays start and its normals.
struct TargetView {
    origin: vec3<f32>,
    normal: vec3<f32>,
    geometric_normal: vec3<f32>,
}

// target_value from an emitter point at `position` facing `normal` of luminance `brightness`.
fn target_value_seen(v: TargetView, position: vec3<f32>, normal: vec3<f32>, brightness: f32) -> f32 {
    let to_light = position - v.origin;
    let d2 = dot(to_light, to_light);
    let cos_light = -dot(normal, to_light);
    let cos_surface = dot(v.normal, to_light);
    if cos_light <= 0.0 || cos_surface <= 0.0 || dot(v.geometric_normal, to_light) <= 0.0 || d2 <= 0.0 {
        return 0.0;
    }
    // The cosines of unnormalised vectors: d² twice over.
    return brightness * cos_surface * cos_light / (d2 * d2);
}

// Streams one candidate of resampling weight `weight` into r (Algorithm 2's update); `m` is
// how many candidates it stands for. Whether r now holds it.
fn reservoir_add(r: ptr<function, Reservoir>, emitter: u32, bary: vec2<f32>, target_value: f32, weight: f32, m: f32, u: f32) -> bool {
    (*r).m += m;
    if weight <= 0.0 {
        return false;
    }
    (*r).weight_sum += weight;
    if u * (*r).weight_sum < weight {
        (*r).emitter = emitter;
        (*r).bary = bary;
        (*r).target_value = target_value;
        return true;
    }
    return false;
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
    _ = reservoir_add(r, other.emitter, other.bary, here, here * other.w * other.m, other.m, u);
}

// RIS over `candidates` emitter points picked through the emitter grid for the surface's cell:
// the reservoir that keeps one, its W set (no shadow ray yet).
fn resample_emitters(s: Surface, origin: vec3<f32>, candidates: u32, rng: ptr<function, u32>) -> Reservoir {
    return resample_emitters_drawn(s, origin, candidates, PickSequence(false, 0.0, 0u), rng);
}

// Where a pixel's candidates take their picks (`pick_emitter`'s one number) when the frames they
// are drawn in are averaged (a still view's running mean): candidate n of the pixel's run is
// point n of the golden-ratio sequence, fract(shift + n / φ), so that a frame's candidates, and
// all of its frames' together, spread evenly over the grid's distribution. Any run of it is as
// even, whatever its start or length. Over a random shift each pick is drawn with the grid's
// pdf, and RIS needs no more for its estimate to stay unbiased (not that the candidates be
// independent); for a fixed shift the mean over frames converges to the same light, as the
// sequence fills [0, 1) evenly.
struct PickSequence {
    on: bool,
    // The pixel's turn of the sequence, the same every frame.
    shift: f32,
    // The sequence's index of this frame's first candidate.
    first: u32,
}

// resample_emitters, its picks drawn along `sequence` where it is on.
fn resample_emitters_drawn(s: Surface, origin: vec3<f32>, candidates: u32, sequence: PickSequence, rng: ptr<function, u32>) -> Reservoir {
    var r = empty_reservoir();
    // Room for emitters but none placed (a host's scene), or every one removed: no grid to read.
    if scene_info.emitter_count == 0u || scene_info.grid_clusters == 0u {
        return r;
    }
    let cell = emitter_cell(origin);
    for (var i = 0u; i < candidates; i++) {
        var u = rand(rng);
        if sequence.on {
            // n × 2³²/φ, wrapping: the fraction of n/φ in 32 bits, kept to 24.
            u = fract(sequence.shift + f32(((sequence.first + i) * 2654435769u) >> 8u) * (1.0 / 16777216.0));
        }
        let pick = pick_emitter(cell, u);
        let bary = uniform_triangle(rand2(rng));
        let e = emitter_point(pick.index, bary);
        let value = target_value(s, origin, e);
        _ = reservoir_add(&r, pick.index, bary, value, value / (e.pdf_area * pick.cluster_probability), 1.0, rand(rng));
    }
    reservoir_finish(&r);
    return r;
}

// The light r's sample brings, f(y) · W, with its diffuse part, where it reaches the surface
// unblocked (one shadow ray); zero otherwise.
fn reservoir_light(s: Surface, wo: vec3<f32>, origin: vec3<f32>, r: Reservoir) -> DirectLight {
    let none = DirectLight(vec3<f32>(0.0), vec3<f32>(0.0));
    if r.emitter >= scene_info.emitter_count || r.w <= 0.0 {
        return none;
    }
    let e = emitter_point(r.emitter, r.bary);
    let reach = emitter_reach(s, wo, origin, e);
    if all(reach.light == vec3<f32>(0.0)) || !emitter_visible(origin, reach.wi, reach.distance, e) {
        return none;
    }
    return with_diffuse(s, reach.light * r.w, reach.arriving * r.w);
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

// Reservoirs in an rgba32uint texel: the emitter, the barycentrics as two 16-bit unorms, W and
// M, whose sign bit (M is never negative) holds `fresh`.
const RESERVOIR_FRESH_BIT: u32 = 0x80000000u;

fn pack_reservoir(r: Reservoir) -> vec4<u32> {
    let m = bitcast<u32>(r.m) | select(0u, RESERVOIR_FRESH_BIT, r.fresh);
    return vec4<u32>(r.emitter, pack2x16unorm(r.bary), bitcast<u32>(r.w), m);
}

fn unpack_reservoir(texel: vec4<u32>) -> Reservoir {
    var r = empty_reservoir();
    r.emitter = texel.x;
    r.bary = unpack2x16unorm(texel.y);
    r.w = bitcast<f32>(texel.z);
    r.m = bitcast<f32>(texel.w & ~RESERVOIR_FRESH_BIT);
    r.fresh = (texel.w & RESERVOIR_FRESH_BIT) != 0u;
    return r;
}

// The solid-angle pdf with which the emitter grid's pick and a uniform point on the triangle
// find emitter `index` `distance` from `origin`, seen at `cos_light` there: the light
// strategy's pdf in the MIS weights against BRDF sampling. The resampled pdf has no closed
// form; weights that sum to one for every direction keep an estimator unbiased whatever pdf
// they are built on, and a sample's own weight stays the reservoir's W.
fn emitter_solid_angle_pdf(origin: vec3<f32>, index: u32, distance: f32, cos_light: f32) -> f32 {
    // No grid (every emitter removed): no light strategy, so the BRDF ray's weight is 1.
    if scene_info.grid_clusters == 0u {
        return 0.0;
    }
    return emitter_area_pdf(emitter_cell(origin), index) * distance * distance / max(cos_light, 1e-8);
}

// An emitter sample before its shadow ray: RIS over `candidates` points the emitter grid picks,
// the point, and in `light` what it brings if nothing blocks it (light 0: nothing to trace),
// weighed against a BRDF-sampled ray by the power heuristic where `weighs_brdf` (the light
// strategy's pdf: emitter_solid_angle_pdf, here and at a BRDF ray's emitter hit alike). Used by
// the path tracer's next-event estimation and by emitter_light_both_ways. What it costs where the
// weights fit badly, and why p̂ over an estimate of its integral was no better:
// docs/notes/light-quality.md, 2026-11-27.
struct EmitterSampleUnshadowed {
    point: EmitterSample,
    light: EmitterReach,
}

fn emitter_sample_unshadowed(s: Surface, wo: vec3<f32>, origin: vec3<f32>, candidates: u32, weighs_brdf: bool, rng: ptr<function, u32>) -> EmitterSampleUnshadowed {
    var out: EmitterSampleUnshadowed;
    if SCENE_HAS_EMITTERS == 0u {
        return out;
    }
    let r = resample_emitters(s, origin, candidates, rng);
    if r.emitter >= scene_info.emitter_count || r.w <= 0.0 {
        return out;
    }
    out.point = emitter_point(r.emitter, r.bary);
    out.light = emitter_reach(s, wo, origin, out.point);
    if all(out.light.light == vec3<f32>(0.0)) {
        return out;
    }
    var w = 1.0;
    if weighs_brdf {
        let light_pdf = emitter_solid_angle_pdf(origin, r.emitter, out.light.distance, out.light.cos_light);
        w = power_heuristic(light_pdf, brdf_pdf(s, wo, out.light.wi));
    }
    out.light.light = out.light.light * r.w * w;
    return out;
}

// The emitters' light at s from both strategies, each weighed against the other by the power
// heuristic (the path tracer's next-event estimation and its BRDF ray, for one bounce): RIS
// over `candidates` with one shadow ray, and one BRDF-sampled ray that counts the emitter it
// meets. For a surface whose sharp specular lobe sees a small part of an emitter: the grid's
// picks, blind to the BRDF, seldom fall there, and one that does brings hundreds of times the
// mean; the BRDF ray falls there as often as the lobe points there.
fn emitter_light_both_ways(s: Surface, wo: vec3<f32>, candidates: u32, rng: ptr<function, u32>) -> vec3<f32> {
    var light = vec3<f32>(0.0);
    let origin = shadow_origin(s);
    let e = emitter_sample_unshadowed(s, wo, origin, candidates, true, rng);
    if any(e.light.light != vec3<f32>(0.0)) && emitter_visible(origin, e.light.wi, e.light.distance, e.point) {
        light = e.light.light;
    }
    let b = brdf_sample(s, wo, rand(rng), rand2(rng));
    if b.pdf <= 0.0 || dot(b.dir, s.geometric_normal) <= 0.0 {
        return light;
    }
    let hit = trace_ray(origin, b.dir, RAY_FAR, false);
    if hit.triangle == INVALID {
        return light;
    }
    let h = surface_at(origin, b.dir, hit.t, hit.triangle, hit.instance, hit.bary);
    if all(h.emission == vec3<f32>(0.0)) {
        return light;
    }
    let cos_light = abs(dot(h.geometric_normal, b.dir));
    let light_pdf = emitter_solid_angle_pdf(origin, hit_emitter(hit.instance, hit.triangle), hit.t, cos_light);
    return light + h.emission * b.weight * power_heuristic(b.pdf, light_pdf);
}

// An unbiased estimate of the direct light from every emitter at a ray's hit: RIS over
// HIT_EMITTER_CANDIDATES candidates and one shadow ray.
fn emitter_light(s: Surface, wo: vec3<f32>, rng: ptr<function, u32>) -> vec3<f32> {
    return emitter_light_from(s, wo, HIT_EMITTER_CANDIDATES, rng);
}

// emitter_light with RIS over `candidates`.
fn emitter_light_from(s: Surface, wo: vec3<f32>, candidates: u32, rng: ptr<function, u32>) -> vec3<f32> {
    return emitter_light_split(s, wo, candidates, rng).total;
}

// emitter_light_from with its diffuse part (frame/direct).
fn emitter_light_split(s: Surface, wo: vec3<f32>, candidates: u32, rng: ptr<function, u32>) -> DirectLight {
    if SCENE_HAS_EMITTERS == 0u {
        return DirectLight(vec3<f32>(0.0), vec3<f32>(0.0));
    }
    let origin = shadow_origin(s);
    return reservoir_light(s, wo, origin, resample_emitters(s, origin, candidates, rng));
}
