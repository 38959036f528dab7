// ddgi/gather_upsample: the half-size gather (`gather.half_resolution`) at every pixel of the
// frame's `indirect`. A texel holds the light gathered on its 2×2 block's top-left pixel, so a
// pixel reads the (up to) four texels whose pixels surround it, each weighted bilinearly and by
// how well its surface agrees with the pixel's (joint bilateral upsampling, Kopf et al. 2007),
// so that light does not cross edges. The texels hold the light arriving (ddgi/gather); the
// pixel's own diffuse weight (its albedo) multiplies it here. Detail finer than a block, as a
// normal map's, is the query's: the light is scaled by the query at the pixel over the query at
// those texels' pixels (`gather_query`). Where no texel's surface agrees (a thin object between
// the blocks' pixels), or the surface reflects no diffuse light, the pixel keeps the query
// ddgi/resolve wrote.
#import gbuffer
#import history
#import brdf
#import ddgi_gather

@group(2) @binding(10) var indirect: texture_storage_2d<rgba32float, read_write>;
@group(2) @binding(33) var upsample_source: texture_2d<f32>;
@group(2) @binding(34) var upsample_query: texture_2d<f32>;

// Below this summed weight no texel speaks for the pixel.
const LEAST_AGREEMENT: f32 = 1e-3;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let depth = gbuffer_depth_at(id.xy);
    let query = textureLoad(indirect, id.xy);
    if depth < 0.0 || query.a <= 0.0 {
        return;
    }
    let s = gbuffer_surface(id.xy);
    let diffuse = diffuse_weight(s);
    if luminance(diffuse) < DARKEST_DIFFUSE {
        return;
    }
    let x = s.position;
    let n = gbuffer_normal_at(id.xy);
    let size = vec2<i32>(scaled_size(GATHER_SCALE));
    // Texel t's pixel is scale·t, so pixel p lies at p / scale in texel units.
    let at = vec2<f32>(id.xy) / f32(GATHER_SCALE);
    let base = vec2<i32>(floor(at));
    let f = at - floor(at);
    var light = vec3<f32>(0.0);
    var queried = 0.0;
    var weights = 0.0;
    for (var k = 0u; k < 4u; k++) {
        let corner = vec2<u32>(k & 1u, k >> 1u);
        let t = base + vec2<i32>(corner);
        let bilinear = select(1.0 - f, f, corner == vec2<u32>(1u));
        if any(t >= size) || bilinear.x * bilinear.y <= 0.0 {
            continue;
        }
        let q = scaled_pixel(vec2<u32>(t), GATHER_SCALE);
        let q_depth = gbuffer_depth_at(q);
        if q_depth < 0.0 {
            continue;
        }
        let w = bilinear.x * bilinear.y * surface_agreement(x, n, q, q_depth);
        let q_query = textureLoad(upsample_query, t, 0);
        light += w * textureLoad(upsample_source, t, 0).rgb;
        queried += w * q_query.a;
        weights += w;
    }
    if weights < LEAST_AGREEMENT {
        return;
    }
    light /= weights;
    queried /= weights;
    // The query's detail as a ratio; where the query is far darker than the gathered light
    // (light the probes miss) the ratio is noise, so it fades to 1 there.
    let floor_light = 0.1 * luminance(light) + 1e-9;
    // Bounded, for a pixel whose query differs from its neighbours' by more than light does
    // within two pixels on one surface (a probe's visibility edge).
    let detail = clamp((arriving_luminance(query, diffuse) + floor_light) / (queried + floor_light), 0.25, 4.0);
    textureStore(indirect, id.xy, vec4<f32>(diffuse * light * detail, 1.0));
}
