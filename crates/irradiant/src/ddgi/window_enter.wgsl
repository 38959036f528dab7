// ddgi/window_enter: on the frame a tracking window steps (003 §7.3), the probes of the planes
// that entered (their slots held probes that left) start over: no offset, vigilant, nothing
// blended (their first blend discards what the slot held), and a fresh count, so that they are
// relocated and classified on frames of their own (ddgi/relocate, ddgi/probe_states). The
// planes that stopped or started being the grid's outer layer are classified again too (an
// outer probe reaches without limit outwards, ddgi/probe_states), keeping their light where
// they had any. Those this frame's list of updating probes lacks are added to it.
#import ddgi_volume
#import ddgi_rays
#import ddgi_states
#import ddgi_active_list

@group(2) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(2) @binding(13) var<storage, read_write> probe_offsets: array<vec4<f32>>;
@group(2) @binding(16) var<storage, read_write> probe_states: array<u32>;

// Whether the probe at `coord` lies on a plane whose outer-layer role the step changed: along
// an axis that stepped less than the grid, the plane next to the entering ones (outer before,
// inner now) and the outer plane on the other side (inner before).
fn changed_layer(coord: vec3<u32>) -> bool {
    let start = volume.entering_start.xyz;
    let end = volume.entering_end.xyz;
    let last = volume.counts - 1u;
    var changed = false;
    for (var axis = 0u; axis < 3u; axis++) {
        let s = start[axis];
        let e = end[axis];
        let c = coord[axis];
        if s < e && !(s == 0u && e == volume.counts[axis]) {
            if s > 0u {
                // Entered at the top: the plane below them, and the bottom plane.
                changed = changed || c == s - 1u || c == 0u;
            } else {
                changed = changed || c == e || c == last[axis];
            }
        }
    }
    return changed;
}

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>, @builtin(local_invocation_index) li: u32) {
    let probe = id.x + id.y * groups.x * 64u;
    var unlisted = false;
    if probe < volume.probe_count && volume.entering_start.w != 0u {
        let coord = probe_grid_coord(probe);
        let word = probe_states[probe];
        let fresh = min(volume.entering_end.w, PROBE_FRESH_MASK) << PROBE_FRESH_SHIFT;
        let entered = (coord >= volume.entering_start.xyz) & (coord < volume.entering_end.xyz);
        if any(entered) {
            unlisted = !probe_traces(word, volume.every_probe_updates);
            probe_offsets[probe] = vec4<f32>(0.0);
            probe_states[probe] = PROBE_VIGILANT | fresh;
        } else if changed_layer(coord) {
            unlisted = !probe_traces(word, volume.every_probe_updates);
            // A probe that updated keeps its light; one that slept holds none worth keeping.
            let blends = select(0u, probe_blends(word), probe_updates(word));
            probe_states[probe] = PROBE_VIGILANT | fresh | (blends << PROBE_AGE_SHIFT);
        }
    }
    list_if(LIST_UPDATING, probe, unlisted, li);
}
