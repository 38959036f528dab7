// frame/direct_reuse (with emitter resampling only): each pixel merges its reservoir from
// frame/direct with `reuse_neighbours` neighbours' whose surfaces agree with its own (ReSTIR
// DI's spatial reuse, unbiased with `reuse_visibility`), shades the winner with one shadow ray,
// adds the punctual lights and keeps the running mean. The reservoir it keeps, W zeroed where
// the shadow ray was blocked, is next frame's history.
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
        var r = empty_reservoir();
        reservoir_merge(&r, s, origin, own, rand(&rng));
        // The neighbours merged, kept to count which of them could have drawn the winner.
        var taken: array<vec2<u32>, MAX_REUSE_NEIGHBOURS>;
        var taken_m: array<f32, MAX_REUSE_NEIGHBOURS>;
        var count = 0u;
        for (var k = 0u; k < min(frame.reuse_neighbours, MAX_REUSE_NEIGHBOURS); k++) {
            let q = neighbour(id.xy, &rng);
            if all(q == id.xy) {
                continue;
            }
            let other = history_geometry(q);
            if other.w < 0.0 || abs(other.w - geometry.w) > REUSE_DEPTH_TOLERANCE * geometry.w || dot(other.xyz, geometry.xyz) < REUSE_NORMAL_TOLERANCE {
                continue;
            }
            let theirs = unpack_reservoir(textureLoad(direct_reservoirs, q, 0));
            reservoir_merge(&r, s, origin, theirs, rand(&rng));
            taken[count] = q;
            taken_m[count] = theirs.m;
            count++;
        }
        // Bitterli et al. 2020, Algorithm 6: W divides by the candidates of the pixels that could
        // have drawn the winner, not by all. With `reuse_visibility` that takes a shadow ray a
        // neighbour and is unbiased; without, a neighbour that faces the winner but is shadowed
        // from it still counts, which darkens shadow edges a little.
        var z = own.m;
        for (var k = 0u; k < count; k++) {
            if could_draw(taken[k], r) {
                z += taken_m[k];
            }
        }
        r.m = z;
        reservoir_finish(&r);
        let emitted = reservoir_light(s, wo, origin, r);
        kept = r;
        if all(emitted.total == vec3<f32>(0.0)) {
            kept.w = 0.0;
        }
        light = add_direct(direct_punctual_split(s, wo), emitted);
    }
    textureStore(direct_reservoirs_final, id.xy, pack_reservoir(kept));
    keep_direct_mean(id.xy, light);
}

// Whether the surface at pixel q could have drawn r's sample: it faces the sample, and with
// `reuse_visibility` nothing blocks the way (one shadow ray).
fn could_draw(q: vec2<u32>, r: Reservoir) -> bool {
    if r.emitter >= scene_info.emitter_count {
        return false;
    }
    let s = gbuffer_surface(q);
    let origin = shadow_origin(s);
    let e = emitter_point(r.emitter, r.bary);
    return target_value(s, origin, e) > 0.0 && (frame.reuse_visibility == 0u || point_visible(origin, e));
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
