// ddgi: tracing a probe ray (ddgi/trace, and ddgi/shade when it traces its own rays).
#import ddgi_probes
#import bvh

// A probe ray's closest hit. The ray starts PROBE_RAY_LEAD × the smallest spacing behind the
// probe, and the hit's distance is still counted from the probe (but never below a hair of the
// lead, so that a backface hit keeps its sign). A surface through the probe's centre — a
// volume fitted to a room's one-sided walls puts whole layers of probes in them — is then hit
// from both sides, and relocation moves the probe off it; from the centre itself a ray would
// miss the surface and the probe would see half the void beyond the wall.
fn trace_probe_ray(probe: u32, dir: vec3<f32>) -> Hit {
    let lead = PROBE_RAY_LEAD * volume.min_spacing;
    var hit = trace_ray(probe_position(probe) - dir * lead, dir, volume.max_ray_distance + lead, false);
    hit.t = max(hit.t - lead, 1e-3 * lead);
    return hit;
}
