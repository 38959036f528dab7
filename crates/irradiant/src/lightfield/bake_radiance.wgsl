// lightfield/bake_radiance: the light leaving each probe texel's surface towards the probe:
// direct light (every punctual light with a shadow ray, `emitter_samples` samples of the
// emitters) and, from the second bounce on, the diffuse reflection of the irradiance the last
// bounce's prefiltered probes give there (the paper fills its maps by iterating its own
// shading; this iterates the prefiltered query, as DDGI's probe rays do). Emission itself is
// left out, as in DDGI's probes: the frame's direct pass samples emitters already. Rays that
// leave the scene see the sky; rays that meet a back face see nothing.
#import lightfield
#import ddgi_query
#import bvh
#import scene
#import resampling
#import random

@group(2) @binding(26) var target_radiance: texture_storage_2d_array<r32uint, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    let size = lightfield.resolution;
    if id.x >= size || id.y >= size || id.z >= lightfield.probe_count {
        return;
    }
    let probe = id.z;
    let origin = lf_probe_position(probe);
    let dir = lf_direction((vec2<f32>(id.xy) + 0.5) / f32(size));
    let hit = trace_ray(origin, dir, RAY_FAR, false);
    var l = scene_info.sky;
    if hit.triangle != INVALID {
        l = vec3<f32>(0.0);
        let tri = triangle_at(hit.triangle);
        let face = to_world_normal(instances[hit.instance], cross(tri.e1, tri.e2));
        if dot(face, dir) < 0.0 {
            let s = surface_at(origin, dir, hit.t, hit.triangle, hit.instance, hit.bary);
            let wo = -dir;
            l = direct_punctual(s, wo);
            if scene_info.emitter_count > 0u {
                var rng = rng_seed((probe * size + id.y) * size + id.x, lightfield.bounce, 0x51ed270bu);
                var sum = vec3<f32>(0.0);
                for (var i = 0u; i < lightfield.emitter_samples; i++) {
                    sum += emitter_light(s, wo, &rng);
                }
                l += sum / f32(lightfield.emitter_samples);
            }
            if lightfield.bounce > 0u {
                l += diffuse_weight(s) * ddgi_irradiance(s.position, s.normal, wo).irradiance;
            }
        }
    }
    textureStore(target_radiance, id.xy, probe, vec4<u32>(pack_r11g11b10(l), 0u, 0u, 0u));
}
