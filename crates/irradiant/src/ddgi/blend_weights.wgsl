// ddgi/blend_weights: once a frame, for every texel of a probe tile, the rays that weigh in its
// blend and their weights. Every probe shares this frame's rotated ray set, so the lists are the
// same for all probes: the blend passes then only gather (no dot products, no powers), and
// skip the rays whose weight is 0 — behind the texel, half of them for irradiance — or, for
// the distance blend's cosine power, under 2^-34 of the texel's largest weight, which cannot
// change an f32 sum (the nearest ray alone outweighs all of them by 2^26).
//
// Layout of blend_weights (texel t of a set of T texels, m rays a probe): irradiance texels
// first, then distance texels at irradiance_texels² × (m + 1); in each set, T headers
// (GpuDdgiBlendWeight: entry count, weight sum), then entry k of texel t at T + k × T + t, so
// that the threads of a warp, one texel each, read neighbouring entries.
#import ddgi_volume
#import ddgi_rays

@group(2) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(2) @binding(3) var<storage, read> directions: array<vec4<f32>>;
@group(2) @binding(18) var<storage, read_write> blend_weights: array<GpuDdgiBlendWeight>;

// Weights under this share of a texel's largest distance weight are left out.
const NEGLIGIBLE_LOG2: f32 = -34.0;
const THREADS: u32 = 64u;

var<workgroup> scan: array<u32, THREADS>;
var<workgroup> reduce: array<f32, THREADS>;

// Sums (or, with `largest`, maxes) each thread's value over the workgroup; every thread gets it.
fn workgroup_reduce(li: u32, value: f32, largest: bool) -> f32 {
    reduce[li] = value;
    workgroupBarrier();
    for (var stride = THREADS / 2u; stride > 0u; stride >>= 1u) {
        if li < stride {
            let other = reduce[li + stride];
            reduce[li] = select(reduce[li] + other, max(reduce[li], other), largest);
        }
        workgroupBarrier();
    }
    let result = reduce[0];
    workgroupBarrier();
    return result;
}

// One workgroup a texel, a thread a ray: the texel's list is compacted in ray order with a
// prefix sum over the workgroup, THREADS rays at a time.
@compute @workgroup_size(THREADS, 1, 1)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) li: u32) {
    let m = volume.rays_per_probe;
    let irradiance_count = volume.irradiance_texels * volume.irradiance_texels;
    let distance_count = volume.distance_texels * volume.distance_texels;
    if group.x >= irradiance_count + distance_count {
        return;
    }
    let is_irradiance = group.x < irradiance_count;
    let t = select(group.x - irradiance_count, group.x, is_irradiance);
    let texels = select(volume.distance_texels, volume.irradiance_texels, is_irradiance);
    let texel_count = texels * texels;
    let base = select(irradiance_count * (m + 1u), 0u, is_irradiance);
    let dir = texel_direction(vec2<u32>(t % texels, t / texels), texels);
    // Irradiance: cosine weights, every ray in front. Distance: cos^exponent from the cut on.
    var own_largest = 0.0;
    for (var r = li; r < m; r += THREADS) {
        own_largest = max(own_largest, dot(dir, directions[r].xyz));
    }
    let largest = workgroup_reduce(li, own_largest, true);
    let cut = select(largest * exp2(NEGLIGIBLE_LOG2 / max(volume.distance_exponent, 1e-3)), 0.0, is_irradiance);
    var count = 0u;
    var own_total = 0.0;
    for (var first = 0u; first < m; first += THREADS) {
        let r = first + li;
        let c = select(-1.0, dot(dir, directions[min(r, m - 1u)].xyz), r < m);
        let take = c > 0.0 && c >= cut;
        // Inclusive prefix sum of `take` (Hillis–Steele).
        scan[li] = u32(take);
        workgroupBarrier();
        for (var stride = 1u; stride < THREADS; stride <<= 1u) {
            let before = select(0u, scan[li - min(stride, li)], li >= stride);
            workgroupBarrier();
            scan[li] += before;
            workgroupBarrier();
        }
        if take {
            let w = select(pow(c, volume.distance_exponent), c, is_irradiance);
            let k = count + scan[li] - 1u;
            blend_weights[base + texel_count + k * texel_count + t] = GpuDdgiBlendWeight(r, w);
            own_total += w;
        }
        count += scan[THREADS - 1u];
        workgroupBarrier();
    }
    let total = workgroup_reduce(li, own_total, false);
    if li == 0u {
        blend_weights[base + t] = GpuDdgiBlendWeight(count, total);
    }
}
