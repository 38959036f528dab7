// A volume's share of the light at a pixel, blended over the finer volumes' (ddgi/resolve's
// and ddgi/gather's `blended_light`): times the surface's diffuse weight (albedo included)
// where BLEND_DIFFUSE_WEIGHT, else the light arriving, as ddgi/gather keeps it.
#import gbuffer
#import brdf

// `sum` (the finer volumes' weighted light at `pixel`) with this volume's share added.
fn blended_light(pixel: vec2<u32>, tile: vec2<u32>, local_index: u32, sum: vec4<f32>) -> vec4<f32> {
    if gbuffer_depth_at(pixel) < 0.0 {
        return sum;
    }
    let s = gbuffer_surface(pixel);
    let weight = volume_share(s.position, sum.a);
    if weight <= 0.0 {
        return sum;
    }
    var light = pixel_light(s, pixel, tile, local_index);
    if BLEND_DIFFUSE_WEIGHT {
        light *= diffuse_weight(s);
    }
    return sum + vec4<f32>(light * weight, weight);
}
