// A workgroup's rays walked by lanes that fetch (issue 42): the workgroup takes a run of
// `count` rays, and a lane whose ray ends takes the run's next ray within the same loop, so
// that a warp's lanes keep walking while its longest ray does. With a ray a thread, a warp of
// incoherent rays walks as long as its longest ray while the finished lanes idle (Aila and
// Laine 2009's dynamic fetch, within a workgroup: a workgroup atomic rather than a global one).
//
// Only for a scene of one wide tree (GpuScene::fetches_rays: BLAS_WIDE and ONE_INSTANCE). The
// loop repeats trace_blas_wide's step by hand: a step shared as a function has cost the
// traversal 4.5–6 % before (notes/traversal.md).
//
// A dispatch of such workgroups gives each a run of fetch_run(rays, FETCH_WORKGROUPS) rays
// (dispatch.wgsl): a run grows past 64 only once the rays would fill more than FETCH_WORKGROUPS
// workgroups (a constant of the pass), so that the GPU stays full.
//
// The importing kernel defines
//   fn fetched_ray(k: u32) -> FetchedRay   the run's ray k (k < count), in world space;
//   fn fetched_hit(k: u32, hit: Hit)       what to do with its hit (hit.triangle INVALID: none);
// a lane calls fetched_hit(k) for the ray k of its last fetched_ray, before its next.
#import bvh
#import dispatch

struct FetchedRay {
    origin: vec3<f32>,
    t_max: f32,
    dir: vec3<f32>,
}

var<workgroup> next_fetched: atomic<u32>;

// Traces the workgroup's run of `count` rays, TRACE_CLOSEST, TRACE_ANY or TRACE_UNTIL (whose
// trace_stop fetched_ray sets for each ray). Every thread of the workgroup calls it, in uniform
// control flow (a barrier starts the run). Runs of 64 rays are walked by the same loop: a
// branch to a ray a thread through trace() beside it made the kernel's fetching runs 6–8 %
// slower (H200, notes/traversal.md).
fn trace_fetching(count: u32, mode: u32, local_index: u32) {
    if local_index == 0u {
        atomicStore(&next_fetched, 0u);
    }
    workgroupBarrier();
    let inst = instances[0];
    var k = 0u;
    var walking = false;
    var origin = vec3<f32>(0.0);
    var dir = vec3<f32>(0.0);
    var inv_dir = vec3<f32>(0.0);
    var oct_inv4 = 0u;
    var stack: array<vec2<u32>, BLAS_STACK_SIZE>;
    var sp = 0u;
    var node_group = vec2<u32>(0u);
    var triangle_group = vec2<u32>(0u);
    var hit: Hit;
    loop {
        if !walking {
            k = atomicAdd(&next_fetched, 1u);
            if k >= count {
                break;
            }
            let ray = fetched_ray(k);
            origin = to_object_point(inst, ray.origin);
            dir = to_object_vector(inst, ray.dir);
            inv_dir = safe_inverse(dir);
            oct_inv4 = wide_octant_inv4(dir);
            sp = 0u;
            // The root as trace_blas_wide starts it: one hit inner child at slot 0.
            node_group = vec2<u32>(inst.blas_root, 1u << (24u + (oct_inv4 & 7u)));
            triangle_group = vec2<u32>(0u);
            hit.t = min(ray.t_max, RAY_FAR);
            hit.triangle = INVALID;
            hit.instance = INVALID;
            hit.bary = vec2<f32>(0.0);
            walking = true;
        }
        var done = false;
        if (node_group.y & 0xff000000u) != 0u {
            let hits_imask = node_group.y;
            let bit = firstLeadingBit(hits_imask);
            node_group.y &= ~(1u << bit);
            if (node_group.y & 0xff000000u) != 0u && sp < BLAS_STACK_SIZE {
                stack[sp] = node_group;
                sp++;
            }
            let slot = (bit - 24u) ^ (oct_inv4 & 0xffu);
            let n = wide_node(node_group.x + countOneBits(hits_imask & ~(0xffffffffu << slot)));
            let hits = wide_intersect(n, origin, inv_dir, oct_inv4, hit.t);
            node_group = vec2<u32>(n.child_base, (hits & 0xff000000u) | (n.exponents_imask >> 24u));
            triangle_group = vec2<u32>(n.primitive_base, hits & 0x00ffffffu);
        }
        while triangle_group.y != 0u {
            let bit = firstLeadingBit(triangle_group.y);
            triangle_group.y &= ~(1u << bit);
            let i = triangle_group.x + bit;
            let tri = triangle_at(i);
            let r = intersect_triangle(tri, origin, dir, hit.t);
            if r.x < hit.t {
                if (tri.flags & TRIANGLE_ALPHA_TESTED) != 0u && is_alpha_hole(i, r.yz) {
                    continue;
                }
                hit.t = r.x;
                hit.triangle = i;
                hit.instance = 0u;
                hit.bary = r.yz;
                if mode == TRACE_ANY || (mode == TRACE_UNTIL && r.x < trace_stop) {
                    done = true;
                    break;
                }
            }
        }
        if !done && (node_group.y & 0xff000000u) == 0u {
            if sp == 0u {
                done = true;
            } else {
                sp--;
                node_group = stack[sp];
            }
        }
        if done {
            fetched_hit(k, hit);
            walking = false;
        }
    }
}
