// frame/direct: direct light at each G-buffer pixel. Without emitter resampling: punctual lights
// with shadow rays and `area_light_samples` samples of the emissive triangles, kept as a running
// mean while the view and the scene stay still (restarted by the frame's one reset mechanism;
// with TAA's jitter the mean also averages over the pixel's footprint). With resampling
// (frame.emitter_candidates > 0, a scene with emitters) this pass only makes each pixel's
// reservoir: RIS over the candidates, a shadow ray for the one kept (where it will be reused),
// then last frame's reservoir where the motion vectors find the same surface;
// frame/direct_reuse takes the neighbours', shades and keeps the mean. In a frame where no
// pixel takes another's reservoir or last frame's (`direct_in_reuse`) this pass does not run
// and frame/direct_reuse does all of it.
#import direct_mean
#import history
#import resampling
#import random

@group(2) @binding(1) var direct_reservoirs: texture_storage_2d<rgba32uint, write>;
@group(2) @binding(2) var direct_reservoirs_final: texture_2d<u32>;
@group(2) @binding(3) var direct_reservoir_geometry: texture_2d<f32>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    if !in_frame(id.xy) {
        return;
    }
    let index = id.y * frame.width + id.x;
    let resampling = scene_info.emitter_count > 0u && frame.emitter_candidates > 0u;
    let surface = gbuffer_depth_at(id.xy) >= 0.0;
    if resampling {
        var r = empty_reservoir();
        if surface {
            r = temporal_reservoir(id.xy, index);
        }
        textureStore(direct_reservoirs, id.xy, pack_reservoir(r));
        return;
    }
    var light = DirectLight(vec3<f32>(0.0), vec3<f32>(0.0));
    if surface {
        let s = gbuffer_surface(id.xy);
        let wo = view_dir(s.position);
        light = direct_punctual_split(s, wo);
        if scene_info.emitter_count > 0u && frame.area_light_samples > 0u {
            var rng = rng_seed(index, frame.frame_index, frame.seed ^ 0x5bd1e995u);
            let weight = 1.0 / f32(frame.area_light_samples);
            for (var i = 0u; i < frame.area_light_samples; i++) {
                let sample = emitter_light_split(s, wo, HIT_EMITTER_CANDIDATES, &rng);
                light = add_direct(light, DirectLight(sample.total * weight, sample.diffuse * weight));
            }
        }
    }
    keep_direct_mean(id.xy, light);
}

// This frame's candidates, their winner tested for visibility, merged with the reservoir last
// frame kept for this surface. A pixel with none to take draws `cut_candidates`.
fn temporal_reservoir(pixel: vec2<u32>, index: u32) -> Reservoir {
    let s = gbuffer_surface(pixel);
    let origin = shadow_origin(s);
    let old_pixel = history_pixel(pixel, s);
    let fresh_only = old_pixel.x < 0;
    var rng = candidate_stream(index);
    let candidates = select(frame.emitter_candidates, frame.cut_candidates, fresh_only);
    var fresh = resample_emitters_drawn(s, origin, candidates, candidate_sequence(index), &rng);
    fresh.fresh = fresh_only;
    // Visibility reuse: a winner shadowed here loses its weight before it meets last frame's
    // or the neighbours take it. Where neither happens (a still view's later frames),
    // frame/direct_reuse tests the same sample when it shades it: this ray would be that one.
    let reused = frame.reuse_neighbours > 0u || frame.cut_neighbours > 0u || frame.reservoir_history > 0u;
    if reused && !reservoir_visible(origin, fresh) {
        fresh.w = 0.0;
    }
    if fresh_only {
        return fresh;
    }
    var old = unpack_reservoir(textureLoad(direct_reservoirs_final, old_pixel, 0));
    old.m = min(old.m, f32(frame.reservoir_history));
    var r = empty_reservoir();
    _ = reservoir_add(&r, fresh.emitter, fresh.bary, fresh.target_value, fresh.target_value * fresh.w * fresh.m, fresh.m, rand(&rng));
    reservoir_merge(&r, s, origin, old, rand(&rng));
    reservoir_finish(&r);
    return r;
}

// Where last frame's reservoir for the surface at `pixel` lies, or (-1, -1) where there is none
// to take: no temporal reuse this frame, off the image, or another surface there.
fn history_pixel(pixel: vec2<u32>, s: Surface) -> vec2<i32> {
    let none = vec2<i32>(-1);
    if frame.reservoir_history == 0u {
        return none;
    }
    let old_pixel = vec2<i32>(floor(history_position(pixel)));
    let size = vec2<i32>(i32(frame.width), i32(frame.height));
    if any(old_pixel < vec2<i32>(0)) || any(old_pixel >= size) {
        return none;
    }
    let old_geometry = textureLoad(direct_reservoir_geometry, old_pixel, 0);
    if !same_surface(old_geometry, s.position, s.normal, REUSE_DEPTH_TOLERANCE, REUSE_NORMAL_TOLERANCE) {
        return none;
    }
    return old_pixel;
}
