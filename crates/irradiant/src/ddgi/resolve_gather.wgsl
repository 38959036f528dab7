// ddgi/gather's light at a pixel (`pixel_light`), the final gather (GATHER_RAYS =
// DdgiGatherSettings::rays_per_pixel): that many cosine-distributed rays, each hit shaded as a
// probe ray's (ddgi_hit_light), each bounded by GATHER_FIREFLY_CLAMP
// (DdgiGatherSettings::firefly_clamp) times the probes' light at the pixel. ddgi/gather calls
// it where the pixel's tile gathers this frame (gather_tile_traces); ddgi/temporal averages it
// over frames.
#import ddgi_hit_light

// The luminance of the probes' light arriving at this thread's pixel, every volume's query as
// ddgi/resolve wrote it (arriving_query): ddgi/gather's main sets it before blended_light, so
// that the firefly bound costs no second query of the probes. It is exact where every channel
// of the surface's diffuse weight is over DARKEST_DIFFUSE; a darker channel cannot tell that
// light from the surface's colour, and gathered_light queries the probes there.
var<private> probes_light_here: f32;

fn pixel_light(s: Surface, pixel: vec2<u32>, tile: vec2<u32>, local_index: u32) -> vec3<f32> {
    bvh_thread(local_index);
    return gathered_light(s, pixel);
}

// The cosine-weighted mean radiance GATHER_RAYS rays from the pixel's surface bring back
// (traced_light).
fn gathered_light(s: Surface, pixel: vec2<u32>) -> vec3<f32> {
    let index = pixel.y * frame.width + pixel.x;
    var rng = rng_seed(index, frame.frame_index, frame.seed ^ 0x3c6ef372u ^ volume.volume_index);
    // The directions walk the R2 sequence (Roberts 2018) frame after frame, from a place of
    // the pixel's own: the running mean's rays cover the hemisphere evenly instead of
    // clumping at random.
    var pixel_rng = rng_seed(index, frame.seed, 0x9e3779b9u ^ volume.volume_index);
    let start = rand2(&pixel_rng);
    // A tile gathers every gather_interval-th frame: its gathers are consecutive points.
    let gather = frame.frame_index / max(volume.gather_interval, 1u);
    let origin = offset_ray(s.position, s.geometric_normal);
    let around = basis(s.normal);
    // The probes' light here: smooth and averaged over thousands of rays, the scale against
    // which a single ray's light is a firefly.
    var bound = 3.0e38;
    if GATHER_FIREFLY_CLAMP > 0.0 {
        var probes = probes_light_here;
        if any(diffuse_weight(s) <= vec3<f32>(DARKEST_DIFFUSE)) {
            probes = luminance(ddgi_irradiance(s.position, s.normal, view_dir(s.position)).irradiance);
        }
        bound = GATHER_FIREFLY_CLAMP * max(probes, 1e-4);
    }
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < GATHER_RAYS; i++) {
        let dir = normalize(around * cosine_hemisphere(r2_point(gather * GATHER_RAYS + i, start)));
        // The update's blind bounces are not the gather's: at every pixel's ray they took
        // Sibenik's gather from 2.76 to 3.62 ms at 1080p (H100; docs/ddgi.md, "Tracing on
        // where the probes are blind").
        let light = traced_light(origin, dir, 0u, GATHER_EMITTER_CANDIDATES, &rng);
        sum += light * min(1.0, bound / max(luminance(light), 1e-12));
    }
    return sum / f32(GATHER_RAYS);
}

// Point n of the R2 sequence shifted by `start`, in [0, 1)²: 2³²/g and 2³²/g² (g the plastic
// number) in fixed point, so that it stays exact however many frames go by.
fn r2_point(n: u32, start: vec2<f32>) -> vec2<f32> {
    let step = vec2<u32>(n * 0xc13fa9a9u, n * 0x91e10da6u);
    return fract(vec2<f32>(step) * 2.3283064e-10 + start);
}
