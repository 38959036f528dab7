// ddgi/gather_filter: one pass of the final gather's filter across the image
// (`gather.filter_passes`), after ddgi/temporal. A running mean of a few dozen one-ray gathers
// is noise in every pixel (two-rooms: eight times the rays took `quality`'s relative MSE from
// 0.0175 to 0.0077, docs/notes/light-quality.md). Each pass is a 3×3 à-trous step (Dammertz et
// al. 2010) at FILTER_STEP pixels between taps; a neighbour counts where it lies on the
// pixel's plane, faces its way and reads a light within a few standard errors of the
// difference between the two, the error of each pixel's mean estimated from its gathers'
// second moment, as SVGF does (Schied et al. 2017). The difference's error is both pixels'
// (the centre's smoothed, the neighbour's its own; SVGF takes the centre's alone): else a pixel
// whose mean holds one rare bright gather takes its quiet neighbours while they refuse it, and
// the light of rare bright paths is lost (the glossy-floor Cornell box's ceiling, lit by the
// lamp through the metal floor, read 10 % dark). Where both are noisy it reaches a little wider:
// `quality`'s FLIP on the glossy box 0.0429 → 0.0479, the Cornell box 0.0427 → 0.0438, the
// glossy floor 0.0774 → 0.0686 (lavapipe, 96×72; docs/notes/light-quality.md). The filter
// works on irradiance, before the albedo: texture detail is never blurred. The history keeps
// the unfiltered mean, so nothing the filter does stays.
//
// FILTER_FIRST: the source is this frame's mean (rgb, gathers in a) and its moment; later
// passes read the last pass's (rgb, variance of the mean); the last pass writes
// ddgi/gather_upsample's source. All on the gather's image: with `gather.half_resolution`
// (GATHER_SCALE 2) a texel is a 2×2 block, read on its top-left pixel's surface, and the taps'
// steps are in texels.
#import gbuffer
#import history
#import sampling

@group(2) @binding(30) var filter_source: texture_2d<f32>;
@group(2) @binding(31) var filter_moment: texture_2d<f32>;
@group(2) @binding(32) var filter_target: texture_storage_2d<rgba32float, write>;

// The binomial weight at 0 and 1 taps out: 3×3 taps a pass. 5×5 taps (the B3 spline) read
// no better at two passes (lavapipe, 128×96, FLIP / relative MSE: Cornell 0.0341 / 0.00063
// against 0.0333 / 0.00062, two-rooms 0.0831 / 0.00794 against 0.0818 / 0.00814) for 25
// taps a pixel instead of 9.
fn kernel(taps_out: i32) -> f32 {
    return select(0.25, 0.5, taps_out == 0);
}
// How many standard errors of the difference between a pixel's light and a neighbour's the two
// may differ by and still count fully (SVGF's σ_l).
const LIGHT_SIGMA: f32 = 2.0;

// The light at a pixel and the variance of that light as an estimate of the truth.
struct Light {
    rgb: vec3<f32>,
    variance: f32,
}

fn source_light(pixel: vec2<i32>) -> Light {
    let s = textureLoad(filter_source, pixel, 0);
    if FILTER_FIRST == 0u {
        return Light(s.rgb, s.a);
    }
    // A mean of n gathers: the gathers' own variance over n. With none it is the probes'
    // query, smooth already; a mean of one gather gets the variance of a light that could as
    // well have been zero.
    let gathers = s.a;
    if gathers < 1.0 {
        return Light(s.rgb, 0.0);
    }
    let l = luminance(s.rgb);
    let spread = max(textureLoad(filter_moment, pixel, 0).r - l * l, select(0.0, l * l, gathers < 2.0));
    return Light(s.rgb, spread / gathers);
}

// The variance of the pixel's light, smoothed over its 3×3 neighbours in the first pass (a
// single pixel's estimate of its own variance is itself noisy); later passes read variances
// the passes before already averaged.
fn smoothed_variance(pixel: vec2<i32>, own: f32, size: vec2<i32>) -> f32 {
    if FILTER_FIRST == 0u {
        return own;
    }
    var variance = 0.0;
    var around = 0.0;
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let q = pixel + vec2<i32>(dx, dy);
            if all(q >= vec2<i32>(0)) && all(q < size) && gbuffer_depth_at(scaled_pixel(vec2<u32>(q), GATHER_SCALE)) >= 0.0 {
                let w = kernel(abs(dx)) * kernel(abs(dy));
                variance += w * source_light(q).variance;
                around += w;
            }
        }
    }
    return variance / around;
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(scaled_size(GATHER_SCALE));
    if any(vec2<i32>(id.xy) >= size) {
        return;
    }
    let pixel = vec2<i32>(id.xy);
    let surface_pixel = scaled_pixel(id.xy, GATHER_SCALE);
    let depth = gbuffer_depth_at(surface_pixel);
    let here = source_light(pixel);
    if depth < 0.0 {
        textureStore(filter_target, pixel, vec4<f32>(0.0));
        return;
    }
    let x = gbuffer_position(surface_pixel, depth);
    let n = gbuffer_normal_at(surface_pixel);
    let variance = smoothed_variance(pixel, here.variance, size);
    let l = luminance(here.rgb);
    var sum = vec3<f32>(0.0);
    var sum_variance = 0.0;
    var weights = 0.0;
    for (var ty = -1; ty <= 1; ty++) {
        for (var tx = -1; tx <= 1; tx++) {
            let q = pixel + vec2<i32>(tx, ty) * i32(FILTER_STEP);
            if any(q < vec2<i32>(0)) || any(q >= size) {
                continue;
            }
            let q_pixel = scaled_pixel(vec2<u32>(q), GATHER_SCALE);
            let q_depth = gbuffer_depth_at(q_pixel);
            if q_depth < 0.0 {
                continue;
            }
            let there = source_light(q);
            var w = kernel(abs(tx)) * kernel(abs(ty));
            if tx != 0 || ty != 0 {
                let error = sqrt(variance + there.variance);
                let apart = abs(luminance(there.rgb) - l) / (LIGHT_SIGMA * error + 1e-9 + 1e-3 * l);
                w *= surface_agreement(x, n, q_pixel, q_depth) * exp(-apart);
            }
            sum += w * there.rgb;
            sum_variance += w * w * there.variance;
            weights += w;
        }
    }
    // Every pass writes (light, variance): the next pass reads both, ddgi/gather_upsample the
    // light.
    textureStore(filter_target, pixel, vec4<f32>(sum / weights, sum_variance / (weights * weights)));
}
