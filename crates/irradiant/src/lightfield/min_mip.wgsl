// lightfield/min_mip: the distance maps' second level, 1/16² of their resolution (the paper's
// two-level hierarchy): each texel the nearest surface of its 16×16 block, so that the coarse
// march can skip a block wherever the ray stays nearer than it.
#import lightfield

@group(2) @binding(25) var target_low: texture_storage_2d_array<r32float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = lightfield.low_resolution;
    if id.x >= size || id.y >= size || id.z >= lightfield.probe_count {
        return;
    }
    var nearest = LF_NO_SURFACE;
    for (var y = 0u; y < MIN_MIP_FACTOR; y++) {
        for (var x = 0u; x < MIN_MIP_FACTOR; x++) {
            let texel = id.xy * MIN_MIP_FACTOR + vec2<u32>(x, y);
            nearest = min(nearest, geometry_distance(textureLoad(lightfield_geometry, texel, id.z, 0).r));
        }
    }
    textureStore(target_low, id.xy, id.z, vec4<f32>(nearest, 0.0, 0.0, 0.0));
}
