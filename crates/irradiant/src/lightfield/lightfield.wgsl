// lightfield: world-space rays traced through light-field probes (McGuire, Mara,
// Nowrouzezahrai and Luebke 2017, §4). Each probe of a regular grid holds octahedral maps of
// what it sees: the radiance leaving the nearest surface in every direction, that surface's
// normal and its radial distance, and a min-mip of the distances (one texel a 16² block).
//
// A ray is traced through one probe at a time. Seen from the probe, the ray is a polyline on
// the octahedral map with at most four straight segments (one per octant it crosses); each is
// marched, first over the min-mip (a block whose nearest surface is farther than the ray there
// is skipped), then texel by texel. At each texel the ray's radial distance is compared with
// the stored one: reaching it within the surface's thickness, on a front face, is a hit;
// passing behind it means this probe cannot see the ray there, and another probe takes over
// from that point: first the cage probe nearest the ray's line, then i' = (i + 3) mod 8, and the
// next cage when the ray has left this one. A ray no probe resolves hits the last point seen.
//
// Storage (8 bytes a texel, as the paper's): radiance packed as R11G11B10 floats in an r32uint
// (it excludes emission: the frame's direct pass samples emitters, so the probes hold
// reflected light only); normal (octahedral, 2 × 8 bits) and distance (f16) packed in another.
#import lightfield_constants
#import ddgi_constants
#import probe_grid
#import octahedral

struct GpuLightfieldParams {
    origin: vec3<f32>,
    probe_count: u32,
    spacing: vec3<f32>,
    resolution: u32,
    counts: vec3<u32>,
    low_resolution: u32,
    min_thickness: f32,
    max_thickness: f32,
    thickness_distance: f32,
    max_probe_visits: u32,
    max_distance: f32,
    prefilter_resolution: u32,
    emitter_samples: u32,
    bounce: u32,
    algorithm: u32,
    lambert_rays: u32,
    glossy_rays: u32,
    frame: u32,
    lambert_hysteresis: f32,
    glossy_hysteresis: f32,
    history_valid: u32,
    irradiance_block: u32,
    glossy_max_roughness: f32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

@group(2) @binding(20) var<uniform> lightfield: GpuLightfieldParams;
@group(2) @binding(21) var lightfield_radiance: texture_2d_array<u32>;
@group(2) @binding(22) var lightfield_geometry: texture_2d_array<u32>;
@group(2) @binding(23) var lightfield_low: texture_2d_array<f32>;
// DDGI's probe state words (lightfield/probe_states): PROBE_OFF for probes inside geometry.
@group(2) @binding(53) var<storage, read> lightfield_probe_states: array<u32>;
// Where lightfield/relocate moved each probe from its grid position (DDGI's offsets).
@group(2) @binding(54) var<storage, read> lightfield_probe_offsets: array<vec4<f32>>;

struct LightfieldHit {
    // LF_HIT or LF_MISS
    result: u32,
    t: f32,
    probe: u32,
    texel: vec2<u32>,
    visits: u32,
}

// Far enough for any ray that starts in the scene (or at a camera near it) to leave it.
fn lf_far() -> f32 {
    return 4.0 * lightfield.max_distance;
}

fn lf_probe_position(probe: u32) -> vec3<f32> {
    let grid = lightfield.origin + vec3<f32>(grid_coord(probe, lightfield.counts)) * lightfield.spacing;
    return grid + lightfield_probe_offsets[probe].xyz;
}

// --- packing ---------------------------------------------------------------------------

// Non-negative RGB as R11G11B10 floats: f16 with the sign dropped and the mantissa rounded to
// 6 (red, green) or 5 (blue) bits.
fn pack_r11g11b10(c: vec3<f32>) -> u32 {
    let v = clamp(c, vec3<f32>(0.0), vec3<f32>(65000.0));
    let rg = pack2x16float(v.rg);
    let b = pack2x16float(vec2<f32>(v.b, 0.0));
    let r11 = min(((rg & 0xffffu) + 0x8u) >> 4u, 0x7bfu);
    let g11 = min(((rg >> 16u) + 0x8u) >> 4u, 0x7bfu);
    let b10 = min(((b & 0xffffu) + 0x10u) >> 5u, 0x3dfu);
    return r11 | (g11 << 11u) | (b10 << 22u);
}

fn unpack_r11g11b10(p: u32) -> vec3<f32> {
    let r = (p & 0x7ffu) << 4u;
    let g = ((p >> 11u) & 0x7ffu) << 4u;
    let b = ((p >> 22u) & 0x3ffu) << 5u;
    return vec3<f32>(unpack2x16float(r | (g << 16u)), unpack2x16float(b).x);
}

// A unit normal (octahedral, 8 bits an axis) and a distance (f16) in one word.
fn pack_geometry(n: vec3<f32>, distance: f32) -> u32 {
    let normal = pack4x8unorm(vec4<f32>(oct_encode(n) * 0.5 + 0.5, 0.0, 0.0)) & 0xffffu;
    let d = pack2x16float(vec2<f32>(0.0, min(distance, LF_NO_SURFACE))) & 0xffff0000u;
    return normal | d;
}

fn geometry_distance(g: u32) -> f32 {
    return unpack2x16float(g).y;
}

fn geometry_normal(g: u32) -> vec3<f32> {
    return oct_decode(unpack4x8unorm(g).xy * 2.0 - 1.0);
}

// --- one probe ----------------------------------------------------------------------------

// The map texel that direction-map coordinate uv (in [0, 1]²) falls in, at `size` texels.
fn lf_texel(uv: vec2<f32>, size: u32) -> vec2<u32> {
    return min(vec2<u32>(max(uv, vec2<f32>(0.0)) * f32(size)), vec2<u32>(size - 1u));
}

fn lf_uv(d: vec3<f32>) -> vec2<f32> {
    return oct_encode(d) * 0.5 + 0.5;
}

fn lf_direction(uv: vec2<f32>) -> vec3<f32> {
    return oct_decode(uv * 2.0 - 1.0);
}

// The distance from the probe (the origin of probe space) at which the direction v meets the
// line o + t d: s v = o + t d, so s (v × d) = o × d.
fn radial_distance(o: vec3<f32>, d: vec3<f32>, v: vec3<f32>) -> f32 {
    let c = cross(v, d);
    let denominator = dot(c, c);
    if denominator < 1e-12 {
        // v along the line: the line passes (nearly) through the probe.
        return max(dot(o, v), 0.0);
    }
    return max(dot(cross(o, d), c) / denominator, 0.0);
}

// The surface's thickness for a hit: thin head-on, thicker at grazing views and far away,
// since a texel's surface then covers a longer stretch of the ray.
fn thickness(d: vec3<f32>, w: vec3<f32>, n: vec3<f32>, t: f32) -> f32 {
    let grow = max(dot(d, w), 0.0) * (2.0 - abs(dot(d, n))) * clamp(t / lightfield.thickness_distance, 0.05, 1.0);
    return lightfield.min_thickness + (lightfield.max_thickness - lightfield.min_thickness) * grow;
}

struct SegmentState {
    t_min: f32,
    t_max: f32,
    hit_uv: vec2<f32>,
}

// The coarse march over the min-mip from uv_start towards uv_end: the first low texel whose
// nearest surface is no farther than the ray somewhere inside it (the ray's radial distance is
// convex along the line, so its largest value over a texel is at the entry or the exit).
// Returns the texel's entry and exit in `span`, or false when the whole segment stays clear.
fn coarse_march(probe: u32, o: vec3<f32>, d: vec3<f32>, uv_start: vec2<f32>, uv_end: vec2<f32>, span: ptr<function, vec4<f32>>) -> bool {
    let size = f32(lightfield.low_resolution);
    var p0 = uv_start * size;
    var p1 = uv_end * size;
    if dot(p1 - p0, p1 - p0) < 1e-4 {
        p1 += vec2<f32>(0.01);
    }
    var delta = p1 - p0;
    let permute = abs(delta.x) < abs(delta.y);
    if permute {
        p0 = p0.yx;
        p1 = p1.yx;
        delta = delta.yx;
    }
    let step_sign = select(-1.0, 1.0, delta.x >= 0.0);
    let dp = vec2<f32>(step_sign, delta.y / abs(delta.x));
    let max_length2 = dot(uv_end - uv_start, uv_end - uv_start);
    var p = p0;
    var previous = radial_distance(o, d, lf_direction(uv_start));
    for (var i = 0u; i < 2u * lightfield.low_resolution + 4u; i++) {
        if p.x * step_sign > p1.x * step_sign {
            break;
        }
        let here = select(p, p.yx, permute);
        let texel = min(vec2<u32>(max(floor(here), vec2<f32>(0.0))), vec2<u32>(lightfield.low_resolution - 1u));
        let nearest = textureLoad(lightfield_low, texel, probe, 0).r;
        // Distance along the major axis to the texel's next edge.
        let f = fract(p);
        var to_x = select(f.x, 1.0 - f.x, step_sign > 0.0);
        if to_x <= 0.0 {
            to_x = 1.0;
        }
        var k = to_x;
        if dp.y != 0.0 {
            let to_y = select(f.y, 1.0 - f.y, dp.y > 0.0);
            k = min(k, max(to_y, 1e-4) / abs(dp.y));
        }
        let leave = p + dp * k;
        var exit_uv = select(leave, leave.yx, permute) / size;
        if dot(exit_uv - uv_start, exit_uv - uv_start) > max_length2 {
            exit_uv = uv_end;
        }
        let r = radial_distance(o, d, lf_direction(exit_uv));
        if nearest < max(r, previous) {
            *span = vec4<f32>(here / size, exit_uv);
            return true;
        }
        previous = r;
        p += dp * (k + 1e-3);
    }
    return false;
}

// The fine march over the full-resolution maps between uv_start and uv_end, a texel at a time
// along the major axis: LF_HIT (state.t_max, state.hit_uv set), LF_UNKNOWN (state.t_min
// advanced to where the ray passed behind a surface) or LF_MISS.
fn fine_march(probe: u32, o: vec3<f32>, d: vec3<f32>, uv_start: vec2<f32>, uv_end: vec2<f32>, state: ptr<function, SegmentState>) -> u32 {
    let size = f32(lightfield.resolution);
    let delta = uv_end - uv_start;
    let length_uv = max(length(delta), 1e-7);
    let along = delta / length_uv;
    let step = length_uv / max(max(abs(delta.x), abs(delta.y)) * size, 1e-7);
    var dir_before = lf_direction(uv_start);
    var r_before = radial_distance(o, d, dir_before);
    var x = 0.0;
    for (var i = 0u; i < 2u * lightfield.resolution + 2u; i++) {
        if x > length_uv {
            break;
        }
        let uv_mid = uv_start + along * min(x + 0.5 * step, length_uv);
        let texel = lf_texel(uv_mid, lightfield.resolution);
        let g = textureLoad(lightfield_geometry, texel, probe, 0).r;
        let surface = geometry_distance(g);
        let uv_after = uv_start + along * min(x + step, length_uv);
        let dir_after = lf_direction(uv_after);
        let r_after = radial_distance(o, d, dir_after);
        if max(r_before, r_after) >= surface {
            let w = lf_direction(uv_mid);
            let n = geometry_normal(g);
            // Where the probe sees the surface, as a distance along the ray.
            let t_hit = dot(surface * w - o, d);
            if min(r_before, r_after) < surface + thickness(d, w, n, t_hit) && dot(n, d) < 0.0 {
                (*state).t_max = max(t_hit, (*state).t_min);
                (*state).hit_uv = uv_mid;
                return LF_HIT;
            }
            // Behind the surface (or at its back): the probe cannot see the ray from here.
            let t_before = dot(r_before * dir_before - o, d);
            (*state).t_min = max((*state).t_min, min(t_hit, t_before));
            return LF_UNKNOWN;
        }
        r_before = r_after;
        dir_before = dir_after;
        x += step;
    }
    return LF_MISS;
}

// One segment (within one octant): coarse, then fine where the coarse march stopped.
fn trace_segment(probe: u32, o: vec3<f32>, d: vec3<f32>, uv_start: vec2<f32>, uv_end: vec2<f32>, state: ptr<function, SegmentState>) -> u32 {
    var uv = uv_start;
    let texel_uv = 1.0 / f32(lightfield.resolution);
    for (var i = 0u; i < 2u * lightfield.low_resolution + 4u; i++) {
        var span: vec4<f32>;
        if !coarse_march(probe, o, d, uv, uv_end, &span) {
            return LF_MISS;
        }
        let result = fine_march(probe, o, d, span.xy, span.zw, state);
        if result != LF_MISS {
            return result;
        }
        let towards = uv_end - span.xy;
        if dot(towards, towards) < 1e-14 {
            return LF_MISS;
        }
        let direction = normalize(towards);
        if dot(direction, uv_end - span.zw) <= texel_uv {
            return LF_MISS;
        }
        uv = span.zw + direction * 0.1 * texel_uv;
    }
    return LF_UNKNOWN;
}

// The ray from `origin` along unit `d` between state.t_min and state.t_max, as one probe sees
// it: split where it crosses the probe's three axis planes, each piece marched on its octant.
fn trace_probe(probe: u32, origin: vec3<f32>, d: vec3<f32>, state: ptr<function, SegmentState>) -> u32 {
    let o = origin - lf_probe_position(probe);
    // Plane crossings, sorted; a direction parallel to a plane never crosses it.
    let safe = select(d, vec3<f32>(1e-20), abs(d) < vec3<f32>(1e-20));
    var t = -o / safe;
    t = select(t, vec3<f32>(-1.0), abs(d) < vec3<f32>(1e-20));
    let t0 = min(t.x, min(t.y, t.z));
    let t2 = max(t.x, max(t.y, t.z));
    let t1 = t.x + t.y + t.z - t0 - t2;
    let bounds = array<f32, 3>(t0, t1, t2);
    var start = (*state).t_min;
    for (var i = 0u; i < 4u; i++) {
        let end = select((*state).t_max, clamp(bounds[min(i, 2u)], (*state).t_min, (*state).t_max), i < 3u);
        if end - start >= 1e-3 {
            var ps = o + d * (start + 1e-4);
            let pe = o + d * (end - 1e-4);
            if dot(ps, ps) < 1e-6 {
                ps = d;
            }
            let result = trace_segment(probe, o, d, lf_uv(normalize(ps)), lf_uv(normalize(pe)), state);
            if result != LF_MISS {
                return result;
            }
        }
        start = max(start, end);
    }
    return LF_MISS;
}

// --- every probe --------------------------------------------------------------------------

// The lowest corner of the probe cage around point p.
fn cage_base(p: vec3<f32>) -> vec3<u32> {
    let grid = (p - lightfield.origin) / lightfield.spacing;
    let last = max(vec3<i32>(lightfield.counts) - 2, vec3<i32>(0));
    return vec3<u32>(clamp(vec3<i32>(floor(grid)), vec3<i32>(0), last));
}

fn cage_probe(base: vec3<u32>, i: u32) -> u32 {
    let offset = vec3<u32>(i & 1u, (i >> 1u) & 1u, (i >> 2u) & 1u);
    return grid_index(min(base + offset, lightfield.counts - 1u), lightfield.counts);
}

fn lf_probe_off(probe: u32) -> bool {
    return (lightfield_probe_states[probe] & PROBE_STATE_MASK) == PROBE_OFF;
}

// The cage corner whose probe lies nearest the ray's line (its projected polyline is the
// shortest, and it likely sees the whole unoccluded ray); probes inside geometry last.
fn nearest_to_line(base: vec3<u32>, p: vec3<f32>, d: vec3<f32>) -> u32 {
    var best = 0u;
    var best_distance = 3.0e38;
    for (var i = 0u; i < 8u; i++) {
        if lf_probe_off(cage_probe(base, i)) {
            continue;
        }
        let to_probe = lf_probe_position(cage_probe(base, i)) - p;
        let off_line = to_probe - d * dot(to_probe, d);
        let distance = dot(off_line, off_line);
        if distance < best_distance {
            best_distance = distance;
            best = i;
        }
    }
    return best;
}

// Traces the ray from `origin` along unit `d` up to t_max through the light field.
fn lightfield_trace(origin: vec3<f32>, d: vec3<f32>, t_max: f32) -> LightfieldHit {
    var state = SegmentState(0.0, t_max, vec2<f32>(0.0));
    var base = cage_base(origin);
    var corner = nearest_to_line(base, origin, d);
    var tried_in_cage = 0u;
    var probe = cage_probe(base, corner);
    var hit = LightfieldHit(LF_MISS, t_max, probe, vec2<u32>(0u), 0u);
    for (var visit = 0u; visit < lightfield.max_probe_visits; visit++) {
        probe = cage_probe(base, corner);
        hit.visits = visit + 1u;
        // A probe inside geometry cannot tell: the next one of the cage takes over.
        var result = LF_UNKNOWN;
        if !lf_probe_off(probe) {
            result = trace_probe(probe, origin, d, &state);
        }
        if result == LF_HIT {
            hit.result = LF_HIT;
            hit.t = state.t_max;
            hit.probe = probe;
            hit.texel = lf_texel(state.hit_uv, lightfield.resolution);
            return hit;
        }
        if result == LF_MISS {
            return hit;
        }
        let p = origin + d * state.t_min;
        let next = cage_base(p);
        if any(next != base) {
            base = next;
            corner = nearest_to_line(base, p, d);
            tried_in_cage = 0u;
        } else {
            corner = (corner + 3u) & 7u;
            tried_in_cage++;
            if tried_in_cage >= 8u {
                break;
            }
        }
    }
    // No probe resolved it: the ray hits the last point a probe saw, lit as that probe saw it.
    let p = origin + d * state.t_min - lf_probe_position(probe);
    hit.result = LF_HIT;
    hit.t = state.t_min;
    hit.probe = probe;
    hit.texel = lf_texel(lf_uv(normalize(p + d * 1e-6)), lightfield.resolution);
    return hit;
}

// The radiance a light-field hit brings back, or the sky for a miss.
fn lightfield_radiance_of(hit: LightfieldHit, sky: vec3<f32>) -> vec3<f32> {
    if hit.result != LF_HIT {
        return sky;
    }
    return unpack_r11g11b10(textureLoad(lightfield_radiance, hit.texel, hit.probe, 0).r);
}
