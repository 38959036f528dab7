// ssil/temporal's `uncovered_light` for ssil+ddgi with the bent fill (`bent_fill`): the probes'
// light read around the mean of the directions the screen left uncovered (the bent normal)
// instead of around the normal. Where the screen covers a bright wall beside a dim ceiling,
// the uncovered directions lean towards the ceiling, and so does their light (docs/ssil.md).
// The finest volume reads both; its share of the pixel (1 with one volume) moves the blended
// light by the difference, which keeps the other volumes' light.
#import ddgi_query

fn uncovered_light(s: Surface, probes: vec3<f32>, coverage: f32, covered: vec3<f32>) -> vec3<f32> {
    if coverage <= 1e-3 || coverage >= 1.0 {
        return probes;
    }
    // The cosine lobe's directions weigh ∫ ω cos θ dω / π = (2/3) n in all; less the covered
    // ones', the uncovered ones'. Its component along n can still fall below 0: the covered
    // sum was taken about each level's voted normal, not this pixel's. It is kept a little
    // above, so that the bent normal faces out.
    var uncovered = (2.0 / 3.0) * s.normal - covered;
    uncovered += s.normal * max(0.05 * length(uncovered) - dot(uncovered, s.normal), 0.0);
    if dot(uncovered, uncovered) < 1e-8 {
        return probes;
    }
    let bent = normalize(uncovered);
    let share = volume_share(s.position, 0.0);
    if share <= 0.0 {
        return probes;
    }
    let wo = view_dir(s.position);
    let around_normal = ddgi_irradiance(s.position, s.normal, wo).irradiance;
    let around_bent = ddgi_irradiance_along(s.position, s.normal, bent, wo).irradiance;
    return max(probes + share * diffuse_weight(s) * (around_bent - around_normal), vec3<f32>(0.0));
}
