// ddgi/gather: the final gather on a half-size image (`gather.half_resolution`). Where a
// tile of `gathered` gathers this frame, one texel a 2×2 block: the gathered light at the
// block's top-left pixel (resolve_gather.wgsl), this volume's share of it blended over the
// finer volumes' as ddgi/resolve blends `indirect`. Elsewhere, and for every texel in
// `gather_query`, the probes' query at that pixel, which ddgi/resolve wrote into `indirect`
// before: ddgi/temporal holds it where no gather is, ddgi/gather_upsample scales by it.
#import history

@group(2) @binding(10) var indirect: texture_storage_2d<rgba32float, read_write>;
@group(2) @binding(11) var gathered: texture_storage_2d<rgba32float, read_write>;
@group(2) @binding(12) var gather_query: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local_index: u32, @builtin(workgroup_id) tile: vec3<u32>) {
    if any(id.xy >= scaled_size(GATHER_SCALE)) {
        return;
    }
    let texel = vec2<i32>(id.xy);
    let pixel = scaled_pixel(id.xy, GATHER_SCALE);
    let traces = gather_tile_traces(tile.xy, frame.frame_index);
    if volume.volume_index == 0u {
        let query = textureLoad(indirect, pixel);
        textureStore(gather_query, texel, query);
        if !traces {
            textureStore(gathered, texel, query);
        }
    }
    if !traces {
        return;
    }
    var sum = vec4<f32>(0.0);
    if volume.volume_index > 0u {
        sum = textureLoad(gathered, texel);
    }
    textureStore(gathered, texel, blended_light(pixel, tile.xy, local_index, sum));
}
