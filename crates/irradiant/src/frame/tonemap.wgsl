// frame/tonemap: linear radiance → exposure → filmic curve (ACES fit, Narkowicz 2015) → sRGB
// → packed RGBA8.

struct GpuTonemapParams {
    width: u32,
    height: u32,
    exposure: f32,
    // 0: filmic; 1: clamp only (for comparisons with other renderers' plain output)
    curve: u32,
}

@group(0) @binding(0) var<uniform> params: GpuTonemapParams;
// rgb sum and sample count (a), as the accumulation buffers store them
@group(0) @binding(1) var<storage, read> radiance: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read_write> output: array<u32>;

fn aces_fit(x: vec3<f32>) -> vec3<f32> {
    return saturate((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14));
}

fn linear_to_srgb(c: vec3<f32>) -> vec3<f32> {
    let lo = c * 12.92;
    let hi = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(hi, lo, c <= vec3<f32>(0.0031308));
}

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = id.x;
    if index >= params.width * params.height {
        return;
    }
    let v = radiance[index];
    var c = v.rgb / max(v.a, 1.0) * params.exposure;
    if params.curve == 0u {
        c = aces_fit(c);
    }
    let srgb = linear_to_srgb(saturate(c));
    output[index] = pack4x8unorm(vec4<f32>(srgb, 1.0));
}
