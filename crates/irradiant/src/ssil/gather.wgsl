// ssil/gather_<level>: one level's screen-space gather (Soler et al. 2009, §3–4). Each texel
// of pyramid level k sums the light of `samples` texels of the same level on the disc of
// radius r around it (the start level) or the ring r/2…r (the others) — r in pixels of the
// level, so each level reaches twice as far as the one before — as the irradiance they send
// it: the point-to-disc form factor (eq. 4), with each sample's surface area from its screen
// area (eqs. 2–3: the level's pixel area, 2^(2k) times level 0's, over the samples, at the
// sample's depth, corrected for its tilt), and visibility from marching the level's voxel grid.
// In ssil+ddgi only senders within `reach` of the receiver count (the near field).
// For the last bounce the samples are importance-sampled around the mirror direction
// projected on the screen (f(θ) = α + exp(−s (θr − θ)² / 2π)) and the full BRDF gathers them.
// Writes (E: cosine-weighted incident radiance ∫L cos dω, coverage: the share of the cosine
// lobe the samples covered, each by its sender's diffuse share) and the glossy radiance; with
// ssil+ddgi's bent fill also the covered directions (covered_directions.wgsl). GATHER_LANES
// threads share a texel, each taking every GATHER_LANES-th sample; their sums meet in
// workgroup memory.
#import ssil_common
#import gbuffer
#import brdf
#import random

@group(2) @binding(0) var<uniform> ssil: GpuSsilParams;
@group(2) @binding(1) var<uniform> ssil_pass: GpuSsilPass;
@group(2) @binding(2) var pyramid_normal_depth: texture_2d<f32>;
@group(2) @binding(3) var source_radiance: texture_2d<f32>;
@group(2) @binding(4) var ssil_voxels: texture_2d<u32>;
@group(2) @binding(5) var target_light: texture_storage_2d<rgba16float, write>;
@group(2) @binding(6) var target_specular: texture_storage_2d<rgba16float, write>;

// Whether the segment between two surface points of this level — texel positions a and b,
// view depths da and db — crosses a solid voxel of the level's grid, skipping
// `visibility_bias` of it at each end (the surfaces' own voxels). The march steps evenly over
// the screen, where the grid's texels are, with the depth interpolated perspective-correctly
// (1/depth is linear in screen space): no projection per step.
fn occluded(a: vec2<f32>, da: f32, b: vec2<f32>, db: f32, level: u32) -> bool {
    let grid = vec2<f32>(level_size(level));
    let voxel_level = level - ssil.start_level;
    let steps = ssil.visibility_steps;
    let inv_a = 1.0 / da;
    let inv_b = 1.0 / db;
    for (var i = 0u; i < steps; i++) {
        let t = ssil.visibility_bias + (1.0 - 2.0 * ssil.visibility_bias) * (f32(i) + 0.5) / f32(steps);
        let texel = mix(a, b, t);
        if any(texel < vec2<f32>(0.0)) || any(texel >= grid) {
            continue;
        }
        let depth = 1.0 / mix(inv_a, inv_b, t);
        if voxel_bit(textureLoad(ssil_voxels, vec2<u32>(texel), voxel_level), slice_of(depth)) {
            return true;
        }
    }
    return false;
}

// The standard normal's inverse CDF would be costly; Box–Muller from two uniforms.
fn gaussian_sample(u: vec2<f32>) -> f32 {
    return sqrt(-2.0 * log(max(u.x, 1e-7))) * cos(TAU * u.y);
}

// A wrapped Gaussian of standard deviation sigma at angle difference d, summed over the three
// nearest periods (enough below sigma = π).
fn wrapped_gaussian(d: f32, sigma: f32) -> f32 {
    var g = 0.0;
    for (var k = -1; k <= 1; k++) {
        let x = d + TAU * f32(k);
        g += exp(-x * x / (2.0 * sigma * sigma));
    }
    return g;
}

fn wrap_angle(a: f32) -> f32 {
    return a - TAU * floor((a + PI) / TAU);
}

// One lane's sums: E (rgb), coverage, the glossy radiance and the covered directions.
struct LaneSum {
    light: vec4<f32>,
    specular: vec3<f32>,
    covered: vec3<f32>,
}

const TEXELS_PER_GROUP: u32 = GATHER_TILE * GATHER_TILE;
// The lanes' sums, each part apart: without the bent fill COVERS_DIRECTIONS is a constant
// false, and the compiler drops the covered directions' array with the code that uses it.
var<workgroup> lane_light: array<vec4<f32>, GATHER_LANES * TEXELS_PER_GROUP>;
var<workgroup> lane_specular: array<vec3<f32>, GATHER_LANES * TEXELS_PER_GROUP>;
var<workgroup> lane_covered: array<vec3<f32>, GATHER_LANES * TEXELS_PER_GROUP>;

// `lane`'s share of texel `texel`'s samples at this level.
fn gather_lane(texel: vec2<u32>, lane: u32) -> LaneSum {
    var sum = LaneSum(vec4<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
    let level = ssil_pass.level;
    let size = level_size(level);
    let nd = textureLoad(pyramid_normal_depth, texel, level);
    if nd.w < 0.0 {
        return sum;
    }
    let x = level_position(texel, level, nd.w);
    let n = nd.xyz;
    let wo = normalize(frame.camera.position - x);
    let image = vec2<f32>(f32(frame.width), f32(frame.height));
    // The receiver's material, for the glossy gather: the full-resolution texel at this
    // texel's centre.
    let full = min(vec2<u32>(level_to_image(vec2<f32>(texel) + 0.5, level)), vec2<u32>(frame.width, frame.height) - 1u);
    var receiver = gbuffer_surface(full);
    receiver.normal = n;
    receiver.position = x;
    let glossy = ssil_pass.last_bounce == 1u && has_specular(receiver) && receiver.roughness > ssil.glossy_above;
    // eq. 2: the world area of one pixel of this level at unit depth, facing the camera:
    // 2^(2k) times a level-0 pixel's.
    let pixel_area = 4.0 * frame.camera.tan_half_fov_y * frame.camera.tan_half_fov_y * frame.camera.aspect
        / (image.x * image.y) * f32(1u << (2u * level));
    let r = ssil.radius;
    let inner = select(0.5 * r, 0.0, ssil_pass.first == 1u);
    let region = PI * (r * r - inner * inner);
    // Importance of angles around the projected mirror direction (glossy last bounce only).
    var lobe_angle = 0.0;
    var sigma = 1e6;
    if glossy {
        let reflected = reflect(-wo, n);
        let ahead = project(frame.camera, x + reflected * max(0.1 * view_depth(x), 1e-3), image) - project(frame.camera, x, image);
        let alpha = max(receiver.roughness * receiver.roughness, 1e-3);
        // Phong exponent of the GGX lobe (Walter et al. 2007), and the Gaussian's width.
        let s = clamp(2.0 / (alpha * alpha) - 2.0, 0.0, 1e4);
        if dot(ahead, ahead) > 1e-6 && s > 0.0 {
            lobe_angle = atan2(ahead.y, ahead.x);
            sigma = sqrt(PI / s);
        }
    }
    let importance = sigma < PI;
    let uniform_weight = TAU * ssil.importance_alpha;
    let gaussian_weight = sqrt(TAU) * sigma;
    // The spiral's rotation is the texel's (every lane draws the same); the jitter is the lane's.
    let texel_seed = rng_seed(texel.y * size.x + texel.x, frame.frame_index, level * 7919u + 0x2545f491u);
    var rng = texel_seed;
    let rotation = TAU * rand(&rng);
    rng = rng_seed(texel_seed, lane, 0x68e31da4u);
    let n_samples = ssil.samples;
    for (var i = lane; i < n_samples; i += GATHER_LANES) {
        // Radius uniform in area over the disc or ring, stratified; angle along a golden-angle
        // spiral, or drawn from the importance function.
        let u = (f32(i) + rand(&rng)) / f32(n_samples);
        let rho = sqrt(mix(inner * inner, r * r, u));
        var angle = rotation + f32(i) * 2.39996323;
        var weight = 1.0;
        if importance {
            if rand(&rng) * (uniform_weight + gaussian_weight) < uniform_weight {
                angle = TAU * rand(&rng);
            } else {
                angle = lobe_angle + sigma * gaussian_sample(rand2(&rng));
            }
            let pdf = (ssil.importance_alpha + wrapped_gaussian(wrap_angle(angle - lobe_angle), sigma)) / (uniform_weight + gaussian_weight);
            weight = 1.0 / (TAU * pdf);
        }
        let q = vec2<f32>(texel) + 0.5 + rho * vec2<f32>(cos(angle), sin(angle));
        if any(q < vec2<f32>(0.0)) || any(q >= vec2<f32>(size)) {
            continue;
        }
        let qi = vec2<u32>(q);
        let ndq = textureLoad(pyramid_normal_depth, qi, level);
        if ndq.w < 0.0 {
            continue;
        }
        let xi = level_position(qi, level, ndq.w);
        let d = xi - x;
        let r2 = dot(d, d);
        // ssil+ddgi: senders past the near field are the probes' (docs/ssil.md).
        if r2 < 1e-10 || (ssil.reach >= 0.0 && r2 > ssil.reach * ssil.reach) {
            continue;
        }
        let wi = d * inverseSqrt(r2);
        let cos_receiver = dot(n, wi);
        let cos_sender = dot(ndq.xyz, -wi);
        if cos_receiver <= 0.0 || cos_sender <= 0.0 {
            continue;
        }
        // eqs. 2–3: the sample's surface area from its share of the region's pixels.
        let view = normalize(xi - frame.camera.position);
        let cos_alpha = dot(view, frame.camera.forward);
        let cos_beta = max(abs(dot(ndq.xyz, view)), 0.05);
        let ds = ndq.w * ndq.w * pixel_area * (region / f32(n_samples)) * weight * cos_alpha / cos_beta;
        // eq. 4: the point-to-disc form factor, bounded where the sample is close.
        let disc = cos_sender * ds / PI;
        let g = cos_receiver * cos_sender * ds / (r2 + disc);
        if ssil.visibility == 1u && occluded(vec2<f32>(texel) + 0.5, nd.w, vec2<f32>(qi) + 0.5, ndq.w, level) {
            continue;
        }
        // The sender's light and the share of what it reflects that it sends every way: the
        // screen covers its direction by that share only (frame/pyramid).
        let sent = textureLoad(source_radiance, qi, ssil_pass.radiance_level);
        let l = sent.rgb;
        let covered = sent.a * g / PI;
        sum.light += vec4<f32>(l * g, covered);
        // Only the last bounce's directions are read (ssil/temporal).
        if COVERS_DIRECTIONS && ssil_pass.last_bounce == 1u {
            sum.covered += wi * covered;
        }
        if glossy {
            let f = brdf_eval(receiver, wo, wi) - diffuse_weight(receiver) / PI;
            sum.specular += max(f, vec3<f32>(0.0)) * l * g;
        }
    }
    return sum;
}

// Workgroup: GATHER_TILE × GATHER_TILE texels, GATHER_LANES threads each (x: the lane).
@compute @workgroup_size(GATHER_LANES, TEXELS_PER_GROUP, 1)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_id) local: vec3<u32>) {
    let size = level_size(ssil_pass.level);
    let texel = group.xy * GATHER_TILE + vec2<u32>(local.y % GATHER_TILE, local.y / GATHER_TILE);
    let inside = all(texel < size);
    var own = LaneSum(vec4<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
    if inside {
        own = gather_lane(texel, local.x);
    }
    let slot = local.y * GATHER_LANES + local.x;
    lane_light[slot] = own.light;
    lane_specular[slot] = own.specular;
    if COVERS_DIRECTIONS {
        lane_covered[slot] = own.covered;
    }
    workgroupBarrier();
    if local.x != 0u || !inside {
        return;
    }
    var total = own;
    for (var lane = 1u; lane < GATHER_LANES; lane++) {
        let other = local.y * GATHER_LANES + lane;
        total.light += lane_light[other];
        total.specular += lane_specular[other];
        if COVERS_DIRECTIONS {
            total.covered += lane_covered[other];
        }
    }
    textureStore(target_light, vec2<i32>(texel), vec4<f32>(total.light.rgb, min(total.light.a, 1.0)));
    textureStore(target_specular, vec2<i32>(texel), vec4<f32>(total.specular, 1.0));
    store_covered(vec2<i32>(texel), covered_within_lobe(total.covered, total.light.a));
}
