// ddgi/resolve: indirect diffuse light at each G-buffer pixel from this probe volume, blended
// into `indirect` (rgb: weighted sum, a: weight so far). Volumes run finest first; each takes
// the weight the finer ones left where the point lies inside it (fading out over the last
// grid cell before its outermost probes), and the coarsest takes all that is left, so that one
// volume alone lights everything, as it always did. With GATHER_RAYS > 0 (DdgiGatherSettings::
// rays_per_pixel) the light is a final gather where the pixel's tile gathers this frame
// (gather_tile_traces): that many cosine-distributed rays a pixel, each hit shaded as a probe
// ray's (ddgi_hit_light); ddgi/temporal averages it over frames.
#import ddgi_hit_light
#import gbuffer

@group(2) @binding(10) var indirect: texture_storage_2d<rgba32float, read_write>;

// 1 inside the volume's probe box by more than a cell, falling to 0 at its outermost probes.
fn volume_weight(p: vec3<f32>) -> f32 {
    let last = volume.origin + vec3<f32>(volume.counts - 1u) * volume.spacing;
    let inside = min(p - volume.origin, last - p) / volume.spacing;
    // Axes with one probe have no extent to fade over.
    let fade = select(saturate(inside), vec3<f32>(1.0), volume.counts == vec3<u32>(1u));
    return fade.x * fade.y * fade.z;
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local_index: u32, @builtin(workgroup_id) tile: vec3<u32>) {
    bvh_thread(local_index);
    if !in_frame(id.xy) {
        return;
    }
    var sum = vec4<f32>(0.0);
    if volume.volume_index > 0u {
        sum = textureLoad(indirect, id.xy);
    }
    if gbuffer_depth_at(id.xy) < 0.0 {
        textureStore(indirect, id.xy, sum);
        return;
    }
    let s = gbuffer_surface(id.xy);
    var weight = 1.0 - sum.a;
    if volume.volume_is_last == 0u {
        weight *= volume_weight(s.position);
    }
    if weight <= 0.0 {
        textureStore(indirect, id.xy, sum);
        return;
    }
    var light: vec3<f32>;
    if GATHER_RAYS > 0u && gather_tile_traces(tile.xy, frame.frame_index) {
        light = gathered_light(s, id.xy);
    } else {
        light = ddgi_irradiance(s.position, s.normal, view_dir(s.position));
    }
    light *= diffuse_weight(s);
    textureStore(indirect, id.xy, sum + vec4<f32>(light * weight, weight));
}

// The cosine-weighted mean radiance GATHER_RAYS rays from the pixel's surface bring back. A ray
// that leaves the scene takes the sky; one that meets a back face is shaded from that side,
// as the path tracer does.
fn gathered_light(s: Surface, pixel: vec2<u32>) -> vec3<f32> {
    var rng = rng_seed(pixel.y * frame.width + pixel.x, frame.frame_index, frame.seed ^ 0x3c6ef372u ^ volume.volume_index);
    let origin = offset_ray(s.position, s.geometric_normal);
    let around = basis(s.normal);
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < GATHER_RAYS; i++) {
        let dir = normalize(around * cosine_hemisphere(rand2(&rng)));
        let hit = trace_ray(origin, dir, RAY_FAR, false);
        if hit.triangle == INVALID {
            sum += scene_info.sky;
            continue;
        }
        let h = surface_at(origin, dir, hit.t, hit.triangle, hit.instance, hit.bary);
        let wo = -dir;
        sum += hit_punctual_light(h, wo, rand(&rng)) + hit_emitter_and_probe_light(h, wo, hit.t, &rng);
    }
    return sum / f32(GATHER_RAYS);
}
