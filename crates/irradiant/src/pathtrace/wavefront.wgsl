// pathtrace/camera and pathtrace/bounce: the reference path tracer as a wavefront
// (PathSchedule::Wavefront). Each pass takes one vertex of every live path, one thread a path:
// pathtrace/camera starts a path a pixel at its camera ray, and each pathtrace/bounce takes the
// paths the pass before left alive. A path that ends adds its radiance to its pixel; one that
// goes on is appended to the next pass's queue, which that pass's indirect dispatch covers
// exactly, so that no warp waits on the longest path of its pixels as the megakernel's do.
// WAVEFRONT_CAMERA (0 or 1, from Wavefront::new in wavefront.rs): which of the two passes.
#import path
#import pathtrace_params
#import dispatch
#import random

// A queue of live paths. Its first 16 bytes are the indirect dispatch that takes them (its
// count, then the workgroups in x, y, z); the host clears the header (32 bytes, the bounce
// with it) before a pass appends.
struct GpuPathQueue {
    count: atomic<u32>,
    groups_x: atomic<u32>,
    groups_y: atomic<u32>,
    groups_z: atomic<u32>,
    // the bounce the queued paths take next
    bounce: atomic<u32>,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
    paths: array<PathState>,
}

@group(1) @binding(0) var<uniform> params: GpuPathTraceParams;
// rgb: sum of radiance samples; a: their count
@group(1) @binding(1) var accumulation: texture_storage_2d<rgba32float, read_write>;
// The queue a pass takes its paths from, read only: it is this pass's indirect dispatch too.
struct GpuPathQueueRead {
    count: u32,
    groups_x: u32,
    groups_y: u32,
    groups_z: u32,
    bounce: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
    paths: array<PathState>,
}

@group(1) @binding(2) var<storage, read> paths_in: GpuPathQueueRead;
@group(1) @binding(3) var<storage, read_write> paths_out: GpuPathQueue;

const THREADS: u32 = 64u;
var<workgroup> appended_in_group: atomic<u32>;
var<workgroup> group_base: u32;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    var path: PathState;
    var valid = false;
    var bounce = 0u;
    if WAVEFRONT_CAMERA == 1u {
        // One 8×8 tile a workgroup, as the megakernel's: neighbouring camera rays together.
        valid = id.x < params.width && id.y < params.height;
        var rng = rng_seed(id.y * params.width + id.x, params.sample_offset, params.seed);
        let dir = pixel_ray_dir(params, id.xy, &rng);
        path = path_start(params.camera.position, dir, rng, id.x | (id.y << 16u));
    } else {
        let i = folded_index(group) * THREADS + local_index;
        valid = i < paths_in.count;
        bounce = paths_in.bounce;
        if valid {
            path = paths_in.paths[i];
        }
    }
    var alive = false;
    if valid {
        alive = path_step(&path, bounce, params.max_bounces, true, params.light_sampling);
        if !alive {
            let pixel = vec2<u32>(path.pixel & 0xffffu, path.pixel >> 16u);
            let sample = vec4<f32>(finite_or_zero(path.radiance), 1.0);
            textureStore(accumulation, pixel, textureLoad(accumulation, pixel) + sample);
        }
    }
    append(alive, path, bounce + 1u, local_index);
}

// Appends the workgroup's live paths to paths_out with one global atomic a workgroup, and
// raises the next pass's indirect dispatch to cover them: ddgi/shade's enqueue_shadow for
// another queue, since WGSL (naga) passes no pointer to storage into a function.
fn append(alive: bool, path: PathState, next_bounce: u32, local_index: u32) {
    if local_index == 0u {
        atomicStore(&appended_in_group, 0u);
    }
    workgroupBarrier();
    var place = 0u;
    if alive {
        place = atomicAdd(&appended_in_group, 1u);
    }
    workgroupBarrier();
    if local_index == 0u {
        let count = atomicLoad(&appended_in_group);
        var base = 0u;
        if count > 0u {
            base = atomicAdd(&paths_out.count, count);
            let groups = folded_groups((base + count + THREADS - 1u) / THREADS);
            atomicMax(&paths_out.groups_x, groups.x);
            atomicMax(&paths_out.groups_y, groups.y);
            atomicMax(&paths_out.groups_z, 1u);
            atomicMax(&paths_out.bounce, next_bounce);
        }
        group_base = base;
    }
    workgroupBarrier();
    if alive {
        paths_out.paths[group_base + place] = path;
    }
}
