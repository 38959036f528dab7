// lightfield/filter: one direction of the separable cross-bilateral filter (§5.1, after G3D's
// BilateralFilter): taps every `stride` pixels out to `radius`, each weighted by a Gaussian of
// its distance and by how much its surface agrees with the centre's — depth within a few
// percent, normals alike — so that light does not bleed across edges.
#import lightfield
#import gbuffer

struct GpuLightfieldFilterPass {
    direction: vec2<i32>,
    radius: u32,
    stride: u32,
}

@group(2) @binding(35) var<uniform> filter_pass: GpuLightfieldFilterPass;
@group(2) @binding(36) var filter_source: texture_2d<f32>;
@group(2) @binding(37) var filter_target: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let centre = vec2<i32>(id.xy);
    let depth = gbuffer_depth_at(id.xy);
    if depth < 0.0 || filter_pass.radius == 0u {
        textureStore(filter_target, centre, textureLoad(filter_source, centre, 0));
        return;
    }
    let normal = gbuffer_normal_at(id.xy);
    let sigma = max(f32(filter_pass.radius) * 0.5, 1.0);
    let last = vec2<i32>(frame_size()) - 1;
    var sum = vec4<f32>(0.0);
    var weight_sum = 0.0;
    let taps = i32(filter_pass.radius / filter_pass.stride);
    for (var k = -taps; k <= taps; k++) {
        let offset = k * i32(filter_pass.stride);
        let p = clamp(centre + filter_pass.direction * offset, vec2<i32>(0), last);
        let d = gbuffer_depth_at(vec2<u32>(p));
        if d < 0.0 {
            continue;
        }
        let n = gbuffer_normal_at(vec2<u32>(p));
        let spatial = exp(-f32(offset * offset) / (2.0 * sigma * sigma));
        let depth_agreement = exp(-abs(d - depth) / (0.02 * depth));
        let normal_agreement = pow(max(dot(n, normal), 0.0), 16.0);
        let w = spatial * depth_agreement * normal_agreement;
        sum += w * textureLoad(filter_source, p, 0);
        weight_sum += w;
    }
    textureStore(filter_target, centre, sum / max(weight_sum, 1e-6));
}
