// ssil/voxel_down: one level of the voxel grid from the level below, conservatively: a voxel
// is solid only where all four beneath it are (AND in x and y; the 128 slices stay).

@group(0) @binding(0) var source_voxels: texture_2d<u32>;
@group(0) @binding(1) var target_voxels: texture_storage_2d<rgba32uint, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(target_voxels);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let last = vec2<i32>(textureDimensions(source_voxels)) - 1;
    var mask = vec4<u32>(0xffffffffu);
    for (var k = 0; k < 4; k++) {
        let p = min(vec2<i32>(id.xy) * 2 + vec2<i32>(k & 1, k >> 1), last);
        mask &= textureLoad(source_voxels, p, 0);
    }
    textureStore(target_voxels, vec2<i32>(id.xy), mask);
}
