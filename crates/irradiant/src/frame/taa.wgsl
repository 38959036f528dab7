// frame/taa: temporal anti-aliasing. The primary rays were jittered inside each pixel; this
// pass blends the frame into the history reprojected along the motion vectors (Catmull-Rom
// resampling), after clipping the history to the current frame's 3×3 neighbourhood (mean ±
// taa_clip_sigma standard deviations in YCoCg: Salvi 2016) so that disoccluded or relit
// pixels do not ghost. While neither the view nor the scene changes (the frame's running
// means keep accumulating) the history is not clipped: a still view needs no protection from
// ghosts, and its average over the pixel should not depend on which jittered samples happened
// to fall on a bright edge. Until the history holds 1/taa_blend frames it is a
// running mean, so a still view converges to the pixel's box-filtered value, as the path
// tracer's is.
#import gbuffer

@group(2) @binding(0) var radiance: texture_2d<f32>;
@group(2) @binding(1) var previous_radiance: texture_2d<f32>;
@group(2) @binding(2) var resolved: texture_storage_2d<rgba32float, write>;

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
// it less the four corners, whose weights are the smallest (Jimenez 2016 takes the same twelve
// in five bilinear taps; the history is f32, which not every adapter filters, so it is loaded
// texel by texel). At a pixel centre it returns that texel.
fn sample_history(position: vec2<f32>) -> vec3<f32> {
    let last = vec2<i32>(i32(frame.width) - 1, i32(frame.height) - 1);
    // A still view's history is the pixel itself (within a thousandth of a pixel): one load
    // instead of twelve.
    let nearest = round(position - 0.5);
    if all(abs(position - 0.5 - nearest) < vec2<f32>(1e-3)) {
        return textureLoad(previous_radiance, clamp(vec2<i32>(nearest), vec2<i32>(0), last), 0).rgb;
    }
    let corner = floor(position - 0.5);
    let f = position - 0.5 - corner;
    let wx = catmull_rom_weights(f.x);
    let wy = catmull_rom_weights(f.y);
    var sum = vec3<f32>(0.0);
    var weight = 0.0;
    for (var j = 0; j < 4; j++) {
        for (var i = 0; i < 4; i++) {
            if (i == 0 || i == 3) && (j == 0 || j == 3) {
                continue;
            }
            let w = wx[i] * wy[j];
            let texel = clamp(vec2<i32>(corner) + vec2<i32>(i - 1, j - 1), vec2<i32>(0), last);
            sum += textureLoad(previous_radiance, texel, 0).rgb * w;
            weight += w;
        }
    }
    // Catmull-Rom overshoots at edges; negative radiance would poison the history.
    return max(sum / weight, vec3<f32>(0.0));
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
    if frame.taa_blend >= 1.0 || frame.history_frames == 0u {
        textureStore(resolved, pixel, vec4<f32>(current, 1.0));
        return;
    }
    let previous = vec2<f32>(id.xy) + 0.5 + gbuffer_motion_at(id.xy);
    let size = frame_size();
    var alpha = max(frame.taa_blend, 1.0 / (f32(frame.history_frames) + 1.0));
    var history = current;
    if all(previous >= vec2<f32>(0.0)) && all(previous <= size) {
        history = sample_history(previous);
        if frame.accumulated_frames == 0u {
            history = clip_to_neighbourhood(history, pixel);
        }
    } else {
        // Off screen last frame: nothing to blend with.
        alpha = 1.0;
    }
    textureStore(resolved, pixel, vec4<f32>(mix(history, current, alpha), 1.0));
}
