// frame/taa: temporal anti-aliasing. The primary rays were jittered inside each pixel; this
// pass blends the frame into the history reprojected along the motion vectors (Catmull-Rom
// resampling), after clipping the history to the current frame's 3×3 neighbourhood (mean ±
// taa_clip_sigma standard deviations in YCoCg: Salvi 2016) so that disoccluded or relit
// pixels do not ghost. While neither the view nor the scene changes (the frame's running
// means keep accumulating) the history is not clipped: a still view needs no protection from
// ghosts, and its average over the pixel should not depend on which jittered samples happened
// to fall on a bright edge. Until the history holds 1/taa_blend frames it is a
// running mean, so a still view converges to the pixel's box-filtered value, as the path
// tracer's is. A pixel with no history takes its neighbours' samples too (reconstruct_current).
#import gbuffer
#import random
#import sampling

@group(2) @binding(0) var radiance: texture_2d<f32>;
@group(2) @binding(1) var previous_radiance: texture_2d<f32>;
@group(2) @binding(2) var linear_clamp: sampler;
@group(2) @binding(3) var resolved: texture_storage_2d<rgba16float, write>;

fn rgb_to_ycocg(c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b, -0.25 * c.r + 0.5 * c.g - 0.25 * c.b);
}

fn ycocg_to_rgb(c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z);
}

// Catmull-Rom's weights for the four texels about a point at fraction f past the second.
fn catmull_rom_weights(f: f32) -> vec4<f32> {
    let f2 = f * f;
    let f3 = f2 * f;
    return vec4<f32>(-0.5 * f3 + f2 - 0.5 * f, 1.5 * f3 - 2.5 * f2 + 1.0, -1.5 * f3 + 2.0 * f2 + 0.5 * f, 0.5 * f3 - 0.5 * f2);
}

// The history at a point (in pixels, centres at .5) by Catmull-Rom over the 4×4 texels about
// it less the four corners, whose weights are the smallest, in five bilinear taps (Jimenez
// 2016). At a pixel centre it returns that texel.
fn sample_history(position: vec2<f32>) -> vec3<f32> {
    let last = vec2<i32>(i32(frame.width) - 1, i32(frame.height) - 1);
    // A still view's history is the pixel itself (within a thousandth of a pixel): one load
    // instead of five taps.
    let nearest = round(position - 0.5);
    if all(abs(position - 0.5 - nearest) < vec2<f32>(1e-3)) {
        return textureLoad(previous_radiance, clamp(vec2<i32>(nearest), vec2<i32>(0), last), 0).rgb;
    }
    let size = frame_size();
    let centre = floor(position - 0.5) + 0.5;
    let f = position - centre;
    let wx = catmull_rom_weights(f.x);
    let wy = catmull_rom_weights(f.y);
    let w0 = vec2<f32>(wx.x, wy.x);
    let w12 = vec2<f32>(wx.y + wx.z, wy.y + wy.z);
    let w3 = vec2<f32>(wx.w, wy.w);
    // The middle two texels of each axis in one bilinear tap, placed by their weights.
    let t0 = (centre - 1.0) / size;
    let t12 = (centre + vec2<f32>(wx.z, wy.z) / w12) / size;
    let t3 = (centre + 2.0) / size;
    var sum = textureSampleLevel(previous_radiance, linear_clamp, vec2<f32>(t12.x, t0.y), 0.0).rgb * (w12.x * w0.y);
    sum += textureSampleLevel(previous_radiance, linear_clamp, vec2<f32>(t0.x, t12.y), 0.0).rgb * (w0.x * w12.y);
    sum += textureSampleLevel(previous_radiance, linear_clamp, t12, 0.0).rgb * (w12.x * w12.y);
    sum += textureSampleLevel(previous_radiance, linear_clamp, vec2<f32>(t3.x, t12.y), 0.0).rgb * (w3.x * w12.y);
    sum += textureSampleLevel(previous_radiance, linear_clamp, vec2<f32>(t12.x, t3.y), 0.0).rgb * (w12.x * w3.y);
    let weight = w12.x * w0.y + w0.x * w12.y + w12.x * w12.y + w3.x * w12.y + w12.x * w3.y;
    // Catmull-Rom overshoots at edges; negative radiance would poison the history.
    return max(sum / weight, vec3<f32>(0.0));
}

// The largest finite f16.
const F16_MAX: f32 = 65504.0;

// `v` rounded at random to one of the two f16 values about it so that the mean is v (the one
// farther from zero with probability equal to |v|'s share of the way to it from the nearer
// one), so that the stored history is right on average: nearest
// rounding drops every step of a long running mean under half of f16's last bit, and the
// history stalls short of the light. The result is exactly an f16, so the texture's own
// rounding (nearest or towards zero, by adapter) leaves it alone. `u` is uniform in [0, 1).
fn round_to_f16_stochastically(v: f32, u: f32) -> f32 {
    // A NaN or an infinity stays one, for `irradiant soak` and the tests to find (a bit test:
    // compilers may fold v != v away); finite light past f16's range saturates below.
    let bits = bitcast<u32>(v);
    if (bits & 0x7fffffffu) >= 0x7f800000u {
        return v;
    }
    let x = min(abs(v), F16_MAX);
    // f16's spacing where x lies, 2^(exponent − 10) (2^−24 among its subnormals), and its
    // inverse: powers of two, so that scaling by them is exact (a division need not be).
    let exponent = max(i32((bitcast<u32>(x) >> 23u) & 0xffu) - 127, -14) - 10;
    let spacing = bitcast<f32>(u32(exponent + 127) << 23u);
    let inverse = bitcast<f32>(u32(127 - exponent) << 23u);
    // Below 65504 = 2047 · 32 the sum stays under 2048, so the floor never passes f16's largest.
    return select(1.0, -1.0, v < 0.0) * floor(x * inverse + u) * spacing;
}

fn store_resolved(pixel: vec2<i32>, c: vec3<f32>) {
    // One hash, ten bits a channel: a stream apart from the direct light's samples of the same
    // pixel and frame. Ten bits bias the rounding by at most 2^−11 of f16's last bit.
    let bits = pcg_hash((u32(pixel.y) * frame.width + u32(pixel.x)) ^ pcg_hash(frame.frame_index ^ 0x7f4a7c15u));
    let u = (vec3<f32>(vec3<u32>(bits, bits >> 10u, bits >> 20u) & vec3<u32>(1023u)) + 0.5) / 1024.0;
    let rounded = vec3<f32>(
        round_to_f16_stochastically(c.r, u.x),
        round_to_f16_stochastically(c.g, u.y),
        round_to_f16_stochastically(c.b, u.z),
    );
    textureStore(resolved, pixel, vec4<f32>(rounded, 1.0));
}

// Moves `history` towards the box centre until it lies inside the box.
fn clip_to_box(history: vec3<f32>, centre: vec3<f32>, extent: vec3<f32>) -> vec3<f32> {
    let d = history - centre;
    let units = abs(d) / max(extent, vec3<f32>(1e-6));
    let m = max(units.x, max(units.y, units.z));
    return select(history, centre + d / m, m > 1.0);
}

// The history clipped to the current frame's 3×3 neighbourhood about `pixel`: its mean ±
// taa_clip_sigma standard deviations in YCoCg.
fn clip_to_neighbourhood(history: vec3<f32>, pixel: vec2<i32>) -> vec3<f32> {
    let last = vec2<i32>(i32(frame.width) - 1, i32(frame.height) - 1);
    var m1 = vec3<f32>(0.0);
    var m2 = vec3<f32>(0.0);
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let c = rgb_to_ycocg(textureLoad(radiance, clamp(pixel + vec2<i32>(dx, dy), vec2<i32>(0), last), 0).rgb);
            m1 += c;
            m2 += c * c;
        }
    }
    let mean = m1 / 9.0;
    let sigma = sqrt(max(m2 / 9.0 - mean * mean, vec3<f32>(0.0)));
    return ycocg_to_rgb(clip_to_box(rgb_to_ycocg(history), mean, frame.taa_clip_sigma * sigma));
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let pixel = vec2<i32>(id.xy);
    let current = textureLoad(radiance, pixel, 0).rgb;
    if frame.taa_blend >= 1.0 {
        store_resolved(pixel, current);
        return;
    }
    if frame.history_frames == 0u {
        // Nothing to blend with yet.
        store_resolved(pixel, reconstruct_current(pixel, current));
        return;
    }
    let previous = vec2<f32>(id.xy) + 0.5 + gbuffer_motion_at(id.xy);
    // Written so that a NaN motion vector counts as off screen too.
    if !(all(previous >= vec2<f32>(0.0)) && all(previous <= frame_size())) {
        // Off screen last frame: nothing to blend with.
        store_resolved(pixel, reconstruct_current(pixel, current));
        return;
    }
    var history = sample_history(previous);
    if frame.accumulated_frames == 0u {
        history = clip_to_neighbourhood(history, pixel);
    }
    let alpha = max(frame.taa_blend, 1.0 / (f32(frame.history_frames) + 1.0));
    store_resolved(pixel, mix(history, current, alpha));
}

// The frame's own samples reconstructed at the pixel's centre (`current` is its own), for a
// pixel with no history: the first frame after a cut or a reset, and a pixel whose
// reprojection falls off screen (a disoccluded pixel on screen takes its clipped history).
//
// Its brightness: each of the 3×3 neighbours' samples lies at its pixel's centre plus this
// frame's jitter and weighs by a Gaussian of its distance, exp(−2.29 d²), the fit to a
// Blackman-Harris filter 3.3 pixels wide of Karis's TAA ("High Quality Temporal
// Supersampling", SIGGRAPH 2014). One sample a pixel taken as the pixel's value aliases edges
// and keeps every pixel's noise; the running mean's later frames do the pixel's box filter over
// time, where this one frame holds a share 1/n.
//
// Its colour, in a frame with no history under emitters (COLOUR_FROM_SURFACE, a variant that
// frame/mod.rs runs for such a frame only, so that the other frames' TAA keeps its registers):
// each sample of emitter light is one emitter's, so under emitters of many colours (stained
// glass) one frame's pixels each take one colour, which no 3×3 filter evens out. The colour
// comes from the light on the pixel's surface over a wider footprint (surface_light), and only
// the colour: brightness keeps its edges and shadows. A pixel that reprojects off screen in
// a frame with history (a moving view's edge, a view turned by set_camera rather than cut_to)
// keeps the 3×3 filter's colour; the frames after it average its colour out.
//
// Only reflected light is filtered: a surface's own emission and the sky stay the pixel's own
// sample, since spread, an emitter's pixel lends each neighbour about a tenth of its radiance (a
// halo about every lamp). So does a pixel whose emission f16 could not hold.
fn reconstruct_current(pixel: vec2<i32>, current: vec3<f32>) -> vec3<f32> {
    let own = reflected_light(pixel);
    if own.w == 0.0 {
        return current;
    }
    let p = vec2<u32>(pixel);
    let x = gbuffer_position(p, gbuffer_depth_at(p));
    let n = gbuffer_normal_at(p);
    let last = vec2<i32>(i32(frame.width) - 1, i32(frame.height) - 1);
    var sharp = vec3<f32>(0.0);
    // The same filter with each neighbour on the pixel's surface lending its albedo (under the
    // surface's light, multiplied in below) and the others their sample.
    var albedo_part = vec3<f32>(0.0);
    var others_part = vec3<f32>(0.0);
    var weight_sum = 0.0;
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let q = pixel + vec2<i32>(dx, dy);
            if any(q < vec2<i32>(0)) || any(q > last) {
                continue;
            }
            let seen = reflected_light(q);
            let d = vec2<f32>(f32(dx), f32(dy)) + frame.jitter;
            let w = seen.w * exp(-2.29 * dot(d, d));
            if w == 0.0 {
                // The sky, or an emission f16 could not hold: 0 × ∞ would poison the sums.
                continue;
            }
            sharp += w * seen.rgb;
            weight_sum += w;
            if COLOUR_FROM_SURFACE != 0u {
                var agree = 1.0;
                if dx != 0 || dy != 0 {
                    agree = surface_agreement(x, n, vec2<u32>(q), gbuffer_depth_at(vec2<u32>(q)));
                }
                albedo_part += w * agree * (albedo_at(q) + DEMODULATE_FLOOR);
                others_part += w * (1.0 - agree) * seen.rgb;
            }
        }
    }
    // The pixel's own sample is among them, at a weight of at least exp(−2.29 / 2).
    sharp /= weight_sum;
    if COLOUR_FROM_SURFACE == 0u {
        return current - own.rgb + sharp;
    }
    // Never below zero, where a neighbour's radiance less its emission (rounded apart) dips
    // under it: a negative channel over a small brightness would be scaled without bound.
    let coloured = max((albedo_part * surface_light(pixel, x, n) + others_part) / weight_sum, vec3<f32>(0.0));
    let brightness = luminance(coloured);
    if brightness <= 0.0 {
        return current - own.rgb + sharp;
    }
    return current - own.rgb + coloured * (luminance(sharp) / brightness);
}

// A floor under the albedo the light is divided by: a black surface's light (specular only)
// is carried at this albedo and multiplied back by the same.
const DEMODULATE_FLOOR: f32 = 0.02;
// The footprint over which the first frame's colour is taken: taps every CHROMA_STRIDE pixels,
// CHROMA_TAPS each way from the pixel, weighed by a Gaussian of CHROMA_SIGMA pixels. Colour
// is what the eye resolves least.
const CHROMA_TAPS: i32 = 3;
const CHROMA_STRIDE: i32 = 3;
const CHROMA_SIGMA: f32 = 8.0;

// The light arriving at the pixel's surface: the reflected light of the neighbours on that
// surface over their albedo, as a ratio of the two sums, so that a dark neighbour whose light
// is mostly its specular highlight lends it at its albedo's weight rather than 1/floor times
// over. The pixel's own tap is always among them (weight 1), so the albedo sum is at least
// the floor.
fn surface_light(pixel: vec2<i32>, x: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let last = vec2<i32>(i32(frame.width) - 1, i32(frame.height) - 1);
    var light = vec3<f32>(0.0);
    var albedo = vec3<f32>(0.0);
    for (var ty = -CHROMA_TAPS; ty <= CHROMA_TAPS; ty++) {
        for (var tx = -CHROMA_TAPS; tx <= CHROMA_TAPS; tx++) {
            let q = pixel + vec2<i32>(tx, ty) * CHROMA_STRIDE;
            if any(q < vec2<i32>(0)) || any(q > last) {
                continue;
            }
            let seen = reflected_light(q);
            if seen.w == 0.0 {
                continue;
            }
            let d = vec2<f32>(f32(tx), f32(ty)) * f32(CHROMA_STRIDE);
            var w = exp(-dot(d, d) / (2.0 * CHROMA_SIGMA * CHROMA_SIGMA));
            if tx != 0 || ty != 0 {
                w *= surface_agreement(x, n, vec2<u32>(q), gbuffer_depth_at(vec2<u32>(q)));
            }
            if w == 0.0 {
                continue;
            }
            light += w * max(seen.rgb, vec3<f32>(0.0));
            albedo += w * (albedo_at(q) + DEMODULATE_FLOOR);
        }
    }
    return light / albedo;
}

fn albedo_at(pixel: vec2<i32>) -> vec3<f32> {
    return textureLoad(gbuffer_albedo, vec2<u32>(pixel), 0).rgb;
}

// The light the pixel's surface reflects (its radiance less its emission), w 1; w 0 where the
// sample is the sky or its emission passes f16's largest value (the G-buffer then holds an
// infinity, and radiance − emission would be NaN).
fn reflected_light(pixel: vec2<i32>) -> vec4<f32> {
    let p = vec2<u32>(pixel);
    let emission = textureLoad(gbuffer_emission, p, 0).rgb;
    if gbuffer_depth_at(p) < 0.0 || !all(emission <= vec3<f32>(F16_MAX)) {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(textureLoad(radiance, pixel, 0).rgb - emission, 1.0);
}
