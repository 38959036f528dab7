// ddgi/gather: the final gather on its own image, a texel a pixel or, with
// `gather.half_resolution` (GATHER_SCALE 2), a texel a 2×2 block, read at the block's top-left
// pixel (scaled_pixel). Where a tile of `gathered` gathers this frame: the light gathered there
// (resolve_gather.wgsl), this volume's share of it blended over the finer volumes' as
// ddgi/resolve blends `indirect`. Elsewhere, and for every texel in `gather_query`, the probes'
// query there: ddgi/temporal holds it where no gather is, ddgi/gather_upsample scales by it.
// All of it is the light arriving, before the surface's diffuse weight (its albedo), so that
// ddgi/gather_filter never blurs a texture and ddgi/gather_upsample weighs each pixel by its
// own.
#import history
#import ddgi_gather

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
    if volume.volume_index > 0u && !traces {
        return;
    }
    let query = arriving_query(pixel);
    if volume.volume_index == 0u {
        textureStore(gather_query, texel, query);
        if !traces {
            textureStore(gathered, texel, vec4<f32>(query.rgb, 1.0));
            return;
        }
    }
    probes_light_here = luminance(query.rgb);
    var sum = vec4<f32>(0.0);
    if volume.volume_index > 0u {
        sum = textureLoad(gathered, texel);
    }
    textureStore(gathered, texel, blended_light(pixel, tile.xy, local_index, sum));
}

// The query ddgi/resolve wrote into `indirect` at `pixel` (every volume's, weighted), over the
// surface's diffuse weight (rgb: a channel the surface does not reflect reads 0, which it
// never shows), and its luminance as ddgi/gather_upsample measures a pixel's (a).
fn arriving_query(pixel: vec2<u32>) -> vec4<f32> {
    if gbuffer_depth_at(pixel) < 0.0 {
        return vec4<f32>(0.0);
    }
    let weight = diffuse_weight(gbuffer_surface(pixel));
    let resolved = textureLoad(indirect, pixel);
    let arriving = resolved.rgb / max(resolved.a, 1.0) / max(weight, vec3<f32>(DARKEST_DIFFUSE));
    return vec4<f32>(arriving, arriving_luminance(resolved, weight));
}
