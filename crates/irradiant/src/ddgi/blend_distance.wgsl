// ddgi/blend_distance: one workgroup a probe. Each interior texel takes the
// cosine^exponent-weighted mean of hit distance and of its square (the moments that Chebyshev
// visibility needs) and blends them with hysteresis. Which rays weigh in, and how much, comes
// from ddgi/blend_weights: with exponent 50 about a fifth of them. The workgroup then fills
// its tile's border too (probe_atlas's border_source).
#import ddgi_volume
#import ddgi_rays
#import ddgi_states
#import ddgi_active

@group(2) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(2) @binding(6) var<storage, read> samples: array<GpuDdgiRaySample>;
@group(2) @binding(15) var<storage, read> probe_states: array<u32>;
@group(2) @binding(18) var<storage, read> blend_weights: array<GpuDdgiBlendWeight>;
@group(2) @binding(8) var<storage, read_write> distance_atlas: array<vec2<f32>>;

// BLEND_THREADS, TILE_TEXELS and BLEND_CHUNK: see ddgi/blend_irradiance.
// BLEND_SPLIT threads share each tile texel, each summing every BLEND_SPLIT-th of its
// entries: small tiles (irradiance: 8×8) still fill the workgroup, and each thread's chain
// of dependent loads is that much shorter.
const SLOT_THREADS: u32 = BLEND_THREADS / BLEND_SPLIT;
const SLOTS: u32 = (TILE_TEXELS + SLOT_THREADS - 1u) / SLOT_THREADS;
// (distance, distance²) of each ray of the chunk.
var<workgroup> cache_moments: array<vec2<f32>, BLEND_CHUNK>;
var<workgroup> partial: array<vec4<f32>, BLEND_THREADS>;
var<workgroup> tile_values: array<vec2<f32>, TILE_TEXELS>;

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
    let texels = volume.distance_texels;
    let tile = texels + 2u;
    let texel_count = texels * texels;
    let m = volume.rays_per_probe;
    let weights_base = volume.irradiance_texels * volume.irradiance_texels * (m + 1u);
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
        let header = blend_weights[weights_base + t];
        let count = select(0u, header.ray, interior);
        var sum = vec2<f32>(0.0);
        var cursor = part;
        var entry = blend_weights[weights_base + texel_count + min(part, max(count, 1u) - 1u) * texel_count + t];
        for (var base = 0u; base < m; base += BLEND_CHUNK) {
            workgroupBarrier();
            for (var r = li; r < BLEND_CHUNK; r += BLEND_THREADS) {
                if base + r < m {
                    let d = min(abs(samples[probe * m + base + r].distance), volume.max_ray_distance);
                    cache_moments[r] = vec2<f32>(d, d * d);
                }
            }
            workgroupBarrier();
            if m <= BLEND_CHUNK {
                // One chunk holds every ray: a counted loop whose loads do not wait on each other.
                for (var k = part; k < count; k += BLEND_SPLIT) {
                    let e = blend_weights[weights_base + texel_count + k * texel_count + t];
                    sum += e.weight * cache_moments[e.ray];
                }
            } else {
                // The texel's entries are in ray order: take those in this chunk.
                loop {
                    if cursor >= count || entry.ray >= base + BLEND_CHUNK {
                        break;
                    }
                    sum += entry.weight * cache_moments[entry.ray - base];
                    cursor += BLEND_SPLIT;
                    entry = blend_weights[weights_base + texel_count + min(cursor, count - 1u) * texel_count + t];
                }
            }
        }
        if BLEND_SPLIT > 1u {
            partial[li] = vec4<f32>(sum, 0.0, 0.0);
            workgroupBarrier();
            for (var p = 1u; p < BLEND_SPLIT; p++) {
                sum += partial[p * SLOT_THREADS + li % SLOT_THREADS].xy;
            }
        }
        if interior && part == 0u {
            let index = (origin.y + y) * width + origin.x + x;
            let old = distance_atlas[index];
            var blended = old;
            // A texel no ray came near this frame keeps its old value.
            if header.weight > 0.0 || samples_held(state) == 0u {
                let value = select(vec2<f32>(volume.max_ray_distance, volume.max_ray_distance * volume.max_ray_distance), sum / header.weight, header.weight > 0.0);
                let hysteresis = startup_hysteresis(volume.distance_hysteresis, samples_held(state));
                blended = mix(value, old, hysteresis);
                distance_atlas[index] = blended;
            }
            tile_values[i] = blended;
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
        distance_atlas[(origin.y + y) * width + origin.x + x] = tile_values[source.y * tile + source.x];
    }
}
