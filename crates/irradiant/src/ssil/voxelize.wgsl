// ssil/voxelize: solid voxelization of the view frustum (Eisemann and Décoret 2008), at the
// start level's resolution with 128 depth slices a texel, one bit each. Instead of rasterizing
// every triangle with XOR blending, each texel's camera ray collects every surface it crosses
// through our BVH (trace_crossings) and, at each crossing, flips every slice from the
// crossing's slice on: the XOR parity that makes the inside of closed objects solid. Exact per
// texel, independent of the triangle count, and the same traversal the rest of Irradiant uses.
// VOXEL_SEGMENTS threads share a ray, each tracing its share of the depth range; their masks
// combine by XOR. Crossings closer than the ray's precision are one surface: a ray through the
// edge two triangles share hits both. A ray that ends inside (an odd number of crossings) is
// counted, so that the share of open geometry in view can be reported.
#import ssil_common
#import bvh
#import camera

@group(2) @binding(0) var<uniform> ssil: GpuSsilParams;
@group(2) @binding(1) var target_voxels: texture_storage_2d<rgba32uint, write>;
@group(2) @binding(2) var<storage, read_write> ssil_counters: array<atomic<u32>>;
@group(1) @binding(0) var<uniform> frame: GpuFrameParams;

const TEXELS_PER_GROUP: u32 = VOXEL_TILE * VOXEL_TILE;
// Each thread's mask and crossing count, for its texel's first segment to combine.
var<workgroup> segment_masks: array<vec4<u32>, VOXEL_SEGMENTS * TEXELS_PER_GROUP>;
var<workgroup> segment_crossings: array<u32, VOXEL_SEGMENTS * TEXELS_PER_GROUP>;

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

// The parity mask of the crossings of `dir` between distances t0 and t1, and their count.
fn segment_parity(dir: vec3<f32>, t0: f32, t1: f32, cos_forward: f32, count: ptr<function, u32>) -> vec4<u32> {
    let found = min(trace_crossings(frame.camera.position + dir * t0, dir, t1 - t0), MAX_CROSSINGS);
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
    var last = 0.0;
    for (var i = 0u; i < found; i++) {
        let t = t0 + crossing_distances[i];
        // Within the margin of the last surface kept (f32 precision): the same surface.
        if *count > 0u && t - last < 1e-4 * max(1.0, last) {
            continue;
        }
        mask ^= slices_from(slice_of(t * cos_forward));
        *count += 1u;
        last = t;
    }
    return mask;
}

// Workgroup: VOXEL_TILE × VOXEL_TILE texels, VOXEL_SEGMENTS threads each (x: the segment).
@compute @workgroup_size(VOXEL_SEGMENTS, TEXELS_PER_GROUP, 1)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_id) local: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    let size = level_size(ssil.start_level);
    let texel = group.xy * VOXEL_TILE + vec2<u32>(local.y % VOXEL_TILE, local.y / VOXEL_TILE);
    let inside = all(texel < size);
    var mask = vec4<u32>(0u);
    var count = 0u;
    if inside {
        let image = vec2<f32>(f32(frame.width), f32(frame.height));
        let dir = camera_ray_dir(frame.camera, level_to_image(vec2<f32>(texel) + 0.5, ssil.start_level), image);
        let cos_forward = dot(dir, frame.camera.forward);
        // The segment's share of the grid's depth range (the first from the camera, the last
        // to the end of the ray).
        let segment = local.x;
        let depth = ssil.near + (ssil.far - ssil.near) * vec2<f32>(f32(segment), f32(segment + 1u)) / f32(VOXEL_SEGMENTS);
        let t0 = select(depth.x / cos_forward, 0.0, segment == 0u);
        let t1 = select(depth.y / cos_forward, RAY_FAR, segment + 1u == VOXEL_SEGMENTS);
        mask = segment_parity(dir, t0, t1, cos_forward, &count);
    }
    let slot = local.y * VOXEL_SEGMENTS + local.x;
    segment_masks[slot] = mask;
    segment_crossings[slot] = count;
    workgroupBarrier();
    if local.x != 0u || !inside {
        return;
    }
    for (var k = 1u; k < VOXEL_SEGMENTS; k++) {
        mask ^= segment_masks[slot + k];
        count += segment_crossings[slot + k];
    }
    if count % 2u == 1u {
        atomicAdd(&ssil_counters[0], 1u);
    }
    atomicAdd(&ssil_counters[1], 1u);
    textureStore(target_voxels, vec2<i32>(texel), mask);
}
