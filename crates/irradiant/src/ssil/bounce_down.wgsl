// ssil/bounce_down: one level of the bounce light from the level below: the mean of the texels
// under it that see a surface (as the frame's pyramid averages its radiance).
#import ssil_common

@group(2) @binding(0) var<uniform> ssil: GpuSsilParams;
@group(2) @binding(1) var<uniform> ssil_pass: GpuSsilPass;
@group(2) @binding(2) var pyramid_normal_depth: texture_2d<f32>;
@group(2) @binding(3) var source_radiance: texture_2d<f32>;
@group(2) @binding(4) var target_radiance: texture_storage_2d<rgba16float, write>;
@group(1) @binding(0) var<uniform> frame: GpuFrameParams;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let level = ssil_pass.level;
    let size = level_size(level);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let last = vec2<i32>(level_size(level - 1u)) - 1;
    var sum = vec4<f32>(0.0);
    var count = 0.0;
    for (var k = 0; k < 4; k++) {
        let p = min(vec2<i32>(id.xy) * 2 + vec2<i32>(k & 1, k >> 1), last);
        if textureLoad(pyramid_normal_depth, vec2<u32>(p), level - 1u).w >= 0.0 {
            sum += textureLoad(source_radiance, p, 0);
            count += 1.0;
        }
    }
    textureStore(target_radiance, vec2<i32>(id.xy), sum / max(count, 1.0));
}
