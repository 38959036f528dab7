// pathtrace/camera, pathtrace/hits, pathtrace/bounce, pathtrace/tail, pathtrace/shadows and
// pathtrace/shadow_resolve: the reference path tracer as a wavefront (PathSchedule::Wavefront).
// Each bounce pass takes one vertex of every live path, one thread a path: pathtrace/camera
// starts a path a pixel at its camera ray, and each pathtrace/bounce takes the paths the pass
// before left alive. A path that ends adds its radiance to its pixel; one that goes on is
// appended to the next pass's queue, which that pass's indirect dispatch covers exactly, so that
// no warp waits on the longest path of its pixels as the megakernel's do. The pass after the
// first WAVEFRONT_PASSES (wavefront.rs says why), pathtrace/tail, takes the paths left to their
// ends, and the host records no later pass. Its lanes fetch whole paths: a workgroup takes a
// run of the queue (fetch_run over at most TAIL_WORKGROUPS workgroups) and a lane whose path
// ends takes the run's next, so that a warp's lanes keep bouncing while its longest path does
// (bvh_fetch's dynamic fetch, a path rather than a ray at a time).
// FETCH_RAYS (0 or 1, Wavefront::new in wavefront.rs: where GpuScene::fetches_rays): before each
// pathtrace/bounce, pathtrace/hits finds the closest hits of the queue's rays with lanes that
// fetch their next ray (bvh_fetch), a workgroup a run of them, and pathtrace/bounce shades
// from those hits instead of tracing a ray a thread; only while the paths alive are more than
// FETCH_WORKGROUPS runs of 64 (fetch_pays), since a lane with one ray gains nothing from it. The
// camera's rays, neighbours in a tile, keep a ray a thread.
// SHADOWS_APART (0 or 1; only with FETCH_RAYS, where a vertex's lights and emitter sample take
// at most DEFERRED_SHADOWS_MAX shadow rays): in a sample's first WAVEFRONT_PASSES passes,
// while they hold more paths than FETCH_WORKGROUPS runs of 64, pathtrace/camera and
// pathtrace/bounce defer their vertices' shadow rays (SHADOW_SLOTS a vertex at most, path.wgsl's
// DeferredShadow) to a queue. pathtrace/shadows traces it with lanes that fetch and zeroes the
// light of each blocked ray; pathtrace/shadow_resolve then adds each path's light that arrived
// to its pixel, a thread a path of the pass, so that no two lanes add to one pixel at once.
// A non-finite sample (finite_or_zero) is then dropped in two parts, the deferred light and the
// rest, where the megakernel drops the whole: the schedules differ only on such samples.
// WAVEFRONT_STAGE (STAGE_CAMERA … STAGE_TAIL below): which of the six kinds of pass.
#import path
#import pathtrace_params
#import dispatch
#import random
#import bvh_fetch

const STAGE_CAMERA: u32 = 0u;
const STAGE_HITS: u32 = 1u;
const STAGE_BOUNCE: u32 = 2u;
const STAGE_SHADOWS: u32 = 3u;
const STAGE_RESOLVE: u32 = 4u;
const STAGE_TAIL: u32 = 5u;

// A queue of live paths. Its first 16 bytes are the indirect dispatch that takes them (its
// count, then the workgroups in x, y, z), a thread a path; with FETCH_RAYS the next 12 after
// the bounce are pathtrace/hits' dispatch over them, a run of fetch_run paths a workgroup, and
// where the tail takes the queue the 12 after those are its dispatch, a run of fetch_run over
// TAIL_WORKGROUPS a workgroup. The host clears the header (48 bytes) before a pass appends.
struct GpuPathQueue {
    count: atomic<u32>,
    groups_x: atomic<u32>,
    groups_y: atomic<u32>,
    groups_z: atomic<u32>,
    // the bounce the queued paths take next
    bounce: atomic<u32>,
    runs_x: atomic<u32>,
    runs_y: atomic<u32>,
    runs_z: atomic<u32>,
    tail_x: atomic<u32>,
    tail_y: atomic<u32>,
    tail_z: atomic<u32>,
    _pad: u32,
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
    runs_x: u32,
    runs_y: u32,
    runs_z: u32,
    tail_x: u32,
    tail_y: u32,
    tail_z: u32,
    _pad: u32,
    paths: array<PathState>,
}

@group(1) @binding(2) var<storage, read> paths_in: GpuPathQueueRead;
@group(1) @binding(3) var<storage, read_write> paths_out: GpuPathQueue;

// The closest hit of a queued path's ray (pathtrace/hits writes it at the path's place in the
// queue, pathtrace/bounce reads it there). Only scenes of one instance fetch (bvh_fetch), so a
// hit's instance is 0.
struct GpuPathHit {
    t: f32,
    // INVALID: the ray left the scene
    triangle: u32,
    bary: vec2<f32>,
}

@group(1) @binding(4) var<storage, read_write> hits: array<GpuPathHit>;

// The shadow rays a pass deferred. Its header: pathtrace/shadows' dispatch (the rays' count,
// then x, y, z in runs), pathtrace/shadow_resolve's (x, y, z, a thread a path of the pass) and
// how many of `spans` it reads. The host clears the header (32 bytes) before each pass.
struct GpuShadowQueue {
    count: atomic<u32>,
    runs_x: atomic<u32>,
    runs_y: atomic<u32>,
    runs_z: atomic<u32>,
    resolve_x: atomic<u32>,
    resolve_y: atomic<u32>,
    resolve_z: atomic<u32>,
    spans: atomic<u32>,
    rays: array<DeferredShadow>,
}

@group(1) @binding(5) var<storage, read_write> shadows: GpuShadowQueue;
// A path of the pass's deferred rays: (first, count, pixel, 0), at its thread's place.
@group(1) @binding(6) var<storage, read_write> shadow_spans: array<vec4<u32>>;

const THREADS: u32 = 64u;
var<workgroup> appended_in_group: atomic<u32>;
var<workgroup> group_base: u32;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) local_index: u32) {
    bvh_thread(local_index);
    if WAVEFRONT_STAGE == STAGE_HITS {
        let run = fetch_run(paths_in.count, FETCH_WORKGROUPS);
        run_first = folded_index(group) * run;
        let left = paths_in.count - min(run_first, paths_in.count);
        trace_fetching(min(left, run), TRACE_CLOSEST, local_index);
        return;
    }
    if WAVEFRONT_STAGE == STAGE_SHADOWS {
        let count = atomicLoad(&shadows.count);
        let run = fetch_run(count, FETCH_WORKGROUPS);
        run_first = folded_index(group) * run;
        let left = count - min(run_first, count);
        trace_fetching(min(left, run), TRACE_UNTIL, local_index);
        return;
    }
    if WAVEFRONT_STAGE == STAGE_RESOLVE {
        resolve_shadows(folded_index(group) * THREADS + local_index);
        return;
    }
    var path: PathState;
    var valid = false;
    var bounce = 0u;
    // The path's place in paths_in (and its hit's), for the bounce pass.
    var i = folded_index(group) * THREADS + local_index;
    if WAVEFRONT_STAGE == STAGE_CAMERA {
        // One 8×8 tile a workgroup, as the megakernel's: neighbouring camera rays together.
        valid = id.x < params.width && id.y < params.height;
        var rng = rng_seed(id.y * params.width + id.x, params.sample_offset, params.seed);
        let dir = pixel_ray_dir(params, id.xy, &rng);
        path = path_start(params.camera.position, dir, rng, id.x | (id.y << 16u));
    } else {
        bounce = paths_in.bounce;
        valid = WAVEFRONT_STAGE == STAGE_TAIL || i < paths_in.count;
        if valid && WAVEFRONT_STAGE == STAGE_BOUNCE {
            path = paths_in.paths[i];
        }
    }
    // The tail's run of the queue: its lanes take each path from it in the loop below.
    var run_count = 0u;
    if WAVEFRONT_STAGE == STAGE_TAIL {
        let run = fetch_run(paths_in.count, TAIL_WORKGROUPS);
        run_first = folded_index(group) * run;
        run_count = min(paths_in.count - min(run_first, paths_in.count), run);
        if local_index == 0u {
            atomicStore(&next_tail_path, 0u);
        }
        workgroupBarrier();
    }
    // The pass's paths: every pixel's at the camera, else those the pass before left alive.
    let pass_paths = select(paths_in.count, params.width * params.height, WAVEFRONT_STAGE == STAGE_CAMERA);
    let shadows_apart = SHADOWS_APART == 1u && bounce < WAVEFRONT_PASSES && fetch_pays(pass_paths, FETCH_WORKGROUPS);
    if shadows_apart {
        defer_up_to = SHADOW_SLOTS;
    }
    var alive = false;
    if valid {
        // Where pathtrace/hits found the queue's closest hits: a path's first step here.
        let fetched = WAVEFRONT_STAGE != STAGE_CAMERA && FETCH_RAYS == 1u && fetch_pays(paths_in.count, FETCH_WORKGROUPS);
        // One call site of the shading and one of the trace: each is inlined where called.
        // A bounce pass steps once; a tail lane steps until its run has no path left.
        var step = bounce;
        loop {
            if WAVEFRONT_STAGE == STAGE_TAIL && !alive {
                let k = atomicAdd(&next_tail_path, 1u);
                if k >= run_count {
                    break;
                }
                i = run_first + k;
                path = paths_in.paths[i];
                step = bounce;
            }
            var hit: Hit;
            if fetched && step == bounce {
                let found = hits[i];
                let instance = select(0u, INVALID, found.triangle == INVALID);
                hit = Hit(found.t, found.triangle, instance, found.bary);
            } else {
                hit = trace_ray(path.origin, path.dir, RAY_FAR, false);
            }
            alive = path_step_at(&path, hit, step, params.max_bounces, true, params.light_sampling);
            step++;
            if !alive {
                let pixel = vec2<u32>(path.pixel & 0xffffu, path.pixel >> 16u);
                let sample = vec4<f32>(finite_or_zero(path.radiance), 1.0);
                textureStore(accumulation, pixel, textureLoad(accumulation, pixel) + sample);
            }
            if WAVEFRONT_STAGE != STAGE_TAIL {
                break;
            }
        }
    }
    if WAVEFRONT_STAGE == STAGE_TAIL {
        return;
    }
    append(alive, path, bounce + 1u, local_index);
    if shadows_apart {
        // A workgroup's place among the pass's: the camera's 8×8 tiles row by row.
        let tiles_x = (params.width + 7u) / 8u;
        let group_index = select(folded_index(group), group.x + group.y * tiles_x, WAVEFRONT_STAGE == STAGE_CAMERA);
        append_shadows(valid, group_index, path.pixel, local_index);
    }
}

// pathtrace/hits' and pathtrace/tail's first queued path in this workgroup's run.
var<private> run_first: u32;
// The tail's next path in its workgroup's run.
var<workgroup> next_tail_path: atomic<u32>;

fn fetched_ray(k: u32) -> FetchedRay {
    if WAVEFRONT_STAGE == STAGE_SHADOWS {
        let ray = shadows.rays[run_first + k];
        trace_stop = ray.stop;
        return FetchedRay(ray.origin, ray.t_max, ray.dir);
    }
    let path = paths_in.paths[run_first + k];
    return FetchedRay(path.origin, RAY_FAR, path.dir);
}

fn fetched_hit(k: u32, hit: Hit) {
    if WAVEFRONT_STAGE == STAGE_SHADOWS {
        // Arrived: the closest hit is the emitter's point, or none for a punctual light (the
        // scene is one instance: every hit's is 0).
        if hit.triangle != shadows.rays[run_first + k].emitter_triangle {
            shadows.rays[run_first + k].light = vec3<f32>(0.0);
        }
        return;
    }
    hits[run_first + k] = GpuPathHit(hit.t, hit.triangle, hit.bary);
}

var<workgroup> shadows_in_group: atomic<u32>;
var<workgroup> group_has_paths: atomic<u32>;
var<workgroup> shadow_base: u32;

// Appends the workgroup's deferred shadow rays to `shadows` with one global atomic, raises
// pathtrace/shadows' dispatch to cover them (as append does for pathtrace/hits) and
// pathtrace/shadow_resolve's to cover this workgroup's paths, and writes each thread's span
// at its place, `group_index` × THREADS + its index (none where the workgroup has no path).
fn append_shadows(valid: bool, group_index: u32, pixel: u32, local_index: u32) {
    if local_index == 0u {
        atomicStore(&shadows_in_group, 0u);
        atomicStore(&group_has_paths, 0u);
    }
    workgroupBarrier();
    let count = select(0u, deferred_count, valid);
    let place = atomicAdd(&shadows_in_group, count);
    if valid {
        atomicStore(&group_has_paths, 1u);
    }
    workgroupBarrier();
    if local_index == 0u {
        let in_group = atomicLoad(&shadows_in_group);
        var base = 0u;
        if in_group > 0u {
            base = atomicAdd(&shadows.count, in_group);
            let runs = fetch_groups(base + in_group, FETCH_WORKGROUPS);
            atomicMax(&shadows.runs_x, runs.x);
            atomicMax(&shadows.runs_y, runs.y);
            atomicMax(&shadows.runs_z, 1u);
        }
        if atomicLoad(&group_has_paths) != 0u {
            let resolve = folded_groups(group_index + 1u);
            atomicMax(&shadows.resolve_x, resolve.x);
            atomicMax(&shadows.resolve_y, resolve.y);
            atomicMax(&shadows.resolve_z, 1u);
            atomicMax(&shadows.spans, (group_index + 1u) * THREADS);
        }
        shadow_base = base;
    }
    workgroupBarrier();
    if atomicLoad(&group_has_paths) != 0u {
        let first = shadow_base + place;
        shadow_spans[group_index * THREADS + local_index] = vec4<u32>(first, count, pixel, 0u);
        for (var j = 0u; j < count; j++) {
            shadows.rays[first + j] = deferred[j];
        }
    }
}

// Adds the light of the span at `index` that arrived to its pixel.
fn resolve_shadows(index: u32) {
    if index >= atomicLoad(&shadows.spans) {
        return;
    }
    let span = shadow_spans[index];
    if span.y == 0u {
        return;
    }
    var light = vec3<f32>(0.0);
    for (var j = 0u; j < span.y; j++) {
        light += shadows.rays[span.x + j].light;
    }
    let pixel = vec2<u32>(span.z & 0xffffu, span.z >> 16u);
    textureStore(accumulation, pixel, textureLoad(accumulation, pixel) + vec4<f32>(finite_or_zero(light), 0.0));
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
            let in_queue = base + count;
            if next_bounce == WAVEFRONT_PASSES {
                // The tail takes this queue (the last workgroup to append sets its runs).
                let tail = fetch_groups(in_queue, TAIL_WORKGROUPS);
                atomicMax(&paths_out.tail_x, tail.x);
                atomicMax(&paths_out.tail_y, tail.y);
                atomicMax(&paths_out.tail_z, 1u);
            }
            if FETCH_RAYS == 1u && fetch_pays(in_queue, FETCH_WORKGROUPS) {
                // The last workgroup to append counts every queued path, and the maximum
                // covers its runs (ddgi/shade's shadow queue does the same). Fewer paths than
                // that leave pathtrace/hits no workgroup, and pathtrace/bounce traces them.
                let runs = fetch_groups(in_queue, FETCH_WORKGROUPS);
                atomicMax(&paths_out.runs_x, runs.x);
                atomicMax(&paths_out.runs_y, runs.y);
                atomicMax(&paths_out.runs_z, 1u);
            }
        }
        group_base = base;
    }
    workgroupBarrier();
    if alive {
        paths_out.paths[group_base + place] = path;
    }
}
