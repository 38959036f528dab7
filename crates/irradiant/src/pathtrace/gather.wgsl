// pathtrace/gather: the path tracer's truth at points that are not pixels — the probe oracle's
// probe texels and the query oracle's G-buffer points (ddgi::oracle). Each thread takes one
// query and adds `samples` samples of a cos^exponent lobe about its axis to the query's sums:
// for a radiance query the path-traced radiance arriving along the sample (the first surface's
// emission left out, as probes leave it out), so that exponent 1 gives the cosine-weighted mean
// radiance E/π; for a distance query the first hit's distance, capped at `far`, and its square,
// the moments a probe's distance texel holds.
#import path
#import sampling
#import random

struct GpuGatherQuery {
    origin: vec3<f32>,
    // distance queries: misses and longer hits count as this
    far: f32,
    axis: vec3<f32>,
    // lobe: cos^exponent about the axis
    exponent: f32,
    // GATHER_RADIANCE or GATHER_DISTANCE
    kind: u32,
    // 1: the origin lies on a surface whose normal is the axis; rays start just off it
    on_surface: u32,
    _pad0: u32,
    _pad1: u32,
}

struct GpuGatherParams {
    count: u32,
    // index of the first sample of this dispatch (decorrelates dispatches)
    sample_offset: u32,
    samples: u32,
    max_bounces: u32,
    seed: u32,
    light_sampling: u32,
    _pad1: u32,
    _pad2: u32,
}

const GATHER_RADIANCE: u32 = 0u;
const GATHER_DISTANCE: u32 = 1u;
const THREADS: u32 = 64u;

@group(1) @binding(0) var<uniform> params: GpuGatherParams;
@group(1) @binding(1) var<storage, read> queries: array<GpuGatherQuery>;
// Radiance: (rgb sum, sum of luminance²). Distance: (sum, sum of squares, 0, 0).
@group(1) @binding(2) var<storage, read_write> sums: array<vec4<f32>>;

// A direction of the lobe cos^exponent about +z: pdf ∝ cos^exponent θ.
fn power_cosine_lobe(u: vec2<f32>, exponent: f32) -> vec3<f32> {
    let cos_theta = pow(max(u.x, 1e-30), 1.0 / (exponent + 1.0));
    let sin_theta = sqrt(max(0.0, 1.0 - cos_theta * cos_theta));
    let phi = TAU * u.y;
    return vec3<f32>(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
}

@compute @workgroup_size(THREADS, 1, 1)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    let index = (group.x + group.y * groups.x) * THREADS + local_index;
    if index >= params.count {
        return;
    }
    let q = queries[index];
    let frame = basis(q.axis);
    let origin = select(q.origin, offset_ray(q.origin, q.axis), q.on_surface != 0u);
    var sum = vec4<f32>(0.0);
    for (var i = 0u; i < params.samples; i++) {
        var rng = rng_seed(index, params.sample_offset + i, params.seed);
        let dir = frame * power_cosine_lobe(rand2(&rng), q.exponent);
        if q.kind == GATHER_DISTANCE {
            let hit = trace_ray(origin, dir, q.far, false);
            let d = select(min(hit.t, q.far), q.far, hit.triangle == INVALID);
            sum += vec4<f32>(d, d * d, 0.0, 0.0);
        } else {
            let l = finite_or_zero(path_radiance(origin, dir, params.max_bounces, false, params.light_sampling, &rng));
            let y = luminance(l);
            sum += vec4<f32>(l, y * y);
        }
    }
    sums[index] += sum;
}
