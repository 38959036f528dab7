// ddgi/visualize_volumes: which volume lights each pixel (ProbeView::Volumes): the frame's
// `indirect` is filled as ddgi/resolve fills it, volume by volume finest first, but each
// volume gives its share of a colour of its own instead of its light (the finest red, then
// green, blue, yellow, magenta, cyan, white, orange); the coarsest copies the blend into the
// composed radiance. Where volumes blend, the colours mix; a border between cascades shows
// as a hard edge between colours.
#import gbuffer
#import ddgi_volume

@group(2) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(2) @binding(10) var indirect: texture_storage_2d<rgba32float, read_write>;
@group(2) @binding(12) var radiance: texture_storage_2d<rgba32float, write>;

const VOLUME_COLOURS = array<vec3<f32>, 8>(
    vec3<f32>(1.0, 0.0, 0.0),
    vec3<f32>(0.0, 1.0, 0.0),
    vec3<f32>(0.0, 0.0, 1.0),
    vec3<f32>(1.0, 1.0, 0.0),
    vec3<f32>(1.0, 0.0, 1.0),
    vec3<f32>(0.0, 1.0, 1.0),
    vec3<f32>(1.0, 1.0, 1.0),
    vec3<f32>(1.0, 0.5, 0.0),
);

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) || gbuffer_depth_at(id.xy) < 0.0 {
        return;
    }
    var sum = vec4<f32>(0.0);
    if volume.volume_index > 0u {
        sum = textureLoad(indirect, id.xy);
    }
    let weight = volume_share(gbuffer_surface(id.xy).position, sum.a);
    sum += vec4<f32>(VOLUME_COLOURS[volume.volume_index % 8u] * weight, weight);
    textureStore(indirect, id.xy, sum);
    if volume.volume_is_last != 0u {
        textureStore(radiance, id.xy, vec4<f32>(sum.rgb, 1.0));
    }
}
