// ddgi_gather: what ddgi/gather and ddgi/gather_upsample both read the same way.
#import sampling

// The darkest diffuse weight (luminance) the light at a surface is divided by to tell the
// light arriving there; darker surfaces keep the query.
const DARKEST_DIFFUSE: f32 = 1e-4;

// The luminance of the light arriving at a surface, from its texel of ddgi/resolve's `indirect`
// (the volumes' weighted light times the diffuse weight `weight`, their weight in a): by
// luminance, so that a channel the albedo lacks divides nothing.
fn arriving_luminance(resolved: vec4<f32>, weight: vec3<f32>) -> f32 {
    return luminance(resolved.rgb / max(resolved.a, 1.0)) / max(luminance(weight), DARKEST_DIFFUSE);
}
