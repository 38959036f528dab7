// ssil/voxelize: solid voxelization of the view frustum (Eisemann and Décoret 2008), at the
// start level's resolution with 128 depth slices a texel, one bit each. Instead of rasterizing
// every triangle with XOR blending, each texel's camera ray walks through every surface it
// crosses (one closest-hit trace after another through our BVH) and, at each crossing, flips
// every slice from the crossing's slice on: the XOR parity that makes the inside of closed
// objects solid. Exact per texel, independent of the triangle count, and the same traversal
// the rest of Irradiant uses. A ray that ends inside (an odd number of crossings) met an open
// surface: it is counted, so that the scene's watertightness can be reported.
#import ssil_common
#import bvh
#import camera

@group(2) @binding(0) var<uniform> ssil: GpuSsilParams;
@group(2) @binding(1) var target_voxels: texture_storage_2d<rgba32uint, write>;
@group(2) @binding(2) var<storage, read_write> ssil_counters: array<atomic<u32>>;
@group(1) @binding(0) var<uniform> frame: GpuFrameParams;

// Surfaces a ray may cross before it gives up (Sponza's deepest rays cross about 20).
const MAX_CROSSINGS: u32 = 64u;

// Every slice from `slice` on.
fn slices_from(slice: i32) -> vec4<u32> {
    var mask = vec4<u32>(0u);
    for (var w = 0; w < 4; w++) {
        let first = w * 32;
        if slice <= first {
            mask[w] = 0xffffffffu;
        } else if slice < first + 32 {
            mask[w] = 0xffffffffu << u32(slice - first);
        }
    }
    return mask;
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    let size = level_size(ssil.start_level);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let image = vec2<f32>(f32(frame.width), f32(frame.height));
    let dir = camera_ray_dir(frame.camera, level_to_image(vec2<f32>(id.xy) + 0.5, ssil.start_level), image);
    let cos_forward = dot(dir, frame.camera.forward);
    var mask = vec4<u32>(0u);
    var travelled = 0.0;
    var crossings = 0u;
    for (; crossings < MAX_CROSSINGS; crossings++) {
        let hit = trace_ray(frame.camera.position + dir * travelled, dir, RAY_FAR, false);
        if hit.triangle == INVALID {
            break;
        }
        travelled += hit.t;
        mask ^= slices_from(slice_of(travelled * cos_forward));
        // Past the surface, by a margin that grows with the distance (f32 precision).
        travelled += 1e-4 * max(1.0, travelled);
    }
    if crossings % 2u == 1u {
        atomicAdd(&ssil_counters[0], 1u);
    }
    atomicAdd(&ssil_counters[1], 1u);
    textureStore(target_voxels, vec2<i32>(id.xy), mask);
}
