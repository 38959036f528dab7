// ddgi: which probe, and which of its rays, a thread of the passes that work per updating probe
// takes — ddgi/trace, ddgi/shade and the blends, dispatched indirectly over the list of probes
// that update (DdgiActiveProbes, built by ddgi/probe_states the frame before), or in the
// convergence rounds over the list of newly probes (ddgi_convergence).
#import ddgi_states
#import ddgi_rays
#import ddgi_convergence

@group(2) @binding(21) var<storage, read> active_probes: DdgiActiveProbes;

// Returned for a workgroup past the list's end (the last row of a folded dispatch).
const NOT_LISTED: u32 = 0xffffffffu;

// The list this dispatch works through: the newly probes' in a convergence round, else every
// updating probe's.
fn this_list() -> u32 {
    return select(LIST_UPDATING, LIST_NEWLY, convergence.round > 0u);
}

// Probes in this dispatch's list.
fn listed_count() -> u32 {
    return active_probes.lists[this_list()].count;
}

// The `i`th probe of this dispatch's list.
fn listed_at(i: u32) -> u32 {
    return active_probes.probes[this_list() * volume.probe_count + i];
}

// The probe of a blend workgroup (one a listed probe), or NOT_LISTED.
fn listed_probe(group: vec3<u32>) -> u32 {
    let listed = folded_index(group);
    let count = listed_count();
    return select(NOT_LISTED, listed_at(min(listed, count - 1u)), listed < count);
}

// Rays are stored probe-major: ray r of probe p is p × rays_per_probe + r.
struct RaySlot {
    probe: u32,
    ray: u32,
    index: u32,
    valid: bool,
    // The same for every thread of the workgroup: the first probe's index and the ray block,
    // a seed that with one probe a workgroup does not depend on the list's order (atomic, so
    // not repeatable from run to run).
    group_key: u32,
}

// Which ray a thread of ddgi/trace or ddgi/shade takes (ray_place).
fn ray_slot(group: vec3<u32>, local_index: u32) -> RaySlot {
    let place = ray_place(folded_index(group), local_index, volume.rays_per_probe);
    let count = listed_count();
    let last = count - 1u;
    var slot: RaySlot;
    slot.ray = place.ray;
    slot.valid = place.listed < count && slot.ray < volume.rays_per_probe;
    slot.probe = listed_at(min(place.listed, last));
    slot.index = slot.probe * volume.rays_per_probe + slot.ray;
    slot.group_key = listed_at(min(place.first, last)) * ray_blocks(volume.rays_per_probe) + place.block;
    return slot;
}
