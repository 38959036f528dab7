// frame/direct_reuse (with emitter resampling only): each pixel merges its reservoir from
// frame/direct with `reuse_neighbours` neighbours' whose surfaces agree with its own (ReSTIR
// DI's spatial reuse by generalized RIS, unbiased with `reuse_visibility`), shades the winner
// with one shadow ray, adds the punctual lights and keeps the running mean. Its own reservoir,
// W zeroed where it won and the shadow ray was blocked, is next frame's history.
#import direct_mean
#import history
#import resampling
#import random

@group(2) @binding(1) var direct_reservoirs: texture_2d<u32>;
@group(2) @binding(2) var direct_reservoirs_final: texture_storage_2d<rgba32uint, write>;
@group(2) @binding(3) var direct_reservoir_geometry: texture_storage_2d<rgba16float, write>;

// The pixel's own reservoir and its neighbours'.
const REUSE_INPUTS: u32 = MAX_REUSE_NEIGHBOURS + 1u;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    if !in_frame(id.xy) || scene_info.emitter_count == 0u || frame.emitter_candidates == 0u {
        return;
    }
    let geometry = history_geometry(id.xy);
    textureStore(direct_reservoir_geometry, id.xy, geometry);
    var light = DirectLight(vec3<f32>(0.0), vec3<f32>(0.0));
    var kept = empty_reservoir();
    if geometry.w >= 0.0 {
        let s = gbuffer_surface(id.xy);
        let wo = view_dir(s.position);
        let origin = shadow_origin(s);
        var rng = rng_seed(id.y * frame.width + id.x, frame.frame_index, frame.seed ^ 0x68e31da4u);
        let own = unpack_reservoir(textureLoad(direct_reservoirs, id.xy, 0));
        // The reservoirs merged (the pixel's own first) and the surfaces that hold them.
        var inputs: array<Reservoir, REUSE_INPUTS>;
        var views: array<TargetView, REUSE_INPUTS>;
        inputs[0] = own;
        views[0] = TargetView(origin, s.normal, s.geometric_normal);
        var count = 1u;
        for (var k = 0u; k < min(frame.reuse_neighbours, MAX_REUSE_NEIGHBOURS); k++) {
            let q = neighbour(id.xy, &rng);
            if all(q == id.xy) {
                continue;
            }
            let other = history_geometry(q);
            if other.w < 0.0 || abs(other.w - geometry.w) > REUSE_DEPTH_TOLERANCE * geometry.w || dot(other.xyz, geometry.xyz) < REUSE_NORMAL_TOLERANCE {
                continue;
            }
            let there = gbuffer_surface(q);
            inputs[count] = unpack_reservoir(textureLoad(direct_reservoirs, q, 0));
            views[count] = TargetView(shadow_origin(there), there.normal, there.geometric_normal);
            count++;
        }
        // Generalized RIS with the balance heuristic (Lin et al. 2022; Bitterli et al. 2020,
        // §4.3's MIS weights): the sample y_i of reservoir i weighs
        // m_i(y_i) · p̂(y_i) · W_i, m_i = M_i p̂_i / Σ_j M_j p̂_j, and W = Σ weights / p̂(y).
        // A neighbour that drew y rarely (p̂ small there, W large) thus brings it here at the
        // share it could have drawn it, not at full weight: no firefly where y is bright here.
        var r = empty_reservoir();
        var source = 0u;
        for (var i = 0u; i < count; i++) {
            let input = inputs[i];
            if input.emitter >= scene_info.emitter_count || input.w <= 0.0 {
                r.m += input.m;
                continue;
            }
            let e = emitter_point(input.emitter, input.bary);
            let brightness = luminance(e.radiance);
            var everyone = 0.0;
            var its_own = 0.0;
            for (var j = 0u; j < count; j++) {
                let share = inputs[j].m * target_value_seen(views[j], e.position, e.normal, brightness);
                everyone += share;
                its_own = select(its_own, share, j == i);
            }
            let here = target_value_seen(views[0], e.position, e.normal, brightness);
            let weight = select(0.0, its_own / everyone * here * input.w, everyone > 0.0);
            if reservoir_add(&r, input.emitter, input.bary, here, weight, input.m, rand(&rng)) {
                source = i;
            }
        }
        r.w = select(0.0, r.weight_sum / r.target_value, r.target_value > 0.0);
        // p̂ leaves out shadows, so a neighbour shadowed from y still takes a share of y's
        // weight it could never have drawn, which darkens shadow edges a little. With
        // `reuse_visibility` a shadow ray from each neighbour to the winner finds them, and W
        // gives their shares back: unbiased (the own pixel's ray is the shading's).
        if frame.reuse_visibility != 0u && r.w > 0.0 {
            let e = emitter_point(r.emitter, r.bary);
            let brightness = luminance(e.radiance);
            var everyone = own.m * r.target_value;
            var reaching = everyone;
            for (var j = 1u; j < count; j++) {
                let share = inputs[j].m * target_value_seen(views[j], e.position, e.normal, brightness);
                everyone += share;
                if share > 0.0 && point_visible(views[j].origin, e) {
                    reaching += share;
                }
            }
            r.w *= everyone / reaching;
        }
        let emitted = reservoir_light(s, wo, origin, r);
        // Next frame's history is the pixel's own reservoir, not the neighbours' winner: fed
        // back, a neighbour's sample would spread a little further every frame and come back
        // through the neighbours' own histories, and what one pixel overrates would grow into
        // blotches (the many-lights hall's error rose with every frame of a moving view). Its
        // sample loses its weight when this frame's shadow ray found it blocked.
        kept = own;
        if source == 0u && all(emitted.total == vec3<f32>(0.0)) {
            kept.w = 0.0;
        }
        light = add_direct(direct_punctual_split(s, wo), emitted);
    }
    textureStore(direct_reservoirs_final, id.xy, pack_reservoir(kept));
    keep_direct_mean(id.xy, light);
}

// A pixel in a disc of `reuse_radius` around `pixel`, clamped to the image.
fn neighbour(pixel: vec2<u32>, rng: ptr<function, u32>) -> vec2<u32> {
    let u = rand2(rng);
    let radius = frame.reuse_radius * sqrt(u.x);
    let angle = 6.2831853 * u.y;
    let offset = vec2<f32>(cos(angle), sin(angle)) * radius;
    let q = vec2<f32>(pixel) + offset;
    return vec2<u32>(clamp(q, vec2<f32>(0.0), vec2<f32>(f32(frame.width) - 1.0, f32(frame.height) - 1.0)));
}
