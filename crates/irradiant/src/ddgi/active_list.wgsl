// ddgi: appending probes to the list of those that update (DdgiActiveProbesWrite), shared by
// ddgi/probe_states, which builds the next frame's list, and ddgi/window_enter, which adds the
// probes a tracking window's step brought in to this frame's.

@group(2) @binding(21) var<storage, read_write> active_probes: DdgiActiveProbesWrite;

var<workgroup> listed_before: array<u32, 64>;
var<workgroup> list_base: u32;

// Appends the workgroup's updating probes to active_probes in grid order, with one global
// atomic a workgroup, and raises both indirect dispatches to cover them.
fn list_if_updating(probe: u32, updates: bool, li: u32) {
    // Inclusive prefix sum of the flags over the workgroup: each probe's place.
    listed_before[li] = u32(updates);
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
            base = atomicAdd(&active_probes.count, count);
            let listed = base + count;
            let rays = folded_groups((listed + PROBES_PER_GROUP - 1u) / PROBES_PER_GROUP * ray_blocks(volume.rays_per_probe));
            atomicMax(&active_probes.rays_x, rays.x);
            atomicMax(&active_probes.rays_y, rays.y);
            atomicMax(&active_probes.rays_z, 1u);
            let blends = folded_groups(listed);
            atomicMax(&active_probes.blends_x, blends.x);
            atomicMax(&active_probes.blends_y, blends.y);
            atomicMax(&active_probes.blends_z, 1u);
        }
        list_base = base;
    }
    workgroupBarrier();
    if updates {
        active_probes.probes[list_base + listed_before[li] - 1u] = probe;
    }
}

