// ddgi: appending probes to a list of DdgiActiveProbesWrite (those that update, or the newly
// vigilant and awake), shared by ddgi/probe_states, which builds the next frame's lists, and
// ddgi/window_enter, which adds the probes a tracking window's step brought in to this frame's.

@group(2) @binding(21) var<storage, read_write> active_probes: DdgiActiveProbesWrite;

var<workgroup> listed_before: array<u32, 64>;
var<workgroup> list_base: u32;

// Appends the workgroup's probes whose flag is set to list `list` (LIST_*) in grid order,
// with one global atomic a workgroup, and raises both of its indirect dispatches to cover them.
fn list_if(list: u32, probe: u32, listed: bool, li: u32) {
    // Inclusive prefix sum of the flags over the workgroup: each probe's place.
    workgroupBarrier();
    listed_before[li] = u32(listed);
    workgroupBarrier();
    for (var stride = 1u; stride < 64u; stride <<= 1u) {
        var other = 0u;
        if li >= stride {
            other = listed_before[li - stride];
        }
        workgroupBarrier();
        listed_before[li] += other;
        workgroupBarrier();
    }
    if li == 63u {
        let count = listed_before[63];
        var base = 0u;
        if count > 0u {
            base = atomicAdd(&active_probes.lists[list].count, count);
            let listed = base + count;
            let ray_groups = (listed + PROBES_PER_GROUP - 1u) / PROBES_PER_GROUP * ray_blocks(volume.rays_per_probe);
            let rays = folded_groups(ray_groups);
            atomicMax(&active_probes.lists[list].rays_x, rays.x);
            atomicMax(&active_probes.lists[list].rays_y, rays.y);
            atomicMax(&active_probes.lists[list].rays_z, 1u);
            // The last workgroup to append counts the whole list; the maximum covers it (excess
            // workgroups of ddgi/trace find no rays left).
            var trace = rays;
            if FETCH_RAYS == 1u {
                trace = fetch_groups(listed * volume.rays_per_probe, FETCH_WORKGROUPS);
            }
            atomicMax(&active_probes.lists[list].trace_x, trace.x);
            atomicMax(&active_probes.lists[list].trace_y, trace.y);
            atomicMax(&active_probes.lists[list].trace_z, 1u);
            let blends = folded_groups(listed);
            atomicMax(&active_probes.lists[list].blends_x, blends.x);
            atomicMax(&active_probes.lists[list].blends_y, blends.y);
            atomicMax(&active_probes.lists[list].blends_z, 1u);
        }
        list_base = base;
    }
    workgroupBarrier();
    if listed {
        active_probes.probes[list * volume.probe_count + list_base + listed_before[li] - 1u] = probe;
    }
}

