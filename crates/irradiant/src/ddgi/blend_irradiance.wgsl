// ddgi/blend_irradiance: one workgroup a probe. Each interior texel takes the cosine-weighted
// mean of the radiance its probe's rays brought back this frame and blends it into the old
// value with hysteresis, lowered per texel where the light changed a lot (003, §4.3). The
// running value lives in irradiance_history, in f32 and linear light; the atlas the query
// samples gets it perceptually encoded (value^(1/gamma)) in f16. A second running value, the
// bounce copy, blends the same samples at bounce_hysteresis into irradiance_bounce_atlas, which
// probe rays read at their hits: the next bounce then follows within a few frames instead of
// waiting on the slow value (in a white room the paper's single atlas took 170 frames a time
// constant to bring multi-bounce light in; docs/ddgi.md). Blending the f16 atlas into
// itself, as before, lost every update smaller than half its rounding step: texels stalled
// below their target and crept up over thousands of frames (two-rooms 7 % dark after 10 000
// frames at gamma 5 and hysteresis 0.97, 20 % at 0.99; docs/ddgi.md). Which rays weigh in, and
// how much, comes from ddgi/blend_weights. The workgroup then fills its tile's border too
// (probe_atlas's border_source), so bilinear lookups need no separate pass.
#import ddgi_volume
#import ddgi_rays
#import ddgi_states
#import ddgi_active

@group(2) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(2) @binding(6) var<storage, read> samples: array<GpuDdgiRaySample>;
@group(2) @binding(15) var<storage, read> probe_states: array<u32>;
@group(2) @binding(18) var<storage, read> blend_weights: array<GpuDdgiBlendWeight>;
@group(2) @binding(7) var<storage, read_write> irradiance_atlas: array<vec2<u32>>;
// A probe's interior texels in row order, probe after probe (rgb; a spare lane).
@group(2) @binding(19) var<storage, read_write> irradiance_history: array<vec4<f32>>;
// Packed like irradiance_atlas. The bounce copy keeps its running value here, in f16: at its
// low hysteresis an update stalls only within 0.1 % of its target (0.6 % at gamma 5), and
// it only feeds the next bounce — no f32 history to read and write.
@group(2) @binding(20) var<storage, read_write> irradiance_bounce_atlas: array<vec2<u32>>;

// BLEND_THREADS (threads a workgroup), TILE_TEXELS (texels of a tile, border included) and
// BLEND_CHUNK (rays held in workgroup memory at once) come from Ddgi::new.
// BLEND_SPLIT threads share each tile texel, each summing every BLEND_SPLIT-th of its
// entries: small tiles (irradiance: 8×8) still fill the workgroup, and each thread's chain
// of dependent loads is that much shorter.
const SLOT_THREADS: u32 = BLEND_THREADS / BLEND_SPLIT;
const SLOTS: u32 = (TILE_TEXELS + SLOT_THREADS - 1u) / SLOT_THREADS;
var<workgroup> cache_radiance: array<vec4<f32>, BLEND_CHUNK>;
var<workgroup> partial: array<vec4<f32>, BLEND_THREADS>;
var<workgroup> tile_values: array<vec2<u32>, TILE_TEXELS>;
var<workgroup> tile_bounce: array<vec2<u32>, TILE_TEXELS>;

// How much light changed from `before` to `after`, as 003 §4.3 judges it: on perceptually encoded
// values (value^(1/5)), relative to the larger — a change the eye would see.
fn encoded_change(after: vec3<f32>, before: vec3<f32>) -> f32 {
    let gamma_inverse = vec3<f32>(1.0 / CHANGE_GAMMA);
    let a = pow(max(after, vec3<f32>(0.0)), gamma_inverse);
    let b = pow(max(before, vec3<f32>(0.0)), gamma_inverse);
    let delta = abs(a - b);
    let larger = max(max(max(a.x, a.y), a.z), max(max(b.x, b.y), b.z));
    return max(delta.x, max(delta.y, delta.z)) / max(larger, 1e-4);
}

fn decode(packed: vec2<u32>) -> vec3<f32> {
    let e = vec3<f32>(unpack2x16float(packed.x), unpack2x16float(packed.y).x);
    return pow(max(e, vec3<f32>(0.0)), vec3<f32>(volume.irradiance_gamma));
}

fn encode(linear: vec3<f32>) -> vec2<u32> {
    let e = pow(linear, vec3<f32>(1.0 / volume.irradiance_gamma));
    return vec2<u32>(pack2x16float(e.xy), pack2x16float(vec2<f32>(e.z, 0.0)));
}

@compute @workgroup_size(BLEND_THREADS, 1, 1)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) li: u32) {
    // Only probes that update are listed; the state decides, uniformly per workgroup, where
    // the two disagree (a state written since the list was made): the others keep their texels.
    let probe = listed_probe(group);
    if probe == NOT_LISTED {
        return;
    }
    let state = probe_states[probe];
    if !probe_traces(state, volume.every_probe_updates) {
        return;
    }
    let texels = volume.irradiance_texels;
    let tile = texels + 2u;
    let texel_count = texels * texels;
    let m = volume.rays_per_probe;
    let origin = tile_origin(probe, tile);
    let width = atlas_width(tile);
    // Slots: each group of BLEND_SPLIT threads takes tile texels lane, lane + SLOT_THREADS, …
    // (a uniform count, since the loop holds barriers).
    let part = li / SLOT_THREADS;
    for (var slot = 0u; slot < SLOTS; slot++) {
        let i = slot * SLOT_THREADS + li % SLOT_THREADS;
        let x = i % tile;
        let y = i / tile;
        let interior = i < tile * tile && x >= 1u && y >= 1u && x <= texels && y <= texels;
        let t = select(0u, (y - 1u) * texels + x - 1u, interior);
        let header = blend_weights[t];
        let count = select(0u, header.ray, interior);
        var sum = vec3<f32>(0.0);
        var cursor = part;
        var entry = blend_weights[texel_count + min(part, max(count, 1u) - 1u) * texel_count + t];
        for (var base = 0u; base < m; base += BLEND_CHUNK) {
            workgroupBarrier();
            for (var r = li; r < BLEND_CHUNK; r += BLEND_THREADS) {
                if base + r < m {
                    cache_radiance[r] = vec4<f32>(samples[probe * m + base + r].radiance, 0.0);
                }
            }
            workgroupBarrier();
            if m <= BLEND_CHUNK {
                // One chunk holds every ray: a counted loop whose loads do not wait on each other.
                for (var k = part; k < count; k += BLEND_SPLIT) {
                    let e = blend_weights[texel_count + k * texel_count + t];
                    sum += e.weight * cache_radiance[e.ray].rgb;
                }
            } else {
                // The texel's entries are in ray order: take those in this chunk.
                loop {
                    if cursor >= count || entry.ray >= base + BLEND_CHUNK {
                        break;
                    }
                    sum += entry.weight * cache_radiance[entry.ray - base].rgb;
                    cursor += BLEND_SPLIT;
                    entry = blend_weights[texel_count + min(cursor, count - 1u) * texel_count + t];
                }
            }
        }
        if BLEND_SPLIT > 1u {
            partial[li] = vec4<f32>(sum, 0.0);
            workgroupBarrier();
            for (var p = 1u; p < BLEND_SPLIT; p++) {
                sum += partial[p * SLOT_THREADS + li % SLOT_THREADS].xyz;
            }
        }
        if interior && part == 0u {
            let value = select(vec3<f32>(0.0), sum / header.weight, header.weight > 0.0);
            let history_index = probe * texel_count + t;
            let index = (origin.y + y) * width + origin.x + x;
            let old = irradiance_history[history_index].rgb;
            let bounce_old = decode(irradiance_bounce_atlas[index]);
            let startup = samples_held(state);
            var hysteresis = startup_hysteresis(volume.irradiance_hysteresis, startup);
            if volume.convergence_heuristics != 0u && hysteresis > 0.0 {
                if encoded_change(value, old) > 0.8 {
                    // The distribution the probe samples has changed completely.
                    hysteresis = 0.0;
                } else if encoded_change(bounce_old, old) > 0.25 {
                    // A lasting change, judged on the bounce copy (the last frames' fast
                    // average), not on this frame's sample: a decision that depends on the
                    // sample it then weighs more favours the samples that cross the threshold,
                    // and noise is skewed — a few rays that find a bright emitter — so the
                    // paper's per-sample rule read the glowing box 12 % bright (docs/ddgi.md).
                    hysteresis = max(0.0, hysteresis - 0.15);
                }
            }
            // The average is taken in linear light: an average of encoded noisy samples decodes
            // darker than their mean (Jensen's inequality).
            let linear = max(mix(value, old, hysteresis), vec3<f32>(0.0));
            irradiance_history[history_index] = vec4<f32>(linear, 0.0);
            // The bounce copy never lags the value: what lowered its hysteresis lowers this too.
            let bounce_hysteresis = min(startup_hysteresis(volume.bounce_hysteresis, startup), hysteresis);
            let bounce = max(mix(value, bounce_old, bounce_hysteresis), vec3<f32>(0.0));
            let packed = encode(linear);
            let packed_bounce = encode(bounce);
            irradiance_atlas[index] = packed;
            irradiance_bounce_atlas[index] = packed_bounce;
            tile_values[i] = packed;
            tile_bounce[i] = packed_bounce;
        }
    }
    workgroupBarrier();
    for (var i = li; i < tile * tile; i += BLEND_THREADS) {
        let x = i % tile;
        let y = i / tile;
        if (x >= 1u && y >= 1u && x <= texels && y <= texels) {
            continue;
        }
        let source = border_source(x, y, texels);
        let index = (origin.y + y) * width + origin.x + x;
        irradiance_atlas[index] = tile_values[source.y * tile + source.x];
        irradiance_bounce_atlas[index] = tile_bounce[source.y * tile + source.x];
    }
}
