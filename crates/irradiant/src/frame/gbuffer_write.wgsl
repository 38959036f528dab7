// The G-buffer's channels as the passes that write it bind them (frame/gbuffer, which traces
// them, and host/import, which converts a host's): one declaration for both.
#import frame_types
#import gbuffer_layout

@group(1) @binding(0) var<uniform> frame: GpuFrameParams;
@group(1) @binding(1) var gbuffer_depth: texture_storage_2d<r32float, write>;
@group(1) @binding(2) var gbuffer_normal: texture_storage_2d<rgba16float, write>;
@group(1) @binding(3) var gbuffer_albedo: texture_storage_2d<rgba16float, write>;
@group(1) @binding(4) var gbuffer_emission: texture_storage_2d<rgba16float, write>;
@group(1) @binding(5) var gbuffer_motion: texture_storage_2d<rgba32float, write>;

fn gbuffer_store(pixel: vec2<i32>, t: GBufferTexels) {
    textureStore(gbuffer_depth, pixel, vec4<f32>(t.depth, 0.0, 0.0, 0.0));
    textureStore(gbuffer_normal, pixel, t.normal);
    textureStore(gbuffer_albedo, pixel, t.albedo);
    textureStore(gbuffer_emission, pixel, t.emission);
    textureStore(gbuffer_motion, pixel, t.motion);
}
