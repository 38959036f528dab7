// ddgi: the irradiance query at any point of the volume: the 8-probe cage, trilinear (extrapolated
// just past the outermost probes) × smooth backface (wrap) × Chebyshev visibility × low-weight
// crush × `tied_probe_weight` for tied probes, with the self-shadow bias, normalised. Shared by
// the probe rays' shading (ddgi/shade) and the camera (ddgi/resolve).
#import ddgi_probes

@group(2) @binding(0) var<uniform> volume: GpuDdgiVolume;
// Texture copies of the atlases (DdgiResources::irradiance_texture): irradiance rgb
// (value^(1/gamma)) as rgba16float, sampled bilinearly; (mean distance, mean squared distance)
// as rg32float, gathered and blended here, since f32 textures do not filter everywhere.
@group(3) @binding(0) var irradiance_texture: texture_2d<f32>;
@group(3) @binding(1) var distance_texture: texture_2d<f32>;
@group(3) @binding(2) var atlas_bilinear: sampler;
@group(3) @binding(3) var atlas_gather: sampler;

// `uv`: the direction's place in a tile (tile_uv).
fn sample_irradiance_encoded(cell: vec2<u32>, uv: vec2<f32>) -> vec3<f32> {
    let c = atlas_tile_coord_at(cell, volume.irradiance_texels, uv);
    let size = vec2<f32>(textureDimensions(irradiance_texture));
    return textureSampleLevel(irradiance_texture, atlas_bilinear, (c + 0.5) / size, 0.0).rgb;
}

fn sample_distance(cell: vec2<u32>, d: vec3<f32>) -> vec2<f32> {
    let c = atlas_tile_coord(cell, volume.distance_texels, d);
    let c0 = floor(c);
    let f = c - c0;
    // Gathering at the corner between the footprint's four texels returns them as
    // (bottom-left, bottom-right, top-right, top-left).
    let corner = (c0 + 1.0) / vec2<f32>(textureDimensions(distance_texture));
    let mean = textureGather(0, distance_texture, atlas_gather, corner);
    let square = textureGather(1, distance_texture, atlas_gather, corner);
    let top = mix(vec2<f32>(mean.w, square.w), vec2<f32>(mean.z, square.z), f.x);
    let bottom = mix(vec2<f32>(mean.x, square.x), vec2<f32>(mean.y, square.y), f.x);
    return mix(top, bottom, f.y);
}

// The mean distance to the first surface in direction d, from the nearest texel alone: a cheap
// look for whether a probe has a surface close by that way.
fn nearest_mean_distance(cell: vec2<u32>, uv: vec2<f32>) -> f32 {
    let c = atlas_tile_coord_at(cell, volume.distance_texels, uv);
    return textureLoad(distance_texture, vec2<i32>(round(c)), 0).x;
}

// What the probes hold for a point.
struct ProbeRead {
    // Cosine-weighted mean radiance arriving around the normal (irradiance / π): a Lambertian
    // surface of albedo ρ reflects ρ times this.
    irradiance: vec3<f32>,
    // The share of the cage's trilinear weight whose probes see the point (Chebyshev): 1 in
    // open space, the near side's share at a wall between two layers, near 0 in a slit's
    // reveals, whose irradiance then comes from probes that stand in other light.
    seen: f32,
}

// The probes' light at p around normal n; `wo` points from p towards the viewer.
fn ddgi_irradiance(p: vec3<f32>, n: vec3<f32>, wo: vec3<f32>) -> ProbeRead {
    return ddgi_irradiance_along(p, n, n, wo);
}

// ddgi_irradiance seen from a viewer `viewer_distance` away along `wo` (the final gather's
// rays, which start on a surface): the bias towards the viewer goes at most half that far, so
// that a hit next to the ray's own surface is not moved through it (a 10 cm wall lit on its
// other side read bright along its seams).
fn ddgi_irradiance_seen_from(p: vec3<f32>, n: vec3<f32>, wo: vec3<f32>, viewer_distance: f32) -> ProbeRead {
    let scale = volume.spacing * (0.75 * volume.self_shadow_bias);
    var view_bias = wo * 0.8 * scale;
    let view_length = length(view_bias);
    if view_length > 0.5 * viewer_distance {
        view_bias *= 0.5 * viewer_distance / view_length;
    }
    return irradiance_at_biased(p, n, p + n * 0.2 * scale + view_bias);
}

// ddgi_irradiance read around `lookup` instead of the normal, with the cage's weights (its
// backface wrap, visibility and bias) still those of the surface at p with normal n: the probes'
// light arriving around a bent normal (ssil+ddgi's fill of what the screen does not cover).
fn ddgi_irradiance_along(p: vec3<f32>, n: vec3<f32>, lookup: vec3<f32>, wo: vec3<f32>) -> ProbeRead {
    // 003's bias scales with the smallest spacing; here each axis with its own, so that on a
    // grid of tall cells (Sibenik's 4 m layers) the bias is the same share of the cell that
    // the visibility test has to reach across along that axis.
    let bias = (n * 0.2 + wo * 0.8) * volume.spacing * (0.75 * volume.self_shadow_bias);
    return irradiance_along_biased(p, n, lookup, p + bias);
}

// The query at p around n, its cage, weights and visibility taken at `biased`.
fn irradiance_at_biased(p: vec3<f32>, n: vec3<f32>, biased: vec3<f32>) -> ProbeRead {
    return irradiance_along_biased(p, n, n, biased);
}

// The query at p read around `lookup`, its cage, weights and visibility taken for normal n at
// `biased`.
fn irradiance_along_biased(p: vec3<f32>, n: vec3<f32>, lookup: vec3<f32>, biased: vec3<f32>) -> ProbeRead {
    let max_base = vec3<i32>(volume.counts) - vec3<i32>(2);
    let grid = (biased - volume.origin) / volume.spacing;
    let base = clamp(vec3<i32>(floor(grid)), vec3<i32>(0), max(max_base, vec3<i32>(0)));
    let alpha = saturate(grid - vec3<f32>(base));
    // Past the outermost probes (a wall beyond the last layer) the clamped cage reads the last
    // layer's value, darker than the wall's light; the same cage also extrapolates the last two
    // layers' trend up to `extrapolation` cells out. Its trilinear weights go negative there,
    // so it is kept only where visibility leaves most of its weight standing.
    let alpha_out = clamp(grid - vec3<f32>(base), vec3<f32>(-volume.extrapolation), vec3<f32>(1.0 + volume.extrapolation));
    // Inside the grid both cages are one: only points past it pay for the second.
    let outside = any(alpha_out != alpha);
    // Half of the gamma curve is decoded before blending probes and half after, so that the
    // probes blend in a perceptual (gamma 2) space (003, Listing 2).
    let half_gamma = volume.irradiance_gamma * 0.5;
    let n_uv = tile_uv(n);
    let lookup_uv = tile_uv(lookup);
    var sum = vec3<f32>(0.0);
    var weight_sum = 0.0;
    var sum_out = vec3<f32>(0.0);
    var weight_sum_out = 0.0;
    var trend_broken = false;
    var seen = 0.0;
    for (var i = 0u; i < 8u; i++) {
        let offset = vec3<u32>(i & 1u, (i >> 1u) & 1u, (i >> 2u) & 1u);
        let coord = min(vec3<u32>(base) + offset, volume.counts - 1u);
        let probe = probe_index(coord);
        if !probe_shades(probe) {
            continue;
        }
        let probe_pos = probe_position_at(coord, probe);
        let cell = atlas_tile_cell(probe, volume.probes_per_row);
        var w = 1.0;
        if (volume.weights & WEIGHT_BACKFACE) != 0u {
            // Smooth backface: wrap shading of the direction to the probe.
            let to_probe = normalize(probe_pos - p);
            let wrap = (dot(to_probe, n) + 1.0) * 0.5;
            w *= wrap * wrap + 0.2;
        }
        var visibility = 1.0;
        if (volume.weights & WEIGHT_CHEBYSHEV) != 0u {
            let probe_to_point = biased - probe_pos;
            let r = length(probe_to_point);
            let moments = sample_distance(cell, probe_to_point / max(r, 1e-6));
            if r > moments.x {
                let variance = abs(moments.y - moments.x * moments.x);
                let d = r - moments.x;
                let chebyshev = variance / (variance + d * d);
                visibility = max(chebyshev * chebyshev * chebyshev, 0.0);
            }
        }
        w *= visibility;
        w = max(w, 1e-6);
        // Crush tiny weights (the "log perception" weight): light leaks read as far brighter
        // than their weight suggests in the dark.
        let crush = 0.2;
        if w < crush {
            w *= w * w / (crush * crush);
        }
        if probe_is_tied(probe) {
            w *= volume.tied_probe_weight;
        }
        let w_visible = w;
        let trilinear = mix(1.0 - alpha, alpha, vec3<f32>(offset));
        let cage_weight = trilinear.x * trilinear.y * trilinear.z;
        seen += visibility * cage_weight;
        w *= cage_weight;
        let encoded = sample_irradiance_encoded(cell, lookup_uv);
        // Gamma 2 (light-field probes' static atlases) needs no decode before the blend.
        var blendable = max(encoded, vec3<f32>(0.0));
        if half_gamma != 1.0 {
            blendable = pow(blendable, vec3<f32>(half_gamma));
        }
        sum += w * blendable;
        weight_sum += w;
        if outside {
            let trilinear_out = mix(1.0 - alpha_out, alpha_out, vec3<f32>(offset));
            let w_out = w_visible * trilinear_out.x * trilinear_out.y * trilinear_out.z;
            // A far-layer probe with a surface nearer than the smallest probe spacing along n
            // (one relocated under a table top) reads a pocket, not the field's trend: the
            // trend is not extrapolated.
            if !trend_broken && any(trilinear_out < vec3<f32>(0.0)) && nearest_mean_distance(cell, n_uv) < volume.min_spacing {
                trend_broken = true;
            }
            sum_out += w_out * blendable;
            weight_sum_out += w_out;
        }
    }
    var blended = sum / max(weight_sum, 1e-9);
    if outside && !trend_broken && weight_sum_out > 0.5 * weight_sum {
        // At most twice or half the clamped value (√2 in this gamma-2 space).
        let extrapolated = sum_out / weight_sum_out;
        blended = clamp(extrapolated, blended * 0.70710678, blended * 1.41421356);
    }
    return ProbeRead(blended * blended, seen);
}
