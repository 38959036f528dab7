// ssil/voxelize: solid voxelization of the view frustum (Eisemann and Décoret 2008), at the
// start level's resolution with 128 depth slices a texel, one bit each. Instead of rasterizing
// every triangle with XOR blending, each texel's camera ray collects every surface it crosses
// in one traversal of our BVH (trace_crossings) and, at each crossing, flips every slice from
// the crossing's slice on: the XOR parity that makes the inside of closed objects solid. Exact
// per texel, independent of the triangle count, and the same traversal the rest of Irradiant
// uses. Crossings closer than the ray's precision are one surface: a ray through the edge two
// triangles share hits both. A ray that ends inside (an odd number of crossings) is counted,
// so that the share of open geometry in view can be reported.
#import ssil_common
#import bvh
#import camera

@group(2) @binding(0) var<uniform> ssil: GpuSsilParams;
@group(2) @binding(1) var target_voxels: texture_storage_2d<rgba32uint, write>;
@group(2) @binding(2) var<storage, read_write> ssil_counters: array<atomic<u32>>;
@group(1) @binding(0) var<uniform> frame: GpuFrameParams;

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
    let found = min(trace_crossings(frame.camera.position, dir, RAY_FAR), MAX_CROSSINGS);
    // Nearest first (insertion sort: a few dozen at most).
    for (var i = 1u; i < found; i++) {
        let t = crossing_distances[i];
        var j = i;
        while j > 0u && crossing_distances[j - 1u] > t {
            crossing_distances[j] = crossing_distances[j - 1u];
            j--;
        }
        crossing_distances[j] = t;
    }
    var mask = vec4<u32>(0u);
    var crossings = 0u;
    var last = 0.0;
    for (var i = 0u; i < found; i++) {
        let t = crossing_distances[i];
        // Within the margin of the last surface kept (f32 precision): the same surface.
        if crossings > 0u && t - last < 1e-4 * max(1.0, last) {
            continue;
        }
        mask ^= slices_from(slice_of(t * cos_forward));
        crossings++;
        last = t;
    }
    if crossings % 2u == 1u {
        atomicAdd(&ssil_counters[0], 1u);
    }
    atomicAdd(&ssil_counters[1], 1u);
    textureStore(target_voxels, vec2<i32>(id.xy), mask);
}
