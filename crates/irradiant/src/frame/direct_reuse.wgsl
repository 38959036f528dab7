// frame/direct_reuse (with emitter resampling only): each pixel merges its reservoir from
// frame/direct with `reuse_neighbours` neighbours' whose surfaces agree with its own (ReSTIR
// DI's spatial reuse by generalized RIS, unbiased with `reuse_visibility`), shades the winner
// with one shadow ray, adds the punctual lights and keeps the running mean. Its own reservoir,
// W zeroed where it won and the shadow ray was blocked, is next frame's history. In a frame
// where no pixel takes another's reservoir or last frame's (`direct_in_reuse`: a still view
// after its first frame) frame/direct does not run and this pass draws the pixel's candidates.
#import direct_mean
#import history
#import resampling
#import random

@group(2) @binding(1) var direct_reservoirs: texture_2d<u32>;
@group(2) @binding(2) var direct_reservoirs_final: texture_storage_2d<rgba32uint, write>;
@group(2) @binding(3) var direct_reservoir_geometry: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    if !in_frame(id.xy) || frame.emitter_candidates == 0u {
        return;
    }
    if scene_info.emitter_count == 0u {
        // Room for emitters but none placed: frame/direct lights the pixel by the punctual
        // lights alone, unless this frame left it out, and then this pass does.
        if frame.direct_in_reuse != 0u {
            keep_direct_mean(id.xy, punctual_light_at(id.xy));
        }
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
        let index = id.y * frame.width + id.x;
        var own: Reservoir;
        if frame.direct_in_reuse != 0u {
            // No history and no neighbours: a pixel with none, as frame/direct draws it, and
            // packed as its texture holds it (barycentrics in 16 bits), so that both ways
            // make the same image.
            var stream = candidate_stream(index);
            var drawn = resample_emitters_drawn(s, origin, frame.cut_candidates, candidate_sequence(index), &stream);
            drawn.fresh = true;
            own = unpack_reservoir(pack_reservoir(drawn));
        } else {
            own = unpack_reservoir(textureLoad(direct_reservoirs, id.xy, 0));
        }
        var rng = rng_seed(index, frame.frame_index, frame.seed ^ 0x68e31da4u);
        // The neighbours whose surfaces agree with this one, and the candidates all count for.
        var taken: array<vec2<u32>, MAX_REUSE_NEIGHBOURS>;
        var count = 0u;
        var total_m = own.m;
        let neighbours = select(frame.reuse_neighbours, frame.cut_neighbours, own.fresh);
        for (var k = 0u; k < min(neighbours, MAX_REUSE_NEIGHBOURS); k++) {
            let q = neighbour(id.xy, &rng);
            if all(q == id.xy) {
                continue;
            }
            let other = history_geometry(q);
            if other.w < 0.0 || abs(other.w - geometry.w) > REUSE_DEPTH_TOLERANCE * geometry.w || dot(other.xyz, geometry.xyz) < REUSE_NORMAL_TOLERANCE {
                continue;
            }
            taken[count] = q;
            total_m += unpack_reservoir(textureLoad(direct_reservoirs, q, 0)).m;
            count++;
        }
        // Generalized RIS (Lin et al. 2022) with pairwise MIS weights (Bitterli 2022, his thesis),
        // confidence-weighted by M: each neighbour i is weighed against this pixel's own
        // reservoir alone, pair_i(y) = M_i p̂_i(y) / (M_i p̂_i(y) + M_own p̂(y) / k), and
        // y_i weighs m_i(y_i) · p̂(y_i) · W_i, m_i = (M_i + M_own / k) / ΣM · pair_i; the own
        // sample takes what the pairs leave, m_own = Σ_i (M_i + M_own / k) / ΣM · (1 − pair_i).
        // W = Σ weights / p̂(y). A neighbour that drew y rarely (p̂ small there, its W large)
        // brings y here at the share it could have drawn it: no firefly where y is bright here
        // (Algorithm 6's 1/Z took it at full weight). 3k target evaluations, no array of
        // surfaces. p̂ leaves out shadows, so a neighbour shadowed from the own sample still
        // takes a share of it, which darkens shadow edges a little; with `reuse_visibility` a
        // shadow ray from each neighbour finds those, and the reuse is unbiased.
        var r = empty_reservoir();
        let own_point = emitter_point(min(own.emitter, scene_info.emitter_count - 1u), own.bary);
        let own_brightness = luminance(own_point.radiance);
        let own_valid = own.emitter < scene_info.emitter_count && own.w > 0.0;
        let own_view = TargetView(origin, s.normal, s.geometric_normal);
        let own_here = select(0.0, target_value_seen(own_view, own_point.position, own_point.normal, own_brightness), own_valid);
        let own_share = own.m / f32(max(count, 1u));
        var own_weight = select(1.0, 0.0, count > 0u);
        for (var k = 0u; k < count; k++) {
            let q = taken[k];
            let theirs = unpack_reservoir(textureLoad(direct_reservoirs, q, 0));
            let there = gbuffer_surface(q);
            let view = TargetView(shadow_origin(there), there.normal, there.geometric_normal);
            let budget = (theirs.m + own_share) / total_m;
            // The own sample, as this neighbour would have weighed it.
            if own_here > 0.0 {
                var own_there = target_value_seen(view, own_point.position, own_point.normal, own_brightness);
                if own_there > 0.0 && frame.reuse_visibility != 0u && !point_visible(view.origin, own_point) {
                    own_there = 0.0;
                }
                let own_part = own_share * own_here;
                own_weight += budget * own_part / (theirs.m * own_there + own_part);
            }
            // This neighbour's sample.
            if theirs.emitter >= scene_info.emitter_count || theirs.w <= 0.0 {
                r.m += theirs.m;
                continue;
            }
            let e = emitter_point(theirs.emitter, theirs.bary);
            let brightness = luminance(e.radiance);
            let here = target_value_seen(own_view, e.position, e.normal, brightness);
            let their_part = theirs.m * target_value_seen(view, e.position, e.normal, brightness);
            let pair = select(0.0, their_part / (their_part + own_share * here), their_part > 0.0);
            _ = reservoir_add(&r, theirs.emitter, theirs.bary, here, budget * pair * here * theirs.w, theirs.m, rand(&rng));
        }
        let own_won = reservoir_add(&r, own.emitter, own.bary, own_here, own_weight * own_here * own.w, own.m, rand(&rng));
        r.w = select(0.0, r.weight_sum / r.target_value, r.target_value > 0.0);
        let emitted = reservoir_light(s, wo, origin, r);
        // Next frame's history is the pixel's own reservoir, not the neighbours' winner: fed
        // back, a neighbour's sample would spread a little further every frame and come back
        // through the neighbours' own histories, and what one pixel overrates would grow into
        // blotches (the many-lights hall's error rose with every frame of a moving view). Its
        // sample loses its weight when this frame's shadow ray found it blocked.
        kept = own;
        kept.fresh = false;
        if own_won && all(emitted.total == vec3<f32>(0.0)) {
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
