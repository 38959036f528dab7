// frame/compose: emission + direct + the technique's indirect light (+ sky where the camera
// ray left the scene) → linear radiance for tonemapping.
#import frame_types

@group(0) @binding(0) var<uniform> params: GpuFrameParams;
@group(0) @binding(1) var<storage, read> gbuffer: array<GpuGBufferTexel>;
@group(0) @binding(2) var<storage, read> direct: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> indirect: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> radiance: array<vec4<f32>>;
@group(0) @binding(5) var<uniform> sky: vec4<f32>;

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = id.x;
    if index >= params.width * params.height {
        return;
    }
    let g = gbuffer[index];
    var l = sky.rgb;
    if g.depth >= 0.0 {
        l = g.emission + direct[index].rgb + indirect[index].rgb;
    }
    radiance[index] = vec4<f32>(l, 1.0);
}
