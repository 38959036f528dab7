// lightfield/trace_rays: arbitrary rays traced through the light field, for the tests and the
// agreement figures against the BVH (Lightfield::trace_rays).
#import lightfield


struct GpuLightfieldHit {
    result: u32,
    t: f32,
    probe: u32,
    visits: u32,
}

// raycast's GpuRay, two vec4 a ray: (origin, t_max), (direction, unused).
@group(2) @binding(50) var<storage, read> test_rays: array<vec4<f32>>;
@group(2) @binding(51) var<storage, read_write> test_hits: array<GpuLightfieldHit>;

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if 2u * id.x >= arrayLength(&test_rays) {
        return;
    }
    let origin = test_rays[2u * id.x];
    let direction = test_rays[2u * id.x + 1u].xyz;
    let hit = lightfield_trace(origin.xyz, normalize(direction), origin.w);
    test_hits[id.x] = GpuLightfieldHit(hit.result, hit.t, hit.probe, hit.visits);
}
