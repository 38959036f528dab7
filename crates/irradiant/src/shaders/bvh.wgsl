// Two-level BVH traversal in compute: a top level over instances, a bottom level per mesh.
// Nodes hold both children's boxes; the nearer inner child is visited first, the other
// pushed on a per-thread stack; leaves are intersected as soon as their box is hit.
#import scene

// BLAS_STACK_SIZE and TLAS_STACK_SIZE come from GpuScene::shader_constants: the stacks are
// exactly as deep as the scene's trees, which keeps per-thread memory small. BLAS_WIDE (0 or
// 1, from there too) picks the bottom level's layout: binary nodes in bvh_nodes, or
// compressed 8-wide nodes in wide_nodes.
// ONE_INSTANCE (0 or 1, from there too) is 1 where the scene holds one instance for good.
// STACK_IN_WORKGROUP (0 or 1, also from there) puts the bottom-level stack in workgroup memory,
// a slice per thread; every tracing kernel runs 64 threads a workgroup and calls
// bvh_thread(local_invocation_index) first.

// COUNT_WORK (0 or 1, from there too; 1 only in raycast/trace's counting variant) counts the
// node visits and triangle tests of the last trace() in work_nodes and work_triangles.
var<private> work_nodes: u32;
var<private> work_triangles: u32;

const STACK_THREADS: u32 = 64u;
var<workgroup> blas_stack_memory: array<u32, STACK_THREADS * BLAS_STACK_SIZE * STACK_IN_WORKGROUP + 1u>;
var<private> bvh_stack_base: u32;

fn bvh_thread(local_index: u32) {
    bvh_stack_base = local_index * BLAS_STACK_SIZE;
}
const NO_HIT: f32 = 3.0e38;
// Rays never reach beyond this, so an absent child's box (a point at 1e30) is never hit.
const RAY_FAR: f32 = 1.0e20;
const INVALID: u32 = 0xffffffffu;

// What a traversal looks for: the closest hit, any hit (shadow rays), every crossing
// (trace_crossings), or the closest hit unless a hit nearer than trace_stop ends the search
// (trace_ray_until).
const TRACE_CLOSEST: u32 = 0u;
const TRACE_ANY: u32 = 1u;
const TRACE_ALL: u32 = 2u;
const TRACE_UNTIL: u32 = 3u;
// TRACE_UNTIL's distance, a private variable rather than a parameter: a parameter carried through
// every traversal made closest-hit passes that never stop early up to 8 % slower (H100).
var<private> trace_stop: f32;

// trace_crossings' record: the distance of every surface the ray crosses, in the order the
// traversal finds them (the first MAX_CROSSINGS), and how many it crossed.
var<private> crossing_distances: array<f32, MAX_CROSSINGS>;
var<private> crossing_count: u32;

fn record_crossing(t: f32) {
    if crossing_count < MAX_CROSSINGS {
        crossing_distances[crossing_count] = t;
    }
    crossing_count++;
}

struct Hit {
    t: f32,
    triangle: u32,
    instance: u32,
    bary: vec2<f32>,
}

fn safe_inverse(d: vec3<f32>) -> vec3<f32> {
    // A zero component would give 0 × ∞ = NaN in the slab test.
    let tiny = vec3<f32>(1e-20);
    let fixed = select(d, select(-tiny, tiny, d >= vec3<f32>(0.0)), abs(d) < tiny);
    return 1.0 / fixed;
}

// Entry distance of the ray into the box, or NO_HIT.
fn slab(origin: vec3<f32>, inv_dir: vec3<f32>, lo: vec3<f32>, hi: vec3<f32>, t_max: f32) -> f32 {
    let t0 = (lo - origin) * inv_dir;
    let t1 = (hi - origin) * inv_dir;
    let near = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), max(min(t0.z, t1.z), 0.0));
    let far = min(min(min(max(t0.x, t1.x), max(t0.y, t1.y)), max(t0.z, t1.z)) * SLAB_FAR_SCALE, t_max);
    return select(NO_HIT, near, near <= far);
}

// Möller–Trumbore; returns (t, u, v) with t = NO_HIT on a miss.
fn intersect_triangle(tri: GpuTriangle, origin: vec3<f32>, dir: vec3<f32>, t_max: f32) -> vec3<f32> {
    let p = cross(dir, tri.e2);
    let det = dot(tri.e1, p);
    let inv = 1.0 / det;
    let s = origin - tri.v0;
    let u = dot(s, p) * inv;
    let q = cross(s, tri.e1);
    let v = dot(dir, q) * inv;
    let t = dot(tri.e2, q) * inv;
    let hit = abs(det) > 1e-20 && u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 && t < t_max;
    return select(vec3<f32>(NO_HIT, 0.0, 0.0), vec3<f32>(t, u, v), hit);
}

// Walks one bottom-level tree with the ray in its object space, updating `hit` (a ray's t is
// the same in object and world space). With TRACE_ANY, returns true at the first hit, and with
// TRACE_UNTIL at the first hit nearer than trace_stop; with TRACE_ALL, records every crossing
// and leaves `hit` as it was.
fn trace_blas(root: u32, instance: u32, origin: vec3<f32>, dir: vec3<f32>, mode: u32, hit: ptr<function, Hit>) -> bool {
    if BLAS_WIDE == 1u {
        return trace_blas_wide(root, instance, origin, dir, mode, hit);
    }
    let inv_dir = safe_inverse(dir);
    var stack: array<u32, BLAS_STACK_SIZE>;
    var sp = 0u;
    var node = root;
    loop {
        let n = bvh_nodes[node];
        if COUNT_WORK == 1u {
            work_nodes++;
        }
        let ta = slab(origin, inv_dir, n.a_min, n.a_max, (*hit).t);
        let tb = slab(origin, inv_dir, n.b_min, n.b_max, (*hit).t);
        // Leaves first: a hit shortens the ray before the inner children are ordered.
        for (var k = 0u; k < 2u; k++) {
            let t_box = select(tb, ta, k == 0u);
            let count = select(n.b_count, n.a_count, k == 0u);
            let first = select(n.b_first, n.a_first, k == 0u);
            if t_box < (*hit).t && count > 0u {
                for (var i = first; i < first + count; i++) {
                    if COUNT_WORK == 1u {
                        work_triangles++;
                    }
                    let tri = triangle_at(i);
                    let r = intersect_triangle(tri, origin, dir, (*hit).t);
                    if r.x < (*hit).t {
                        if (tri.flags & TRIANGLE_ALPHA_TESTED) != 0u && is_alpha_hole(i, r.yz) {
                            continue;
                        }
                        if mode == TRACE_ALL {
                            record_crossing(r.x);
                            continue;
                        }
                        (*hit).t = r.x;
                        (*hit).triangle = i;
                        (*hit).instance = instance;
                        (*hit).bary = r.yz;
                        if mode == TRACE_ANY || (mode == TRACE_UNTIL && r.x < trace_stop) {
                            return true;
                        }
                    }
                }
            }
        }
        let go_a = ta < (*hit).t && n.a_count == 0u && n.a_first != INVALID;
        let go_b = tb < (*hit).t && n.b_count == 0u && n.b_first != INVALID;
        if go_a && go_b {
            let a_first = ta <= tb;
            node = select(n.b_first, n.a_first, a_first);
            if sp < BLAS_STACK_SIZE {
                let far = select(n.a_first, n.b_first, a_first);
                if STACK_IN_WORKGROUP == 1u {
                    blas_stack_memory[bvh_stack_base + sp] = far;
                } else {
                    stack[sp] = far;
                }
                sp++;
            }
        } else if go_a {
            node = n.a_first;
        } else if go_b {
            node = n.b_first;
        } else {
            if sp == 0u {
                break;
            }
            sp--;
            if STACK_IN_WORKGROUP == 1u {
                node = blas_stack_memory[bvh_stack_base + sp];
            } else {
                node = stack[sp];
            }
        }
    }
    return false;
}

// The wide bottom level (BLAS_WIDE == 1): compressed 8-wide nodes (irradiant_bvh::wide,
// Ylitie, Karras and Laine 2017). The traversal keeps two groups: the node group (a node's
// children still to visit: child_base and, in bits 24–31, one bit per hit inner child,
// ordered near to far; bits 0–7 keep imask for finding a child's index) and the triangle
// group (primitive_base and one bit per hit triangle slot in bits 0–23). The stack holds node
// groups only, so it needs one entry a tree level.

// 0x04040404 etc. for a ray going up x, y or z: XORed with an inner child's slot it gives the
// child's place in the near-to-far order the builder laid the slots out for.
fn wide_octant_inv4(dir: vec3<f32>) -> u32 {
    return select(0u, 0x04040404u, dir.x >= 0.0) | select(0u, 0x02020202u, dir.y >= 0.0) | select(0u, 0x01010101u, dir.z >= 0.0);
}

// The bits of four children (one word of child_meta) for a hit mask: inner children set bit
// 24 + (slot ^ octant), leaves set their triangle slots' bits.
fn wide_hits4(meta4: u32, oct_inv4: u32, lo_x: u32, hi_x: u32, lo_y: u32, hi_y: u32, lo_z: u32, hi_z: u32, scale_dir: vec3<f32>, shift: vec3<f32>, t_max: f32) -> u32 {
    // Bit 4 of a byte is set in both meta4 and meta4 << 1 only for inner children (24–31).
    let inner = ((meta4 & (meta4 << 1u)) & 0x10101010u) >> 4u;
    let bit_index4 = (meta4 ^ (oct_inv4 & (inner * 0xffu))) & 0x1f1f1f1fu;
    let child_bits4 = (meta4 >> 5u) & 0x07070707u;
    var hits = 0u;
    for (var k = 0u; k < 4u; k++) {
        let s = 8u * k;
        let lo = vec3<f32>(f32((lo_x >> s) & 0xffu), f32((lo_y >> s) & 0xffu), f32((lo_z >> s) & 0xffu)) * scale_dir + shift;
        let hi = vec3<f32>(f32((hi_x >> s) & 0xffu), f32((hi_y >> s) & 0xffu), f32((hi_z >> s) & 0xffu)) * scale_dir + shift;
        let near = max(max(lo.x, lo.y), max(lo.z, 0.0));
        let far = min(min(min(hi.x, hi.y), hi.z) * SLAB_FAR_SCALE, t_max);
        if near <= far {
            hits |= ((child_bits4 >> s) & 0xffu) << ((bit_index4 >> s) & 0xffu);
        }
    }
    return hits;
}

// Which of the node's eight children the ray enters before t_max, as a hit mask (above).
fn wide_intersect(n: GpuWideBvhNode, origin: vec3<f32>, inv_dir: vec3<f32>, oct_inv4: u32, t_max: f32) -> u32 {
    let e = n.exponents_imask;
    let scale = vec3<f32>(bitcast<f32>((e & 0xffu) << 23u), bitcast<f32>(((e >> 8u) & 0xffu) << 23u), bitcast<f32>(((e >> 16u) & 0xffu) << 23u));
    // t of grid plane q on each axis = q · scale_dir + shift.
    let scale_dir = scale * inv_dir;
    let shift = (n.origin - origin) * inv_dir;
    // A ray going down an axis enters a box through its max plane.
    let neg = inv_dir < vec3<f32>(0.0);
    var hits = 0u;
    for (var w = 0u; w < 2u; w++) {
        hits |= wide_hits4(
            n.child_meta[w], oct_inv4,
            select(n.q_min_x[w], n.q_max_x[w], neg.x), select(n.q_max_x[w], n.q_min_x[w], neg.x),
            select(n.q_min_y[w], n.q_max_y[w], neg.y), select(n.q_max_y[w], n.q_min_y[w], neg.y),
            select(n.q_min_z[w], n.q_max_z[w], neg.z), select(n.q_max_z[w], n.q_min_z[w], neg.z),
            scale_dir, shift, t_max);
    }
    return hits;
}

// Node `index` of wide_nodes from its five 16-byte words (GpuWideBvhNode's layout): a vector
// load each, where a load of the struct leaves the split to the compiler.
fn wide_node(index: u32) -> GpuWideBvhNode {
    let base = index * 5u;
    let a = wide_nodes[base];
    let b = wide_nodes[base + 1u];
    let c = wide_nodes[base + 2u];
    let d = wide_nodes[base + 3u];
    let e = wide_nodes[base + 4u];
    return GpuWideBvhNode(bitcast<vec3<f32>>(a.xyz), a.w, b.x, b.y, b.zw, c.xy, c.zw, d.xy, d.zw, e.xy, e.zw);
}

fn trace_blas_wide(root: u32, instance: u32, origin: vec3<f32>, dir: vec3<f32>, mode: u32, hit: ptr<function, Hit>) -> bool {
    let inv_dir = safe_inverse(dir);
    let oct_inv4 = wide_octant_inv4(dir);
    var stack: array<vec2<u32>, BLAS_STACK_SIZE>;
    var sp = 0u;
    // The root as a group of one hit inner child at slot 0 of "node" root: bit 24 + (0 ^ oct).
    var node_group = vec2<u32>(root, 1u << (24u + (oct_inv4 & 7u)));
    var triangle_group = vec2<u32>(0u);
    loop {
        if (node_group.y & 0xff000000u) != 0u {
            let hits_imask = node_group.y;
            let bit = firstLeadingBit(hits_imask);
            node_group.y &= ~(1u << bit);
            if (node_group.y & 0xff000000u) != 0u && sp < BLAS_STACK_SIZE {
                stack[sp] = node_group;
                sp++;
            }
            let slot = (bit - 24u) ^ (oct_inv4 & 0xffu);
            let index = node_group.x + countOneBits(hits_imask & ~(0xffffffffu << slot));
            let n = wide_node(index);
            if COUNT_WORK == 1u {
                work_nodes++;
            }
            let hits = wide_intersect(n, origin, inv_dir, oct_inv4, (*hit).t);
            node_group = vec2<u32>(n.child_base, (hits & 0xff000000u) | (n.exponents_imask >> 24u));
            triangle_group = vec2<u32>(n.primitive_base, hits & 0x00ffffffu);
        }
        // The leaf test repeats trace_blas's by hand: as a shared function it made ddgi/shade
        // 6 % and binary-BVH rays 4.5 % slower on an H200 (BENCHMARKS.md).
        while triangle_group.y != 0u {
            let bit = firstLeadingBit(triangle_group.y);
            triangle_group.y &= ~(1u << bit);
            let i = triangle_group.x + bit;
            if COUNT_WORK == 1u {
                work_triangles++;
            }
            let tri = triangle_at(i);
            let r = intersect_triangle(tri, origin, dir, (*hit).t);
            if r.x < (*hit).t {
                if (tri.flags & TRIANGLE_ALPHA_TESTED) != 0u && is_alpha_hole(i, r.yz) {
                    continue;
                }
                if mode == TRACE_ALL {
                    record_crossing(r.x);
                    continue;
                }
                (*hit).t = r.x;
                (*hit).triangle = i;
                (*hit).instance = instance;
                (*hit).bary = r.yz;
                if mode == TRACE_ANY || (mode == TRACE_UNTIL && r.x < trace_stop) {
                    return true;
                }
            }
        }
        if (node_group.y & 0xff000000u) == 0u {
            if sp == 0u {
                break;
            }
            sp--;
            node_group = stack[sp];
        }
    }
    return false;
}

// Traces a world-space ray through the top level; returns the closest hit (or, with
// `any_hit`, any hit) before t_max. hit.triangle is INVALID on a miss.
fn trace_ray(origin: vec3<f32>, dir: vec3<f32>, t_max: f32, any_hit: bool) -> Hit {
    return trace(origin, dir, t_max, select(TRACE_CLOSEST, TRACE_ANY, any_hit));
}

// The closest hit before t_max, or the first hit the traversal finds nearer than `stop`: what
// a test needs that only asks whether the closest hit lies in [stop, t_max) (an emitter's
// shadow ray: any surface short of the emitter's point blocks it, so the search ends there).
fn trace_ray_until(origin: vec3<f32>, dir: vec3<f32>, t_max: f32, stop: f32) -> Hit {
    trace_stop = stop;
    return trace(origin, dir, t_max, TRACE_UNTIL);
}

// Every surface a world-space ray crosses before t_max, whatever its order or facing: their
// count, and their distances in crossing_distances (the first MAX_CROSSINGS, unsorted).
fn trace_crossings(origin: vec3<f32>, dir: vec3<f32>, t_max: f32) -> u32 {
    crossing_count = 0u;
    trace(origin, dir, t_max, TRACE_ALL);
    return crossing_count;
}

fn trace(origin: vec3<f32>, dir: vec3<f32>, t_max: f32, mode: u32) -> Hit {
    var hit: Hit;
    hit.t = min(t_max, RAY_FAR);
    hit.triangle = INVALID;
    hit.instance = INVALID;
    if COUNT_WORK == 1u {
        work_nodes = 0u;
        work_triangles = 0u;
    }
    // Instances with wide trees: both levels in one loop. A scene of one instance for good (no
    // room for a host's) keeps the bottom level's loop alone: in the one loop single-mesh scenes'
    // G-buffer ran 7–11 % slower and their path-traced sample 2–3 % (H100, notes/traversal.md).
    if BLAS_WIDE == 1u && ONE_INSTANCE == 0u {
        trace_levels_wide(origin, dir, mode, &hit);
        return hit;
    }
    // One instance (a static OBJ scene): skip the top level.
    if scene_info.instance_count == 1u {
        let inst = instances[0];
        trace_blas(inst.blas_root, 0u, to_object_point(inst, origin), to_object_vector(inst, dir), mode, &hit);
        return hit;
    }
    let inv_dir = safe_inverse(dir);
    var stack: array<u32, TLAS_STACK_SIZE>;
    var sp = 0u;
    var node = scene_info.tlas_root;
    loop {
        let n = bvh_nodes[node];
        if COUNT_WORK == 1u {
            work_nodes++;
        }
        let ta = slab(origin, inv_dir, n.a_min, n.a_max, hit.t);
        let tb = slab(origin, inv_dir, n.b_min, n.b_max, hit.t);
        for (var k = 0u; k < 2u; k++) {
            let t_box = select(tb, ta, k == 0u);
            let count = select(n.b_count, n.a_count, k == 0u);
            let first = select(n.b_first, n.a_first, k == 0u);
            if t_box < hit.t && count > 0u {
                for (var i = first; i < first + count; i++) {
                    let inst = instances[i];
                    if trace_blas(inst.blas_root, i, to_object_point(inst, origin), to_object_vector(inst, dir), mode, &hit) {
                        return hit;
                    }
                }
            }
        }
        let go_a = ta < hit.t && n.a_count == 0u && n.a_first != INVALID;
        let go_b = tb < hit.t && n.b_count == 0u && n.b_first != INVALID;
        if go_a && go_b {
            let a_first = ta <= tb;
            node = select(n.b_first, n.a_first, a_first);
            if sp < TLAS_STACK_SIZE {
                stack[sp] = select(n.a_first, n.b_first, a_first);
                sp++;
            }
        } else if go_a {
            node = n.a_first;
        } else if go_b {
            node = n.b_first;
        } else {
            if sp == 0u {
                break;
            }
            sp--;
            node = stack[sp];
        }
    }
    return hit;
}

// Both levels in one loop (BLAS_WIDE == 1 and ONE_INSTANCE == 0): each turn visits one wide
// node and its leaf's triangles in the instance the ray is in; a lane not in an instance first
// walks the top level, in a loop of its own, to its next leaf. A warp's rays thus advance
// together whichever level each is at, where a loop over the top level with the bottom level's
// inside it made the lanes between instances wait for those in one, and ran each instance a
// warp's rays entered at a different turn in a round of its own. A top-level entry is (node, 0)
// or (first instance, count) of a leaf; build_tlas puts one instance in a leaf, and a count past
// one would be walked within the stack's room. Updates `hit` as trace_blas does.
fn trace_levels_wide(world_origin: vec3<f32>, world_dir: vec3<f32>, mode: u32, hit: ptr<function, Hit>) -> bool {
    let world_inv_dir = safe_inverse(world_dir);
    var top_stack: array<vec2<u32>, TLAS_STACK_SIZE>;
    var top_sp = 0u;
    // The next top-level entry; x = INVALID: the next comes off the stack. One instance (a host's
    // scene with room for more) has no top level to walk: its one leaf is the first entry.
    var top_next = select(vec2<u32>(scene_info.tlas_root, 0u), vec2<u32>(0u, 1u), scene_info.instance_count == 1u);
    // The instance the ray is in, and the ray in its object space (a ray's t is the same there).
    var instance = INVALID;
    var origin = world_origin;
    var dir = world_dir;
    var inv_dir = world_inv_dir;
    var oct_inv4 = 0u;
    var stack: array<vec2<u32>, BLAS_STACK_SIZE>;
    var sp = 0u;
    var node_group = vec2<u32>(0u);
    var triangle_group = vec2<u32>(0u);
    loop {
        if instance == INVALID {
            // The top level, in a loop of its own, until a leaf's instance is entered: a lane
            // between instances reaches the next in one turn of the outer loop.
            loop {
                if top_next.x == INVALID {
                    if top_sp == 0u {
                        break;
                    }
                    top_sp--;
                    top_next = top_stack[top_sp];
                }
                if top_next.y != 0u {
                    break;
                }
                let n = bvh_nodes[top_next.x];
                if COUNT_WORK == 1u {
                    work_nodes++;
                }
                let ta = slab(world_origin, world_inv_dir, n.a_min, n.a_max, (*hit).t);
                let tb = slab(world_origin, world_inv_dir, n.b_min, n.b_max, (*hit).t);
                let a = vec2<u32>(n.a_first, n.a_count);
                let b = vec2<u32>(n.b_first, n.b_count);
                let go_a = ta < (*hit).t && n.a_first != INVALID;
                let go_b = tb < (*hit).t && n.b_first != INVALID;
                if go_a && go_b {
                    let a_first = ta <= tb;
                    top_next = select(b, a, a_first);
                    if top_sp < TLAS_STACK_SIZE {
                        top_stack[top_sp] = select(a, b, a_first);
                        top_sp++;
                    }
                } else if go_a {
                    top_next = a;
                } else if go_b {
                    top_next = b;
                } else {
                    top_next.x = INVALID;
                }
            }
            if top_next.x == INVALID {
                break;
            }
            // A leaf: enter its first instance, the rest of it back on the stack.
            instance = top_next.x;
            if top_next.y > 1u && top_sp < TLAS_STACK_SIZE {
                top_stack[top_sp] = top_next + vec2<u32>(1u, 0xffffffffu);
                top_sp++;
            }
            top_next.x = INVALID;
            let m = mat3x4<f32>(instances[instance].world_to_object0, instances[instance].world_to_object1, instances[instance].world_to_object2);
            origin = vec4<f32>(world_origin, 1.0) * m;
            dir = vec4<f32>(world_dir, 0.0) * m;
            inv_dir = safe_inverse(dir);
            oct_inv4 = wide_octant_inv4(dir);
            // The root as a group of one hit inner child at slot 0 of "node" root: bit 24 + (0 ^ oct).
            node_group = vec2<u32>(instances[instance].blas_root, 1u << (24u + (oct_inv4 & 7u)));
        }
        if (node_group.y & 0xff000000u) != 0u {
            let hits_imask = node_group.y;
            let bit = firstLeadingBit(hits_imask);
            node_group.y &= ~(1u << bit);
            if (node_group.y & 0xff000000u) != 0u && sp < BLAS_STACK_SIZE {
                stack[sp] = node_group;
                sp++;
            }
            let slot = (bit - 24u) ^ (oct_inv4 & 0xffu);
            let index = node_group.x + countOneBits(hits_imask & ~(0xffffffffu << slot));
            let n = wide_node(index);
            if COUNT_WORK == 1u {
                work_nodes++;
            }
            let hits = wide_intersect(n, origin, inv_dir, oct_inv4, (*hit).t);
            node_group = vec2<u32>(n.child_base, (hits & 0xff000000u) | (n.exponents_imask >> 24u));
            triangle_group = vec2<u32>(n.primitive_base, hits & 0x00ffffffu);
        }
        // The leaf test repeats trace_blas's by hand: as a shared function it made ddgi/shade
        // 6 % and binary-BVH rays 4.5 % slower on an H200 (BENCHMARKS.md).
        while triangle_group.y != 0u {
            let bit = firstLeadingBit(triangle_group.y);
            triangle_group.y &= ~(1u << bit);
            let i = triangle_group.x + bit;
            if COUNT_WORK == 1u {
                work_triangles++;
            }
            let tri = triangle_at(i);
            let r = intersect_triangle(tri, origin, dir, (*hit).t);
            if r.x < (*hit).t {
                if (tri.flags & TRIANGLE_ALPHA_TESTED) != 0u && is_alpha_hole(i, r.yz) {
                    continue;
                }
                if mode == TRACE_ALL {
                    record_crossing(r.x);
                    continue;
                }
                (*hit).t = r.x;
                (*hit).triangle = i;
                (*hit).instance = instance;
                (*hit).bary = r.yz;
                if mode == TRACE_ANY || (mode == TRACE_UNTIL && r.x < trace_stop) {
                    return true;
                }
            }
        }
        if (node_group.y & 0xff000000u) == 0u {
            if sp == 0u {
                // The instance is done: back to the top level.
                instance = INVALID;
            } else {
                sp--;
                node_group = stack[sp];
            }
        }
    }
    return false;
}

// Whether anything blocks the segment from `origin` along `dir` up to `distance`.
fn occluded(origin: vec3<f32>, dir: vec3<f32>, distance: f32) -> bool {
    return trace_ray(origin, dir, distance, true).triangle != INVALID;
}

// Offsets a ray origin off a surface along its geometric normal, scaled with the magnitude
// of the position so that it works at any scene scale (after Wächter and Binder 2019, simplified).
fn offset_ray(p: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let scale = 1e-4 * max(1.0, max(abs(p.x), max(abs(p.y), abs(p.z))));
    return p + n * scale;
}
