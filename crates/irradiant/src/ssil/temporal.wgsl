// ssil/temporal: eq. 6 — the light blended with last frame's, warped along the motion vectors
// (camera and moving objects alike), where last frame's pixel held the same surface: its
// stored depth within depth_tolerance of this surface's depth seen from last frame's camera,
// its normal within normal_tolerance. The weight a falls with motion, and more for the glossy
// light, which moves over a surface differently from the surface itself. The result, with the
// geometry it was filtered on, is next frame's history; and it resolves into the frame's
// indirect light: the diffuse share of the irradiance plus the glossy radiance. In ssil+ddgi
// (`hybrid`) DDGI has already written its diffuse light there (its reflections come after,
// whole); the screen-space light replaces it in the share of the cosine lobe the screen
// covered (coverage C, senders in the near field only) and the probes keep the rest —
// off-screen, hidden and farther senders — so that nothing is counted twice. The probes' light for the rest is read around the directions the screen left
// uncovered (`uncovered_light`, from one of two files compiled after this one: SsilPipelines).
// The bindings start at 60, clear of DDGI's, whose query the hybrid's file imports; `indirect`
// keeps the slot DDGI's passes give it (10), which the query does not use.
#import ssil_common
#import gbuffer
#import history
#import brdf

@group(2) @binding(60) var<uniform> ssil: GpuSsilParams;
@group(2) @binding(61) var pyramid_normal_depth: texture_2d<f32>;
@group(2) @binding(62) var ssil_full: texture_2d<f32>;
@group(2) @binding(63) var ssil_full_specular: texture_2d<f32>;
@group(2) @binding(64) var ssil_history: texture_2d<f32>;
@group(2) @binding(65) var ssil_history_specular: texture_2d<f32>;
@group(2) @binding(66) var ssil_history_geometry: texture_2d<f32>;
@group(2) @binding(67) var ssil_filtered: texture_storage_2d<rgba16float, write>;
@group(2) @binding(68) var ssil_filtered_specular: texture_storage_2d<rgba16float, write>;
@group(2) @binding(69) var ssil_filtered_geometry: texture_storage_2d<rgba32float, write>;
@group(2) @binding(10) var indirect: texture_storage_2d<rgba32float, read_write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let texel = vec2<i32>(id.xy);
    let here = textureLoad(pyramid_normal_depth, id.xy, 0);
    textureStore(ssil_filtered_geometry, texel, here);
    if here.w < 0.0 {
        textureStore(ssil_filtered, texel, vec4<f32>(0.0));
        textureStore(ssil_filtered_specular, texel, vec4<f32>(0.0));
        store_covered(texel, vec3<f32>(0.0));
        textureStore(indirect, texel, vec4<f32>(0.0));
        return;
    }
    var light = textureLoad(ssil_full, texel, 0);
    var specular = textureLoad(ssil_full_specular, texel, 0).rgb;
    var covered = source_covered(texel);
    let s = gbuffer_surface(id.xy);
    if ssil.history_frames > 0u {
        let previous = history_position(id.xy);
        if all(previous >= vec2<f32>(0.0)) && all(previous < frame_size()) {
            let p = vec2<i32>(previous);
            let old = textureLoad(ssil_history_geometry, p, 0);
            let x = level_position(id.xy, 0u, here.w);
            if same_surface(old, x, here.xyz, ssil.depth_tolerance, ssil.normal_tolerance) {
                // A running mean of the frames since a reset until it reaches the hysteresis:
                // the first frame after a reset (a cut, or ssil+ddgi's reach returning to the
                // near field) weighs no more than the ones after it.
                let frames = f32(ssil.history_frames);
                let held = min(ssil.hysteresis, frames / (frames + 1.0));
                let a = held * exp(-length(gbuffer_motion_at(id.xy)) / ssil.motion_pixels);
                let a_specular = a * clamp(2.0 * s.roughness, 0.2, 1.0);
                light = mix(light, textureLoad(ssil_history, p, 0), a);
                covered = mix(covered, history_covered(p), a);
                specular = mix(specular, textureLoad(ssil_history_specular, p, 0).rgb, a_specular);
            }
        }
    }
    textureStore(ssil_filtered, texel, light);
    textureStore(ssil_filtered_specular, texel, vec4<f32>(specular, 1.0));
    store_covered(texel, covered);
    var out = diffuse_weight(s) / PI * light.rgb + specular;
    if ssil.hybrid == 1u {
        let probes = textureLoad(indirect, texel);
        let coverage = min(light.a, 1.0);
        out += (1.0 - coverage) * uncovered_light(s, probes.rgb / max(probes.a, 1e-6), coverage, covered);
    }
    textureStore(indirect, texel, vec4<f32>(out, 1.0));
}
