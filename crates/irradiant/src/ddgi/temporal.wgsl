// ddgi/temporal: with the final gather (DdgiGatherSettings), the light arriving as a
// running mean of the gathers of up to `gather_history_frames` frames, reprojected along the
// motion vectors where last frame's pixel held the same surface (the module `history`);
// elsewhere, and after the frame's history resets, it starts over, from the probes' query
// until the pixel's tile gathers. The mean, the gathers in it (a), the mean of the gathers'
// squared luminance (ddgi/gather_filter's estimate of the mean's error) and the geometry it
// was taken on are next frame's history (two sets, ping-ponged). f32, so that a long mean does
// not stall on f16's rounding. `gather_source` is ddgi/gather's image, a texel a pixel or with
// `gather.half_resolution` (GATHER_SCALE 2) a 2×2 block, its geometry the block's top-left
// pixel's.
#import ddgi_volume
#import gbuffer
#import history
#import sampling

@group(2) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(2) @binding(10) var gather_source: texture_2d<f32>;
@group(2) @binding(20) var gather_history: texture_2d<f32>;
@group(2) @binding(21) var gather_history_geometry: texture_2d<f32>;
@group(2) @binding(22) var gather_mean: texture_storage_2d<rgba32float, write>;
@group(2) @binding(23) var gather_mean_geometry: texture_storage_2d<rgba32float, write>;
@group(2) @binding(24) var gather_history_moment: texture_2d<f32>;
@group(2) @binding(25) var gather_moment: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(workgroup_id) tile: vec3<u32>) {
    if any(id.xy >= scaled_size(GATHER_SCALE)) {
        return;
    }
    let pixel = vec2<i32>(id.xy);
    let surface_pixel = scaled_pixel(id.xy, GATHER_SCALE);
    let here = history_geometry(surface_pixel);
    textureStore(gather_mean_geometry, pixel, here);
    if here.w < 0.0 {
        textureStore(gather_mean, pixel, vec4<f32>(0.0));
        textureStore(gather_moment, pixel, vec4<f32>(0.0));
        return;
    }
    // The volumes' weighted sum over its weight: this frame's gather where the tile traced,
    // else the probes' query (ddgi/gather).
    let now = textureLoad(gather_source, pixel, 0);
    var light = now.rgb / max(now.a, 1.0);
    let traced = gather_tile_traces(tile.xy, frame.frame_index);
    // Gathers in the mean (0: it holds the query alone), at most those of history_frames.
    var gathers = select(0.0, 1.0, traced);
    let square = luminance(light) * luminance(light);
    var moment = select(0.0, square, traced);
    let most = max(f32(volume.gather_history_frames / max(volume.gather_interval, 1u)), 1.0);
    let p = same_surface_texel_scaled(surface_pixel, here.xyz, gather_history_geometry, GATHER_SCALE);
    if p.x >= 0 {
        let old = textureLoad(gather_history, p, 0);
        let old_moment = textureLoad(gather_history_moment, p, 0).r;
        if traced {
            gathers = min(old.a + 1.0, most);
            light = mix(old.rgb, light, 1.0 / gathers);
            moment = mix(old_moment, square, 1.0 / gathers);
        } else if old.a > 0.0 {
            gathers = old.a;
            light = old.rgb;
            moment = old_moment;
        }
    }
    textureStore(gather_mean, pixel, vec4<f32>(light, gathers));
    textureStore(gather_moment, pixel, vec4<f32>(moment));
}
