// ddgi/resolve: indirect diffuse light at each G-buffer pixel from this probe volume, blended
// into `indirect` (rgb: weighted sum, a: weight so far). Volumes run finest first, each taking
// its share of the weight (volume_share in ddgi_volume), so that one volume alone lights
// everything, as it always did. The light at a pixel, `pixel_light`, is the query
// (resolve_query.wgsl, compiled after this one), so the resolve carries no tracing code; the
// final gather is ddgi/gather's (gather.wgsl), which shares each pixel's share
// (resolve_blend.wgsl).

@group(2) @binding(10) var indirect: texture_storage_2d<rgba32float, read_write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local_index: u32, @builtin(workgroup_id) tile: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    var sum = vec4<f32>(0.0);
    if volume.volume_index > 0u {
        sum = textureLoad(indirect, id.xy);
    }
    textureStore(indirect, id.xy, blended_light(id.xy, tile.xy, local_index, sum));
}
